//! Errors of ROM construction.

use crate::eigen::EigenError;

/// Why a ROM could not be built.
#[derive(Debug, thiserror::Error)]
pub enum RomError {
    #[error("mode selection: {0}")]
    Selection(String),
    #[error("mode {0} has no eigenvectors (infinite eigenvalue)")]
    MissingVectors(usize),
    #[error("{0} is singular: no static response can be computed")]
    SingularStatic(&'static str),
    #[error("a velocity output of this ROM would need the time derivative of its inputs (its statically residualized states respond to u̇): keep those modes, or measure displacements")]
    ImproperRate,
    #[error("imposed motion: {0}")]
    Imposed(String),
    #[error(transparent)]
    Eigen(#[from] EigenError),
    #[error("discrete-time ROM: {0}")]
    Discrete(String),
    #[error("balanced reduction: {0}")]
    Balanced(String),
    #[error("frequency grid: {0}")]
    Grid(String),
}
