//! Why a run (or a reference solution) stopped.

use crate::solve::{AssemblyError, NewtonFailure};

/// An observer's failure (e.g. a file that cannot be written).
pub type ObserverError = Box<dyn std::error::Error + Send + Sync>;

/// Why a run stopped.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error("invalid initial-value problem: {0}")]
    Problem(String),
    #[error(transparent)]
    Assembly(AssemblyError),
    #[error("initial derivatives: {0}")]
    Derivatives(NewtonFailure),
    #[error("static equilibrium: {0}")]
    Static(NewtonFailure),
    #[error("step {step} of {steps} (t = {time} s): {failure}")]
    Step { step: usize, steps: usize, time: f64, failure: NewtonFailure },
    #[error("eigenanalysis {index} at t = {time} s: {message}")]
    Eigen { index: usize, time: f64, message: String },
    #[error(transparent)]
    Observer(ObserverError),
}
