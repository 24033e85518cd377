//! Frequency and damping of the lowest modes against a design parameter (a Campbell /
//! root-locus style view of a sweep): two panels sharing the parameter axis, SVG and PNG.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::atomic::OutputError;
use super::figure::{write_figure, Figure, COLORS, FONT};

/// One curve: a mode's frequency [Hz] and damping ratio [-] at each parameter value (NaN
/// where the design point failed or has fewer modes: a gap).
#[derive(Clone, Debug)]
pub struct ModeCurve {
    pub label: String,
    pub parameter: Vec<f64>,
    pub freq_hz: Vec<f64>,
    pub damping: Vec<f64>,
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
    fn panel<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>, caption: Option<&str>, (y_label, y_min_width): (&str, f64), value: impl Fn(&ModeCurve) -> &[f64], legend: bool) -> Result<(), String> {
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
            let color = COLORS[k % COLORS.len()];
            let style = ShapeStyle { color: color.to_rgba(), filled: false, stroke_width: 2 };
            for (r, run) in runs(&c.parameter, value(c)).into_iter().enumerate() {
                let drawn = chart.draw_series(LineSeries::new(run.iter().copied(), style)).map_err(|e| err(&e))?;
                if r == 0 && legend {
                    drawn.label(&c.label).legend(move |(x, y)| PathElement::new(vec![(x - 5, y), (x + 15, y)], style));
                }
                chart.draw_series(run.iter().map(|p| Circle::new(*p, 4, style.filled()))).map_err(|e| err(&e))?;
            }
        }
        if legend {
            chart.configure_series_labels().position(SeriesLabelPosition::UpperRight).label_font((FONT, 18)).background_style(WHITE.mix(0.85)).border_style(BLACK).draw().map_err(|e| err(&e))?;
        }
        Ok(())
    }
}

impl Figure for SweepPlot {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (top, bottom) = root.split_vertically(root.dim_in_pixel().1 / 2);
        self.panel(&top, Some(&self.title), ("frequency |Im λ|/2π [Hz]", 0.0), |c| &c.freq_hz, true)?;
        // Damping axes span at least 0.02 (±1 % around an undamped model's rounding noise).
        self.panel(&bottom, None, ("damping ratio −Re λ/|λ| [-]", 0.02), |c| &c.damping, false)?;
        root.present().map_err(|e| e.to_string())
    }
}

/// Writes the plot as SVG and PNG (each atomically); refuses a plot without a finite point.
pub fn write_sweep_plot(plot: &SweepPlot, svg_path: &Path, png_path: &Path) -> Result<(), OutputError> {
    if plot.curves.iter().all(|c| runs(&c.parameter, &c.freq_hz).is_empty()) {
        return Err(OutputError::Invalid { path: svg_path.to_path_buf(), message: "no design point has a mode to plot".into() });
    }
    write_figure(plot, (1200, 1000), svg_path, png_path)
}
