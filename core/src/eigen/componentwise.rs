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

/// Every dynamic mode's error estimate replaced by the componentwise one where that is
/// smaller ([`componentwise_error`]), for a model whose unknowns mix units: `classes`
/// (`true` for the non-mechanical unknowns and equations, by index) sets each entry's
/// rounding floor to its own kind's largest (a piston's metres are not rounding next to its
/// chambers' pascals). The labels (dynamic, zero, infinite) stay those of eqs. 32–35.
pub fn refine_errors_by_units(modal: &mut crate::eigen::ModalAnalysis, fyd: &SparseMatrix, fy: &SparseMatrix, classes: &[bool]) {
    if !classes.iter().any(|c| *c) || classes.len() != fyd.nrows() {
        return;
    }
    for m in modal.modes.iter_mut().filter(|m| m.kind == crate::eigen::ModeKind::Dynamic) {
        let (Some(v), Some(u)) = (&m.right, &m.left) else { continue };
        if let Some(e) = componentwise_error(fyd, fy, m.lambda, v, u, classes) {
            m.error = m.error.min(e);
        }
    }
}

/// The componentwise estimate of `|δλ|` [rad/s] for `λ` with right and left vectors `v`,
/// `u` of `λ F_yd + F_y` (module doc); `None` for a non-finite `λ` or `uᵀ F_yd v = 0`.
/// A row whose residual is at the level of the vector's own rounding (entries that are zero
/// in exact arithmetic computed as 1e-14 of the vector, a constrained node's x) says
/// nothing about the matrices, and the two-sided quotient is second-order in the vectors'
/// errors: such rows are left out of the backward error (the floor is `1e3 ε` of what the
/// row gives with every entry of the vector at the largest of its kind, `classes`).
pub(crate) fn componentwise_error(fyd: &SparseMatrix, fy: &SparseMatrix, lambda: c64, v: &Col<c64>, u: &Col<c64>, classes: &[bool]) -> Option<f64> {
    if !(lambda.re.is_finite() && lambda.im.is_finite()) {
        return None;
    }
    let l = lambda.norm();
    let magnitudes = |x: &Col<c64>| x.iter().map(|z| z.norm()).collect::<Vec<f64>>();
    let (va, ua) = (magnitudes(v), magnitudes(u));
    let combine = |a: Vec<f64>, b: Vec<f64>| a.iter().zip(&b).map(|(x, y)| x + l * y).collect::<Vec<f64>>();
    // Each entry replaced by the largest of its kind.
    let tops = |x: &[f64]| {
        let top = |kind: bool| x.iter().zip(classes).filter(|(_, c)| **c == kind).map(|(a, _)| *a).fold(0.0, f64::max);
        let (mechanical, other) = (top(false), top(true));
        classes.iter().map(|c| if *c { other } else { mechanical }).collect::<Vec<f64>>()
    };
    let backward = |residual: Col<c64>, magnitude: &[f64], transpose: bool| {
        let scale = combine(fy.abs_mul(magnitude, transpose), fyd.abs_mul(magnitude, transpose));
        let top = tops(magnitude);
        let floor = combine(fy.abs_mul(&top, transpose), fyd.abs_mul(&top, transpose));
        residual.iter().zip(scale.iter().zip(&floor)).filter(|(r, (_, f))| r.norm() > 1e3 * f64::EPSILON * *f).map(|(r, (s, _))| r.norm() / s).fold(f64::EPSILON, f64::max)
    };
    let (fyd_v, fy_v) = (fyd.mul_complex(v), fy.mul_complex(v));
    let (fyd_u, fy_u) = (fyd.mul_t_complex(u), fy.mul_t_complex(u));
    let right = backward(Col::from_fn(v.nrows(), |i| fyd_v[i] * lambda + fy_v[i]), &va, false);
    let left = backward(Col::from_fn(u.nrows(), |i| fyd_u[i] * lambda + fy_u[i]), &ua, true);
    let denominator = u.iter().zip(fyd_v.iter()).fold(c64::new(0.0, 0.0), |s, (a, b)| s + a * b).norm();
    let kappa = (fy.abs_bilinear(u, v) + l * fyd.abs_bilinear(u, v)) / denominator;
    let estimate = right.max(left) * kappa;
    (estimate.is_finite() && denominator > 0.0).then_some(estimate)
}
