//! What a run did that a user must know although it succeeded: the initial state it started
//! from (velocities, the derivatives phase) and eigenanalyses that are one-sided or not
//! certified. `romdyn run` prints them, a study made at a reference that comes from a run
//! (`eig`, `rom`, … at the initial time or `--at`) carries them, and Python raises them.

use std::fmt;

use super::run::RunReport;

/// A warning of a run, in words that hold for `run` and for a linearization at its state.
#[derive(Clone, Debug, PartialEq)]
pub enum RunWarning {
    /// The written initial velocities violate a joint's velocity constraint `Φ_/q q̇`: the
    /// equation and its rate [m/s or rad/s].
    InconsistentVelocity { equation: String, rate: f64 },
    /// The derivatives phase failed with MBDyn's momenta (Newton's, kept) and converged with
    /// romdyn's (set from their definitions): why it failed.
    MbdynMomentaFailure { failure: String },
    /// `derivatives coefficient: auto` accepted the coefficient of the smallest residual with
    /// the tolerance raised (MBDyn's `DerivativeSolver::Advance`): dCoef [s] and tolerance.
    DerivativesToleranceRaised { dcoef: f64, tolerance: f64 },
    /// The derivatives phase failed at the file's coefficient (`failure`) and went on with
    /// the coefficients of MBDyn's `derivatives coefficient: auto`, which the file does not ask for.
    DerivativesAutoFallback { failure: String },
    /// The momenta left by the derivatives phase start the motion as from a written velocity
    /// changed by more than the tolerance: its name and the change [m/s or rad/s].
    MomentumVelocityChange { velocity: String, change: f64 },
    /// Eigenanalysis `index` at `time` [s] linearized an element at a point where its
    /// residual is not differentiable: why.
    OneSided { index: usize, time: f64, why: String },
    /// Eigenanalysis `index` at `time` [s] on the sparse route is not certified: why.
    NotCertified { index: usize, time: f64, why: String },
    /// Eigenanalysis `index` at `time` [s] depends on reaction multipliers' values: why.
    ReactionDependent { index: usize, time: f64, why: String },
}

impl RunWarning {
    /// Whether the warning is about an eigenanalysis (else about the initial state).
    pub fn is_eigenanalysis(&self) -> bool {
        matches!(self, RunWarning::OneSided { .. } | RunWarning::NotCertified { .. } | RunWarning::ReactionDependent { .. })
    }
}

impl fmt::Display for RunWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RunWarning::InconsistentVelocity { equation, rate } => write!(f, "the initial velocities do not satisfy the joints ({equation} changes at {rate:.3e} per s); they are kept for the initial derivatives, as in MBDyn, and a time step changes them"),
            RunWarning::MbdynMomentaFailure { failure } => write!(f, "the derivatives phase did not converge with the momenta of its Newton iterations, which MBDyn keeps ({failure}); romdyn set them from their definitions at the written velocities and converged, so the motion starts from those velocities; where MBDyn's own iteration does not converge either it stops, or with `derivatives coefficient: auto` raises its tolerance"),
            RunWarning::DerivativesAutoFallback { failure } => write!(f, "the derivatives phase did not converge at the file's derivatives coefficient ({failure}); romdyn went on with the coefficients of MBDyn's `derivatives coefficient: auto`, which the file does not ask for (MBDyn 1.7.3 stops there, unless its own iteration takes another path: it starts a beam slider's abscissa at the slider's initial node); the initial accelerations and reactions are not to be trusted, and the first steps correct them"),
            RunWarning::DerivativesToleranceRaised { dcoef, tolerance } => write!(f, "the derivatives phase converged at no derivatives coefficient; as MBDyn does with `derivatives coefficient: auto`, it was accepted at the coefficient with the smallest residual (dCoef = {dcoef:.3e} s) with its tolerance raised to {tolerance:.3e}: the initial accelerations and reactions are not to be trusted (typically a joint that does not hold to round-off after the initial assembly, divided by dCoef, or the momenta's dCoef·ṗ left by Newton)"),
            RunWarning::MomentumVelocityChange { velocity, change } => write!(f, "the derivatives phase keeps Newton's momenta, as MBDyn's does, and they start the motion as from a written velocity changed by more than the tolerance ({velocity} by {change:.3e}; about the derivatives coefficient dCoef times the acceleration: a smaller `derivatives coefficient` reduces it)"),
            RunWarning::OneSided { index, time, why } => write!(f, "eigenanalysis {index} at t = {time} s: {why}; the linearization takes a one-sided derivative there, and its eigenvalues describe only motion to that side"),
            RunWarning::NotCertified { index, time, why } => write!(f, "eigenanalysis {index} at t = {time} s: the sparse route's modes are NOT certified ({why}): a mode below the highest one written may be missing"),
            RunWarning::ReactionDependent { index, time, why } => write!(f, "eigenanalysis {index} at t = {time} s: {why}"),
        }
    }
}

impl RunReport {
    /// The run's warnings, the initial state's first, then each eigenanalysis' in order.
    pub fn warnings(&self) -> Vec<RunWarning> {
        let mut w = Vec::new();
        if let Some((equation, rate)) = &self.inconsistent_velocity {
            w.push(RunWarning::InconsistentVelocity { equation: equation.clone(), rate: *rate });
        }
        if let Some(failure) = &self.mbdyn_momenta_failure {
            w.push(RunWarning::MbdynMomentaFailure { failure: failure.clone() });
        }
        for e in &self.eigenanalyses {
            let (index, time) = (e.index, e.time);
            w.extend(e.non_smooth.iter().map(|why| RunWarning::OneSided { index, time, why: why.clone() }));
            w.extend(e.not_certified.iter().map(|why| RunWarning::NotCertified { index, time, why: why.clone() }));
            w.extend(e.reaction_dependent.iter().map(|why| RunWarning::ReactionDependent { index, time, why: why.clone() }));
        }
        if let Some(failure) = &self.derivatives_auto_fallback {
            w.push(RunWarning::DerivativesAutoFallback { failure: failure.clone() });
        }
        if let Some((dcoef, tolerance)) = self.derivatives_tolerance_raised {
            w.push(RunWarning::DerivativesToleranceRaised { dcoef, tolerance });
        }
        if let Some((velocity, change)) = &self.momentum_velocity_change {
            w.push(RunWarning::MomentumVelocityChange { velocity: velocity.clone(), change: *change });
        }
        w
    }
}
