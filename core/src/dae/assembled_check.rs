//! Finite-difference check of the assembled `F_/ẏ` and `F_/y` (eqs. 13–16) against the whole
//! residual `F(y, ẏ, t)`, at a state put in the form the model is linearized in
//! ([`State::linearization_base`]: a spinning node's angular velocity carried in `W_ref`).
//!
//! The element-by-element check ([`super::check_jacobians`]) sees one element at a time;
//! this one sees what the linearization sees: the nodes' own rows (momentum definitions,
//! `γ̇ + ẋ × β`), every element summed, and the map from the orientation parameters to
//! `R` and `ω`. Column `j` of `F_/ẏ` is compared with `(F(ẏ_j + h) − F(ẏ_j − h))/2h`, column
//! `j` of `F_/y` with the same in `y_j`, in the plain constraint form (eq. 29: multipliers in
//! `y`), whatever form the model integrates with; `h` is 1e-6 and 1e-4 times `1 + |y_j|`,
//! and an entry disagrees when it disagrees at both.

use std::collections::BTreeMap;

use super::{Assembler, Coefficients, State};
use crate::model::ConstraintForm;

/// The worst entry of one assembled matrix.
#[derive(Clone, Debug, Default)]
pub struct AssembledMismatch {
    /// `"F/y'"` or `"F/y"`.
    pub matrix: &'static str,
    pub equation: String,
    pub unknown: String,
    pub analytic: f64,
    pub finite_difference: f64,
    /// `(|analytic − fd| − rounding) / max(max |row i|, max |column j|, 1e-9 max |matrix|)`:
    /// the difference beyond the central difference's own rounding, relative to the size of
    /// the entry's equation or unknown (an entry of 1e-17 in a row and column of order 1 is
    /// round-off, not a wrong term).
    pub relative_error: f64,
}

impl AssembledMismatch {
    pub fn within(&self, tolerance: f64) -> bool {
        self.relative_error <= tolerance
    }
}

/// Checks `F_/ẏ` and `F_/y` of the whole model at `state` (put in the linearization form
/// here, a copy); returns the worst entry of each.
pub fn check_assembled(asm: &Assembler, state: &State) -> [AssembledMismatch; 2] {
    let mut st = state.clone();
    st.linearization_base(&asm.dofs);
    let n = asm.dofs.len;
    let form = ConstraintForm::Plain;
    let f0 = asm.residual(&st, form, 1.0);
    let mut out = [AssembledMismatch { matrix: "F/y'", ..Default::default() }, AssembledMismatch { matrix: "F/y", ..Default::default() }];
    for (which, (a, b)) in [(1.0, 0.0), (0.0, 1.0)].into_iter().enumerate() {
        let (cols, row_size) = columns(asm, &st, a, b);
        let col_size: Vec<f64> = cols.iter().map(|c| c.values().fold(0.0f64, |m, v| m.max(v.abs()))).collect();
        let largest = col_size.iter().copied().fold(0.0f64, f64::max);
        let worst = &mut out[which];
        for j in 0..n {
            let value = if which == 0 { st.yp[j] } else { st.y[j] };
            // Two steps: 1e-6 relative, and 1e-4 relative where the residual sums terms much
            // larger than itself (a preloaded isolator: the differences of forces of 1e5 N
            // lose digits the larger step keeps). A wrong term disagrees at both.
            let mut fd_at = |rel: f64| {
                let h = rel * (1.0 + value.abs());
                let mut at = |s: f64| {
                    let v = if which == 0 { &mut st.yp[j] } else { &mut st.y[j] };
                    *v = value + s * h;
                    let f = asm.residual(&st, form, 1.0);
                    let v = if which == 0 { &mut st.yp[j] } else { &mut st.y[j] };
                    *v = value;
                    f
                };
                let (fp, fm) = (at(1.0), at(-1.0));
                // Rounding of the two residuals, each to a few ulps of its size.
                (0..n).map(|i| ((fp[i] - fm[i]) / (2.0 * h), 16.0 * f64::EPSILON * (fp[i].abs() + fm[i].abs() + f0[i].abs()) / (2.0 * h))).collect::<Vec<_>>()
            };
            let (fine, coarse) = (fd_at(1e-6), fd_at(1e-4));
            for i in 0..n {
                let analytic = cols[j].get(&i).copied().unwrap_or(0.0);
                let scale = row_size[i].max(col_size[j]).max(1e-9 * largest).max(f64::EPSILON * f0[i].abs()).max(f64::MIN_POSITIVE);
                let error_of = |(fd, rounding): (f64, f64)| {
                    let e = ((analytic - fd).abs() - rounding).max(0.0) / scale;
                    if e.is_nan() { f64::INFINITY } else { e }
                };
                let (e1, e2) = (error_of(fine[i]), error_of(coarse[i]));
                let (err, fd) = if e1 <= e2 { (e1, fine[i].0) } else { (e2, coarse[i].0) };
                if err > worst.relative_error {
                    *worst = AssembledMismatch { matrix: worst.matrix, equation: asm.dofs.equation_name(asm.model, i), unknown: asm.dofs.unknown_name(asm.model, j), analytic, finite_difference: fd, relative_error: err };
                }
            }
        }
    }
    out
}

/// The columns of `a F_/ẏ + b F_/y` (plain form) as sorted `row → value` maps, duplicate
/// triplets summed, and each row's largest entry.
fn columns(asm: &Assembler, st: &State, a: f64, b: f64) -> (Vec<BTreeMap<usize, f64>>, Vec<f64>) {
    let n = asm.dofs.len;
    let t = asm.jacobian(st, Coefficients { a, b, form: ConstraintForm::Plain, dcoef: 1.0 });
    let mut cols: Vec<BTreeMap<usize, f64>> = vec![BTreeMap::new(); n];
    for k in 0..t.values.len() {
        *cols[t.cols[k]].entry(t.rows[k]).or_insert(0.0) += t.values[k];
    }
    let mut row_size = vec![0.0f64; n];
    for c in &cols {
        for (&i, &v) in c {
            row_size[i] = row_size[i].max(v.abs());
        }
    }
    (cols, row_size)
}
