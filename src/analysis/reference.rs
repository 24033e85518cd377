//! The reference solution of a model file at a time: the file's problem integrated from its
//! initial time up to that time (no eigenanalyses, no output), as `eig --at`, `rom --at` and
//! `check --at` linearize there.

use super::run::{run, RunError};
use crate::dae::State;
use crate::model::{InitialValueProblem, Model};

/// The solution at the first step whose time reaches `at` (the initial time, after the
/// consistent initial derivatives, when `at` is `None`).
pub fn reference_state(model: &Model, problem: &InitialValueProblem, at: Option<f64>) -> Result<State, RunError> {
    let mut p = problem.clone();
    p.eigenanalysis = None;
    p.abort_after = None;
    p.final_time = match at {
        None => p.initial_time,
        Some(t) if t.is_finite() && t >= p.initial_time => t,
        Some(t) => return Err(RunError::Problem(format!("time {t} s is before the initial time {} s", p.initial_time))),
    };
    Ok(run(model, &p, &mut ())?.final_state)
}
