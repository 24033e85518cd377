//! Frequency grid and curves for `--bode` / `romdyn freq`.

use std::path::Path;

use anyhow::{Context, Result};
use faer::{c64, Mat};
use romdyn::linear::{LinearDae, ModalAnalysis, ModeKind};
use romdyn::output::bode::{write_bode, BodePlot, CurveStyle, ResponseCurve};
use romdyn::output::prefixed_path;
use romdyn::output::response_csv::write_response_csv;
use romdyn::rom::{full_frequency_response, log_frequencies, OrdinaryRom};

use super::args::FrequencyArgs;

pub struct Curves {
    freq_hz: Vec<f64>,
    inputs: Vec<String>,
    outputs: Vec<String>,
    curves: Vec<ResponseCurve>,
}

/// Default band: a decade below the lowest and above the highest of `focus` (or of all
/// dynamic modes when `focus` is empty).
fn default_band(modal: &ModalAnalysis, focus: &[c64]) -> (f64, f64) {
    let hz = |l: &c64| l.norm() / (2.0 * std::f64::consts::PI);
    let mut f: Vec<f64> = if focus.is_empty() {
        modal.of_kind(ModeKind::Dynamic).map(|i| modal.modes[i].freq_hz()).collect()
    } else {
        focus.iter().map(hz).collect()
    };
    f.retain(|x| x.is_finite() && *x > 0.0);
    let lo = f.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = f.iter().copied().fold(0.0, f64::max);
    if lo.is_finite() && hi > 0.0 { (lo / 10.0, hi * 10.0) } else { (0.01, 100.0) }
}

fn curves_of(label: &str, style: CurveStyle, freq_hz: &[f64], h: &[Mat<c64>], inputs: &[String], outputs: &[String]) -> Vec<ResponseCurve> {
    let mut out = Vec::new();
    for (i, output) in outputs.iter().enumerate() {
        for (j, input) in inputs.iter().enumerate() {
            out.push(ResponseCurve {
                label: label.to_string(),
                input: input.clone(),
                output: output.clone(),
                freq_hz: freq_hz.to_vec(),
                values: h.iter().map(|m| m[(i, j)]).collect(),
                style,
            });
        }
    }
    out
}

impl Curves {
    /// The full model's response on the requested (or default) grid.
    pub fn new(dae: &LinearDae, modal: &ModalAnalysis, f: &FrequencyArgs, focus: &[c64]) -> Self {
        let (lo, hi) = default_band(modal, focus);
        let freq_hz = log_frequencies(f.fmin.unwrap_or(lo), f.fmax.unwrap_or(hi), f.points.max(2));
        let h = full_frequency_response(dae, &freq_hz);
        let curves = curves_of("full model", CurveStyle::Full, &freq_hz, &h, &dae.input_names, &dae.output_names);
        Curves { freq_hz, inputs: dae.input_names.clone(), outputs: dae.output_names.clone(), curves }
    }

    pub fn with_rom(mut self, label: &str, rom: &OrdinaryRom) -> Self {
        let h = rom.frequency_response(&self.freq_hz);
        self.curves.extend(curves_of(label, CurveStyle::Rom, &self.freq_hz, &h, &self.inputs, &self.outputs));
        self
    }
}

/// Writes PREFIX.csv, PREFIX.svg and PREFIX.png.
pub fn write_bode_files(c: &Curves, prefix: &Path) -> Result<()> {
    let (csv, svg, png) = (prefixed_path(prefix, "csv"), prefixed_path(prefix, "svg"), prefixed_path(prefix, "png"));
    write_response_csv(&c.curves, &csv).with_context(|| format!("writing {}", csv.display()))?;
    let plot = BodePlot {
        title: "Frequency response".into(),
        magnitude_unit: "output unit / input unit (SI)".into(),
        curves: c.curves.clone(),
    };
    write_bode(&plot, &svg, &png).with_context(|| format!("writing {} and {}", svg.display(), png.display()))?;
    eprintln!("wrote {}, {}, {}", csv.display(), svg.display(), png.display());
    Ok(())
}
