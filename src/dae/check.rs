//! Finite-difference check of every element's Jacobian against its residual.
//!
//! For each unknown `j` the state is perturbed the way Newton moves it — `ẏ_j ± h` and
//! `y_j ± c h` for differential unknowns, `y_j ± h` (eq. 30) or `y_j ± c h` (eq. 29) for
//! multipliers — so the central difference of `F` is column `j` of `J(c)`. The step makes
//! `y_j` move by about `1e-6 (1 + |y_j|)` whatever `c` is (a step of `c h` with a small `c`
//! would drown the difference of a stiff element's residual in rounding), and `ẏ_j` by at
//! least `1e-6 (1 + |ẏ_j|)`.

use super::{Assembler, Coefficients, State};
use crate::linear::ConstraintForm;

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
}

impl JacobianMismatch {
    /// Whether the worst entry agrees within `tolerance` (a NaN error does not).
    pub fn within(&self, tolerance: f64) -> bool {
        self.relative_error <= tolerance
    }
}

/// Checks every element at `st` with coefficient `dcoef`; returns each element's worst
/// entry (all of them, sorted by decreasing error).
pub fn check_jacobians(asm: &Assembler, st: &State, dcoef: f64, form: ConstraintForm) -> Vec<JacobianMismatch> {
    let dofs = &asm.dofs;
    let mut out = Vec::new();
    for (e, el) in asm.model.elements.iter().enumerate() {
        let analytic = asm.element_jacobian(st, e, Coefficients::newton(dcoef, form)).to_dense();
        let mut unknowns: Vec<usize> = dofs.element_nodes[e].iter().flat_map(|&n| dofs.node_first[n]..dofs.node_first[n] + dofs.node_kind[n].unknowns()).collect();
        unknowns.extend(dofs.element_first[e]..dofs.element_first[e] + dofs.element_len[e]);
        let scale = analytic.norm_max().max(1.0);
        let mut worst = JacobianMismatch { element: format!("{} {}", el.type_name(), el.label()), equation: String::new(), unknown: String::new(), analytic: 0.0, finite_difference: 0.0, relative_error: 0.0 };
        for &j in &unknowns {
            let multiplier = dofs.is_multiplier(j);
            let moves_y_by_h = multiplier && form == ConstraintForm::Scaled;
            let h = if moves_y_by_h { 1e-6 * (1.0 + st.y[j].abs()) } else { 1e-6 * (1.0 + st.yp[j].abs()).max((1.0 + st.y[j].abs()) / dcoef) };
            let perturbed = |sign: f64| {
                let mut s = st.clone();
                if multiplier {
                    s.y[j] += sign * h * if form == ConstraintForm::Scaled { 1.0 } else { dcoef };
                } else {
                    s.yp[j] += sign * h;
                    s.y[j] += sign * h * dcoef;
                }
                asm.element_residual(&s, e, form, dcoef)
            };
            let (fp, fm) = (perturbed(1.0), perturbed(-1.0));
            for i in 0..dofs.len {
                let fd = (fp[i] - fm[i]) / (2.0 * h);
                let err = (analytic[(i, j)] - fd).abs() / scale;
                if err > worst.relative_error {
                    worst = JacobianMismatch {
                        element: worst.element.clone(),
                        equation: dofs.equation_name(asm.model, i),
                        unknown: dofs.unknown_name(asm.model, j),
                        analytic: analytic[(i, j)],
                        finite_difference: fd,
                        relative_error: err,
                    };
                }
            }
        }
        out.push(worst);
    }
    out.sort_by(|a, b| b.relative_error.total_cmp(&a.relative_error));
    out
}
