//! Finite-difference check of every element's Jacobian against its residual.
//!
//! For each unknown `j` the state is perturbed the way Newton moves it — `ẏ_j ± h` and
//! `y_j ± c h` for differential unknowns, `y_j ± h` (eq. 30) or `y_j ± c h` (eq. 29) for
//! multipliers — so the central difference of `F` is column `j` of `J(c)`. The step makes
//! `y_j` move by about `1e-6 (1 + |y_j|)` whatever `c` is (a step of `c h` with a small `c`
//! would drown the difference of a stiff element's residual in rounding), and `ẏ_j` by at
//! least `1e-6 (1 + |ẏ_j|)`. An element's differential state (a friction model's bristle
//! deflection, about 1e-4 m) moves by `1e-6 (1e-6 + |y_j|)`, relative to its own size.

use std::collections::HashMap;

use super::{Assembler, Coefficients, State};
use crate::model::ConstraintForm;

/// The worst disagreement found in one element.
#[derive(Clone, Debug)]
pub struct JacobianMismatch {
    pub element: String,
    pub equation: String,
    pub unknown: String,
    pub analytic: f64,
    pub finite_difference: f64,
    /// `|analytic − fd| / max(max |J_element|, 1)`.
    pub relative_error: f64,
    /// The element's drives read the model's state: the finite differences hold them at the
    /// checked state, since their derivatives are in no Jacobian (as in MBDyn, see
    /// [`crate::element::drive::TimeFunction`]).
    pub drive_held: bool,
}

impl JacobianMismatch {
    /// Whether the worst entry agrees within `tolerance` (a NaN error does not).
    pub fn within(&self, tolerance: f64) -> bool {
        self.relative_error <= tolerance
    }
}

/// The unknowns (and equations) an element touches: its nodes' (structural and scalar) and
/// its own multipliers, each with the index of the structural node that owns it.
fn element_unknowns(dofs: &super::DofMap, e: usize) -> Vec<(usize, Option<usize>)> {
    let mut u: Vec<(usize, Option<usize>)> = dofs.element_nodes[e].iter().flat_map(|&n| (dofs.node_first[n]..dofs.node_first[n] + dofs.node_kind[n].unknowns()).map(move |j| (j, Some(n)))).collect();
    let mut scalars = dofs.element_scalars[e].clone();
    scalars.sort_unstable();
    scalars.dedup();
    u.extend(scalars.iter().map(|&k| (dofs.scalar_first + k, None)));
    u.extend((dofs.element_first[e]..dofs.element_first[e] + dofs.element_len[e]).map(|j| (j, None)));
    u
}

/// Checks every element at `st` with coefficient `dcoef`; returns each element's worst
/// entry (all of them, sorted by decreasing error). Work per element is proportional to its
/// own size: only the perturbed node's frame is recomputed, and only the element's
/// equations are compared.
pub fn check_jacobians(asm: &Assembler, st: &State, dcoef: f64, form: ConstraintForm) -> Vec<JacobianMismatch> {
    let dofs = &asm.dofs;
    let mut st = st.clone();
    let mut frames = asm.frames(&st);
    let held = frames.clone();
    let mut out = Vec::new();
    for (e, el) in asm.model.elements.iter().enumerate() {
        let unknowns = element_unknowns(dofs, e);
        let local: HashMap<usize, usize> = unknowns.iter().enumerate().map(|(k, &(j, _))| (j, k)).collect();
        let m = unknowns.len();
        // Analytic block (rows and columns: the element's equations and unknowns).
        let mut analytic = vec![0.0; m * m];
        let t = asm.element_jacobian(&st, &frames, e, Coefficients::newton(dcoef, form));
        for k in 0..t.values.len() {
            if let (Some(&r), Some(&c)) = (local.get(&t.rows[k]), local.get(&t.cols[k])) {
                analytic[r * m + c] += t.values[k];
            }
        }
        let scale = analytic.iter().fold(1.0f64, |a, v| a.max(v.abs()));
        let mut worst = JacobianMismatch { element: format!("{} {}", el.type_name(), el.label()), equation: String::new(), unknown: String::new(), analytic: 0.0, finite_difference: 0.0, relative_error: 0.0, drive_held: el.reads_state() };
        for (c, &(j, node)) in unknowns.iter().enumerate() {
            let multiplier = dofs.is_multiplier(j);
            let moves_y_by_h = multiplier && form == ConstraintForm::Scaled;
            let h = if moves_y_by_h {
                1e-6 * (1.0 + st.y[j].abs())
            } else if dofs.is_state(j) {
                // An element's state (a bristle deflection of 1e-4 m whose friction law
                // bends within a fraction of that) moves relative to its own size, and by at
                // least 1e-9 (a modal coordinate at zero in a position constraint scaled by
                // 1/c: a 1e-12 step left 5e-5 of rounding in MBDyn's modal beam_2.mbd).
                1e-6 * (1e-6 + st.yp[j].abs()).max((1e-3 + st.y[j].abs()) / dcoef)
            } else {
                1e-6 * (1.0 + st.yp[j].abs()).max((1.0 + st.y[j].abs()) / dcoef)
            };
            let (y0, yp0) = (st.y[j], st.yp[j]);
            let mut residual_at = |sign: f64| {
                if multiplier {
                    st.y[j] = y0 + sign * h * if form == ConstraintForm::Scaled { 1.0 } else { dcoef };
                } else {
                    st.yp[j] = yp0 + sign * h;
                    st.y[j] = y0 + sign * h * dcoef;
                }
                let saved = node.map(|n| std::mem::replace(&mut frames[n], st.node_frame(dofs, n)));
                let mut f = vec![0.0; m];
                for (i, v) in asm.element_residual(&st, &frames, &held, e, form, dcoef) {
                    if let Some(&r) = local.get(&i) {
                        f[r] += v;
                    }
                }
                if let (Some(n), Some(fr)) = (node, saved) {
                    frames[n] = fr;
                }
                (st.y[j], st.yp[j]) = (y0, yp0);
                f
            };
            let (fp, fm) = (residual_at(1.0), residual_at(-1.0));
            for r in 0..m {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                let a = analytic[r * m + c];
                let err = (a - fd).abs() / scale;
                if err > worst.relative_error || (err.is_nan() && !worst.relative_error.is_nan()) {
                    let i = unknowns[r].0;
                    worst = JacobianMismatch { element: worst.element.clone(), equation: dofs.equation_name(asm.model, i), unknown: dofs.unknown_name(asm.model, j), analytic: a, finite_difference: fd, relative_error: err, drive_held: worst.drive_held };
                }
            }
        }
        out.push(worst);
    }
    out.sort_by(|a, b| b.relative_error.total_cmp(&a.relative_error));
    out
}
