//! The run driver: what MBDyn's `initial value` problem does (manual, "Initial-Value
//! Problem"). Consistent initial derivatives at the initial time, then fixed steps of the
//! file's method until the final time; an eigenanalysis at the first solution whose time
//! reaches each requested time (at the initial time: after the derivatives).
//!
//! `abort after: input` or `assembly` stops before the derivatives, `derivatives` or
//! `dummy steps` right after them (no eigenanalysis, as in MBDyn). A final time equal to the
//! initial time runs the derivatives and the eigenanalyses at the initial time.

use std::time::{Duration, Instant};

use faer::c64;

use crate::limits::readable;

use super::eigen::{check_request, Eigenanalysis};
use super::error::{ObserverError, RunError};
use super::observer::{Derivatives, EigenDone, RunObserver, RunStart, StepDone};
use crate::dae::{Assembler, State};
use crate::eigen::ModeKind;
use crate::model::{AbortAfter, EigenSolverRequest, InitialValueProblem, Method, Model};
use crate::solve::{constraint_rate, initial_assembly, initial_derivatives_in, momentum_velocity_change, AssemblyReport, DerivativeMomenta, Integrator, NewtonSettings, NewtonWorkspace};


/// One eigenanalysis in the report.
#[derive(Clone, Debug)]
pub struct EigenSummary {
    pub index: usize,
    /// [s]
    pub time: f64,
    /// [s]
    pub dcoef: f64,
    pub dynamic: Vec<c64>,
    pub zero: usize,
    pub infinite: usize,
    /// Elements at a point where their residual is not differentiable (the linearization
    /// took a one-sided derivative there), with why.
    pub non_smooth: Vec<String>,
    /// Elements whose linearization depends on the values of reaction multipliers (a
    /// friction force proportional to a normal reaction), with why: the eigenvalues carry
    /// the multipliers' integration noise (`Element::reaction_dependence`).
    pub reaction_dependent: Vec<String>,
    /// How the modes were computed (dense: every eigenvalue; sparse: the lowest modes).
    pub solver: String,
    /// Every eigenvalue was computed (the dense route): the zero and infinite counts hold.
    pub every_eigenvalue: bool,
    /// The sparse route's modes are not certified: why.
    pub not_certified: Option<String>,
}

/// What a run did.
#[derive(Clone, Debug)]
pub struct RunReport {
    pub steps: usize,
    /// Newton iterations of the time steps.
    pub newton_iterations: usize,
    /// Newton iterations of the initial derivatives.
    pub derivatives_iterations: usize,
    /// Newton iterations (derivatives and steps) that assembled and factored a Jacobian;
    /// the others solved with the last factorization (MBDyn's `modified` Newton–Raphson,
    /// [`crate::solve::NewtonWorkspace::keep_jacobian_below`]).
    pub factorizations: usize,
    pub wall_time: Duration,
    pub eigenanalyses: Vec<EigenSummary>,
    /// What MBDyn's initial assembly changed.
    pub assembly: AssemblyReport,
    /// The joint whose constraint the initial velocities violate most, and the rate
    /// `Φ_/q q̇` [m/s or rad/s], when it exceeds the tolerance: the velocities written in the
    /// file are not consistent, and the first step changes them (as in MBDyn).
    pub inconsistent_velocity: Option<(String, f64)>,
    /// The largest change of a written velocity that the momenta left by the derivatives
    /// phase imply, with its name, [m/s or rad/s], when it exceeds the tolerance: MBDyn's
    /// derivatives phase keeps Newton's momenta, about dCoef times the node's force off
    /// their definitions, and the steps start from the momenta (as in MBDyn).
    pub momentum_velocity_change: Option<(String, f64)>,
    /// Why the derivatives phase did not converge with MBDyn's momenta (Newton's, kept), when
    /// it then converged with the momenta set from their definitions (romdyn's): the
    /// residual dCoef·ṗ they leave stayed above the derivatives tolerance at every
    /// coefficient tried, where MBDyn stops (or, with `auto`, raises its tolerance).
    pub mbdyn_momenta_failure: Option<String>,
    /// With `derivatives coefficient: auto`, when no coefficient converged: the coefficient
    /// dCoef [s] of the smallest residual and the derivatives tolerance raised to 1.01 times
    /// that residual, with which the derivatives were accepted as MBDyn accepts them
    /// (stepsol.cc, `DerivativeSolver::Advance`: "choose those coefficient with smallest
    /// residual error and increase the tolerance, so it will converge in any case").
    pub derivatives_tolerance_raised: Option<(f64, f64)>,
    /// Without `derivatives coefficient: auto`, when the derivatives phase did not converge
    /// at the file's coefficient either way (MBDyn's momenta, romdyn's): that failure, after
    /// which the coefficients of MBDyn's `auto` were tried in turn (and, if none converged,
    /// its last chance, `derivatives_tolerance_raised`). MBDyn's own iteration may take
    /// another path there: it starts a beam slider's abscissa at its initial node, romdyn at
    /// the line's point nearest the slider.
    pub derivatives_auto_fallback: Option<String>,
    /// Requested eigenanalysis times the run did not reach [s].
    pub eigen_times_not_reached: Vec<f64>,
    pub final_state: State,
}

/// Steps from the initial to the final time as MBDyn counts them: it adds the step to the
/// time until the sum reaches the final time (solver.cc, `Solver::Advance`: `dTime >=
/// dFinalTime`), so the rounding of that sum decides the last step (ten steps of 0.01 s sum
/// to 0.09999999999999999 s, and MBDyn takes an eleventh). Runs longer than 1e8 steps are
/// counted without the sum: the first `k` with `t₀ + k h ≥ t_f`.
fn step_count(p: &InitialValueProblem) -> usize {
    let n = (p.final_time - p.initial_time) / p.time_step;
    if !(n > 0.0) {
        return 0;
    }
    if n > 1e8 {
        return (n - 1e-6).ceil() as usize;
    }
    let (mut t, mut k) = (p.initial_time, 0usize);
    while t < p.final_time {
        t += p.time_step;
        k += 1;
    }
    k
}

fn validate(p: &InitialValueProblem) -> Result<(), RunError> {
    let bad = |m: String| Err(RunError::Problem(m));
    if !(p.time_step > 0.0 && p.time_step.is_finite()) {
        return bad(format!("time step {} s must be positive", p.time_step));
    }
    if !(p.initial_time.is_finite() && p.final_time.is_finite()) || p.final_time < p.initial_time {
        return bad(format!("final time {} s must not be before initial time {} s", p.final_time, p.initial_time));
    }
    // Steps are counted before the run: a final time of 1e308 s or a step of 1e-300 s
    // would never end (and fill the disk with output).
    let steps = (p.final_time - p.initial_time) / p.time_step;
    if !(steps <= crate::limits::MAX_TIME_STEPS) {
        return bad(format!(
            "from initial time {} s to final time {} s with time step {} s is {} steps, more than romdyn's limit of {:e} steps per run",
            readable(p.initial_time),
            readable(p.final_time),
            readable(p.time_step),
            readable(steps.round()),
            crate::limits::MAX_TIME_STEPS
        ));
    }
    let end = p.initial_time.abs().max(p.final_time.abs());
    if end + p.time_step == end {
        return bad(format!("time step {} s is below the resolution of the time {end} s: the time would not advance", p.time_step));
    }
    if let Some(t) = p.eigenanalysis.as_ref().and_then(|r| r.times.iter().copied().find(|t| !(*t >= p.initial_time))) {
        return bad(format!("eigenanalysis time {t} s is before the initial time {} s", p.initial_time));
    }
    if !(p.tolerance > 0.0) || !(p.derivatives_tolerance > 0.0) {
        return bad(format!("tolerances must be positive (tolerance {}, derivatives tolerance {})", p.tolerance, p.derivatives_tolerance));
    }
    if let Some(c) = p.eigenanalysis.as_ref().and_then(|r| r.dcoef).filter(|c| !(*c > 0.0 && c.is_finite())) {
        return bad(format!("eigenanalysis coefficient dCoef = {c} s must be positive"));
    }
    Ok(())
}

/// A step event: `(iterations, residual_norm)` of the Newton iteration that produced `state`.
fn step_done<'a>(asm: &'a Assembler, step: usize, time_step: f64, (iterations, residual_norm): (usize, f64), state: &'a State) -> StepDone<'a> {
    StepDone { step, time: state.t, time_step, iterations, residual_norm, model: asm.model, assembler: asm, state }
}

/// Runs `problem` on `model`, reporting every event to `observer`.
pub fn run(model: &Model, problem: &InitialValueProblem, observer: &mut dyn RunObserver) -> Result<RunReport, RunError> {
    validate(problem)?;
    if let Some(request) = &problem.eigenanalysis
        && let Some(&time) = request.times.first()
    {
        check_request(model, request).map_err(|message| RunError::Eigen { index: 0, time, message })?;
    }
    let clock = Instant::now();
    let observed = |r: Result<(), ObserverError>| r.map_err(RunError::Observer);
    let asm = Assembler::new(model);
    // A model run again starts its step drives from their initial memory.
    for d in &model.step_drives {
        d.reset();
    }
    let mut state = State::initial(model, &asm.dofs);
    state.t = problem.initial_time;
    let assembly = if problem.abort_after == Some(AbortAfter::Input) { AssemblyReport::default() } else { initial_assembly(model, &mut state, &problem.assembly).map_err(RunError::Assembly)? };
    let steps = step_count(problem);
    let times: &[f64] = problem.eigenanalysis.as_ref().map_or(&[], |r| &r.times);
    observed(observer.started(&RunStart { model, problem, steps, eigenanalyses: times.len() }))?;
    let mut report = RunReport {
        steps: 0,
        newton_iterations: 0,
        derivatives_iterations: 0,
        factorizations: 0,
        wall_time: Duration::ZERO,
        eigenanalyses: Vec::new(),
        assembly,
        inconsistent_velocity: None,
        momentum_velocity_change: None,
        mbdyn_momenta_failure: None,
        derivatives_tolerance_raised: None,
        derivatives_auto_fallback: None,
        eigen_times_not_reached: times.to_vec(),
        final_state: state.clone(),
    };
    if matches!(problem.abort_after, Some(AbortAfter::Input | AbortAfter::Assembly)) {
        observed(observer.step(&step_done(&asm, 0, problem.time_step, (0, f64::NAN), &state)))?;
        report.wall_time = clock.elapsed();
        return Ok(report);
    }

    let derivative_settings = NewtonSettings { tolerance: problem.derivatives_tolerance, norm: problem.residual_norm, increment_tolerance: problem.increment_tolerance, max_iterations: problem.derivatives_max_iterations };
    report.inconsistent_velocity = constraint_rate(&asm, &state).filter(|(_, rate)| rate.abs() > problem.tolerance);
    // One Newton workspace for the derivatives and the steps: the sparsity pattern, the
    // momenta's elimination and the symbolic factorization are built once.
    let mut workspace = NewtonWorkspace::new();
    if problem.modified_newton {
        workspace.keep_jacobian_below = crate::solve::KEEP_JACOBIAN_BELOW;
    }
    let (done, mbdyn_momenta_failure) = derivatives(&asm, &mut state, problem, &derivative_settings, &mut workspace, report.inconsistent_velocity.is_none()).map_err(|mut failure| {
        // Velocities that violate a joint cannot be changed by the derivatives phase, which
        // holds them: name the joint, whichever row ended the iteration.
        if let Some((equation, rate)) = &report.inconsistent_velocity {
            let violation = format!("the written velocities violate {equation} ({rate:.3e})");
            failure.reason = Some(failure.reason.take().map_or(violation.clone(), |r| format!("{r}; {violation}")));
        }
        RunError::Derivatives(failure)
    })?;
    report.derivatives_iterations = done.iterations;
    match mbdyn_momenta_failure {
        DerivativesFallback::None => {}
        DerivativesFallback::MomentaFromDefinitions(f) => report.mbdyn_momenta_failure = Some(f.to_string()),
        DerivativesFallback::ToleranceRaised { dcoef, tolerance } => report.derivatives_tolerance_raised = Some((dcoef, tolerance)),
        DerivativesFallback::Auto { failure, raised } => {
            report.derivatives_auto_fallback = Some(failure.to_string());
            report.derivatives_tolerance_raised = raised;
        }
    }
    report.momentum_velocity_change = momentum_velocity_change(&asm, &state).filter(|(_, dv)| dv.abs() > problem.tolerance);
    observed(observer.derivatives(&Derivatives { time: state.t, iterations: done.iterations, residual_norm: done.residual_norm }))?;
    observed(observer.step(&step_done(&asm, 0, problem.time_step, (done.iterations, done.residual_norm), &state)))?;
    if matches!(problem.abort_after, Some(AbortAfter::Derivatives | AbortAfter::DummySteps)) {
        report.final_state = state;
        report.wall_time = clock.elapsed();
        return Ok(report);
    }

    let mut next_eigen = 0;
    let mut eigenanalyses_due = |state: &State, observer: &mut dyn RunObserver, report: &mut RunReport| -> Result<(), RunError> {
        let Some(request) = &problem.eigenanalysis else { return Ok(()) };
        while next_eigen < times.len() && times[next_eigen] <= state.t + 1e-6 * problem.time_step {
            let e = Eigenanalysis::at(model, state, next_eigen, request)?;
            observed(observer.eigenanalysis(&EigenDone { analysis: &e }))?;
            report.eigenanalyses.push(EigenSummary {
                index: e.index,
                time: e.time,
                dcoef: e.dcoef,
                dynamic: e.dynamic_eigenvalues(),
                zero: e.modal.count(ModeKind::Zero),
                infinite: e.modal.count(ModeKind::Infinite),
                non_smooth: asm.non_smooth_elements(state),
                reaction_dependent: asm.reaction_dependent_elements(state),
                every_eigenvalue: matches!(request.solver, EigenSolverRequest::Dense),
                solver: e.solver.clone(),
                not_certified: e.not_certified.clone(),
            });
            next_eigen += 1;
        }
        report.eigen_times_not_reached = times[next_eigen..].to_vec();
        Ok(())
    };
    eigenanalyses_due(&state, observer, &mut report)?;

    let settings = NewtonSettings { tolerance: problem.tolerance, norm: problem.residual_norm, increment_tolerance: problem.increment_tolerance, max_iterations: problem.max_iterations };
    let mut integrator = Integrator::with_workspace(&asm, state, problem.method, problem.time_step, settings, workspace);
    for step in 1..=steps {
        integrator.method = method_at(&asm, problem, &integrator.state, integrator.state.t + problem.time_step)?;
        let r = integrator.step().map_err(|failure| RunError::Step { step, steps, time: failure.time, failure })?;
        report.steps = step;
        report.newton_iterations += r.iterations;
        observed(observer.step(&step_done(&asm, step, problem.time_step, (r.iterations, r.residual_norm), &integrator.state)))?;
        eigenanalyses_due(&integrator.state, observer, &mut report)?;
    }
    report.factorizations = integrator.workspace().factored;
    report.final_state = integrator.state;
    report.wall_time = clock.elapsed();
    Ok(report)
}

/// The integration method of the step to time `t`, from the solution `st` before it: the
/// file's, with a varying spectral radius evaluated there (MBDyn's
/// `MultistepSolver::SetCoef`, after `DataManager::SetTime` to the step's time and before
/// the prediction). A radius outside [0, 1] beyond round-off (or not a number) stops the run.
pub fn method_at(asm: &Assembler, problem: &InitialValueProblem, st: &State, t: f64) -> Result<Method, RunError> {
    let Some(drive) = &problem.varying_radius else {
        return Ok(problem.method);
    };
    let rho = asm.drive_value(drive, st, t);
    // MBDyn checks no range; romdyn stops outside [0, 1] beyond round-off (a linear drive
    // reaching 1 at an accumulated time reads 1 + 4e-16).
    if !(-1e-9..=1.0 + 1e-9).contains(&rho) {
        return Err(RunError::Problem(format!("the method's asymptotic spectral radius is {rho} at t = {t} s, not between 0 and 1")));
    }
    Ok(match problem.method {
        Method::Ms { .. } => Method::Ms { rho },
        Method::Bathe { .. } => Method::Bathe { rho },
        other => other,
    })
}

/// How [`derivatives`] converged when the file's own settings did not.
enum DerivativesFallback {
    None,
    /// With the momenta from their definitions (romdyn's), after MBDyn's way failed so.
    MomentaFromDefinitions(crate::solve::NewtonFailure),
    /// MBDyn's last chance with `auto`: at `dcoef` [s] with the tolerance raised.
    ToleranceRaised { dcoef: f64, tolerance: f64 },
    /// Without `auto` in the file, after both ways failed at its coefficient (`failure`):
    /// `auto`'s coefficients, converged at one of them, or at its last chance (`raised`:
    /// the coefficient and the raised tolerance).
    Auto { failure: crate::solve::NewtonFailure, raised: Option<(f64, f64)> },
}

/// The initial derivatives at the file's derivatives coefficient, and with `auto` at the
/// coefficients MBDyn tries after it in turn (each from the state as given) until one
/// converges, with MBDyn's momenta ([`DerivativeMomenta::AsNewton`]). With `auto`, when
/// none converges, MBDyn's last chance: the coefficient of the smallest final residual
/// again, with the tolerance raised to 1.01 times that residual (stepsol.cc,
/// `DerivativeSolver::Advance`), which converges unless the residual is not finite.
/// Without `auto`, the same coefficient with the momenta from their definitions (romdyn's),
/// whose residual has no dCoef·ṗ floor, returning MBDyn's way's failure with the result;
/// MBDyn stops there. The first failure is reported when nothing converges.
///
/// Without `auto`, when neither way converges at the file's coefficient with the residual
/// left on a node's equilibrium (`velocities_consistent`: the written velocities satisfy the
/// joints), `auto`'s coefficients and last chance follow (issue 38 point 2): a classic beam slider's
/// reaction moments act on the rotation of the beam node that holds the abscissa while its
/// constraints act on the positions that define the line's tangent, so with the velocities
/// held no inertia sets those multipliers; their Newton step needs velocity increments the
/// phase puts back, and the equilibrium rows stall (the sky-engin beam slider: 1.1 N from
/// the first iteration on). MBDyn 1.7.3, starting the abscissa at the initial node, takes
/// another path and converges there; the steps that follow correct what the phase leaves.
fn derivatives(asm: &Assembler, state: &mut State, problem: &InitialValueProblem, settings: &NewtonSettings, workspace: &mut NewtonWorkspace, velocities_consistent: bool) -> Result<(crate::solve::Convergence, DerivativesFallback), crate::solve::NewtonFailure> {
    let initial = problem.derivatives_coefficient * problem.time_step;
    if let Some(auto) = problem.derivatives_coefficient_auto {
        return coefficients_in_turn(asm, state, settings, workspace, auto.sequence(initial).collect()).map_err(|(failure, _)| failure);
    }
    let failure = match coefficients_in_turn(asm, state, settings, workspace, vec![initial]) {
        Ok(done) => return Ok(done),
        Err((failure, _)) => failure,
    };
    let mut trial = state.clone();
    if let Ok(done) = initial_derivatives_in(asm, &mut trial, settings, initial, DerivativeMomenta::FromDefinitions, workspace) {
        *state = trial;
        return Ok((done, DerivativesFallback::MomentaFromDefinitions(failure)));
    }
    // A singular Jacobian (an unknown no equation determines) is the model's, not the
    // coefficient's, and a constraint the held positions or velocities violate (its row the
    // worst, or written velocities off a joint) is the file's: refused as they are, where
    // MBDyn stops too. Only a residual left on the nodes' equilibrium goes on.
    let on_equilibrium = failure.worst_equation.starts_with("node ") && failure.worst_equation.ends_with(" equilibrium");
    if failure.singular || !on_equilibrium || !velocities_consistent {
        return Err(failure);
    }
    let sequence = crate::model::AutoCoefficient::default().sequence(initial).skip(1).collect();
    match coefficients_in_turn(asm, state, settings, workspace, sequence) {
        Ok((done, DerivativesFallback::ToleranceRaised { dcoef, tolerance })) => Ok((done, DerivativesFallback::Auto { failure, raised: Some((dcoef, tolerance)) })),
        Ok((done, _)) => Ok((done, DerivativesFallback::Auto { failure, raised: None })),
        Err(_) => Err(failure),
    }
}

/// MBDyn's `derivatives coefficient: auto` (stepsol.cc, `DerivativeSolver::Advance`): the
/// `coefficients` in turn, each from the state as given, with MBDyn's momenta; when none
/// converges, the one of the smallest final residual again with the tolerance raised to
/// 1.01 times that residual (MBDyn's last chance; one coefficient alone has none). The
/// first failure (and whether a last chance was tried) when nothing converges.
fn coefficients_in_turn(asm: &Assembler, state: &mut State, settings: &NewtonSettings, workspace: &mut NewtonWorkspace, coefficients: Vec<f64>) -> Result<(crate::solve::Convergence, DerivativesFallback), (crate::solve::NewtonFailure, bool)> {
    let mut first_failure: Option<crate::solve::NewtonFailure> = None;
    // The coefficient with the smallest final residual (MBDyn's dCoefBest, dResErrMin).
    let mut best: Option<(f64, f64)> = None;
    for &dcoef in &coefficients {
        let mut trial = state.clone();
        match initial_derivatives_in(asm, &mut trial, settings, dcoef, DerivativeMomenta::AsNewton, workspace) {
            Ok(done) => {
                *state = trial;
                return Ok((done, DerivativesFallback::None));
            }
            Err(failure) => {
                if failure.residual_norm.is_finite() && best.is_none_or(|(_, r)| failure.residual_norm < r) {
                    best = Some((dcoef, failure.residual_norm));
                }
                first_failure.get_or_insert(failure);
            }
        }
    }
    let first_failure = first_failure.unwrap_or_else(|| unreachable!("at least one coefficient is tried"));
    if coefficients.len() < 2 {
        return Err((first_failure, false));
    }
    if let Some((dcoef, residual)) = best {
        let tolerance = 1.01 * residual;
        let raised = NewtonSettings { tolerance, ..*settings };
        let mut trial = state.clone();
        if let Ok(done) = initial_derivatives_in(asm, &mut trial, &raised, dcoef, DerivativeMomenta::AsNewton, workspace) {
            *state = trial;
            return Ok((done, DerivativesFallback::ToleranceRaised { dcoef, tolerance }));
        }
    }
    Err((first_failure, true))
}
