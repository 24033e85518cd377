//! Frequency grids and responses of a study.

use faer::c64;

use crate::output::frequency_plot::{default_band, FrequencyResponses};
use crate::rom::log_frequencies;

use super::{Study, StudyError};

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

impl Study {
    /// The frequencies [Hz] of `grid`, defaults a decade below the lowest and above the
    /// highest of `focus` (eigenvalues in rad/s; all dynamic modes when empty).
    pub fn frequencies(&self, grid: &FrequencyGrid, focus: &[c64]) -> Result<Vec<f64>, StudyError> {
        let (lo, hi) = default_band(&self.modal, focus);
        Ok(log_frequencies(grid.fmin_hz.unwrap_or(lo), grid.fmax_hz.unwrap_or(hi), grid.points.max(2)))
    }

    /// The full model's responses at `freq_hz`, to which ROMs can be added.
    pub fn full_responses(&self, freq_hz: Vec<f64>) -> FrequencyResponses {
        FrequencyResponses::full(&self.dae, freq_hz)
    }
}
