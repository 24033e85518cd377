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
use crate::linear::FrequencyResponse;

const SIZE: (u32, u32) = (1200, 900);

/// Whether a curve is the full model (solid) or a ROM (dashed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveStyle {
    Full,
    Rom,
}

/// One input→output channel of one model in a [`FrequencyResponse`]: the values, with the
/// channel's indices into the response's ports (its grid and names stay in the response).
#[derive(Clone, Debug)]
pub struct ResponseCurve<'a> {
    /// Model name, e.g. "full model", "ROM".
    pub label: &'a str,
    /// Row (output) and column (input) of the transfer matrix.
    pub output: usize,
    pub input: usize,
    /// `z/u` at each frequency of the response's grid.
    pub values: Vec<c64>,
    pub style: CurveStyle,
}

/// The curves of `panels` (output, input): for each, the full model's and then every
/// reduced model's.
pub fn response_curves<'a>(response: &'a FrequencyResponse, panels: &[(usize, usize)]) -> Vec<ResponseCurve<'a>> {
    let mut curves = Vec::new();
    for &(i, j) in panels {
        curves.push(ResponseCurve { label: "full model", output: i, input: j, values: FrequencyResponse::channel(&response.full, i, j), style: CurveStyle::Full });
        for (label, h) in &response.reduced {
            curves.push(ResponseCurve { label, output: i, input: j, values: FrequencyResponse::channel(h, i, j), style: CurveStyle::Rom });
        }
    }
    curves
}

/// Every channel of a response, by rows (one row per output).
pub fn every_channel(response: &FrequencyResponse) -> Vec<(usize, usize)> {
    (0..response.outputs.len()).flat_map(|i| (0..response.inputs.len()).map(move |j| (i, j))).collect()
}

/// A Bode plot: curves of one response sharing a magnitude unit.
#[derive(Clone, Debug)]
pub struct BodePlot<'a> {
    pub title: String,
    /// Unit of |z/u|, e.g. "m/N".
    pub magnitude_unit: String,
    pub response: &'a FrequencyResponse,
    pub curves: Vec<ResponseCurve<'a>>,
}

/// Phase in degrees, unwrapped along the curve, starting in (−180°, 180°] (a real negative
/// start is −180°). A step of less than half a turn is taken as it is. An exact sign flip
/// of an undamped response (a step within 1° of ±180°) is ambiguous in the phase alone:
/// it is a pole (−180°) when |H| peaks there and a zero (+180°) when |H| dips, as the phase
/// of a lightly damped pole or zero would run.
pub fn unwrapped_phase_deg(values: &[c64]) -> Vec<f64> {
    let raw: Vec<f64> = values.iter().map(|v| v.im.atan2(v.re).to_degrees()).collect();
    let mag: Vec<f64> = values.iter().map(|v| v.norm()).collect();
    let mut out = Vec::with_capacity(values.len());
    for (k, &p) in raw.iter().enumerate() {
        let Some(&prev) = out.last() else {
            out.push(if p > 179.999 { p - 360.0 } else { p });
            continue;
        };
        let prev: f64 = prev;
        // The step to the nearest branch, in (−180, 180].
        let mut d = (p - prev).rem_euclid(360.0);
        if d > 180.0 {
            d -= 360.0;
        }
        if (d.abs() - 180.0).abs() < 1.0 {
            let inner = mag[k - 1].max(f64::MIN_POSITIVE).ln() + mag[k].max(f64::MIN_POSITIVE).ln();
            let outer_l = if k >= 2 { mag[k - 2] } else { mag[k - 1] };
            let outer_r = if k + 1 < mag.len() { mag[k + 1] } else { mag[k] };
            let outer = outer_l.max(f64::MIN_POSITIVE).ln() + outer_r.max(f64::MIN_POSITIVE).ln();
            let pole = inner >= outer;
            d = if pole { -d.abs() } else { d.abs() };
        }
        out.push(prev + d);
    }
    out
}

/// Unwrapped phases of curves of one channel from a common reference: each curve is
/// unwrapped along frequency ([`unwrapped_phase_deg`]), then every curve after the first
/// is shifted by whole turns to meet the first at the lowest frequency where their
/// magnitudes agree within 1 % (else at the lowest frequency), so that curves overlay
/// wherever they agree.
pub fn common_reference_phases(curves: &[&ResponseCurve]) -> Vec<Vec<f64>> {
    let mut phases: Vec<Vec<f64>> = curves.iter().map(|c| unwrapped_phase_deg(&c.values)).collect();
    let Some(reference) = curves.first() else { return phases };
    for k in 1..curves.len() {
        let c = curves[k];
        let at = (0..c.values.len().min(reference.values.len()))
            .find(|&i| {
                let (a, b) = (reference.values[i].norm(), c.values[i].norm());
                a > 0.0 && ((b - a) / a).abs() <= 0.01
            })
            .unwrap_or(0);
        if at < phases[k].len() && at < phases[0].len() {
            let turns = ((phases[0][at] - phases[k][at]) / 360.0).round();
            phases[k].iter_mut().for_each(|p| *p += 360.0 * turns);
        }
    }
    phases
}

fn magnitude_db(v: c64) -> Option<f64> {
    let m = v.norm();
    (m > 0.0 && m.is_finite()).then(|| 20.0 * m.log10())
}

fn range(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (lo, hi) = values.filter(|x| x.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    if lo.is_finite() { (lo - pad, hi + pad) } else { (-1.0, 1.0) }
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

/// A tick label on a log frequency axis spanning `decades`: over more than one and a half
/// decades only the 1-2-5 ticks of each decade are labelled (plotters puts a tick at every
/// integer multiple, whose labels "80", "90", "100" ran into each other), the others keep
/// their grid line and an empty label.
pub(super) fn log_tick_label(x: f64, decades: f64) -> String {
    if decades > 1.5 {
        let mantissa = x.abs() / 10f64.powf(x.abs().log10().floor());
        if ![1.0, 2.0, 5.0, 10.0].iter().any(|m| (mantissa - m).abs() < 1e-6 * m) {
            return String::new();
        }
    }
    tick_label(x)
}

/// Largest |value| of a curve.
fn peak(c: &ResponseCurve) -> f64 {
    c.values.iter().map(|v| v.norm()).fold(0.0, f64::max)
}

/// A channel whose largest magnitude is below this fraction of the plot's largest is zero.
pub const ZERO_CHANNEL: f64 = 1e-12;

/// One input→output pair and the curves of every model for it.
struct Channel<'p, 'a> {
    output: usize,
    input: usize,
    curves: Vec<&'p ResponseCurve<'a>>,
}

fn channels<'p, 'a>(plot: &'p BodePlot<'a>) -> Vec<Channel<'p, 'a>> {
    let mut out: Vec<Channel> = Vec::new();
    for c in &plot.curves {
        match out.iter_mut().find(|ch| ch.output == c.output && ch.input == c.input) {
            Some(ch) => ch.curves.push(c),
            None => out.push(Channel { output: c.output, input: c.input, curves: vec![c] }),
        }
    }
    out
}

fn models<'a>(plot: &BodePlot<'a>) -> Vec<(&'a str, CurveStyle)> {
    let mut labels: Vec<(&str, CurveStyle)> = Vec::new();
    for c in &plot.curves {
        if !labels.iter().any(|(l, _)| *l == c.label) {
            labels.push((c.label, c.style));
        }
    }
    labels
}

/// Grid of a plot with `n_out × n_in` channels: (rows, columns).
fn grid(plot: &BodePlot) -> (usize, usize) {
    let chans = channels(plot);
    let outs: Vec<usize> = chans.iter().map(|c| c.output).fold(Vec::new(), |mut v, o| {
        if !v.contains(&o) {
            v.push(o)
        }
        v
    });
    let n = chans.len();
    // One row per output when there are at most 4 inputs.
    super::figure::grid_shape(n, (!outs.is_empty() && n % outs.len() == 0).then(|| n / outs.len()), 4)
}

/// Pixel size of a plot: 1200 × 900 for one channel, 640 × 620 per channel cell otherwise.
pub fn plot_size(plot: &BodePlot) -> (u32, u32) {
    match grid(plot) {
        (1, 1) => SIZE,
        (r, c) => (640 * c as u32, 620 * r as u32 + 60),
    }
}

type Series = Vec<(f64, f64)>;

#[allow(clippy::too_many_arguments)]
fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, series: &[(&ResponseCurve, Series)], y_desc: &str, x_range: (f64, f64), styles: &[(RGBColor, &str)], legend: bool, font: u32, caption: Option<&str>) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let (ylo, yhi) = range(series.iter().flat_map(|(_, p)| p.iter().map(|q| q.1)), 5.0);
    let mut builder = ChartBuilder::on(area);
    builder.margin(10).margin_right(25).x_label_area_size(font * 5 / 2).y_label_area_size(font * 4);
    if let Some(c) = caption {
        builder.caption(c, (FONT, font + 2));
    }
    let mut chart = builder.build_cartesian_2d((x_range.0..x_range.1).log_scale(), ylo..yhi).map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("frequency [Hz]")
        .y_desc(y_desc)
        .axis_desc_style((FONT, font + 2))
        .label_style((FONT, font))
        .x_labels(if font > 16 { 12 } else { 6 })
        .x_label_formatter(&|x| log_tick_label(*x, (x_range.1 / x_range.0).log10()))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| err(&e))?;
    for (curve, points) in series {
        let (color, label) = styles.iter().find(|(_, l)| *l == curve.label).copied().unwrap_or((BLACK, ""));
        let style = ShapeStyle { color: color.to_rgba(), filled: false, stroke_width: if curve.style == CurveStyle::Full { 3 } else { 2 } };
        let drawn = match curve.style {
            CurveStyle::Full => chart.draw_series(LineSeries::new(points.clone(), style)).map_err(|e| err(&e))?,
            CurveStyle::Rom => chart.draw_series(DashedLineSeries::new(points.clone(), 12, 8, style)).map_err(|e| err(&e))?,
        };
        if legend {
            let dashed = curve.style == CurveStyle::Rom;
            drawn.label(label.to_string()).legend(move |(x, y)| {
                let pts = if dashed { vec![(x - 5, y), (x + 3, y)] } else { vec![(x - 5, y), (x + 15, y)] };
                PathElement::new(pts, style)
            });
        }
    }
    if legend {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerLeft)
            .label_font((FONT, font))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
    }
    Ok(())
}

fn draw_channel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, ch: &Channel, styles: &[(RGBColor, &str)], x_range: (f64, f64), plot: &BodePlot, legend: bool, font: u32, largest: f64, single: bool) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let (output, input) = (plot.response.outputs[ch.output].label(), plot.response.inputs[ch.input].label());
    let caption = format!("{output} / {input}");
    let zero = |c: &ResponseCurve| peak(c) <= ZERO_CHANNEL * largest;
    if ch.curves.iter().all(|c| zero(c)) {
        let area = area.margin(20, 20, 20, 20);
        area.draw(&Text::new(caption.clone(), (10, 10), (FONT, font + 2))).map_err(|e| err(&e))?;
        let text = format!("exactly zero: {output} does not respond to {input}");
        area.draw(&Text::new(text, (10, 60), (FONT, font + 2).into_font().color(&RED))).map_err(|e| err(&e))?;
        area.draw(&Text::new("(every model; nothing to plot)".to_string(), (10, 60 + 2 * font as i32), (FONT, font))).map_err(|e| err(&e))?;
        return Ok(());
    }
    let drawn: Vec<&ResponseCurve> = ch.curves.iter().copied().filter(|c| !zero(c)).collect();
    let (top, bottom) = area.split_vertically(area.dim_in_pixel().1 as i32 * 52 / 100);
    let mag: Vec<(&ResponseCurve, Series)> = drawn.iter().map(|c| (*c, plot.response.freq_hz.iter().zip(&c.values).filter_map(|(f, v)| magnitude_db(*v).map(|m| (*f, m))).collect())).collect();
    let phases = common_reference_phases(&drawn);
    let phase: Vec<(&ResponseCurve, Series)> = drawn.iter().zip(phases).map(|(c, p)| (*c, plot.response.freq_hz.iter().copied().zip(p).filter(|(_, p)| p.is_finite()).collect())).collect();
    let unit = if single { format!("magnitude [dB re 1 {}]", plot.magnitude_unit) } else { "magnitude [dB]".to_string() };
    draw_panel(&top, &mag, &unit, x_range, styles, legend, font, Some(caption.as_str()))?;
    draw_panel(&bottom, &phase, "phase [deg]", x_range, styles, false, font, None)?;
    for (k, c) in ch.curves.iter().filter(|c| zero(c)).enumerate() {
        let text = format!("{}: exactly zero in this channel (not drawn)", c.label);
        top.draw(&Text::new(text, (font as i32 * 5, font as i32 * (3 + k as i32)), (FONT, font).into_font().color(&RED))).map_err(|e| err(&e))?;
    }
    Ok(())
}

impl Figure for BodePlot<'_> {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        let plot = self;
        let err = |e: &dyn std::fmt::Display| e.to_string();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let (rows, cols) = grid(plot);
        let single = rows * cols == 1;
        let title = if single { plot.title.clone() } else { format!("{} (magnitude in dB re 1 {})", plot.title, plot.magnitude_unit) };
        let root = root.titled(&title, (FONT, 28)).map_err(|e| err(&e))?;
        let font = if single { 18 } else { 15 };
        let (flo, fhi) = range(plot.response.freq_hz.iter().copied().filter(|f| *f > 0.0), 0.0);
        // Colour by model: the full model black and solid, each ROM its own colour, dashed.
        let styles: Vec<(RGBColor, &str)> = models(plot).iter().enumerate().map(|(k, (l, _))| (COLORS[k % COLORS.len()], *l)).collect();
        let largest = plot.curves.iter().map(peak).fold(0.0, f64::max);
        let cells = root.split_evenly((rows, cols));
        let chans = channels(plot);
        // The legend goes on the first channel that has something drawn.
        let legend_at = chans.iter().position(|ch| ch.curves.iter().any(|c| peak(c) > ZERO_CHANNEL * largest)).unwrap_or(0);
        for (k, ch) in chans.iter().enumerate() {
            draw_channel(&cells[k], ch, &styles, (flo, fhi), plot, k == legend_at, font, largest, single)?;
        }
        root.present().map_err(|e| err(&e))
    }
}

/// Writes the plot as SVG and PNG (each atomically).
pub fn write_bode(plot: &BodePlot, svg_path: &Path, png_path: &Path) -> Result<(), OutputError> {
    if plot.curves.is_empty() {
        return Err(OutputError::Invalid { path: svg_path.to_path_buf(), message: "no curve to plot".into() });
    }
    write_figure(plot, plot_size(plot), svg_path, png_path)
}

#[cfg(test)]
mod tests {
    use super::log_tick_label;

    /// Over three decades only 1-2-5 ticks carry a label; over less than one all of them do.
    #[test]
    fn log_ticks_label_one_two_five() {
        let labels: Vec<String> = [10.0, 20.0, 30.0, 50.0, 90.0, 100.0].iter().map(|&x| log_tick_label(x, 3.0)).collect();
        assert_eq!(labels, ["10", "20", "", "50", "", "100"]);
        assert_eq!(log_tick_label(0.3, 3.0), "");
        assert_eq!(log_tick_label(0.2, 3.0), "0.2");
        assert_eq!(log_tick_label(30.0, 0.8), "30");
    }
}
