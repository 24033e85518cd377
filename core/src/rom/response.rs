//! Frequency responses and static gains of the full linear DAE (paper §7, eq. 40).

use faer::{c64, Mat};

use super::dense::{solve_or_free_direction, transfer_with_rates};
use super::RomError;
use crate::linear::LinearDae;
use crate::linear::rad_per_s;

/// `n` frequencies [Hz] spaced logarithmically from `fmin` to `fmax` (inclusive).
pub fn log_frequencies(fmin_hz: f64, fmax_hz: f64, n: usize) -> Vec<f64> {
    if n < 2 {
        return vec![fmin_hz];
    }
    let (a, b) = (fmin_hz.ln(), fmax_hz.ln());
    (0..n).map(|k| (a + (b - a) * k as f64 / (n - 1) as f64).exp()).collect()
}

/// [`log_frequencies`] after checking the grid: `0 < fmin < fmax` finite and
/// `2 ≤ n ≤` [`MAX_FREQUENCY_POINTS`](crate::limits::MAX_FREQUENCY_POINTS) (each point
/// holds an outputs × inputs response of the full model and of each ROM).
pub fn frequency_grid(fmin_hz: f64, fmax_hz: f64, n: usize) -> Result<Vec<f64>, RomError> {
    let max = crate::limits::MAX_FREQUENCY_POINTS;
    if !(n >= 2 && n <= max) {
        return Err(RomError::Grid(format!("{n} points: a frequency grid has 2 to {max} points")));
    }
    if !(fmin_hz > 0.0 && fmin_hz < fmax_hz && fmax_hz.is_finite()) {
        return Err(RomError::Grid(format!("from {fmin_hz} Hz to {fmax_hz} Hz: the band must satisfy 0 < fmin < fmax (finite)")));
    }
    Ok(log_frequencies(fmin_hz, fmax_hz, n))
}

/// `z/u = (C̃ + jω C̃_v) (jω F_yd + F_y)⁻¹ B̃` at each frequency [Hz] (outputs × inputs),
/// with `F_yd`, `F_y` in the form of eq. 29 ([`LinearDae::plain_derivatives`]), so that f = 0
/// gives the static gain.
pub fn full_frequency_response(dae: &LinearDae, freq_hz: &[f64]) -> Vec<Mat<c64>> {
    let (fyd, fy) = dae.plain_derivatives();
    freq_hz.iter().map(|f| transfer_with_rates(rad_per_s(*f), &fyd, &fy, &dae.b, &dae.c, dae.c_rate.as_ref(), None)).collect()
}

/// Static gain `C̃ S⁻¹ B̃` with `S` = [`LinearDae::static_matrix`] (`F_y`, with the
/// constraint rows and multiplier columns of eq. 30 restored). Fails when `S` is singular:
/// free-floating models, or a pencil in the form of eq. 30 whose multipliers are unknown.
pub fn full_static_gain(dae: &LinearDae) -> Result<Mat<f64>, RomError> {
    full_static_gain_or_free_direction(dae).map_err(|e| e.0)
}

/// [`full_static_gain`], with the direction a singular `S` leaves free in the unknowns
/// (largest entry 1) from the same factorization, when it could be formed.
pub fn full_static_gain_or_free_direction(dae: &LinearDae) -> Result<Mat<f64>, (RomError, Option<Vec<f64>>)> {
    full_static_gain_and_scale(dae).map(|(g, _)| g)
}

/// [`full_static_gain_or_free_direction`] and, per channel (outputs × inputs), the scale
/// its rounding is relative to: `Σ_k |C̃_ik| · max_m |x_mj|`, `x = S⁻¹ B̃` over the unknowns
/// that are not multipliers. An LU's rounding is relative to the whole solution, not to one
/// small entry of it (a node beside a clamp reads 1e-3 of the tip's deflection).
pub fn full_static_gain_and_scale(dae: &LinearDae) -> Result<(Mat<f64>, Mat<f64>), (RomError, Option<Vec<f64>>)> {
    let x = solve_or_free_direction(&dae.static_matrix(), &dae.b).map_err(|free| (RomError::SingularStatic("the static matrix of the full model"), free))?;
    let largest: Vec<f64> = (0..x.ncols()).map(|j| (0..x.nrows()).filter(|m| !dae.multipliers.contains(m)).map(|m| x[(m, j)].abs()).fold(0.0, f64::max)).collect();
    let scale = Mat::from_fn(dae.c.nrows(), x.ncols(), |i, j| (0..dae.c.ncols()).map(|k| dae.c[(i, k)].abs()).sum::<f64>() * largest[j]);
    Ok((&dae.c * &x, scale))
}
