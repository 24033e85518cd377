//! Every element's analytic Jacobian against central finite differences of its residual, at
//! a model file's reference solution (`dae::check_jacobians`), with the coefficient the
//! file's integrator uses (`c = b₀`, eq. 5).

use super::reference::{reference_state, Reference};
use super::error::RunError;
use crate::dae::{check_assembled, check_jacobians, AssembledMismatch, Assembler, JacobianMismatch};
use crate::model::{InitialValueProblem, Model};
use crate::output::jacobian_check::jacobian_check_text;
use crate::solve::newton_dcoef;

/// An element disagrees when its worst `|analytic − fd| / max(max |J_element|, 1)` exceeds
/// this. Central differences moving `y_j` by about `1e-6 (1 + |y_j|)` (see
/// `dae::check_jacobians`) are accurate to about 1e-9 on the elements of the library (worst
/// measured 4.5e-10 at random states; 4e-11 on the loaded 10-element cantilever), so 1e-6
/// flags wrong terms, not rounding.
pub const JACOBIAN_CHECK_TOLERANCE: f64 = 1e-6;

/// The result of checking every element of a model.
#[derive(Clone, Debug)]
pub struct JacobianCheck {
    /// Time of the reference solution [s].
    pub time: f64,
    /// `c` of `J(c) = F_/ẏ + c F_/y` [s].
    pub dcoef: f64,
    pub tolerance: f64,
    /// Each element's worst entry, largest error first.
    pub elements: Vec<JacobianMismatch>,
    /// The worst entries of the whole model's `F_/ẏ` and `F_/y` against differences of the
    /// whole residual, in the linearization form ([`check_assembled`]).
    pub assembled: [AssembledMismatch; 2],
}

impl JacobianCheck {
    /// Elements whose worst entry exceeds the tolerance.
    pub fn failures(&self) -> impl Iterator<Item = &JacobianMismatch> {
        self.elements.iter().filter(|e| !e.within(self.tolerance))
    }

    pub fn passed(&self) -> bool {
        self.failures().next().is_none() && self.assembled.iter().all(|m| m.within(self.tolerance))
    }

    /// The report as text: one row per element, then a summary line.
    pub fn to_text(&self) -> String {
        jacobian_check_text(&self.elements, &self.assembled, self.tolerance, self.time, self.dcoef)
    }
}

/// Checks every element of `model` at its reference solution.
pub fn check_model_jacobians(model: &Model, problem: &InitialValueProblem, reference: Reference, tolerance: f64) -> Result<JacobianCheck, RunError> {
    let mut state = reference_state(model, problem, reference)?;
    let asm = Assembler::new(model);
    // The form the model is linearized in (and Newton iterates in after a prediction): a
    // node's angular velocity carried in W_ref.
    state.linearization_base(&asm.dofs);
    let dcoef = newton_dcoef(super::run::method_at(&asm, problem, &state, state.t)?, problem.time_step);
    let elements = check_jacobians(&asm, &state, dcoef, model.constraint_form);
    let assembled = check_assembled(&asm, &state);
    Ok(JacobianCheck { time: state.t, dcoef, tolerance, elements, assembled })
}
