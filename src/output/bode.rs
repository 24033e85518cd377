//! Bode plots (magnitude in dB and phase in degrees against log frequency) as SVG and PNG.
//!
//! Text uses DejaVu Sans embedded in the binary, so plots render on machines without
//! fonts or fontconfig.

use std::path::Path;

use faer::c64;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::atomic::OutputError;
use super::figure::{write_figure, Figure, COLORS, FONT};

const SIZE: (u32, u32) = (1200, 900);

/// Whether a curve is the full model (solid) or a ROM (dashed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveStyle {
    Full,
    Rom,
}

/// One input→output frequency response of one model.
#[derive(Clone, Debug)]
pub struct ResponseCurve {
    /// Model name, e.g. "full model", "ROM".
    pub label: String,
    pub input: String,
    pub output: String,
    pub freq_hz: Vec<f64>,
    /// `z/u` at each frequency.
    pub values: Vec<c64>,
    pub style: CurveStyle,
}

/// A Bode plot: curves sharing a magnitude unit.
#[derive(Clone, Debug)]
pub struct BodePlot {
    pub title: String,
    /// Unit of |z/u|, e.g. "m/N".
    pub magnitude_unit: String,
    pub curves: Vec<ResponseCurve>,
}

/// Phase in degrees, unwrapped along the curve.
pub fn unwrapped_phase_deg(values: &[c64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(values.len());
    let mut offset = 0.0;
    let mut prev: Option<f64> = None;
    for v in values {
        let p = v.im.atan2(v.re).to_degrees();
        if let Some(q) = prev {
            let d = p + offset - q;
            // Half turns (the sign flips of undamped responses) go down: a phase lag.
            offset -= 360.0 * (d / 360.0 + 0.5).floor();
        }
        let u = p + offset;
        prev = Some(u);
        out.push(u);
    }
    out
}

fn magnitude_db(v: c64) -> Option<f64> {
    let m = v.norm();
    (m > 0.0 && m.is_finite()).then(|| 20.0 * m.log10())
}

fn range(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (lo, hi) = values.filter(|x| x.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    if lo.is_finite() { (lo - pad, hi + pad) } else { (-1.0, 1.0) }
}

/// Colour and legend text of each curve: colour by input/output pair when there are
/// several pairs, by model otherwise.
fn legend_entries(curves: &[ResponseCurve]) -> Vec<(RGBColor, String)> {
    let mut pairs: Vec<(&str, &str)> = Vec::new();
    let mut labels: Vec<&str> = Vec::new();
    for c in curves {
        if !pairs.contains(&(c.output.as_str(), c.input.as_str())) {
            pairs.push((&c.output, &c.input));
        }
        if !labels.contains(&c.label.as_str()) {
            labels.push(&c.label);
        }
    }
    curves
        .iter()
        .map(|c| {
            let pair = pairs.iter().position(|p| *p == (c.output.as_str(), c.input.as_str())).unwrap_or(0);
            let label = labels.iter().position(|l| *l == c.label).unwrap_or(0);
            let color = if pairs.len() > 1 { pair } else { label };
            (COLORS[color % COLORS.len()], format!("{}: {} / {}", c.label, c.output, c.input))
        })
        .collect()
}

/// A frequency tick: plain decimals between 1e-3 and 1e4, scientific outside.
pub(super) fn tick_label(x: f64) -> String {
    if (1e-3..1e4).contains(&x.abs()) {
        let s = format!("{x:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{x:.0e}")
    }
}

type Plotted<'a> = Vec<(&'a ResponseCurve, Vec<(f64, f64)>)>;

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    plot: &BodePlot,
    series: Plotted<'_>,
    y_desc: &str,
    legend: bool,
    x_range: (f64, f64),
) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let (ylo, yhi) = range(series.iter().flat_map(|(_, p)| p.iter().map(|q| q.1)), 5.0);
    let mut chart = ChartBuilder::on(area)
        .margin(15)
        .margin_right(30)
        .x_label_area_size(55)
        .y_label_area_size(90)
        .build_cartesian_2d((x_range.0..x_range.1).log_scale(), ylo..yhi)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("frequency [Hz]")
        .y_desc(y_desc)
        .axis_desc_style((FONT, 22))
        .label_style((FONT, 18))
        .x_labels(12)
        .x_label_formatter(&|x| tick_label(*x))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| err(&e))?;
    let entries = legend_entries(&plot.curves);
    for (k, (curve, points)) in series.into_iter().enumerate() {
        let (color, text) = entries[k].clone();
        let style = ShapeStyle { color: color.to_rgba(), filled: false, stroke_width: 2 };
        let drawn = match curve.style {
            CurveStyle::Full => chart.draw_series(LineSeries::new(points, style)).map_err(|e| err(&e))?,
            CurveStyle::Rom => chart.draw_series(DashedLineSeries::new(points, 12, 8, style)).map_err(|e| err(&e))?,
        };
        if legend && k < 12 {
            drawn.label(text).legend(move |(x, y)| PathElement::new(vec![(x - 5, y), (x + 15, y)], style));
        }
    }
    if legend {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerLeft)
            .label_font((FONT, 18))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
    }
    Ok(())
}

impl Figure for BodePlot {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        let plot = self;
        let err = |e: &dyn std::fmt::Display| e.to_string();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let root = root.titled(&plot.title, (FONT, 28)).map_err(|e| err(&e))?;
        let (top, bottom) = root.split_vertically(SIZE.1 as i32 * 52 / 100);
        let (flo, fhi) = range(plot.curves.iter().flat_map(|c| c.freq_hz.iter().copied().filter(|f| *f > 0.0)), 0.0);
        let mag: Plotted = plot
            .curves
            .iter()
            .map(|c| (c, c.freq_hz.iter().zip(&c.values).filter_map(|(f, v)| magnitude_db(*v).map(|m| (*f, m))).collect()))
            .collect();
        let phase: Plotted = plot
            .curves
            .iter()
            .map(|c| (c, c.freq_hz.iter().copied().zip(unwrapped_phase_deg(&c.values)).filter(|(_, p)| p.is_finite()).collect()))
            .collect();
        let unit = format!("magnitude [dB re 1 {}]", plot.magnitude_unit);
        draw_panel(&top, plot, mag, &unit, true, (flo, fhi))?;
        draw_panel(&bottom, plot, phase, "phase [deg]", false, (flo, fhi))?;
        root.present().map_err(|e| err(&e))
    }
}

/// Writes the plot as SVG and PNG (each atomically).
pub fn write_bode(plot: &BodePlot, svg_path: &Path, png_path: &Path) -> Result<(), OutputError> {
    if plot.curves.is_empty() {
        return Err(OutputError::Invalid { path: svg_path.to_path_buf(), message: "no curve to plot".into() });
    }
    write_figure(plot, SIZE, svg_path, png_path)
}
