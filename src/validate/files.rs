//! The files of `romdyn validate PREFIX`: PREFIX.csv (estimate, coherence, full model and
//! ROM on the estimate's bins), PREFIX.time.csv (input, nonlinear and ROM outputs in time),
//! PREFIX.svg and PREFIX.png (Bode overlay with a coherence panel per channel). Each is
//! written atomically; a command puts them in place as one set
//! ([`crate::output::atomic::write_set`]). With several `--amplitudes` the CSVs hold every
//! amplitude's run (columns named with the input's RMS, smallest first); the figures show
//! the smallest amplitude's.

use std::io::Write;
use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::output::atomic::{write_atomic, OutputError};
use crate::output::figure::{write_figure, Figure, COLORS, FONT};
use crate::output::prefixed_path;

use super::Validation;

/// The unit in a port's name, "N" from "node 3 Fx [N]" ("1" without one).
fn unit(name: &str) -> String {
    let unit = crate::linear::Port::from_label(name).unit;
    if unit.is_empty() { "1".to_string() } else { unit }
}

/// Unit of a channel's response, "m/N" from "… [m]" and "… [N]".
fn unit_ratio(output: &str, input: &str) -> String {
    format!("{}/{}", unit(output), unit(input))
}

/// " at A RMS UNIT" naming run `r`'s columns when there are several amplitudes, else "".
fn amplitude_suffix(v: &Validation, r: usize) -> String {
    if v.runs.len() < 2 {
        return String::new();
    }
    let unit = v.runs[r].channels.first().map_or_else(|| "1".to_string(), |c| unit(&c.input));
    let rms: Vec<String> = v.runs[r].amplitude.iter().map(|a| format!("{a:.6e}")).collect();
    format!(" at {} RMS [{unit}]", rms.join(";"))
}

/// PREFIX.csv: `frequency [Hz]`, then per channel the estimate's re/im and its coherence
/// (per amplitude), the full model's and the ROM's re/im.
pub fn write_response_csv(v: &Validation, path: &Path) -> Result<(), OutputError> {
    let first = &v.runs[0];
    write_atomic(path, |w: &mut dyn Write| {
        write!(w, "frequency [Hz]")?;
        for c in &first.channels {
            let (n, u) = (format!("{} / {}", c.output, c.input).replace(',', ";"), unit_ratio(&c.output, &c.input));
            for r in 0..v.runs.len() {
                let at = amplitude_suffix(v, r);
                write!(w, ",{n} estimate re [{u}]{at},{n} estimate im [{u}]{at},{n} coherence [1]{at}")?;
            }
            write!(w, ",{n} full re [{u}],{n} full im [{u}],{n} ROM re [{u}],{n} ROM im [{u}]")?;
        }
        writeln!(w)?;
        for (k, f) in first.channels[0].estimate.freq_hz.iter().enumerate() {
            write!(w, "{f:.12e}")?;
            for (i, c) in first.channels.iter().enumerate() {
                for run in &v.runs {
                    let e = &run.channels[i].estimate;
                    write!(w, ",{:.12e},{:.12e},{:.6}", e.h[k].re, e.h[k].im, e.coherence[k])?;
                }
                let (fu, r) = (c.full[k], c.rom[k]);
                write!(w, ",{:.12e},{:.12e},{:.12e},{:.12e}", fu.re, fu.im, r.re, r.im)?;
            }
            writeln!(w)?;
        }
        Ok(())
    })
}

/// PREFIX.time.csv: `time [s]`, then per amplitude and input run its input and per output
/// the nonlinear model's and the ROM's change from the reference.
pub fn write_time_csv(v: &Validation, path: &Path, t0: f64) -> Result<(), OutputError> {
    let first = &v.runs[0];
    let outputs: Vec<&str> = first.channels.iter().take(first.time[0].nonlinear.len()).map(|c| c.output.as_str()).collect();
    write_atomic(path, |w: &mut dyn Write| {
        write!(w, "time [s]")?;
        for (a, run) in v.runs.iter().enumerate() {
            let at = amplitude_suffix(v, a);
            for r in &run.time {
                write!(w, ",input {}{at}", r.input.replace(',', ";"))?;
                for o in &outputs {
                    write!(w, ",nonlinear {o} (input {}){at},ROM {o} (input {}){at}", r.input, r.input)?;
                }
            }
        }
        writeln!(w)?;
        for k in 0..v.plan.samples {
            write!(w, "{:.12e}", t0 + k as f64 * v.plan.dt)?;
            for run in &v.runs {
                for r in &run.time {
                    write!(w, ",{:.12e}", r.u[k])?;
                    for (y, z) in r.nonlinear.iter().zip(&r.rom) {
                        write!(w, ",{:.12e},{:.12e}", y[k], z[k])?;
                    }
                }
            }
            writeln!(w)?;
        }
        Ok(())
    })
}

/// The Bode overlay: per channel magnitude, phase and coherence panels.
struct ValidationFigure<'a>(&'a Validation);

/// At most this many channels are drawn (a person reads 1–6).
pub const MAX_PLOTTED_CHANNELS: usize = 6;

/// A log axis's tick label: only 1, 2 and 5 times a power of ten (plotters labels every
/// minor tick, which overlap above the first decade's middle).
fn log_tick(x: &f64) -> String {
    // Rounded to 3 digits first: plotters' ticks are 0.09999999999999998 rather than 0.1.
    let Ok(v) = format!("{x:.2e}").parse::<f64>() else { return String::new() };
    let mantissa = v / 10f64.powf(v.log10().floor());
    if [1.0, 2.0, 5.0].iter().any(|d| (mantissa - d).abs() < 1e-6) { format!("{v}") } else { String::new() }
}

fn log_span(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = v.filter(|x| x.is_finite() && *x > 0.0).fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    if !lo.is_finite() { (1e-12, 1.0) } else if hi <= lo { (lo / 2.0, hi * 2.0) } else { (lo / 1.5, hi * 1.5) }
}

impl Figure for ValidationFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        let err = |e: &dyn std::fmt::Display| e.to_string();
        let v = self.0;
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let run = &v.runs[0];
        let channels: Vec<_> = run.channels.iter().take(MAX_PLOTTED_CHANNELS).collect();
        let root = root.titled("Validation: nonlinear run (H1), full linear model, ROM", (FONT, 26)).map_err(|e| err(&e))?;
        let columns = root.split_evenly((1, channels.len()));
        for (c, area) in channels.iter().zip(columns) {
            let panels = area.split_by_breakpoints::<u32, u32, _, _>([], [area.dim_in_pixel().1 * 45 / 100, area.dim_in_pixel().1 * 75 / 100]);
            let f = &c.estimate.freq_hz;
            let (f0, f1) = (f.first().copied().unwrap_or(1.0), f.last().copied().unwrap_or(2.0));
            let mags = |h: &[faer::c64]| h.iter().map(|x| x.norm()).collect::<Vec<_>>();
            let (m0, m1) = log_span(mags(&c.estimate.h).into_iter().chain(mags(&c.full)).chain(mags(&c.rom)));
            let mut measured = v.measured.iter().filter(|m| m.name == format!("{}/{}", 1 + run.channels.iter().position(|x| std::ptr::eq(x, *c)).unwrap_or(0) % run.time[0].nonlinear.len(), 1 + run.channels.iter().position(|x| std::ptr::eq(x, *c)).unwrap_or(0) / run.time[0].nonlinear.len()));
            // The full model under the ROM, wider, so both show where they agree.
            let curves: Vec<(&str, &[faer::c64], &[f64], usize)> = {
                let mut v = vec![("full linear model", &c.full[..], &f[..], 2), ("H1 estimate", &c.estimate.h[..], &f[..], 0), ("ROM", &c.rom[..], &f[..], 1)];
                if let Some(m) = measured.next() {
                    v.push(("measured", &m.measured[..], &m.freq_hz[..], 3));
                }
                v
            };
            let mut mag = ChartBuilder::on(&panels[0]).caption(format!("{} / {}", c.output, c.input), (FONT, 18)).margin(8).x_label_area_size(30).y_label_area_size(80)
                .build_cartesian_2d((f0..f1).log_scale(), (m0..m1).log_scale()).map_err(|e| err(&e))?;
            mag.configure_mesh().x_label_formatter(&log_tick).y_label_formatter(&log_tick).y_desc(format!("|z/u| [{}]", unit_ratio(&c.output, &c.input))).label_style((FONT, 14)).axis_desc_style((FONT, 16)).light_line_style(RGBColor(235, 235, 235)).draw().map_err(|e| err(&e))?;
            let mut phase = ChartBuilder::on(&panels[1]).margin(8).x_label_area_size(30).y_label_area_size(80).build_cartesian_2d((f0..f1).log_scale(), -180.0..180.0).map_err(|e| err(&e))?;
            phase.configure_mesh().x_label_formatter(&log_tick).y_desc("phase [deg]").label_style((FONT, 14)).axis_desc_style((FONT, 16)).light_line_style(RGBColor(235, 235, 235)).draw().map_err(|e| err(&e))?;
            for (label, h, fr, color) in &curves {
                let style = ShapeStyle { color: COLORS[*color].to_rgba(), filled: false, stroke_width: match *color { 2 => 5, 0 => 3, _ => 2 } };
                mag.draw_series(LineSeries::new(fr.iter().zip(h.iter()).map(|(f, h)| (*f, h.norm())), style)).map_err(|e| err(&e))?.label(*label).legend(move |(x, y)| PathElement::new(vec![(x - 5, y), (x + 15, y)], style));
                phase.draw_series(fr.iter().zip(h.iter()).map(|(f, h)| Circle::new((*f, h.arg().to_degrees()), 2, style.filled()))).map_err(|e| err(&e))?;
            }
            mag.configure_series_labels().position(SeriesLabelPosition::LowerLeft).label_font((FONT, 14)).background_style(WHITE.mix(0.85)).border_style(BLACK).draw().map_err(|e| err(&e))?;
            let mut coh = ChartBuilder::on(&panels[2]).margin(8).x_label_area_size(40).y_label_area_size(80).build_cartesian_2d((f0..f1).log_scale(), 0.0..1.05).map_err(|e| err(&e))?;
            coh.configure_mesh().x_label_formatter(&log_tick).x_desc("frequency [Hz]").y_desc("coherence").label_style((FONT, 14)).axis_desc_style((FONT, 16)).light_line_style(RGBColor(235, 235, 235)).draw().map_err(|e| err(&e))?;
            coh.draw_series(LineSeries::new(f.iter().zip(&c.estimate.coherence).map(|(f, g)| (*f, *g)), COLORS[0].stroke_width(2))).map_err(|e| err(&e))?;
            let t = v.plan.coherence;
            coh.draw_series(LineSeries::new([(f0, t), (f1, t)], COLORS[1].stroke_width(1))).map_err(|e| err(&e))?;
        }
        root.present().map_err(|e| err(&e))
    }
}

/// The four files' paths for `prefix`: .csv, .time.csv, .svg, .png.
pub fn output_paths(prefix: &Path) -> [PathBuf; 4] {
    [prefixed_path(prefix, "csv"), prefixed_path(prefix, "time.csv"), prefixed_path(prefix, "svg"), prefixed_path(prefix, "png")]
}

/// Writes the four files (each atomically; inside [`crate::output::atomic::write_set`] as one
/// set). `t0`: the reference time [s].
pub fn write_files(v: &Validation, prefix: &Path, t0: f64) -> Result<[PathBuf; 4], OutputError> {
    let paths = output_paths(prefix);
    write_response_csv(v, &paths[0])?;
    write_time_csv(v, &paths[1], t0)?;
    let n = v.runs[0].channels.len().clamp(1, MAX_PLOTTED_CHANNELS) as u32;
    write_figure(&ValidationFigure(v), (500 * n + 200, 1000), &paths[2], &paths[3])?;
    Ok(paths)
}
