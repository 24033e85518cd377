//! A ROM's accuracy against the full model on a frequency grid: the normwise relative error
//! at each frequency and the worst port pair on its own scale.

use faer::{c64, Mat};

use super::FrequencyResponse;

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

/// A ROM's accuracy against the full model, on a response whose first reduced model is the
/// ROM (`romdyn::study::Study::compare`).
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
    pub fn worst_channel_up_to(&self, top_hz: f64, skip: &dyn Fn(usize, usize) -> bool) -> Option<ChannelError> {
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

