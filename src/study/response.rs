//! Frequency grids and responses of a study, and a ROM's accuracy on a grid (computed by
//! `linear::accuracy` in the core, re-exported here).

use faer::{c64, Mat};

use crate::eigen::{ModalAnalysis, ModeKind};
use crate::linear::{hz, FrequencyResponse, Port};
// A ROM's accuracy on a grid is computed in the core, beside the response it reads.
pub use crate::linear::{ChannelError, GridAccuracy};
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

/// A band around the modes of interest [Hz]: a decade below the lowest and above the
/// highest of `focus` (eigenvalues in rad/s), or of all dynamic modes when `focus` is empty.
pub fn default_band(modal: &ModalAnalysis, focus: &[c64]) -> (f64, f64) {
    let mut f: Vec<f64> = if focus.is_empty() { modal.of_kind(ModeKind::Dynamic).map(|i| modal.modes[i].freq_hz()).collect() } else { focus.iter().map(|l| hz(l.norm())).collect() };
    f.retain(|x| x.is_finite() && *x > 0.0);
    let lo = f.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = f.iter().copied().fold(0.0, f64::max);
    if lo.is_finite() && hi > 0.0 { (lo / 10.0, hi * 10.0) } else { (0.01, 100.0) }
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
