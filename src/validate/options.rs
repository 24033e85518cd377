//! The settings of a validation ([`ValidateOptions`], checked here so every front end refuses
//! the same things the same way) and what they become for one ROM ([`Plan`]: band, step,
//! Welch segments, amplitudes), with defaults from the ROM's kept modes and static gain.

use std::f64::consts::PI;
use std::path::PathBuf;

use crate::dae::ports::OutputPort;
use crate::study::{ReducedModel, Setting, Study};

use super::signal::{SignalKind, SignalSpec};
use super::ValidateError;
use crate::linear::{hz, rad_per_s};

/// Samples per period of the band's top frequency: the input's linear interpolation then
/// lowers |H| by `(π f dt)²/3 ≤ 0.05 %` there.
pub const SAMPLES_PER_PERIOD: f64 = 80.0;
/// The integrator's relative period error per `(ω h)²`: about 0.1 for MBDyn's ms with
/// ρ∞ = 0.6 (measured on a 1.125 Hz, ζ = 0.035 oscillator: 0.43 % at its peak with
/// ω h = 0.0396, and a peak error is the period error over ζ; h² with the step).
pub const PERIOD_ERROR: f64 = 0.1;
/// A damped kept mode's peak error the step may cause: the period error over ζ (above).
pub const PEAK_ERROR: f64 = 5e-3;
/// An undamped kept mode's phase drift [rad] the step may cause over the compared record: the
/// time-domain fit falls by about the drift's RMS, `0.3/√3 ≈ 0.17`, a third of what the
/// default fit threshold 0.5 allows (the README beam's fit fell to 0.47 with 64 averages at
/// the band's step, 17 s of ringing at 49 Hz: 0.8 rad of drift; issue 33).
pub const PHASE_DRIFT: f64 = 0.3;
/// Welch bins per lowest kept natural frequency (frequency resolution `f₁/20`).
pub const BINS_BELOW_FIRST_MODE: f64 = 20.0;
/// Welch bins per half-power bandwidth of the most lightly damped kept mode.
pub const BINS_PER_BANDWIDTH: f64 = 8.0;
/// Modes damped less than this (ζ) are treated as undamped by the resolution rule.
pub const MIN_DAMPING: f64 = 1e-3;
/// Bins of Hann's window the random input extends beyond the compared band: its spectrum
/// ends inside the window's reach of the top bins otherwise, and their estimate leans to the
/// excited side (1.6 % at the top bin of the README beam, 100 Hz, where |H| changes 2.7 % per
/// Hz; issue 33).
pub const EXCITED_BEYOND: f64 = 4.0;
/// Default static response of a displacement output: this fraction of the model's size (an
/// undamped mode's ringing grows the dynamic response some ten times above it, and at 1e-3
/// the README beam's fit already fell from 0.95 to 0.71 by the model's nonlinearity).
pub const STATIC_FRACTION: f64 = 1e-4;

/// How a ROM is validated. Every field has a default ([`ValidateOptions::default`]).
#[derive(Clone, Debug)]
pub struct ValidateOptions {
    pub signal: SignalKind,
    /// RMS values of each input [N or N m], one validation per value (the linearity range);
    /// empty: one, chosen so the static response is [`STATIC_FRACTION`] of the model's size.
    pub amplitudes: Vec<f64>,
    /// Excited and compared band [Hz] (default: 0 to twice the ROM's top frequency of interest).
    pub band_hz: Option<(f64, f64)>,
    /// Welch frequency resolution [Hz] (default, from the kept modes the ports see: the lowest
    /// one's frequency / 20, or an eighth of the narrowest damped one's half-power bandwidth if
    /// finer, down to 1/8 of the former).
    pub resolution_hz: Option<f64>,
    /// Length of the run in Welch segments: `(averages + 2)/2` of them; as many half-overlapping
    /// segments, which the random input's estimate averages as Hann segments overlapping by
    /// three quarters.
    pub averages: usize,
    /// Integration step and sampling period [s] (default: 1/(80 × the band's top), smaller
    /// if a kept mode needs it: [`Plan::new`]).
    pub time_step: Option<f64>,
    pub seed: u64,
    /// Bins with coherence at or above this are compared.
    pub coherence: f64,
    /// Largest relative error |H_ROM − H1|/|H1| the verdict accepts.
    pub tolerance: f64,
    /// Smallest time-domain fit (NRMSE, 1 = perfect) the verdict accepts.
    pub fit: f64,
    /// A measured frequency response to compare with ([`super::read_measured`]).
    pub measured: Option<PathBuf>,
}

impl Default for ValidateOptions {
    fn default() -> Self {
        ValidateOptions { signal: SignalKind::Random, amplitudes: Vec::new(), band_hz: None, resolution_hz: None, averages: 8, time_step: None, seed: 1, coherence: 0.95, tolerance: 0.1, fit: 0.5, measured: None }
    }
}

fn positive(option: Setting, v: Option<f64>, what: &str) -> Result<(), ValidateError> {
    match v {
        Some(x) if !(x > 0.0 && x.is_finite()) => Err(ValidateError::Option { option, message: format!("{what} must be positive and finite, got {x}") }),
        _ => Ok(()),
    }
}

impl ValidateOptions {
    /// Refuses settings out of range, naming the option.
    pub fn check(&self) -> Result<(), ValidateError> {
        for a in &self.amplitudes {
            positive(Setting::Amplitudes, Some(*a), "an RMS input amplitude [N or N m]")?;
        }
        if let Some((lo, hi)) = self.band_hz {
            if !(lo >= 0.0 && hi > lo && hi.is_finite()) {
                return Err(ValidateError::Option { option: Setting::ValidationBand, message: format!("need 0 <= FMIN < FMAX [Hz], got {lo}:{hi}") });
            }
        }
        positive(Setting::Resolution, self.resolution_hz, "the frequency resolution [Hz]")?;
        positive(Setting::TimeStep, self.time_step, "the time step [s]")?;
        if self.averages < 2 || self.averages > 1000 {
            return Err(ValidateError::Option { option: Setting::Averages, message: format!("need 2 to 1000 Welch segments (coherence is 1 with one), got {}", self.averages) });
        }
        let unit = |option, v: f64, what| if (0.0..=1.0).contains(&v) { Ok(()) } else { Err(ValidateError::Option { option, message: format!("{what} must be in [0, 1], got {v}") }) };
        unit(Setting::Coherence, self.coherence, "the coherence threshold")?;
        unit(Setting::Fit, self.fit, "the NRMSE fit threshold")?;
        positive(Setting::Tolerance, Some(self.tolerance), "the relative error tolerance")
    }
}

/// What the options become for one ROM.
#[derive(Clone, Debug)]
pub struct Plan {
    pub kind: SignalKind,
    pub band_hz: (f64, f64),
    /// Integration step = sampling period [s].
    pub dt: f64,
    /// Samples per Welch segment (a power of two).
    pub segment: usize,
    /// Samples of each run (the first at the reference).
    pub samples: usize,
    /// Samples before the estimate starts (the fade-in and the start's transient).
    pub lead_in: usize,
    /// What set the step (the band, a mode's peak error or phase drift).
    pub step_rule: String,
    /// Kept modes that the ports see with ζ < [`MIN_DAMPING`], in the band [Hz]: the estimate
    /// near them is limited by leakage (low coherence, not compared).
    pub undamped_hz: Vec<f64>,
    /// Per amplitude level, the RMS of each input [N or N m].
    pub amplitudes: Vec<Vec<f64>>,
    pub seed: u64,
    pub coherence: f64,
    pub tolerance: f64,
    pub fit: f64,
}

/// Most samples of one run: 2²⁴ steps would take hours.
const MAX_SAMPLES: usize = 1 << 24;

impl Plan {
    /// The plan of `o` for `rom`. Band, resolution and step come from the kept modes the
    /// ports see (dominance above [`crate::rom::NEGLIGIBLE_DOMINANCE`]; a kept mode that
    /// contributes nothing to them has no response to resolve). Step: the band's
    /// [`SAMPLES_PER_PERIOD`], or smaller so that the integrator's period error
    /// `PERIOD_ERROR (ω h)²` stays within [`PEAK_ERROR`] ζ of a damped kept mode, and turns an
    /// undamped one's phase by at most [`PHASE_DRIFT`] over a segment.
    pub fn new(study: &Study, rom: &ReducedModel, outputs: &[OutputPort], o: &ValidateOptions) -> Result<Self, ValidateError> {
        o.check()?;
        let seen: Vec<_> = rom.kept_modes.iter().filter(|m| m.dominance > crate::rom::NEGLIGIBLE_DOMINANCE && m.lambda.norm() > 0.0).collect();
        let hz = |m: &crate::study::KeptMode| hz(m.lambda.norm());
        let zeta = |m: &crate::study::KeptMode| -m.lambda.re / m.lambda.norm();
        let band_hz = match o.band_hz {
            Some(b) => b,
            None if rom.interest_top_hz > 0.0 => (0.0, 2.0 * rom.interest_top_hz),
            None => return Err(ValidateError::Option { option: Setting::ValidationBand, message: "the ROM keeps no oscillating mode to take the band from: give FMIN:FMAX [Hz]".into() }),
        };
        let lowest = seen.iter().map(|m| hz(m)).fold(band_hz.1, f64::min);
        // A damped kept mode's half-power bandwidth `B_r = |Re λ|/π` [Hz] over 8: Hann's
        // resolution bias at its peak, about (1/3)(1.5 Δf/B_r)² (Bendat and Piersol §9.2.3),
        // stays near 1 %. Modes with ζ < 1e-3 (undamped) leave it to the frequency rule.
        let bandwidth = seen.iter().filter(|m| zeta(m) > MIN_DAMPING).map(|m| -m.lambda.re / PI).fold(f64::INFINITY, f64::min);
        // At most 8 times finer than the frequency rule: a run at most 8 times longer.
        let by_frequency = lowest / BINS_BELOW_FIRST_MODE;
        let resolution = o.resolution_hz.unwrap_or(by_frequency.min(bandwidth / BINS_PER_BANDWIDTH).max(by_frequency / 8.0));
        let segment_of = |dt: f64| ((1.0 / (resolution * dt)).ceil().max(64.0) as usize).next_power_of_two();
        let record = |dt: f64| (o.averages + 1) as f64 * (segment_of(dt) / 2) as f64 * dt;
        let (dt, step_rule) = match o.time_step {
            Some(dt) => (dt, Setting::TimeStep.to_string()),
            // The record's length depends on the step through the segment's power of two:
            // from the shortest it can be, until the step no longer shortens it.
            None => {
                let mut rule = step(&seen, band_hz, (o.averages + 1) as f64 / (2.0 * resolution));
                for _ in 0..4 {
                    let next = step(&seen, band_hz, record(rule.0));
                    if next.0 >= rule.0 {
                        break;
                    }
                    rule = next;
                }
                rule
            }
        };
        let segment = segment_of(dt);
        let lead_in = segment / 2;
        let samples = lead_in + (o.averages + 1) * segment / 2;
        if segment > MAX_SAMPLES || samples > MAX_SAMPLES {
            return Err(ValidateError::Option { option: Setting::Resolution, message: format!("{samples} steps of {dt:.3e} s for a resolution of {resolution:.3e} Hz: more than {MAX_SAMPLES}; a coarser --resolution, fewer --averages or a larger --time-step") });
        }
        if 1.0 / (2.0 * dt) <= band_hz.1 {
            return Err(ValidateError::Option { option: Setting::TimeStep, message: format!("{dt} s samples up to {:.4} Hz only, below the band's top {} Hz", 0.5 / dt, band_hz.1) });
        }
        let undamped_hz = seen.iter().filter(|m| zeta(m) < MIN_DAMPING).map(|m| hz(m)).filter(|f| (band_hz.0..=band_hz.1).contains(f)).collect();
        let amplitudes = if o.amplitudes.is_empty() { vec![default_amplitudes(study, rom, outputs)?] } else { o.amplitudes.iter().map(|a| vec![*a; rom.ordinary.b.ncols()]).collect() };
        Ok(Plan { kind: o.signal, band_hz, dt, segment, samples, lead_in, step_rule, undamped_hz, amplitudes, seed: o.seed, coherence: o.coherence, tolerance: o.tolerance, fit: o.fit })
    }

    /// The signal of input `j` at RMS `rms`.
    pub fn signal(&self, j: usize, rms: f64) -> SignalSpec {
        // The random input reaches [`EXCITED_BEYOND`] bins past the compared band; the
        // multisine and the chirp have lines on the bins, no leakage to cover.
        let band_hz = match self.kind {
            SignalKind::Random => {
                let beyond = EXCITED_BEYOND / (self.segment as f64 * self.dt);
                ((self.band_hz.0 - beyond).max(0.0), (self.band_hz.1 + beyond).min(0.25 / self.dt))
            }
            SignalKind::Multisine | SignalKind::Chirp => self.band_hz,
        };
        SignalSpec { kind: self.kind, samples: self.samples, dt: self.dt, band_hz, rms, fade: self.lead_in / 2, segment: self.segment, seed: self.seed.wrapping_add(j as u64) }
    }
}

/// The default step [s] and what set it: the band's top sampled [`SAMPLES_PER_PERIOD`] times
/// a period, or a kept mode (frequency ω, damping ζ) whose period error `D = PERIOD_ERROR
/// (ω h)²` must stay within `PEAK_ERROR ζ` (damped: its peak error `D/ζ`) or turn its ringing
/// by at most `PHASE_DRIFT` over the compared record of `horizon` seconds (undamped:
/// `ω D horizon`).
fn step(seen: &[&crate::study::KeptMode], band_hz: (f64, f64), horizon: f64) -> (f64, String) {
    let mut best = (1.0 / (SAMPLES_PER_PERIOD * band_hz.1), format!("{SAMPLES_PER_PERIOD} samples per period of the band's top"));
    for m in seen {
        let w = m.lambda.norm();
        let zeta = -m.lambda.re / w;
        let (allowed, why) = if zeta >= MIN_DAMPING { (PEAK_ERROR * zeta, "peak error") } else { (PHASE_DRIFT / (w * horizon), "phase drift over the record") };
        let h = (allowed / PERIOD_ERROR).sqrt() / w;
        if h < best.0 {
            best = (h, format!("the integrator's {why} at the kept mode of {:.4} Hz (damping {zeta:.2e})", hz(w)));
        }
    }
    best
}

/// Per input, the RMS whose static response (the ROM's static gain) is at most
/// [`STATIC_FRACTION`] of the model's size on a displacement output, that fraction of a
/// radian on a rotation, and for rates that times 2π × the band's top.
fn default_amplitudes(study: &Study, rom: &ReducedModel, outputs: &[OutputPort]) -> Result<Vec<f64>, ValidateError> {
    let size = study.model().map_or(1.0, |m| {
        let n = m.nodes.len().max(1) as f64;
        let centre = m.nodes.iter().fold(crate::kinematics::Vec3::zeros(), |a, n| a + n.position) / n;
        2.0 * m.nodes.iter().map(|n| (n.position - centre).norm()).fold(0.0, f64::max)
    });
    let size = if size > 0.0 { size } else { 1.0 };
    let gain = rom.ordinary.static_gain().map_err(|e| ValidateError::Option { option: Setting::Amplitudes, message: format!("the ROM has no static gain to size the input by ({e}): give the inputs' RMS [N or N m]") })?;
    (0..gain.ncols()).map(|j| {
        let scale = |i: usize| match outputs[i].unit() {
            "m" => STATIC_FRACTION * size,
            "rad" => STATIC_FRACTION,
            "m/s" => STATIC_FRACTION * size * rad_per_s(rom.interest_top_hz),
            _ => STATIC_FRACTION * rad_per_s(rom.interest_top_hz),
        };
        let a = (0..gain.nrows()).map(|i| scale(i) / gain[(i, j)].abs()).fold(f64::INFINITY, f64::min);
        if a.is_finite() && a > 0.0 {
            Ok(a)
        } else {
            Err(ValidateError::Option { option: Setting::Amplitudes, message: format!("input {} has no static response at the outputs to size it by: give the inputs' RMS [N or N m]", j + 1) })
        }
    }).collect()
}
