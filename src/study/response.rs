//! Frequency grids and responses of a study, and a ROM's accuracy on a grid.

use faer::{c64, Mat};

use crate::eigen::{ModalAnalysis, ModeKind};
use crate::linear::{hz, FrequencyResponse, Port};
use crate::rom::frequency_grid;

use super::{ReducedModel, Setting, Study, StudyError};

/// A log-spaced frequency grid [Hz]; missing ends default to a decade around the modes of
/// interest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrequencyGrid {
    pub fmin_hz: Option<f64>,
    pub fmax_hz: Option<f64>,
    pub points: usize,
}

impl Default for FrequencyGrid {
    fn default() -> Self {
        FrequencyGrid { fmin_hz: None, fmax_hz: None, points: 400 }
    }
}

/// How far a ROM's response is from the full model's on a frequency grid.
#[derive(Clone, Debug, PartialEq)]
pub struct GridAccuracy {
    pub fmin_hz: f64,
    pub fmax_hz: f64,
    pub points: usize,
    /// `max_f ‖H_rom(f) − H_full(f)‖_F / ‖H_full(f)‖_F`.
    pub largest_relative_error: f64,
    /// Where it occurs [Hz].
    pub at_hz: f64,
    /// The highest frequency [Hz] below which the relative error stays within 1 % (`None`:
    /// not even at the lowest).
    pub within_1_percent_up_to_hz: Option<f64>,
    /// The worst port pair on its own scale (the normwise figure above hides channels far
    /// below the largest, e.g. a vertical sensor's 1e-7 m/N next to a horizontal 1e-1 m/N).
    pub worst_channel: Option<ChannelError>,
}

/// One port pair's largest relative error `|H_rom − H_full|_ij / |H_full|_ij` over the grid
/// points where `|H_full|_ij` is above [`ChannelError::NEGLIGIBLE`] of that channel's largest.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelError {
    pub output: usize,
    pub input: usize,
    pub relative: f64,
    pub at_hz: f64,
}

impl ChannelError {
    /// Points where a channel is below this fraction of its own largest (a zero of the
    /// transfer function, or a channel zero to rounding) are not compared.
    pub const NEGLIGIBLE: f64 = 1e-6;
    /// Above this relative error a channel is reported as a warning: off by half its own
    /// size (a missing static part gives 0.9 and more; the truncation error of a 0-2 Hz ROM
    /// of examples/ham_sas.mbd with --residualize reaches 0.12 on its smallest cross pair,
    /// 1e-9 m/N, at 3.5 Hz, above its band).
    pub const WARN: f64 = 0.5;
}

/// A band around the modes of interest [Hz]: a decade below the lowest and above the
/// highest of `focus` (eigenvalues in rad/s), or of all dynamic modes when `focus` is empty.
pub fn default_band(modal: &ModalAnalysis, focus: &[c64]) -> (f64, f64) {
    let mut f: Vec<f64> = if focus.is_empty() { modal.of_kind(ModeKind::Dynamic).map(|i| modal.modes[i].freq_hz()).collect() } else { focus.iter().map(|l| hz(l.norm())).collect() };
    f.retain(|x| x.is_finite() && *x > 0.0);
    let lo = f.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = f.iter().copied().fold(0.0, f64::max);
    if lo.is_finite() && hi > 0.0 { (lo / 10.0, hi * 10.0) } else { (0.01, 100.0) }
}

/// A ROM's accuracy against the full model, on a response whose first reduced model is the
/// ROM ([`Study::compare`]).
impl FrequencyResponse {
    pub fn accuracy(&self) -> GridAccuracy {
        // A response without a ROM at some frequency has no accuracy there: NaN, never 0.
        let err: Vec<f64> = self.full.iter().enumerate().map(|(k, f)| self.rom().get(k).map_or(f64::NAN, |r| (r - f).norm_l2() / f.norm_l2().max(f64::MIN_POSITIVE))).collect();
        let (k, worst) = err.iter().enumerate().fold((0, 0.0f64), |(bk, bv), (k, &e)| if e > bv || e.is_nan() { (k, e) } else { (bk, bv) });
        let good = err.iter().take_while(|&&e| e <= 0.01).count();
        GridAccuracy {
            fmin_hz: self.freq_hz[0],
            fmax_hz: self.freq_hz[self.freq_hz.len() - 1],
            points: self.freq_hz.len(),
            largest_relative_error: worst,
            at_hz: self.freq_hz[k],
            within_1_percent_up_to_hz: good.checked_sub(1).map(|g| self.freq_hz[g]),
            worst_channel: self.worst_channel_up_to(f64::INFINITY, &|_, _| false),
        }
    }

    /// The worst port pair on its own scale over the grid points at or below `top_hz`, the
    /// pairs `(output, input)` for which `skip` holds left out. A pair the full model holds
    /// at zero against both its output's and its input's largest responses (below
    /// [`ChannelError::NEGLIGIBLE`] of the smaller: a coupling a symmetry removes, left as
    /// rounding, 7e-14 next to 1 in examples/ham_sas.mbd's transmissibility) has no scale of
    /// its own; the ROM's departure there is measured on that smaller scale, so a coupling
    /// the ROM invents is reported when it is comparable with the responses around it.
    pub(super) fn worst_channel_up_to(&self, top_hz: f64, skip: &dyn Fn(usize, usize) -> bool) -> Option<ChannelError> {
        let (no, ni) = (self.full.first()?.nrows(), self.full.first()?.ncols());
        let overall = self.full.iter().map(|f| f.norm_max()).fold(0.0, f64::max);
        let largest = |pick: &dyn Fn(&Mat<c64>) -> f64| self.full.iter().map(pick).fold(0.0, f64::max);
        let row: Vec<f64> = (0..no).map(|i| largest(&|f| (0..ni).map(|j| f[(i, j)].norm()).fold(0.0, f64::max))).collect();
        let col: Vec<f64> = (0..ni).map(|j| largest(&|f| (0..no).map(|i| f[(i, j)].norm()).fold(0.0, f64::max))).collect();
        let mut worst: Option<ChannelError> = None;
        let mut consider = |e: f64, i: usize, j: usize, at_hz: f64| {
            if worst.as_ref().is_none_or(|w| e > w.relative || e.is_nan()) {
                worst = Some(ChannelError { output: i, input: j, relative: e, at_hz });
            }
        };
        for i in 0..no {
            for j in 0..ni {
                if skip(i, j) {
                    continue;
                }
                let big = largest(&|f| f[(i, j)].norm());
                let around = row[i].min(col[j]);
                let points = self.full.iter().zip(self.rom()).enumerate().take_while(|(k, _)| self.freq_hz[*k] <= top_hz);
                if !(big > ChannelError::NEGLIGIBLE * around) && around > 1e-12 * overall {
                    for (k, (f, r)) in points {
                        consider((r[(i, j)] - f[(i, j)]).norm() / around, i, j, self.freq_hz[k]);
                    }
                    continue;
                }
                // Channels zero to rounding against the whole matrix have no scale of their own.
                if !(big > 1e-12 * overall) {
                    continue;
                }
                for (k, (f, r)) in points {
                    let h = f[(i, j)].norm();
                    if h <= ChannelError::NEGLIGIBLE * big {
                        continue;
                    }
                    consider((r[(i, j)] - f[(i, j)]).norm() / h, i, j, self.freq_hz[k]);
                }
            }
        }
        worst
    }
}

impl Study {
    /// The frequencies [Hz] of `grid`, defaults a decade below the lowest and above the
    /// highest of `focus` (eigenvalues in rad/s; all dynamic modes when empty). Refuses an
    /// empty or reversed grid, a non-positive end (log spacing) and fewer than 2 points.
    pub fn frequencies(&self, grid: &FrequencyGrid, focus: &[c64]) -> Result<Vec<f64>, StudyError> {
        let option = |option, message: String| Err(StudyError::Option { option, message });
        for (name, f) in [(Setting::Fmin, grid.fmin_hz), (Setting::Fmax, grid.fmax_hz)] {
            if let Some(f) = f {
                if !(f.is_finite() && f > 0.0) {
                    return option(name, format!("a frequency of a log-spaced grid must be positive and finite [Hz], got {f}"));
                }
                let (lo, hi) = crate::limits::FREQUENCY_RANGE_HZ;
                if !(lo..=hi).contains(&f) {
                    return option(name, format!("{} Hz is outside romdyn's frequency range, {lo:e} to {hi:e} Hz (beyond, the responses leave the range of doubles)", crate::limits::readable(f)));
                }
            }
        }
        if grid.points < 2 {
            return option(Setting::Points, format!("a frequency grid needs at least 2 points, got {}", grid.points));
        }
        let (lo, hi) = default_band(&self.modal, focus);
        let (a, b) = match (grid.fmin_hz, grid.fmax_hz) {
            (Some(a), Some(b)) => (a, b),
            (Some(a), None) => (a, hi.max(a * 1e3)),
            (None, Some(b)) => (lo.min(b / 1e3), b),
            (None, None) => (lo, hi),
        };
        if !(a < b) {
            return option(Setting::Fmin, format!("need FMIN < FMAX, got FMIN = {a} Hz, FMAX = {b} Hz"));
        }
        // The size budget (romdyn::limits::MAX_FREQUENCY_POINTS) is the grid's own check.
        frequency_grid(a, b, grid.points).map_err(|e| StudyError::Option { option: Setting::Points, message: e.to_string() })
    }

    /// The full model's frequency response `(C̃ + jω C̃_v)(jω F_yd + F_y)⁻¹ B̃` at `freq_hz`
    /// [Hz] (outputs × inputs): on the sparse route by a sparse LU at each frequency, the
    /// symbolic factorization computed once, each solve checked by its true residual.
    pub fn full_frequency_response(&self, freq_hz: &[f64]) -> Result<Vec<Mat<c64>>, StudyError> {
        Ok(self.linear.frequency_response(freq_hz, self.sparse.is_some())?)
    }

    /// The full model's response at `freq_hz`, to which ROMs can be added
    /// ([`FrequencyResponse::with_reduced`]).
    pub fn full_responses(&self, freq_hz: Vec<f64>) -> Result<FrequencyResponse, StudyError> {
        let h = self.full_frequency_response(&freq_hz)?;
        Ok(FrequencyResponse::new(freq_hz, Port::from_labels(self.input_names()), Port::from_labels(self.output_names()), h))
    }

    /// The full model's and `rom`'s responses at `freq_hz` (the ROM labelled "ROM").
    pub fn compare(&self, rom: &ReducedModel, freq_hz: Vec<f64>) -> Result<FrequencyResponse, StudyError> {
        let h = rom.ordinary.frequency_response(&freq_hz);
        Ok(self.full_responses(freq_hz)?.with_reduced("ROM", h))
    }
}
