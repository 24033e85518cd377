//! Newton's method on `F = 0` with `J δ = −F` (eq. 5), sparse LU with symbolic reuse.

use crate::dae::{Assembler, Coefficients, Frames, SparseLu, State, Triplets};
use crate::model::ConstraintForm;
use crate::model::{NodeKind, ResidualNorm};

/// Convergence settings (residual in the units of each equation: N, N m, kg m/s, m).
#[derive(Clone, Copy, Debug)]
pub struct NewtonSettings {
    /// Converged when `‖F‖ ≤ tolerance` (the norm is `norm`) …
    pub tolerance: f64,
    pub norm: ResidualNorm,
    /// … or when the increment `‖δ‖∞ ≤ increment_tolerance` with `‖F‖∞ ≤ 1e3 · tolerance`
    /// (never when 0: MBDyn's default test of the residual alone).
    pub increment_tolerance: f64,
    pub max_iterations: usize,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings { tolerance: 1e-9, norm: ResidualNorm::Max, increment_tolerance: 1e-12, max_iterations: 20 }
    }
}

/// How the unknowns move with a Newton increment δ.
#[derive(Clone, Copy, Debug)]
pub enum Update {
    /// `y += δ` (static analysis, `J = F_/y`).
    Static,
    /// `ẏ += δ`, `y += c δ` (multipliers of eq. 30: `y += δ`), `J = J(c)`.
    Dynamic { dcoef: f64, form: ConstraintForm },
    /// As `Dynamic`, then every node's position, orientation parameters and their
    /// derivatives are put back to their values at entry: MBDyn's derivatives phase solves
    /// for momenta, their derivatives and the multipliers only (strnode.cc,
    /// `StructNode::DerivativesUpdate`: "forza configurazione e velocita' al valore
    /// iniziale"). What the momenta keep is `momenta`.
    Derivatives { dcoef: f64, form: ConstraintForm, momenta: DerivativeMomenta },
}

/// What the derivatives phase leaves in the momenta.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DerivativeMomenta {
    /// Newton's values, `p = p(v) + dCoef Σ δṗ` (stepsol.cc, `DerivativeSolver::UpdateDof`:
    /// a differential unknown moves by dCoef times its derivative's increment, and only the
    /// nodes' kinematics are put back): MBDyn's. Off their definitions `p(v)` at the held
    /// velocities by about dCoef times the node's force, a residual the iteration cannot
    /// reduce (it fails where that exceeds the tolerance, as MBDyn does), and the steps
    /// integrate the momenta: the motion is as from velocities changed by about dCoef times
    /// the accelerations (see [`crate::solve::momentum_velocity_change`]).
    AsNewton,
    /// Set from their definitions at the held velocities after every iteration, so that the
    /// motion starts from the velocities as given: romdyn's own, for models built in Rust.
    FromDefinitions,
}

/// A Newton iteration that did not converge.
#[derive(Clone, Debug, thiserror::Error)]
#[error("Newton failed at t = {time} s, iteration {iteration}: residual norm {residual_norm:.3e}; worst equation: {worst_equation} ({worst_value:.3e}){}", .reason.as_deref().map(|r| format!("; {r}")).unwrap_or_default())]
pub struct NewtonFailure {
    pub time: f64,
    pub iteration: usize,
    pub residual_norm: f64,
    pub worst_equation: String,
    pub worst_value: f64,
    pub reason: Option<String>,
    /// Whether an iteration met a singular Jacobian (and took a regularized step): a model
    /// no coefficient or tolerance makes solvable, typically an unconnected unknown.
    pub singular: bool,
}

/// A converged Newton iteration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Convergence {
    pub iterations: usize,
    /// `‖F‖∞` at the last residual evaluation (before the last update when the increment
    /// test converged), in the units of the worst equation.
    pub residual_norm: f64,
}

/// Solver errors.
#[derive(Clone, Debug, thiserror::Error)]
pub enum SolveError {
    #[error(transparent)]
    Newton(#[from] NewtonFailure),
}

fn worst(f: &[f64]) -> (usize, f64) {
    f.iter().enumerate().fold((0, 0.0), |(bi, bv), (i, &v)| if v.abs() > bv || v.is_nan() { (i, v.abs()) } else { (bi, bv) })
}

/// Largest orientation-parameter change allowed in one static iteration (|δg| ≈ rotation
/// in rad for small steps): longer steps, typical far from equilibrium, are shortened.
const MAX_STATIC_ROTATION_STEP: f64 = 0.5;

fn limit_rotation_step(asm: &Assembler, delta: &mut [f64]) {
    let dofs = &asm.dofs;
    let largest = dofs.node_first.iter().flat_map(|&f| delta[f + 3..f + 6].iter()).fold(0.0f64, |m, x| m.max(x.abs()));
    if largest > MAX_STATIC_ROTATION_STEP {
        let s = MAX_STATIC_ROTATION_STEP / largest;
        delta.iter_mut().for_each(|x| *x *= s);
    }
}

/// How many of the last iterates a failure looks at for kinks they cross: three suffice
/// for a cycle of two or three iterates.
const KINK_ITERATES: usize = 4;

/// Why Newton's last iterates may cycle: the points where an element's residual is not
/// differentiable ([`crate::element::Element::kink_crossed`]) that consecutive iterates
/// cross, each element once. Newton on a piecewise smooth residual can jump from one side
/// of such a point to the other without converging on either (the modlugre friction's
/// multilinear `μ(|v|)` at its kink, tests/multibody/joint_friction.rs).
fn kinks_crossed(asm: &Assembler, iterates: &[State]) -> Option<String> {
    let mut named: Vec<String> = Vec::new();
    for (a, b) in iterates.iter().zip(iterates.iter().skip(1)) {
        for why in asm.kinks_crossed(a, b) {
            let element = why.split(':').next().unwrap_or_default().to_string();
            if !named.iter().any(|n| n.split(':').next() == Some(&element)) {
                named.push(why);
            }
        }
    }
    (!named.is_empty()).then(|| {
        format!("its last {} iterates cross a point where the residual is not differentiable, across which Newton's iterates can cycle instead of converging: {}; a smaller `time step` starts each step's Newton closer to its solution", iterates.len(), named.join("; "))
    })
}

/// What Newton keeps from one iteration (and one step) to the next: the sparse LU with its
/// symbolic factorization, and the Jacobian's storage.
pub struct NewtonWorkspace {
    pub lu: SparseLu,
    jacobian: Triplets,
    /// The Jacobian's values alone, when the LU knows its pattern
    /// ([`Assembler::jacobian_values_at`]).
    values: Vec<f64>,
    /// The node frames of the iterate, computed once for its residual and its Jacobian.
    frames: Frames,
    /// Whether `frames` are those of the solution the last Newton iteration returned (it
    /// converged on the residual of that very state).
    frames_of_solution: bool,
    /// When a time step's Newton iteration keeps its Jacobian's factorization for the next
    /// iteration (MBDyn's `modified` Newton–Raphson, with its reuse decided by convergence):
    /// when the residual norm fell to at most this fraction of the previous iteration's.
    /// Each step's first iteration factors anew, and so does any iteration after one whose
    /// residual fell less; the static analysis and the derivatives phase always do. `0`:
    /// every iteration factors anew (full Newton, the default, as MBDyn's default
    /// `newton raphson`); `romdyn run` sets [`KEEP_JACOBIAN_BELOW`] when the file asks for
    /// `nonlinear solver: newton raphson, modified, …`.
    pub keep_jacobian_below: f64,
    /// Iterations that reused a factorization, and those that assembled and factored a
    /// Jacobian, since the workspace was made.
    pub reused: usize,
    pub factored: usize,
}

/// [`NewtonWorkspace::keep_jacobian_below`] of MBDyn's `modified` Newton–Raphson.
pub const KEEP_JACOBIAN_BELOW: f64 = 0.1;

impl Default for NewtonWorkspace {
    fn default() -> Self {
        NewtonWorkspace { lu: SparseLu::default(), jacobian: Triplets::default(), values: Vec::new(), frames: Frames::default(), frames_of_solution: false, keep_jacobian_below: 0.0, reused: 0, factored: 0 }
    }
}

impl NewtonWorkspace {
    pub fn new() -> Self {
        Self::default()
    }

    /// The node frames of the state the last [`newton`] returned, when it converged on that
    /// state's residual (not after a last increment): a time step re-bases with them.
    pub fn frames_of_solution(&self) -> Option<&Frames> {
        self.frames_of_solution.then_some(&self.frames)
    }
}

/// Sets each dynamic node's momenta so that its momentum definition rows vanish (they read
/// `β − Σ(…)`, linear in β and γ with unit coefficients), and the elements' momenta
/// ([`crate::element::Element::momentum_unknowns`]) likewise.
pub fn momenta_from_definitions(asm: &Assembler, st: &mut State, form: ConstraintForm) {
    let dofs = &asm.dofs;
    let r = asm.residual(st, form, 1.0);
    for i in 0..dofs.node_first.len() {
        if dofs.node_kind[i] == NodeKind::Dynamic {
            let f = dofs.node_first[i];
            for k in 0..6 {
                st.y[f + 6 + k] -= r[f + k];
            }
        }
    }
    for (e, element) in asm.model.elements.iter().enumerate() {
        for k in element.momentum_unknowns() {
            let j = dofs.element_first[e] + k;
            st.y[j] -= r[j];
        }
    }
}

/// How Newton's residual norm went, for a failure: diverged (it grew a thousandfold past
/// its smallest, or ended not finite), still falling at its last iteration (the iterations
/// ran out), or stalled above the tolerance, with the norms by iteration (the first two
/// and the last four when there are more than eight).
fn norm_history(norms: &[f64], tolerance: f64) -> String {
    let smallest = norms.iter().copied().filter(|x| x.is_finite()).fold(f64::INFINITY, f64::min);
    let last = norms.last().copied().unwrap_or(f64::NAN);
    let shown: Vec<String> = norms.iter().enumerate().map(|(k, x)| format!("{k}: {x:.1e}")).collect();
    let shown = if shown.len() > 8 { format!("{}, …, {}", shown[..2].join(", "), shown[shown.len() - 4..].join(", ")) } else { shown.join(", ") };
    if !last.is_finite() || last > 1e3 * smallest {
        format!("the iterates diverged (residual norm by iteration {shown})")
    } else if last <= smallest {
        format!("the residual norm was still falling, above the tolerance {tolerance:.1e}, when the iterations ran out (by iteration {shown})")
    } else {
        format!("the residual norm stalled above the tolerance {tolerance:.1e} (by iteration {shown})")
    }
}

/// Assembles `J` at `st` (whose node frames are `ws.frames`) into the workspace, factors it
/// and solves `J δ = f` in place (`f` holds `−F`, `residual` `F`): the values alone when the
/// LU knows their pattern, triplets otherwise. A singular Jacobian is named in `singular`
/// and one regularized step is taken; `Err` with the reason when even that fails.
#[allow(clippy::too_many_arguments)]
fn factor_and_solve(asm: &Assembler, st: &State, update: Update, coef: Coefficients, ws: &mut NewtonWorkspace, f: &mut Vec<f64>, residual: &[f64], singular: &std::cell::RefCell<Option<String>>, met_singular: &std::cell::Cell<bool>) -> Result<(), String> {
    if matches!(update, Update::Derivatives { .. }) {
        // The positions are held here, so a holonomic row's value `Φ(q)/c` is not this
        // phase's to correct: left in the right-hand side, a rounding-level violation
        // becomes an acceleration `Φ/c²` in the constraint's direction (`0.05 − 1 + 0.95`
        // = 4.2e-17 m of a hinge offset at c = 1e-9 s: 41.6 N in a blade's momentum
        // derivative, its pendulum mode 14.1 rad/s after one step instead of 18.18).
        // The increments then satisfy `Φ_/q δq̇ = 0`: accelerations consistent with the
        // constraints at the velocities given.
        for (i, x) in f.iter_mut().enumerate() {
            if asm.dofs.is_multiplier(i) {
                *x = 0.0;
            }
        }
    }
    let by_values = if ws.lu.knows_shape() {
        let shape = asm.jacobian_values_at(st, &ws.frames, coef, &mut ws.values);
        ws.lu.solve_values(asm.dofs.len, &ws.values, shape, f)
    } else {
        Ok(false)
    };
    let solved = match by_values {
        Ok(true) => Ok(()),
        Ok(false) => {
            asm.jacobian_at(st, &ws.frames, coef, &mut ws.jacobian);
            ws.lu.solve(&ws.jacobian, f)
        }
        Err(e) => {
            // The triplets, for the explanation and the regularized step below.
            asm.jacobian_at(st, &ws.frames, coef, &mut ws.jacobian);
            Err(e)
        }
    };
    if solved.is_err() {
        let j = &mut ws.jacobian;
        met_singular.set(true);
        if singular.borrow().is_none() {
            *singular.borrow_mut() = super::singular::explain_singular_matrix(asm, j);
        }
        // A singular Jacobian, typically at the first static iteration where stiffness
        // comes only from joint reactions that are still zero: take one regularized
        // step, `(J + μ I) δ = −F` with μ a small fraction of the largest entry.
        let mu = 1e-6 * j.values.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1.0);
        for i in 0..j.n {
            j.push(i, i, mu);
        }
        *f = residual.iter().map(|x| -x).collect();
        let mut regularized = SparseLu::new();
        regularized.solve(j, f).map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Iterates to convergence.
pub fn newton(asm: &Assembler, st: &mut State, update: Update, settings: &NewtonSettings, ws: &mut NewtonWorkspace) -> Result<Convergence, NewtonFailure> {
    let (coef, form, dcoef) = match update {
        Update::Static => (Coefficients::static_analysis(), ConstraintForm::Plain, 1.0),
        Update::Dynamic { dcoef, form } | Update::Derivatives { dcoef, form, .. } => (Coefficients::newton(dcoef, form), form, dcoef),
    };
    // Node unknowns x, g and their derivatives, held by the derivatives phase.
    let held: Vec<(usize, f64, f64)> = match update {
        Update::Derivatives { .. } => asm.dofs.node_first.iter().flat_map(|&f| (f..f + 6).map(|i| (i, st.y[i], st.yp[i]))).collect(),
        _ => Vec::new(),
    };
    ws.frames_of_solution = false;
    if !matches!(update, Update::Static) {
        ws.lu.eliminating(&asm.dofs.momentum_pairs());
    }
    let measure = |f: &[f64]| match settings.norm {
        ResidualNorm::Max => worst(f).1,
        ResidualNorm::Euclidean => f.iter().map(|x| x * x).sum::<f64>().sqrt(),
    };
    // Why the matrix was singular, when an iteration found it so (named in a failure).
    let singular: std::cell::RefCell<Option<String>> = Default::default();
    let met_singular = std::cell::Cell::new(false);
    let fail = |st: &State, iteration, f: &[f64], reason: Option<String>| {
        let (i, _) = worst(f);
        let reason = [reason, singular.borrow().clone()].into_iter().flatten().reduce(|a, b| format!("{a}; {b}"));
        NewtonFailure { time: st.t, iteration, residual_norm: measure(f), worst_equation: asm.dofs.equation_name(asm.model, i), worst_value: f[i], reason, singular: met_singular.get() }
    };
    // The last iterates, kept for a failure to name the kinks they cross (see below), and
    // every iteration's residual norm, for a failure to say how Newton went.
    let mut last_iterates: Vec<State> = Vec::new();
    let mut norms: Vec<f64> = Vec::new();
    for iteration in 0..=settings.max_iterations {
        if iteration + KINK_ITERATES > settings.max_iterations {
            last_iterates.push(st.clone());
        }
        asm.frames_into(st, &mut ws.frames);
        let mut f = asm.residual_at(st, &ws.frames, form, dcoef);
        // The derivatives phase holds the positions, so it judges a holonomic row by the
        // violation `Φ` itself, not `Φ/c`: at MBDyn's `derivatives coefficient: 1e-10`
        // (c = 1e-13 s) a hinge offset's 4.2e-17 m of rounding reads 4.2e-4 and no iteration
        // could reduce it. A violation above the tolerance still stops it, named by `Φ`.
        let judged: std::borrow::Cow<[f64]> = match update {
            Update::Derivatives { .. } if form == ConstraintForm::Scaled => f.iter().enumerate().map(|(i, &x)| if asm.dofs.is_multiplier(i) { x * dcoef } else { x }).collect(),
            _ => std::borrow::Cow::Borrowed(&f),
        };
        let norm = measure(&judged);
        norms.push(norm);
        if norm <= settings.tolerance {
            ws.frames_of_solution = held.is_empty();
            return Ok(Convergence { iterations: iteration, residual_norm: norm });
        }
        if !norm.is_finite() || iteration == settings.max_iterations {
            // A drive whose value failed names itself and where it is written (issue 32).
            let not_finite = || match asm.element_failures(st).into_iter().chain(crate::element::drive::take_evaluation_failure(st.t)).collect::<Vec<_>>() {
                why if why.is_empty() => "the residual is not finite".to_string(),
                why => format!("the residual is not finite: {}", why.join("; ")),
            };
            let reason = if norm.is_finite() { kinks_crossed(asm, &last_iterates) } else { Some(not_finite()) };
            let history = Some(norm_history(&norms, settings.tolerance));
            return Err(fail(st, iteration, &judged, [reason, history].into_iter().flatten().reduce(|a, b| format!("{a}; {b}"))));
        }
        drop(judged);
        let residual = f.clone();
        for x in f.iter_mut() {
            *x = -*x;
        }
        // A time step's iteration whose residual fell fast keeps the last factorization (the
        // Jacobian moved only with that iteration's small correction): no assembly, no
        // factorization, the solve alone. Otherwise, and whenever there is no factorization
        // to keep, a fresh Jacobian.
        let keep = matches!(update, Update::Dynamic { .. }) && iteration > 0 && norms[iteration] <= ws.keep_jacobian_below * norms[iteration - 1];
        let kept = keep && matches!(ws.lu.solve_again(&mut f), Ok(true));
        if kept {
            ws.reused += 1;
        } else {
            if keep {
                // A failed reuse may have written into f.
                f = residual.iter().map(|x| -x).collect();
            }
            ws.factored += 1;
            factor_and_solve(asm, st, update, coef, ws, &mut f, &residual, &singular, &met_singular).map_err(|e| fail(st, iteration, &residual, Some(e)))?;
        }
        if let Update::Static = update {
            limit_rotation_step(asm, &mut f);
        }
        let step = f.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (i, d) in f.iter().enumerate() {
            match update {
                Update::Static => st.y[i] += d,
                Update::Dynamic { dcoef, form } | Update::Derivatives { dcoef, form, .. } => {
                    if form == ConstraintForm::Scaled && asm.dofs.is_multiplier(i) {
                        st.y[i] += d;
                    } else {
                        st.yp[i] += d;
                        st.y[i] += dcoef * d;
                    }
                }
            }
        }
        if !held.is_empty() {
            for &(i, y, yp) in &held {
                st.y[i] = y;
                st.yp[i] = yp;
            }
            if matches!(update, Update::Derivatives { momenta: DerivativeMomenta::FromDefinitions, .. }) {
                momenta_from_definitions(asm, st, form);
            }
        }
        if held.is_empty() && settings.increment_tolerance > 0.0 && step <= settings.increment_tolerance && norm <= 1e3 * settings.tolerance {
            return Ok(Convergence { iterations: iteration + 1, residual_norm: norm });
        }
    }
    unreachable!("the loop returns by max_iterations")
}
