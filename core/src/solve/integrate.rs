//! Fixed-step implicit linear multistep integration in predictor–corrector form:
//! `y_k = a₁ y_{k−1} + a₂ y_{k−2} + b₀ ẏ_k + b₁ ẏ_{k−1} + b₂ ẏ_{k−2}` (eq. 2), corrected by
//! Newton with `δy = b₀ δẏ` (eqs. 3–5). Orientations are re-based at every step, so each
//! node's `g` is measured from its orientation at the previous step.
//!
//! MBDyn's `Bathe` method (later MBDyn versions, stepsol.cc `TunableBatheSolver`, the
//! ρ∞-Bathe method of Noh and Bathe, Computers & Structures 212 (2019) 299–310) steps in two
//! sub-steps, each a Newton solve of the same kind with its own dCoef, orientations re-based
//! between them ([`BatheCoefficients`]).

use super::newton::{momenta_from_definitions, newton, Convergence, DerivativeMomenta, NewtonFailure, NewtonSettings, NewtonWorkspace, Update};
use super::forward_difference::forward_derivatives;
use crate::dae::{Assembler, Frames, Owner, State};
use crate::kinematics::{gibbs_from_rotation, gibbs_g, Mat3, Vec3};
use crate::model::ConstraintForm;
use crate::model::{Method, NodeKind};

/// Coefficients `(a₁, a₂, b₀, b₁, b₂)` for step `h` (the `b`'s include `h`).
fn coefficients(method: Method, h: f64, first_step: bool) -> [f64; 5] {
    match method {
        Method::ImplicitEuler => [1.0, 0.0, h, 0.0, 0.0],
        Method::Ms { .. } | Method::HybridImplicitEuler if first_step => [1.0, 0.0, h / 2.0, h / 2.0, 0.0],
        Method::HybridImplicitEuler => [1.0, 0.0, h, 0.0, 0.0],
        Method::Bathe { .. } => unreachable!("a Bathe step is two sub-steps (Integrator::bathe_step)"),
        Method::CrankNicolson => [1.0, 0.0, h / 2.0, h / 2.0, 0.0],
        Method::Ms { rho } => {
            let den = 4.0 - (1.0 - rho).powi(2);
            let beta = (3.0 * (1.0 - rho).powi(2) + 4.0 * (2.0 * rho - 1.0)) / den;
            let delta = (1.0 - rho).powi(2) / (2.0 * den);
            [1.0 - beta, beta, h * (delta + 0.5), h * (beta / 2.0 + 0.5 - 2.0 * delta), h * (beta / 2.0 + delta)]
        }
    }
}

/// The predictor of a derivative `u_k` from the two previous steps.
#[derive(Clone, Copy, Debug)]
enum Predictor {
    /// `u_k = u_{k−1}` (first step, and the one-step methods: MBDyn's Crank–Nicolson).
    Constant,
    /// `u_k = 2 u_{k−1} − u_{k−2}`.
    Linear,
    /// Cubic Hermite extrapolation from the values and derivatives of the two previous
    /// steps, `u_k = −(12/h)(v_{k−1} − v_{k−2}) + 8 u_{k−1} + 5 u_{k−2}` with `u = v̇`
    /// (MBDyn's `ms`, stepsol.cc `MultistepSolver::SetCoef` at a constant step: exact for
    /// cubic `v`).
    CubicHermite { h: f64 },
}

impl Predictor {
    fn of(method: Method, h: f64, two_step: bool) -> Self {
        match method {
            _ if !two_step => Predictor::Constant,
            Method::Ms { .. } => Predictor::CubicHermite { h },
            Method::ImplicitEuler | Method::CrankNicolson | Method::HybridImplicitEuler | Method::Bathe { .. } => Predictor::Linear,
        }
    }

    /// `u_k` from `u_{k−1}`, `u_{k−2}` and the increment `v_{k−1} − v_{k−2}` of `v`.
    fn derivative(self, u1: f64, u2: f64, increment: f64) -> f64 {
        match self {
            Predictor::Constant => u1,
            Predictor::Linear => 2.0 * u1 - u2,
            Predictor::CubicHermite { h } => -12.0 / h * increment + 8.0 * u1 + 5.0 * u2,
        }
    }
}

/// `dCoef = b₀` of the regular steps of `method` with step `h` [s]: the coefficient of
/// `J(c) = F_/ẏ + c F_/y` that Newton uses (eq. 5).
pub fn newton_dcoef(method: Method, h: f64) -> f64 {
    match method {
        // Both sub-steps have the same, `γh/2`.
        Method::Bathe { rho } => BatheCoefficients::new(rho, h).first,
        _ => coefficients(method, h, false)[2],
    }
}

/// The two sub-steps of MBDyn's `Bathe` method (stepsol.cc, `TunableBatheSolver`) for the
/// asymptotic spectral radius `ρ` and the step `h`. The first sub-step is the trapezoidal
/// rule over `γh`, `y_s = y_{k−1} + (γh/2)(ẏ_s + ẏ_{k−1})`, from the predictor `ẏ_s =
/// ẏ_{k−1}`, at time `t_{k−1} + γh`; the second is `y_k = y_{k−1} + b₀ ẏ_k + b₁ ẏ_s + b₂
/// ẏ_{k−1}` (Noh and Bathe's `h (q₂, q₁, q₀)`), from the cubic Hermite predictor through
/// `(y_{k−1}, ẏ_{k−1})` and `(y_s, ẏ_s)`. A multiplier of the form of eq. 30 is predicted as its
/// last value (MBDyn's algebraic predictor), any other unknown is integrated alike.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BatheCoefficients {
    /// `γ = (2 − √(2 + 2ρ))/(1 − ρ) = 2/(2 + √(2 + 2ρ))`: `2 − √2` at ρ = 0, ½ at ρ = 1.
    pub gamma: f64,
    /// `γh/2`, the first sub-step's dCoef (and the second's).
    pub first: f64,
    /// `(b₀, b₁, b₂) = h ((1 − γ)/D, (1 + ρ)/(2D), (2γρ − ρ + 1)/(2D))`, `D = 2 − γ(1 − ρ)`.
    pub b: [f64; 3],
    /// `ẏ_k ≈ m₀ (y_s − y_{k−1}) + n₀ ẏ_s + n₁ ẏ_{k−1}`: `(m₀, n₀, n₁)` with `α = (1 − γ)/γ`,
    /// `m₀ = −6α²(1 + α)/((1 − γ)h)`, `n₀ = 1 + 4α + 3α²`, `n₁ = α(2 + 3α)`.
    pub predictor: [f64; 3],
}

impl BatheCoefficients {
    pub fn new(rho: f64, h: f64) -> Self {
        let gamma = 2.0 / (2.0 + (2.0 + 2.0 * rho).sqrt());
        let d = 2.0 - gamma * (1.0 - rho);
        let alpha = (1.0 - gamma) / gamma;
        BatheCoefficients {
            gamma,
            first: gamma * h / 2.0,
            b: [h * (1.0 - gamma) / d, h * (1.0 + rho) / (2.0 * d), h * (2.0 * gamma * rho - rho + 1.0) / (2.0 * d)],
            predictor: [-6.0 * alpha * alpha * (1.0 + alpha) / ((1.0 - gamma) * h), 1.0 + 4.0 * alpha + 3.0 * alpha * alpha, alpha * (2.0 + 3.0 * alpha)],
        }
    }
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
    /// Per multiplier of the form of eq. 30, its integral's increment over the last step,
    /// `b₀ λ_k + b₁ λ_{k−1} + b₂ λ_{k−2} − a₂ Λ_{k−1}` (MBDyn's `XPrime` of an algebraic
    /// unknown, stepsol.cc): the multiplier's predictor needs it.
    multiplier_increment: Vec<f64>,
    /// Steps accepted so far (the step drives' memory is advanced once per step number).
    accepted: usize,
    /// Whether an element has events, latched after each prediction
    /// ([`crate::element::Element::latch`]).
    events: bool,
    /// The node frames of the solution at the start of a step, for its snapshot and its
    /// re-basing.
    frames: Frames,
}

impl<'a, 'm> Integrator<'a, 'm> {
    pub fn new(asm: &'a Assembler<'m>, state: State, method: Method, h: f64, settings: NewtonSettings) -> Self {
        Self::with_workspace(asm, state, method, h, settings, NewtonWorkspace::new())
    }

    /// As [`Integrator::new`], reusing the workspace of an earlier Newton iteration on the
    /// same model (the derivatives phase's): its sparsity pattern, elimination and symbolic
    /// factorization are kept when the steps' Jacobian has the same triplet positions, so
    /// they are built once per run (on large models their set-up is the run's peak memory).
    pub fn with_workspace(asm: &'a Assembler<'m>, state: State, method: Method, h: f64, settings: NewtonSettings, workspace: NewtonWorkspace) -> Self {
        let multiplier_increment = vec![0.0; asm.dofs.len];
        Integrator { asm, method, h, settings, state, workspace, previous: None, multiplier_increment, accepted: 0, events: asm.has_events(), frames: Frames::default() }
    }

    /// Number of symbolic factorizations so far (1 for a fixed sparsity pattern).
    pub fn symbolic_factorizations(&self) -> usize {
        self.workspace.lu.symbolic_factorizations
    }

    /// Newton's workspace: how many iterations factored a Jacobian and how many kept the
    /// last factorization ([`NewtonWorkspace::keep_jacobian_below`]).
    pub fn workspace(&self) -> &NewtonWorkspace {
        &self.workspace
    }

    /// Re-bases the state Newton converged to, with the node frames of its last residual
    /// when they are this state's ([`NewtonWorkspace::frames_of_solution`]).
    fn rebase_converged(&mut self) {
        match self.workspace.frames_of_solution() {
            Some(frames) => self.state.rebase_with(&self.asm.dofs, frames),
            None => self.state.rebase(&self.asm.dofs),
        }
    }

    /// The solution now, from its node frames (`self.frames`, [`Assembler::frames_into`]).
    fn snapshot(&self) -> Past {
        let frames = &self.frames;
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
        if let Method::Bathe { rho } = self.method {
            return self.bathe_step(rho);
        }
        let asm = self.asm;
        let dofs = &asm.dofs;
        let form = asm.model.constraint_form;
        asm.frames_into(&self.state, &mut self.frames);
        let current = self.snapshot();
        // The step drives' memory from the accepted state, at the new time (a failed
        // attempt is redone from the same memory: the step number is the same).
        asm.begin_step(&self.state, self.accepted + 1, self.state.t + self.h);
        let accepted = self.events.then(|| self.state.clone());
        self.state.rebase_with(dofs, &self.frames);
        let [a1, a2, b0, b1, b2] = coefficients(self.method, self.h, self.previous.is_none());
        let (y1, yp1) = (self.state.y.clone(), self.state.yp.clone());
        let (y2, yp2) = match &self.previous {
            Some(p) => self.past_in_current_frames(p),
            None => (y1.clone(), yp1.clone()),
        };
        let two_step = self.previous.is_some();
        let predictor = Predictor::of(self.method, self.h, two_step);
        for i in 0..dofs.len {
            if form == ConstraintForm::Scaled && dofs.is_multiplier(i) {
                // Algebraic: the multiplier is the derivative of its integral, whose increment
                // over the last step is kept.
                self.state.y[i] = predictor.derivative(y1[i], y2[i], self.multiplier_increment[i]);
                continue;
            }
            let ypred = predictor.derivative(yp1[i], yp2[i], y1[i] - y2[i]);
            self.state.yp[i] = ypred;
            self.state.y[i] = a1 * y1[i] + a2 * y2[i] + b0 * ypred + b1 * yp1[i] + b2 * yp2[i];
        }
        self.state.after_predict(dofs);
        self.state.t += self.h;
        if let Some(before) = &accepted {
            // Events at the predicted state, as MBDyn's AfterPredict (module documentation
            // of `Element::latch`): Newton then sees the latched data fixed.
            self.asm.latch_events(&mut self.state, before);
        }
        let done = newton(self.asm, &mut self.state, Update::Dynamic { dcoef: b0, form }, &self.settings, &mut self.workspace)?;
        if form == ConstraintForm::Scaled {
            for i in (0..dofs.len).filter(|&i| dofs.is_multiplier(i)) {
                let previous = self.multiplier_increment[i];
                self.multiplier_increment[i] = b0 * self.state.y[i] + b1 * y1[i] + b2 * y2[i] - a2 * previous;
            }
        }
        self.rebase_converged();
        self.previous = Some(current);
        self.accepted += 1;
        Ok(StepRecord { t: self.state.t, iterations: done.iterations, residual_norm: done.residual_norm })
    }

    /// One step of MBDyn's `Bathe` method ([`BatheCoefficients`]): two Newton solves, each
    /// after its own prediction and events (MBDyn's `AfterPredict` and `AfterConvergence` per
    /// sub-step), the orientations re-based between them.
    fn bathe_step(&mut self, rho: f64) -> Result<StepRecord, NewtonFailure> {
        let asm = self.asm;
        let dofs = &asm.dofs;
        let form = asm.model.constraint_form;
        let c = BatheCoefficients::new(rho, self.h);
        asm.frames_into(&self.state, &mut self.frames);
        let start = self.snapshot();
        let t0 = self.state.t;
        asm.begin_step(&self.state, self.accepted + 1, t0 + self.h);
        let held = |i: usize| form == ConstraintForm::Scaled && dofs.is_multiplier(i);

        // First sub-step: the trapezoidal rule over γh.
        let before = self.events.then(|| self.state.clone());
        self.state.rebase_with(dofs, &self.frames);
        let (y0, yp0) = (self.state.y.clone(), self.state.yp.clone());
        for i in (0..dofs.len).filter(|&i| !held(i)) {
            self.state.y[i] = y0[i] + c.first * 2.0 * yp0[i];
        }
        self.state.after_predict(dofs);
        self.state.t = t0 + c.gamma * self.h;
        if let Some(before) = &before {
            self.asm.latch_events(&mut self.state, before);
        }
        let first = newton(self.asm, &mut self.state, Update::Dynamic { dcoef: c.first, form }, &self.settings, &mut self.workspace)?;

        // Second sub-step, over the whole step.
        let before = self.events.then(|| self.state.clone());
        self.rebase_converged();
        let (ys, yps) = (self.state.y.clone(), self.state.yp.clone());
        let (y0, yp0) = self.past_in_current_frames(&start);
        let [m0, n0, n1] = c.predictor;
        let [b0, b1, b2] = c.b;
        for i in (0..dofs.len).filter(|&i| !held(i)) {
            let yp = m0 * (ys[i] - y0[i]) + n0 * yps[i] + n1 * yp0[i];
            self.state.yp[i] = yp;
            self.state.y[i] = y0[i] + b0 * yp + b1 * yps[i] + b2 * yp0[i];
        }
        self.state.after_predict(dofs);
        self.state.t = t0 + self.h;
        if let Some(before) = &before {
            self.asm.latch_events(&mut self.state, before);
        }
        let second = newton(self.asm, &mut self.state, Update::Dynamic { dcoef: b0, form }, &self.settings, &mut self.workspace)?;
        self.rebase_converged();
        self.previous = Some(start);
        self.accepted += 1;
        Ok(StepRecord { t: self.state.t, iterations: first.iterations + second.iterations, residual_norm: second.residual_norm })
    }
}

/// Initial derivatives as MBDyn's derivatives phase computes them (stepsol.cc,
/// `DerivativeSolver`): Newton with dCoef = `dcoef` for the momenta's derivatives and the
/// multipliers, every node's position, orientation, velocity and angular velocity held as
/// given, the momenta from their definitions at those velocities
/// ([`DerivativeMomenta::FromDefinitions`]). Constraint rows and the equilibrium of static
/// nodes therefore must already hold to the tolerance.
pub fn initial_derivatives_with(asm: &Assembler, st: &mut State, settings: &NewtonSettings, dcoef: f64) -> Result<Convergence, NewtonFailure> {
    initial_derivatives_in(asm, st, settings, dcoef, DerivativeMomenta::FromDefinitions, &mut NewtonWorkspace::new())
}

/// The derivatives phase with the momenta left as `momenta` says (MBDyn's files:
/// [`DerivativeMomenta::AsNewton`]), in a given Newton workspace, which keeps its sparsity
/// pattern and factorization for the steps that follow ([`Integrator::with_workspace`]).
/// The momenta start from their definitions at the given velocities, as MBDyn's bodies set
/// them (body.cc, `SetValue`).
pub fn initial_derivatives_in(asm: &Assembler, st: &mut State, settings: &NewtonSettings, dcoef: f64, momenta: DerivativeMomenta, workspace: &mut NewtonWorkspace) -> Result<Convergence, NewtonFailure> {
    let form = asm.model.constraint_form;
    if asm.has_events() {
        // The events at the initial time (MBDyn's derivatives phase assembles the residual
        // there first: a bistop law whose activating drive is already non-zero activates).
        let before = st.clone();
        asm.latch_events(st, &before);
    }
    momenta_from_definitions(asm, st, form);
    newton(asm, st, Update::Derivatives { dcoef, form, momenta }, settings, workspace)
}

/// The largest change of a node's velocity that its momenta imply, with its name ("node 3
/// velocity x", "node 3 angular velocity parameter z"), in m/s or (for the orientation
/// parameters' rates, ≈ angular velocity) rad/s. The steps integrate momenta, not
/// velocities: momenta off their definitions `p(v)` at the state's velocities (what MBDyn's
/// derivatives phase leaves, [`DerivativeMomenta::AsNewton`]) start the motion as from
/// velocities `v + δ` with `p(v + δ) = p`, i.e. `δ = −B⁻¹ r` per dynamic node, `r` its six
/// momentum-definition residuals and `B = ∂r/∂v̇-part` their (affine) dependence on its six
/// velocity unknowns, measured by unit changes of those. Directions without inertia (a point
/// mass's rotations) are left out (least-squares solution of `B`).
pub fn momentum_velocity_change(asm: &Assembler, st: &State) -> Option<(String, f64)> {
    let dofs = &asm.dofs;
    let form = asm.model.constraint_form;
    let dynamic: Vec<usize> = (0..dofs.node_first.len()).filter(|&i| dofs.node_kind[i] == NodeKind::Dynamic).collect();
    if dynamic.is_empty() {
        return None;
    }
    let r0 = asm.residual(st, form, 1.0);
    let mut blocks = vec![nalgebra::Matrix6::<f64>::zeros(); dynamic.len()];
    for k in 0..6 {
        let mut moved = st.clone();
        for &i in &dynamic {
            moved.yp[dofs.node_first[i] + k] += 1.0;
        }
        let r = asm.residual(&moved, form, 1.0);
        for (b, &i) in blocks.iter_mut().zip(&dynamic) {
            let f = dofs.node_first[i];
            for row in 0..6 {
                b[(row, k)] = r[f + row] - r0[f + row];
            }
        }
    }
    const NAMES: [&str; 6] = ["velocity x", "velocity y", "velocity z", "angular velocity parameter x", "angular velocity parameter y", "angular velocity parameter z"];
    let mut worst: Option<(String, f64)> = None;
    for (b, &i) in blocks.iter().zip(&dynamic) {
        let f = dofs.node_first[i];
        let r = nalgebra::Vector6::from_iterator((0..6).map(|row| r0[f + row]));
        if r.iter().all(|&x| x == 0.0) {
            continue;
        }
        let svd = b.svd(true, true);
        let eps = 1e-12 * svd.singular_values.max();
        let Ok(delta) = svd.solve(&r, eps) else { continue };
        for (k, d) in (-delta).iter().enumerate() {
            if worst.as_ref().is_none_or(|(_, w)| d.abs() > w.abs()) {
                worst = Some((format!("node {} {}", asm.model.nodes[i].label, NAMES[k]), *d));
            }
        }
    }
    worst
}

/// [`initial_derivatives_with`] at dCoef = 1e-6 s · 1e-3 (MBDyn's default derivatives
/// coefficient times a 1 ms step).
pub fn initial_derivatives(asm: &Assembler, st: &mut State, settings: &NewtonSettings) -> Result<Convergence, NewtonFailure> {
    initial_derivatives_with(asm, st, settings, 1e-9)
}

/// The largest rate of change of a constraint, `max |Φ_/q q̇ + Φ_/t|`, at the state's
/// positions and velocities (and differential scalar nodes' values and derivatives), with
/// the equation's name: non-zero when the velocities written in a file do not satisfy the
/// joints (the first step then changes them). The derivative of `Φ(q + s q̇, t + s)` at
/// `s = 0` is taken one-sided, forward in time (a drive may start with a kink at the
/// initial time), by [`forward_derivatives`]. A velocity-level constraint's own value
/// `ψ(q, q̇, t)` is its violation.
pub fn constraint_rate(asm: &Assembler, st: &State) -> Option<(String, f64)> {
    let dofs = &asm.dofs;
    let moved = |s: f64| {
        let mut m = st.clone();
        // `s` is a representable step from `st.t` (forward_derivatives).
        for &f in &dofs.node_first {
            for i in f..f + 6 {
                m.y[i] += s * st.yp[i];
            }
        }
        for i in (0..dofs.len).filter(|&i| dofs.is_coordinate(i)) {
            m.y[i] += s * st.yp[i];
        }
        // A differential scalar node's value (a pressure, a capacitor's voltage) moves with
        // its derivative too: a clamp driving it along a ramp is then satisfied.
        for (k, _) in dofs.scalar_differential.iter().enumerate().filter(|(_, d)| **d) {
            let i = dofs.scalar_first + k;
            m.y[i] += s * st.yp[i];
        }
        m.t += s;
        asm.residual(&m, ConstraintForm::Plain, 1.0)
    };
    let now = asm.residual(st, ConstraintForm::Plain, 1.0);
    let own = dofs.element_first.iter().zip(&dofs.element_len).flat_map(|(&f, &k)| f..f + k);
    let velocity = own.filter(|&i| !dofs.is_multiplier(i) && !dofs.is_coordinate(i) && !dofs.is_state(i)).map(|i| (i, now[i]));
    // A constraint of an element that reads an algebraic scalar node (a clamp driving a
    // pressure node) is kept at every instant by that node's value, which has no derivative
    // of its own to move with: its rate is the drive's, not a violation.
    let algebraic_scalar = |e: usize| dofs.element_scalars[e].iter().any(|&k| dofs.scalar_differential.get(k) == Some(&false));
    let reads_algebraic = |i: usize| matches!(dofs.owner(i), Owner::Element { index, .. } if algebraic_scalar(index));
    let rows: Vec<usize> = (0..dofs.len).filter(|&i| dofs.is_multiplier(i) && !reads_algebraic(i)).collect();
    let rates = forward_derivatives(&rows, st.t, &now, moved);
    rows.into_iter().zip(rates).chain(velocity.filter(|&(i, _)| !reads_algebraic(i))).fold(None, |best: Option<(usize, f64)>, (i, v)| match best {
        Some((_, b)) if b.abs() >= v.abs() => best,
        _ => Some((i, v)),
    }).map(|(i, v)| (dofs.equation_name(asm.model, i), v))
}

#[cfg(test)]
mod tests {
    use super::Predictor;

    #[test]
    fn cubic_hermite_predictor_is_exact_for_cubics() {
        // v(t) = a + b t + c t² + d t³ with u = v̇, steps at t = −2h, −h, predicting u(0):
        // closed form u(0) = b.
        let (a, b, c, d, h) = (0.3, -1.7, 2.9, 4.1, 1e-3);
        let v = |t: f64| a + b * t + c * t * t + d * t * t * t;
        let u = |t: f64| b + 2.0 * c * t + 3.0 * d * t * t;
        let p = Predictor::CubicHermite { h };
        let predicted = p.derivative(u(-h), u(-2.0 * h), v(-h) - v(-2.0 * h));
        assert!((predicted - b).abs() < 1e-9, "{predicted} against {b}");
        assert_eq!(Predictor::Constant.derivative(2.0, 5.0, 1.0), 2.0);

        // Bathe's second predictor through (−γh, v, u) and (0, v, u), extrapolating u to
        // (1 − γ)h: exact for cubics (t measured from the first sub-step's time).
        for rho in [0.0, 0.3, 0.6, 1.0] {
            let c = super::BatheCoefficients::new(rho, h);
            let g = c.gamma * h;
            let [m0, n0, n1] = c.predictor;
            let predicted = m0 * (v(0.0) - v(-g)) + n0 * u(0.0) + n1 * u(-g);
            let exact = u(h - g);
            assert!((predicted - exact).abs() < 1e-9 * exact.abs().max(1.0), "ρ = {rho}: {predicted} against {exact}");
        }
        assert_eq!(Predictor::Linear.derivative(2.0, 5.0, 1.0), -1.0);
    }
}
