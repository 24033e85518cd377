//! An eigenvalue's error estimate that does not depend on units (issue 34: a hydraulic
//! actuator's pencil mixes pascals and metres, 1e10 apart; the normwise estimate of eqs.
//! 32–35, which measures every perturbation against the whole pencil's norm, gave its
//! ±1414 rad/s pair an error of 2.2e-2 rad/s though the pair is right to 1e-10).
//!
//! Componentwise perturbation theory (Higham, *Accuracy and Stability of Numerical
//! Algorithms*, §7.2, Oettli–Prager; Higham and Higham 1998 for eigenvalues): each entry of
//! `F_y` and `F_yd` perturbed by at most `η` times itself moves a simple eigenvalue by
//!
//! ```text
//! |δλ| ≤ η |u|ᵀ (|F_y| + |λ| |F_yd|) |v| / |uᵀ F_yd v|
//! ```
//!
//! to first order, and the computed pair is exact for such a perturbation with `η` the
//! larger of its right and left componentwise backward errors
//! `maxᵢ |((λ F_yd + F_y) v)ᵢ| / ((|F_y| + |λ| |F_yd|) |v|)ᵢ` (and the same for `u` by
//! columns), never below ε. Scaling a row or a column (a unit) changes none of these.

use faer::{c64, Col};

use crate::linear::SparseMatrix;

/// The componentwise estimate of `|δλ|` [rad/s] for `λ` with right and left vectors `v`,
/// `u` of `λ F_yd + F_y` (module doc); `None` for a non-finite `λ` or `uᵀ F_yd v = 0`.
/// `col`, `row`: the balancing's column and row scales (`v = D_c v'`, `u = D_r u'`): a row
/// whose residual is at the level of the vector's own rounding (entries that are zero in
/// exact arithmetic computed as 1e-14 of the balanced vector, a constrained node's x) says
/// nothing about the matrices, and the two-sided quotient is second-order in the vectors'
/// errors: such rows are left out of the backward error (their floor is `1e3 ε` of what
/// the row gives with every entry of the balanced vector at its largest).
pub(crate) fn componentwise_error(fyd: &SparseMatrix, fy: &SparseMatrix, lambda: c64, v: &Col<c64>, u: &Col<c64>, col: &[f64], row: &[f64]) -> Option<f64> {
    if !(lambda.re.is_finite() && lambda.im.is_finite()) {
        return None;
    }
    let l = lambda.norm();
    let magnitudes = |x: &Col<c64>| x.iter().map(|z| z.norm()).collect::<Vec<f64>>();
    let (va, ua) = (magnitudes(v), magnitudes(u));
    let combine = |a: Vec<f64>, b: Vec<f64>| a.iter().zip(&b).map(|(x, y)| x + l * y).collect::<Vec<f64>>();
    // maxₖ |xₖ| / dₖ: the balanced vector's largest entry.
    let balanced = |x: &[f64], d: &[f64]| x.iter().zip(d).map(|(a, s)| a / s).fold(0.0, f64::max);
    let backward = |residual: Col<c64>, magnitude: &[f64], scales: &[f64], transpose: bool| {
        let scale = combine(fy.abs_mul(magnitude, transpose), fyd.abs_mul(magnitude, transpose));
        let top = balanced(magnitude, scales);
        let floor = combine(fy.abs_mul(scales, transpose), fyd.abs_mul(scales, transpose));
        residual.iter().zip(scale.iter().zip(&floor)).filter(|(r, (_, f))| r.norm() > 1e3 * f64::EPSILON * *f * top).map(|(r, (s, _))| r.norm() / s).fold(f64::EPSILON, f64::max)
    };
    let (fyd_v, fy_v) = (fyd.mul_complex(v), fy.mul_complex(v));
    let (fyd_u, fy_u) = (fyd.mul_t_complex(u), fy.mul_t_complex(u));
    let right = backward(Col::from_fn(v.nrows(), |i| fyd_v[i] * lambda + fy_v[i]), &va, col, false);
    let left = backward(Col::from_fn(u.nrows(), |i| fyd_u[i] * lambda + fy_u[i]), &ua, row, true);
    let denominator = u.iter().zip(fyd_v.iter()).fold(c64::new(0.0, 0.0), |s, (a, b)| s + a * b).norm();
    let kappa = (fy.abs_bilinear(u, v) + l * fyd.abs_bilinear(u, v)) / denominator;
    let estimate = right.max(left) * kappa;
    (estimate.is_finite() && denominator > 0.0).then_some(estimate)
}
