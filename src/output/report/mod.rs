//! A study's report as one HTML page (`romdyn rom … --report DIR`): the ROM's summary and
//! warnings, the modal table, the Bode plot of the full model and the ROM, and each kept
//! mode's shape animated on the model's geometry (nodes and the lines between connected
//! nodes, in 3-D in the browser: `viewer.js`, no library and no network). The page is
//! `DIR/index.html`; the plot beside it (`DIR/bode.csv`, `.svg`, `.png`).

use std::path::{Path, PathBuf};

use faer::c64;
use serde_json::json;

use super::atomic::{write_atomic_bytes, OutputError};
use super::frequency_plot::write_bode_files;
use crate::linear::FrequencyResponse;

/// One kept mode's shape at the nodes: a complex translation [1] per node, scaled so the
/// largest has unit length.
#[derive(Clone, Debug)]
pub struct ModeShape {
    /// What the list of modes shows, e.g. "mode 1: 49.3265 Hz".
    pub label: String,
    pub translations: Vec<[c64; 3]>,
}

/// The model's geometry at the reference: node positions [m], the pairs of nodes an element
/// connects, and the kept modes' shapes.
#[derive(Clone, Debug, Default)]
pub struct Geometry {
    pub nodes: Vec<[f64; 3]>,
    pub node_labels: Vec<u32>,
    pub edges: Vec<(usize, usize)>,
    pub modes: Vec<ModeShape>,
}

/// What the page shows, as text and data (the study writes it: [`crate::study::Study::report`]).
#[derive(Clone, Debug, Default)]
pub struct Report {
    pub title: String,
    /// The ROM's summary, as `romdyn rom` prints it.
    pub summary: String,
    /// Every warning of the study and the ROM.
    pub warnings: Vec<String>,
    /// The modal table, as `romdyn eig` prints it.
    pub modal_table: String,
    /// `None` without a model (a pencil file): no animation.
    pub geometry: Option<Geometry>,
    /// With an imposed motion: the transmissibility of the full model and the ROM (eq. 100),
    /// written beside the page as `transmissibility.{csv,svg,png}`.
    pub transmissibility: Option<super::mimo_plot::MimoPlot>,
    /// Figures their writer puts beside the page (a validation against the nonlinear model).
    pub figures: Vec<Figure>,
}

/// A section with a figure written beside the page by its own writer.
#[derive(Clone, Debug, Default)]
pub struct Figure {
    pub heading: String,
    /// What it says, as the command prints it.
    pub text: String,
    /// The image's and the values' file names, relative to the page.
    pub image: String,
    pub data: String,
}

/// `text` escaped for HTML.
fn html(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

impl Report {
    /// The page (the Bode plot is `bode.svg` beside it).
    pub fn page(&self) -> String {
        let warnings = if self.warnings.is_empty() {
            "<p>No warnings.</p>".to_string()
        } else {
            format!("<ul class=\"warnings\">{}</ul>", self.warnings.iter().map(|w| format!("<li>{}</li>", html(w))).collect::<String>())
        };
        let viewer = match &self.geometry {
            Some(g) if !g.modes.is_empty() => {
                let shape = |part: fn(&c64) -> f64| g.modes.iter().map(|m| m.translations.iter().map(|t| t.iter().map(part).collect::<Vec<_>>()).collect::<Vec<_>>()).collect::<Vec<_>>();
                let (re, im) = (shape(|c| c.re), shape(|c| c.im));
                let modes: Vec<_> = g.modes.iter().enumerate().map(|(k, m)| json!({"label": m.label, "shape_re": re[k], "shape_im": im[k]})).collect();
                let data = json!({"nodes": g.nodes, "labels": g.node_labels, "edges": g.edges.iter().map(|(a, b)| [a, b]).collect::<Vec<_>>(), "modes": modes});
                // `</` cannot end the script element early inside the JSON.
                let data = data.to_string().replace("</", "<\\/");
                format!(
                    "<h2>Kept modes</h2>\n<p>Each kept mode's right eigenvector at the nodes (translations), animated over one period, the largest displacement drawn at a tenth of the model's size; grey: the reference configuration. Drag to turn.</p>\n<p><select id=\"mode\"></select> <button id=\"play\">pause</button></p>\n<canvas id=\"viewer\" width=\"900\" height=\"560\"></canvas>\n<script type=\"application/json\" id=\"romdyn-geometry\">{data}</script>\n<script>{}</script>\n",
                    include_str!("viewer.js")
                )
            }
            _ => "<h2>Kept modes</h2>\n<p>No geometry: the study has no model (a pencil file) or keeps no mode that moves a structural node.</p>\n<script>document.body.dataset.status = \"ok\";</script>\n".to_string(),
        };
        format!(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n<style>\nbody {{ font-family: sans-serif; max-width: 1000px; margin: 1em auto; color: #222; }}\npre {{ background: #f6f6f6; padding: 0.6em; overflow-x: auto; font-size: 12px; }}\ncanvas {{ border: 1px solid #ccc; cursor: grab; }}\n.warnings li {{ color: #8a4b00; }}\nimg {{ max-width: 100%; }}\n</style>\n</head>\n<body>\n<script>window.addEventListener(\"error\", (e) => {{ document.body.dataset.error = String(e.message); }});</script>\n<h1>{title}</h1>\n<p>Written by romdyn {version}. SI units: frequencies in Hz, eigenvalues in rad/s, inputs and outputs in the units of their names.</p>\n<h2>ROM</h2>\n<pre>{summary}</pre>\n<h2>Warnings</h2>\n{warnings}\n{viewer}<h2>Frequency response</h2>\n<p>The full linear model (solid) and the ROM (dashed); the values are in <a href=\"bode.csv\">bode.csv</a>.</p>\n<img src=\"bode.svg\" alt=\"Bode plot of the full model and the ROM\">\n{transmissibility}{figures}<h2>Modal table</h2>\n<pre>{modal}</pre>\n</body>\n</html>\n",
            title = html(&self.title),
            version = env!("CARGO_PKG_VERSION"),
            summary = html(&self.summary),
            modal = html(&self.modal_table),
            figures = self.figures.iter().map(|f| format!("<h2>{}</h2>\n<pre>{}</pre>\n<p>The values are in <a href=\"{}\">{}</a>.</p>\n<img src=\"{}\" alt=\"{}\">\n", html(&f.heading), html(&f.text), html(&f.data), html(&f.data), html(&f.image), html(&f.heading))).collect::<String>(),
            transmissibility = if self.transmissibility.is_some() {
                "<h2>Transmissibility</h2>\n<p>|z/z_e| of the full model and the ROM (eq. 100); the values are in <a href=\"transmissibility.csv\">transmissibility.csv</a>.</p>\n<img src=\"transmissibility.svg\" alt=\"Transmissibility of the full model and the ROM\">\n"
            } else {
                ""
            },
        )
    }

    /// The files [`Report::write`] writes into `dir`.
    pub fn files(dir: &Path) -> [PathBuf; 4] {
        [dir.join("index.html"), dir.join("bode.csv"), dir.join("bode.svg"), dir.join("bode.png")]
    }

    /// Writes `dir/index.html` and the Bode plot of `responses` beside it, and the
    /// transmissibility when there is one (the folder is made if missing; the page last).
    pub fn write(&self, dir: &Path, responses: &FrequencyResponse) -> Result<[PathBuf; 4], OutputError> {
        std::fs::create_dir_all(dir).map_err(|cause| OutputError::Io { path: dir.to_path_buf(), operation: "create the folder", cause })?;
        if let Some(plot) = &self.transmissibility {
            plot.write_files(&dir.join("transmissibility"))?;
        }
        write_bode_files(responses, &dir.join("bode"), &self.title)?;
        let files = Self::files(dir);
        write_atomic_bytes(&files[0], self.page().as_bytes())?;
        Ok(files)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_page_escapes_text_and_carries_the_geometry() {
        let g = Geometry { nodes: vec![[0.0; 3], [1.0, 0.0, 0.0]], node_labels: vec![1, 2], edges: vec![(0, 1)], modes: vec![ModeShape { label: "mode 1: 2 Hz".into(), translations: vec![[c64::new(0.0, 0.0); 3], [c64::new(0.0, 0.0), c64::new(1.0, 0.0), c64::new(0.0, 0.0)]] }] };
        let page = Report { title: "a < b".into(), summary: "s".into(), warnings: vec!["w </script>".into()], modal_table: "t".into(), geometry: Some(g), transmissibility: None, figures: Vec::new() }.page();
        assert!(page.contains("<title>a &lt; b</title>") && page.contains("w &lt;/script&gt;"));
        let start = page.find("id=\"romdyn-geometry\">").unwrap() + "id=\"romdyn-geometry\">".len();
        let end = start + page[start..].find("</script>").unwrap();
        let data: serde_json::Value = serde_json::from_str(&page[start..end]).unwrap();
        assert_eq!(data["edges"], json!([[0, 1]]));
        assert_eq!(data["modes"][0]["shape_re"][1], json!([0.0, 1.0, 0.0]));
    }
}
