//! The reference solution a model file is linearized at: the initial state after consistent
//! initial derivatives, the file's problem integrated up to a time, or the static
//! equilibrium at the initial time (loads and gravity ramped) — as `eig`, `rom`, `freq` and
//! `check` use with `--at TIME` or `--static`.

use super::error::RunError;
use super::run::run;
use super::warning::RunWarning;
use crate::dae::{Assembler, State};
use crate::model::{InitialValueProblem, Model};
use crate::solve::{static_solution, NewtonSettings};

/// Where a model is linearized.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reference {
    /// The initial time, after the consistent initial derivatives (MBDyn's eigenanalysis at
    /// the initial time).
    Initial,
    /// The first step of the file's problem whose time reaches this time [s].
    At(f64),
    /// The static equilibrium at the initial time, loads and gravity applied in
    /// `load_steps` equal increments (prestressed structures, buckling, C4).
    Static { load_steps: usize },
}

impl Reference {
    /// Whether the state comes from integrating the file's problem in time (`At`), which
    /// decides the beams' `auto` update ([`crate::input::mbdyn::BeamUpdateChoice`]).
    pub fn integrates(&self) -> bool {
        matches!(self, Reference::At(_))
    }
}

/// The state at `reference`.
pub fn reference_state(model: &Model, problem: &InitialValueProblem, reference: Reference) -> Result<State, RunError> {
    reference_state_with_warnings(model, problem, reference).map(|(state, _)| state)
}

/// The state at `reference` with the warnings of the run that reached it (the initial
/// state's: velocities, the derivatives phase; none for the static equilibrium).
pub fn reference_state_with_warnings(model: &Model, problem: &InitialValueProblem, reference: Reference) -> Result<(State, Vec<RunWarning>), RunError> {
    let mut p = problem.clone();
    p.eigenanalysis = None;
    p.abort_after = None;
    p.final_time = match reference {
        Reference::Static { load_steps } => return static_state(model, problem, load_steps).map(|state| (state, Vec::new())),
        Reference::Initial => p.initial_time,
        Reference::At(t) if t.is_finite() && t >= p.initial_time => t,
        Reference::At(t) => return Err(RunError::Problem(format!("time {t} s is before the initial time {} s", p.initial_time))),
    };
    let report = run(model, &p, &mut ())?;
    let warnings = report.warnings();
    Ok((report.final_state, warnings))
}

fn static_state(model: &Model, problem: &InitialValueProblem, load_steps: usize) -> Result<State, RunError> {
    if load_steps > crate::limits::MAX_LOAD_STEPS {
        return Err(RunError::Problem(format!("{load_steps} load increments: more than romdyn's limit of {}", crate::limits::MAX_LOAD_STEPS)));
    }
    let asm = Assembler::new(model);
    let mut st = State::initial(model, &asm.dofs);
    st.t = problem.initial_time;
    crate::solve::initial_assembly(model, &mut st, &problem.assembly).map_err(RunError::Assembly)?;
    static_solution(&asm, &mut st, load_steps, &static_settings(problem)).map_err(RunError::Static)?;
    Ok(st)
}

/// Static equilibrium from the straight shape needs more than MBDyn's one default
/// iteration per load step: the file's limit, at least 20.
fn static_settings(problem: &InitialValueProblem) -> NewtonSettings {
    NewtonSettings { tolerance: problem.tolerance, norm: problem.residual_norm, max_iterations: problem.max_iterations.max(20), ..NewtonSettings::default() }
}

/// The static equilibrium at the initial time starting from `start` (a neighbouring design
/// point's equilibrium, the same unknowns) at full load in one increment.
pub fn static_state_from(model: &Model, problem: &InitialValueProblem, start: &State) -> Result<State, RunError> {
    let asm = Assembler::new(model);
    let mut st = State::initial(model, &asm.dofs);
    if st.y.len() != start.y.len() || st.r_ref.len() != start.r_ref.len() {
        return Err(RunError::Problem(format!("the starting solution has {} unknowns, the model {}", start.y.len(), st.y.len())));
    }
    st.y.clone_from(&start.y);
    st.r_ref.clone_from(&start.r_ref);
    st.t = problem.initial_time;
    static_solution(&asm, &mut st, 1, &static_settings(problem)).map_err(RunError::Static)?;
    Ok(st)
}
