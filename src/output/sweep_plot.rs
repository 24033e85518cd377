//! Frequency and damping of the tracked modes against a design parameter (a Campbell /
//! root-locus style view of a sweep): two panels sharing the parameter axis and a legend
//! beside them (outside the data), SVG and PNG. Each curve has its own colour and line
//! style: romdyn's 8 colours x 3 dash patterns, so 24 curves before a style repeats; points whose
//! mode was matched with a low MAC (a veering) are drawn as crosses.

use std::path::Path;

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use super::atomic::OutputError;
use super::figure::{write_figure, Figure, COLORS, FONT};

/// Dash and gap lengths [px] of the three line styles: solid, dashed, dotted.
const DASHES: [(u32, u32); 3] = [(0, 0), (12, 6), (3, 4)];

/// Curve `k`'s colour and dash pattern: no two of the first 24 curves alike.
fn curve_style(k: usize) -> (RGBColor, (u32, u32)) {
    (COLORS[k % COLORS.len()], DASHES[(k / COLORS.len()) % DASHES.len()])
}

/// Width of the legend beside the panels [px].
const LEGEND_WIDTH: u32 = 470;

/// Longest label in the legend [characters]; longer ones end in "…".
const LABEL_CHARS: usize = 44;

/// One curve: a mode's frequency [Hz] and damping ratio [-] at each parameter value (NaN
/// where the design point failed or has fewer modes: a gap).
#[derive(Clone, Debug)]
pub struct ModeCurve {
    pub label: String,
    pub parameter: Vec<f64>,
    pub freq_hz: Vec<f64>,
    pub damping: Vec<f64>,
    /// Points where the mode's match was ambiguous (a veering): drawn as crosses.
    pub ambiguous: Vec<bool>,
}

#[derive(Clone, Debug)]
pub struct SweepPlot {
    pub title: String,
    /// The parameter's name (the file's `set:` variable, in the file's units).
    pub parameter: String,
    pub curves: Vec<ModeCurve>,
}

/// The axis range of the finite values, at least `min_width` wide (damping ratios of
/// undamped modes are rounding noise around 0: their axis must not magnify it).
fn span(v: impl Iterator<Item = f64>, min_width: f64) -> (f64, f64) {
    let (lo, hi) = v.filter(|x| x.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo).max(min_width).max(hi.abs().max(lo.abs()) * 1e-3).max(1e-12));
    (mid - 1.1 * half, mid + 1.1 * half)
}

/// The finite runs of a curve (a failed point breaks the line).
fn runs(x: &[f64], y: &[f64]) -> Vec<Vec<(f64, f64)>> {
    let mut out = vec![Vec::new()];
    for (&a, &b) in x.iter().zip(y) {
        match (a.is_finite() && b.is_finite(), out.last_mut()) {
            (true, Some(run)) => run.push((a, b)),
            (false, Some(run)) if !run.is_empty() => out.push(Vec::new()),
            _ => {}
        }
    }
    out.retain(|r| !r.is_empty());
    out
}

impl SweepPlot {
    fn panel<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>, caption: Option<&str>, (y_label, y_min_width): (&str, f64), value: impl Fn(&ModeCurve) -> &[f64]) -> Result<(), String> {
        let err = |e: &dyn std::fmt::Display| e.to_string();
        let x = span(self.curves.iter().flat_map(|c| c.parameter.iter().copied()), 0.0);
        let y = span(self.curves.iter().flat_map(|c| value(c).iter().copied()), y_min_width);
        let mut builder = ChartBuilder::on(area);
        if let Some(c) = caption {
            builder.caption(c, (FONT, 26));
        }
        let mut chart = builder.margin(20).x_label_area_size(55).y_label_area_size(100).build_cartesian_2d(x.0..x.1, y.0..y.1).map_err(|e| err(&e))?;
        chart.configure_mesh().x_desc(&self.parameter).y_desc(y_label).axis_desc_style((FONT, 22)).label_style((FONT, 18)).light_line_style(RGBColor(235, 235, 235)).draw().map_err(|e| err(&e))?;
        for (k, c) in self.curves.iter().enumerate() {
            let (color, (dash, gap)) = curve_style(k);
            let style = ShapeStyle { color: color.to_rgba(), filled: false, stroke_width: 2 };
            for run in runs(&c.parameter, value(c)) {
                if dash == 0 {
                    chart.draw_series(LineSeries::new(run.iter().copied(), style)).map_err(|e| err(&e))?;
                } else {
                    chart.draw_series(DashedLineSeries::new(run.iter().copied(), dash, gap, style)).map_err(|e| err(&e))?;
                }
            }
            let points = c.parameter.iter().zip(value(c)).zip(&c.ambiguous).filter(|((x, y), _)| x.is_finite() && y.is_finite());
            for ((&x, &y), &ambiguous) in points {
                if ambiguous {
                    chart.draw_series(std::iter::once(Cross::new((x, y), 6, style))).map_err(|e| err(&e))?;
                } else {
                    chart.draw_series(std::iter::once(Circle::new((x, y), 3, style.filled()))).map_err(|e| err(&e))?;
                }
            }
        }
        Ok(())
    }

    /// The legend: one line sample and label per curve, in a column beside the panels.
    fn legend<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let err = |e: &dyn std::fmt::Display| e.to_string();
        let height = area.dim_in_pixel().1 as i32;
        let step = ((height - 120) / self.curves.len().max(1) as i32).clamp(14, 34);
        let font = (FONT, if step < 22 { 14 } else { 18 }).into_font();
        area.draw(&Text::new("modes (label at the first point)", (10, 60), (FONT, 18).into_font())).map_err(|e| err(&e))?;
        for (k, c) in self.curves.iter().enumerate() {
            let y = 95 + k as i32 * step;
            if y > height - 10 {
                let more = format!("… {} more (the table lists them)", self.curves.len() - k);
                area.draw(&Text::new(more, (10, y), font.clone())).map_err(|e| err(&e))?;
                break;
            }
            let (color, (dash, gap)) = curve_style(k);
            let style = ShapeStyle { color: color.to_rgba(), filled: false, stroke_width: 2 };
            let line = vec![(10, y), (60, y)];
            if dash == 0 {
                area.draw(&PathElement::new(line, style)).map_err(|e| err(&e))?;
            } else {
                area.draw(&DashedPathElement::new(line, dash, gap, style)).map_err(|e| err(&e))?;
            }
            let label = if c.label.chars().count() > LABEL_CHARS { format!("{}…", c.label.chars().take(LABEL_CHARS - 1).collect::<String>()) } else { c.label.clone() };
            area.draw(&Text::new(label, (70, y - 8), font.clone())).map_err(|e| err(&e))?;
        }
        Ok(())
    }
}

impl Figure for SweepPlot {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (plots, legend) = root.split_horizontally(root.dim_in_pixel().0 - LEGEND_WIDTH);
        let (top, bottom) = plots.split_vertically(plots.dim_in_pixel().1 / 2);
        self.panel(&top, Some(&self.title), ("frequency |Im λ|/2π [Hz]", 0.0), |c| &c.freq_hz)?;
        // Damping axes span at least 0.02 (±1 % around an undamped model's rounding noise).
        self.panel(&bottom, None, ("damping ratio −Re λ/|λ| [-]", 0.02), |c| &c.damping)?;
        self.legend(&legend)?;
        root.present().map_err(|e| e.to_string())
    }
}

/// Writes the plot as SVG and PNG (each atomically); refuses a plot without a finite point.
pub fn write_sweep_plot(plot: &SweepPlot, svg_path: &Path, png_path: &Path) -> Result<(), OutputError> {
    if plot.curves.iter().all(|c| runs(&c.parameter, &c.freq_hz).is_empty()) {
        return Err(OutputError::Invalid { path: svg_path.to_path_buf(), message: "no design point has a mode to plot".into() });
    }
    write_figure(plot, (1200 + LEGEND_WIDTH, 1000), svg_path, png_path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn twenty_four_curves_have_twenty_four_styles() {
        let styles: Vec<_> = (0..24).map(curve_style).map(|(c, d)| (c.0, c.1, c.2, d)).collect();
        for (i, a) in styles.iter().enumerate() {
            assert!(!styles[..i].contains(a), "curve {i} repeats a style");
        }
        assert_eq!(curve_style(24).0, curve_style(0).0);
    }
}
