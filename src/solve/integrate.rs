//! Fixed-step implicit linear multistep integration in predictor–corrector form:
//! `y_k = a₁ y_{k−1} + a₂ y_{k−2} + b₀ ẏ_k + b₁ ẏ_{k−1} + b₂ ẏ_{k−2}` (eq. 2), corrected by
//! Newton with `δy = b₀ δẏ` (eqs. 3–5). Orientations are re-based at every step, so each
//! node's `g` is measured from its orientation at the previous step.

use super::newton::{momenta_from_definitions, newton, Convergence, NewtonFailure, NewtonSettings, NewtonWorkspace, Update};
use crate::dae::{Assembler, State};
use crate::kinematics::{gibbs_from_rotation, gibbs_g, Mat3, Vec3};
use crate::linear::ConstraintForm;
use crate::model::Method;

/// Coefficients `(a₁, a₂, b₀, b₁, b₂)` for step `h` (the `b`'s include `h`).
fn coefficients(method: Method, h: f64, first_step: bool) -> [f64; 5] {
    match method {
        Method::ImplicitEuler => [1.0, 0.0, h, 0.0, 0.0],
        Method::Ms { .. } if first_step => [1.0, 0.0, h / 2.0, h / 2.0, 0.0],
        Method::CrankNicolson => [1.0, 0.0, h / 2.0, h / 2.0, 0.0],
        Method::Ms { rho } => {
            let den = 4.0 - (1.0 - rho).powi(2);
            let beta = (3.0 * (1.0 - rho).powi(2) + 4.0 * (2.0 * rho - 1.0)) / den;
            let delta = (1.0 - rho).powi(2) / (2.0 * den);
            [1.0 - beta, beta, h * (delta + 0.5), h * (beta / 2.0 + 0.5 - 2.0 * delta), h * (beta / 2.0 + delta)]
        }
    }
}

/// `dCoef = b₀` of the regular steps of `method` with step `h` [s]: the coefficient of
/// `J(c) = F_/ẏ + c F_/y` that Newton uses (eq. 5).
pub fn newton_dcoef(method: Method, h: f64) -> f64 {
    coefficients(method, h, false)[2]
}

/// The solution two steps back, with each node's orientation and angular velocity.
#[derive(Clone)]
struct Past {
    y: Vec<f64>,
    yp: Vec<f64>,
    rotation: Vec<Mat3>,
    omega: Vec<Vec3>,
}

/// What one step did.
#[derive(Clone, Copy, Debug)]
pub struct StepRecord {
    pub t: f64,
    pub iterations: usize,
    /// `‖F‖∞` when Newton stopped.
    pub residual_norm: f64,
}

/// Steps a model in time from a state with consistent derivatives.
pub struct Integrator<'a, 'm> {
    asm: &'a Assembler<'m>,
    pub method: Method,
    pub h: f64,
    pub settings: NewtonSettings,
    pub state: State,
    workspace: NewtonWorkspace,
    previous: Option<Past>,
}

impl<'a, 'm> Integrator<'a, 'm> {
    pub fn new(asm: &'a Assembler<'m>, state: State, method: Method, h: f64, settings: NewtonSettings) -> Self {
        Integrator { asm, method, h, settings, state, workspace: NewtonWorkspace::new(), previous: None }
    }

    /// Number of symbolic factorizations so far (1 for a fixed sparsity pattern).
    pub fn symbolic_factorizations(&self) -> usize {
        self.workspace.lu.symbolic_factorizations
    }

    fn snapshot(&self) -> Past {
        let dofs = &self.asm.dofs;
        let frames: Vec<_> = (0..self.state.r_ref.len()).map(|i| self.state.node_frame(dofs, i)).collect();
        Past { y: self.state.y.clone(), yp: self.state.yp.clone(), rotation: frames.iter().map(|f| f.kin.r).collect(), omega: frames.iter().map(|f| f.kin.omega).collect() }
    }

    /// The older solution's `g` and `ġ` measured from the current reference orientations.
    fn past_in_current_frames(&self, past: &Past) -> (Vec<f64>, Vec<f64>) {
        let (mut y, mut yp) = (past.y.clone(), past.yp.clone());
        for i in 0..self.state.r_ref.len() {
            let f = self.asm.dofs.node_first[i] + 3;
            let g = gibbs_from_rotation(&(past.rotation[i] * self.state.r_ref[i].transpose()));
            let gdot = gibbs_g(&g).try_inverse().unwrap_or_else(Mat3::identity) * past.omega[i];
            for k in 0..3 {
                y[f + k] = g[k];
                yp[f + k] = gdot[k];
            }
        }
        (y, yp)
    }

    /// One step of size `h`: predict, then correct with Newton.
    pub fn step(&mut self) -> Result<StepRecord, NewtonFailure> {
        let dofs = &self.asm.dofs;
        let form = self.asm.model.constraint_form;
        let current = self.snapshot();
        self.state.rebase(dofs);
        let [a1, a2, b0, b1, b2] = coefficients(self.method, self.h, self.previous.is_none());
        let (y1, yp1) = (self.state.y.clone(), self.state.yp.clone());
        let (y2, yp2) = match &self.previous {
            Some(p) => self.past_in_current_frames(p),
            None => (y1.clone(), yp1.clone()),
        };
        for i in 0..dofs.len {
            let two_step = self.previous.is_some();
            if form == ConstraintForm::Scaled && dofs.is_multiplier(i) {
                // Algebraic: the multiplier itself is extrapolated.
                self.state.y[i] = if two_step { 2.0 * y1[i] - y2[i] } else { y1[i] };
                continue;
            }
            let ypred = if two_step { 2.0 * yp1[i] - yp2[i] } else { yp1[i] };
            self.state.yp[i] = ypred;
            self.state.y[i] = a1 * y1[i] + a2 * y2[i] + b0 * ypred + b1 * yp1[i] + b2 * yp2[i];
        }
        self.state.t += self.h;
        let done = newton(self.asm, &mut self.state, Update::Dynamic { dcoef: b0, form }, &self.settings, &mut self.workspace)?;
        self.previous = Some(current);
        Ok(StepRecord { t: self.state.t, iterations: done.iterations, residual_norm: done.residual_norm })
    }
}

/// Initial derivatives as MBDyn's derivatives phase computes them (stepsol.cc,
/// `DerivativeSolver`): Newton with dCoef = `dcoef` for the momenta's derivatives and the
/// multipliers, every node's position, orientation, velocity and angular velocity held as
/// given, the momenta from their definitions at those velocities. Constraint
/// rows and the equilibrium of static nodes therefore must already hold to the tolerance.
pub fn initial_derivatives_with(asm: &Assembler, st: &mut State, settings: &NewtonSettings, dcoef: f64) -> Result<Convergence, NewtonFailure> {
    let form = asm.model.constraint_form;
    momenta_from_definitions(asm, st, form);
    newton(asm, st, Update::Derivatives { dcoef, form }, settings, &mut NewtonWorkspace::new())
}

/// [`initial_derivatives_with`] at dCoef = 1e-6 s · 1e-3 (MBDyn's default derivatives
/// coefficient times a 1 ms step).
pub fn initial_derivatives(asm: &Assembler, st: &mut State, settings: &NewtonSettings) -> Result<Convergence, NewtonFailure> {
    initial_derivatives_with(asm, st, settings, 1e-9)
}

/// The largest rate of change of a constraint, `max |Φ_/q q̇ + Φ_/t|`, at the state's
/// positions and velocities, with the equation's name: non-zero when the velocities written
/// in a file do not satisfy the joints (the first step then changes them). A one-sided
/// difference along `q̇` and `t` (steps of 1e-5 s). A velocity-level constraint's own
/// value `ψ(q, q̇, t)` is its violation.
pub fn constraint_rate(asm: &Assembler, st: &State) -> Option<(String, f64)> {
    let dofs = &asm.dofs;
    let moved = |s: f64| {
        let mut m = st.clone();
        for &f in &dofs.node_first {
            for i in f..f + 6 {
                m.y[i] += s * st.yp[i];
            }
        }
        m.t += s;
        asm.residual(&m, ConstraintForm::Plain, 1.0)
    };
    let now = asm.residual(st, ConstraintForm::Plain, 1.0);
    let own = dofs.element_first.iter().zip(&dofs.element_len).flat_map(|(&f, &k)| f..f + k);
    let velocity = own.filter(|&i| !dofs.is_multiplier(i)).map(|i| (i, now[i]));
    // Forward in time (a drive may start with a kink at the initial time), second order:
    // (−3 Φ(0) + 4 Φ(ε) − Φ(2ε)) / (2ε).
    let eps = 1e-5;
    let (one, two) = (moved(eps), moved(2.0 * eps));
    (0..dofs.len).filter(|&i| dofs.is_multiplier(i)).map(|i| (i, (4.0 * one[i] - 3.0 * now[i] - two[i]) / (2.0 * eps))).chain(velocity).fold(None, |best: Option<(usize, f64)>, (i, v)| match best {
        Some((_, b)) if b.abs() >= v.abs() => best,
        _ => Some((i, v)),
    }).map(|(i, v)| (dofs.equation_name(asm.model, i), v))
}
