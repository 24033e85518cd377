//! Estimate, full linear model and ROM compared on the estimate's bins, the time-domain fit,
//! the verdict and the linearity limit.

use std::sync::Arc;

use faer::{c64, Mat};

use crate::study::{ReducedModel, Setting, Study};

use super::measured::MeasuredResponse;
use super::welch::{h1, magnitude_random_error, Estimate, Window};
use super::{Plan, ValidateError};

/// MATLAB's `compare` fit, `1 − ‖y − ŷ‖ / ‖y − mean(y)‖` (System Identification Toolbox,
/// "NRMSE"): 1 is a perfect fit, 0 no better than the mean, negative worse.
pub fn nrmse(y: &[f64], y_hat: &[f64]) -> f64 {
    let mean = y.iter().sum::<f64>() / y.len().max(1) as f64;
    let err: f64 = y.iter().zip(y_hat).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt();
    let spread: f64 = y.iter().map(|a| (a - mean).powi(2)).sum::<f64>().sqrt();
    if spread > 0.0 { 1.0 - err / spread } else if err == 0.0 { 1.0 } else { f64::NEG_INFINITY }
}

/// Relative output RMS below which a channel is not excited ([`AmplitudeRun::represents`]).
pub const SILENT: f64 = 1e-6;

/// One input/output pair at one amplitude.
#[derive(Clone, Debug)]
pub struct Channel {
    pub input: String,
    pub output: String,
    /// H1 of the nonlinear run, with coherence, on the compared bins.
    pub estimate: Estimate,
    pub full: Vec<c64>,
    pub rom: Vec<c64>,
    /// Largest `|H_ROM − H1|/|H1|` where the coherence is at least the threshold, and its
    /// frequency [Hz] (`None`: no such bin).
    pub rom_error: Option<(f64, f64)>,
    /// The same for the full linear model.
    pub full_error: Option<(f64, f64)>,
    /// Time-domain fit of the ROM to the nonlinear run (NRMSE, 1 = perfect) after the lead-in.
    pub fit: f64,
    /// RMS of the nonlinear output's change from the reference over the compared samples
    /// (the amplitude the linearity limit is about), in the output's unit.
    pub output_rms: f64,
    /// The ROM's, likewise.
    pub rom_rms: f64,
}

impl Channel {
    /// Whether the ROM describes this pair: its error within the tolerance and its fit above
    /// the threshold.
    /// A bin passes when its error is within the tolerance plus twice the estimate's random
    /// error there ([`magnitude_random_error`]: the estimate, not the ROM, is that uncertain).
    /// `silent`: the output's RMS below which a channel is taken as not excited (a pair the
    /// model does not couple): it passes when the ROM's output is as silent.
    pub fn represents(&self, plan: &Plan, silent: f64) -> bool {
        if self.output_rms <= silent {
            return self.rom_rms <= silent;
        }
        let e = &self.estimate;
        let coherent: Vec<usize> = (0..self.rom.len()).filter(|&k| e.coherence[k] >= plan.coherence).collect();
        let within = |k: &usize| (self.rom[*k] - e.h[*k]).norm() / e.h[*k].norm() <= plan.tolerance + 2.0 * magnitude_random_error(e.coherence[*k], e.independent);
        !coherent.is_empty() && coherent.iter().all(within) && self.fit >= plan.fit
    }
}

/// One input's run in time: samples at the plan's step from the reference time.
#[derive(Clone, Debug)]
pub struct TimeRecord {
    pub input: String,
    pub u: Arc<Vec<f64>>,
    /// Per output, the nonlinear model's change from the reference.
    pub nonlinear: Vec<Vec<f64>>,
    /// Per output, the ROM's.
    pub rom: Vec<Vec<f64>>,
}

/// The validation at one amplitude.
#[derive(Clone, Debug)]
pub struct AmplitudeRun {
    /// RMS of each input [N or N m].
    pub amplitude: Vec<f64>,
    /// Channels, output-major within each input: `channels[j * outputs + i]`.
    pub channels: Vec<Channel>,
    pub time: Vec<TimeRecord>,
}

/// Largest relative error of `model` against `estimate` where coherence ≥ `threshold`.
fn worst_error(estimate: &Estimate, model: &[c64], threshold: f64) -> Option<(f64, f64)> {
    (0..model.len()).filter(|&k| estimate.coherence[k] >= threshold).map(|k| ((model[k] - estimate.h[k]).norm() / estimate.h[k].norm(), estimate.freq_hz[k])).max_by(|a, b| a.0.total_cmp(&b.0))
}

impl AmplitudeRun {
    /// `series`: per input, its signal, the nonlinear outputs and the ROM's (samples × outputs).
    pub(super) fn new(study: &Study, rom: &ReducedModel, plan: &Plan, amplitude: Vec<f64>, series: Vec<(Arc<Vec<f64>>, Vec<Vec<f64>>, Mat<f64>)>) -> Result<Self, ValidateError> {
        let (ins, outs) = (study.input_names(), study.output_names());
        let lead = plan.lead_in;
        let mut channels = Vec::new();
        let mut time = Vec::new();
        let mut grid: Option<(Vec<Mat<c64>>, Vec<Mat<c64>>)> = None;
        for (j, (u, y, z)) in series.into_iter().enumerate() {
            let rom_y: Vec<Vec<f64>> = (0..z.ncols()).map(|i| (0..z.nrows()).map(|k| z[(k, i)]).collect()).collect();
            for (i, yi) in y.iter().enumerate() {
                let estimate = h1(&u[lead..], &yi[lead..], plan.dt, plan.segment, plan.band_hz, window_for(plan.kind));
                if grid.is_none() {
                    grid = Some((study.full_frequency_response(&estimate.freq_hz)?, rom.ordinary.frequency_response(&estimate.freq_hz)));
                }
                let (full, romh) = grid.as_ref().map(|(f, r)| (f.iter().map(|m| m[(i, j)]).collect::<Vec<_>>(), r.iter().map(|m| m[(i, j)]).collect::<Vec<_>>())).unwrap_or_default();
                let fit = nrmse(&yi[lead..], &rom_y[i][lead..]);
                let rms = |y: &[f64]| (y.iter().map(|v| v * v).sum::<f64>() / y.len().max(1) as f64).sqrt();
                let (output_rms, rom_rms) = (rms(&yi[lead..]), rms(&rom_y[i][lead..]));
                channels.push(Channel { input: ins[j].clone(), output: outs[i].clone(), rom_error: worst_error(&estimate, &romh, plan.coherence), full_error: worst_error(&estimate, &full, plan.coherence), estimate, full, rom: romh, fit, output_rms, rom_rms });
            }
            time.push(TimeRecord { input: ins[j].clone(), u, nonlinear: y, rom: rom_y });
        }
        Ok(AmplitudeRun { amplitude, channels, time })
    }

    /// Every channel is described; a channel whose output RMS is below [`SILENT`] times the
    /// run's largest of the same unit counts as not excited.
    pub fn represents(&self, plan: &Plan) -> bool {
        self.channels.iter().all(|c| c.represents(plan, self.silent(c)))
    }

    fn silent(&self, c: &Channel) -> f64 {
        let unit = |s: &str| crate::linear::Port::from_label(s).unit;
        SILENT * self.channels.iter().filter(|d| unit(&d.output) == unit(&c.output)).map(|d| d.output_rms.max(d.rom_rms)).fold(0.0, f64::max)
    }
}

/// A measured channel against the full model and the ROM at the measured frequencies.
#[derive(Clone, Debug)]
pub struct MeasuredComparison {
    pub name: String,
    pub freq_hz: Vec<f64>,
    pub measured: Vec<c64>,
    pub full: Vec<c64>,
    pub rom: Vec<c64>,
    /// Largest `|H − H_measured| / |H_measured|` of the full model and of the ROM.
    pub full_error: f64,
    pub rom_error: f64,
}

/// Everything a validation found.
#[derive(Clone, Debug)]
pub struct Validation {
    pub plan: Plan,
    pub runs: Vec<AmplitudeRun>,
    pub measured: Vec<MeasuredComparison>,
    /// The ROM describes the nonlinear model at the smallest amplitude.
    pub represents: bool,
    /// With several amplitudes: the largest input RMS (the first input's) up to which every
    /// amplitude is described, and the first that is not (`None`: all are).
    pub linearity_limit: Option<(Option<f64>, f64)>,
}

/// The estimator's window for an input: none where the input is periodic in the segment
/// ([`Window::Rectangular`]).
fn window_for(kind: super::signal::SignalKind) -> Window {
    match kind {
        super::signal::SignalKind::Random => Window::Hann,
        super::signal::SignalKind::Multisine | super::signal::SignalKind::Chirp => Window::Rectangular,
    }
}

fn relative_error(model: &[c64], data: &[c64]) -> f64 {
    model.iter().zip(data).map(|(m, d)| (m - d).norm() / d.norm()).fold(0.0, f64::max)
}

impl Validation {
    pub(super) fn new(study: &Study, rom: &ReducedModel, plan: Plan, mut runs: Vec<AmplitudeRun>, measured: Option<MeasuredResponse>) -> Result<Self, ValidateError> {
        runs.sort_by(|a, b| a.amplitude[0].total_cmp(&b.amplitude[0]));
        let represents = runs.first().is_some_and(|r| r.represents(&plan));
        let linearity_limit = (runs.len() > 1).then(|| {
            let first_bad = runs.iter().position(|r| !r.represents(&plan));
            first_bad.map(|k| (k.checked_sub(1).map(|g| runs[g].amplitude[0]), runs[k].amplitude[0]))
        }).flatten();
        let mut compared = Vec::new();
        if let Some(m) = measured {
            let full = study.full_frequency_response(&m.freq_hz)?;
            let romh = rom.ordinary.frequency_response(&m.freq_hz);
            for ch in &m.channels {
                let (i, j) = (ch.output, ch.input);
                if i >= study.output_names().len() || j >= study.input_names().len() {
                    return Err(ValidateError::Option { option: Setting::Measured, message: format!("{}: channel {} names output {} and input {}, the ROM has {} outputs and {} inputs", m.path.display(), ch.name, i + 1, j + 1, study.output_names().len(), study.input_names().len()) });
                }
                let f: Vec<c64> = full.iter().map(|h| h[(i, j)]).collect();
                let r: Vec<c64> = romh.iter().map(|h| h[(i, j)]).collect();
                compared.push(MeasuredComparison { name: ch.name.clone(), freq_hz: m.freq_hz.clone(), full_error: relative_error(&f, &ch.values), rom_error: relative_error(&r, &ch.values), measured: ch.values.clone(), full: f, rom: r });
            }
        }
        Ok(Validation { plan, runs, measured: compared, represents, linearity_limit })
    }

    /// The printed summary: per channel the largest ROM-vs-estimate error where coherence is
    /// high, the time-domain fit, then the verdict line.
    pub fn summary(&self) -> String {
        let p = &self.plan;
        let mut s = format!(
            "validation: {:?} input in {:.4}..{:.4} Hz, step {:.4e} s ({}), {} samples ({:.4} s), Welch segments of {} samples ({:.4} Hz bins), coherence >= {}\n",
            p.kind, p.band_hz.0, p.band_hz.1, p.dt, p.step_rule, p.samples, p.dt * (p.samples - 1) as f64, p.segment, 1.0 / (p.segment as f64 * p.dt), p.coherence
        );
        if !p.undamped_hz.is_empty() {
            let f: Vec<String> = p.undamped_hz.iter().map(|f| format!("{f:.4}")).collect();
            s += &format!("undamped kept mode(s) at {} Hz: the response to each segment's input rings beyond it, so near them the estimate is limited by leakage, not by the model (its coherence falls and those bins are not compared; where compared, its random error, sqrt((1 - g2)/(2 g2 n_d)) at coherence g2, is allowed for); more --averages narrow that region\n", f.join(", "));
        }
        for run in &self.runs {
            let rms: Vec<String> = run.amplitude.iter().map(|a| format!("{a:.4e}")).collect();
            s += &format!("input RMS {}: ROM {} the nonlinear model\n", rms.join(", "), if run.represents(p) { "describes" } else { "does NOT describe" });
            for c in &run.channels {
                let err = |e: Option<(f64, f64)>| e.map_or("no bin above the coherence threshold".to_string(), |(e, f)| format!("{:.3} % at {f:.4} Hz", 100.0 * e));
                let high = c.estimate.coherence.iter().filter(|g| **g >= p.coherence).count();
                s += &format!("  {} / {}: ROM vs estimate {}; full model vs estimate {}; fit (NRMSE) {:.4}; output RMS {:.4e}; {high} of {} bins coherent\n", c.output, c.input, err(c.rom_error), err(c.full_error), c.fit, c.output_rms, c.estimate.freq_hz.len());
            }
        }
        for m in &self.measured {
            s += &format!("measured {}: full model within {:.3} %, ROM within {:.3} % ({} frequencies)\n", m.name, 100.0 * m.full_error, 100.0 * m.rom_error, m.freq_hz.len());
        }
        if let Some((good, bad)) = self.linearity_limit {
            s += &match good {
                Some(g) => format!("linearity limit: the ROM describes the model up to input RMS {g:.4e}, not at {bad:.4e}\n"),
                None => format!("linearity limit: below the smallest input RMS {bad:.4e}\n"),
            };
        } else if self.runs.len() > 1 {
            s += "linearity limit: not reached (the ROM describes the model at every amplitude)\n";
        }
        s += &self.verdict();
        s.push('\n');
        s
    }

    /// The warning every front end gives when the ROM does not represent the model (the
    /// CLI prints it, Python raises it as an `AccuracyWarning`).
    pub fn warning(&self) -> Option<&'static str> {
        if self.unjudged().is_some() {
            return Some("the estimate has no bin above the coherence threshold in a channel, so the ROM could not be judged there: more --averages, --signal random on an undamped structure, or a lower --coherence");
        }
        (!self.represents).then_some("the ROM does not represent the nonlinear model in the band: more modes, --residualize, or a smaller amplitude")
    }

    /// The first channel of the smallest amplitude that the output responds to and whose
    /// estimate has no bin with coherence at the threshold: nothing to judge the ROM by (a
    /// multisine on an undamped structure: the fade-in's ringing never decays and leaks into
    /// every bin without a window; the README beam had none of 51 bins coherent).
    fn unjudged(&self) -> Option<&Channel> {
        let run = self.runs.first()?;
        run.channels.iter().find(|c| c.rom_error.is_none() && c.output_rms > run.silent(c))
    }

    /// The verdict line.
    pub fn verdict(&self) -> String {
        let p = &self.plan;
        if let Some(c) = self.unjudged() {
            format!("verdict: the ROM's fidelity is NOT KNOWN: {} / {} has no bin with coherence >= {} (the estimate is not trustworthy anywhere in {:.4}..{:.4} Hz); not a departure of the ROM", c.output, c.input, p.coherence, p.band_hz.0, p.band_hz.1)
        } else if self.represents {
            format!("verdict: the ROM represents the nonlinear model in {:.4}..{:.4} Hz (error <= {} % plus twice the estimate's random error where coherence >= {}, fit >= {})", p.band_hz.0, p.band_hz.1, 100.0 * p.tolerance, p.coherence, p.fit)
        } else {
            format!("verdict: the ROM does NOT represent the nonlinear model in {:.4}..{:.4} Hz (needs error <= {} % plus twice the estimate's random error where coherence >= {}, and fit >= {}): see the channels above", p.band_hz.0, p.band_hz.1, 100.0 * p.tolerance, p.coherence, p.fit)
        }
    }
}
