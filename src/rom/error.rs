//! Errors of ROM construction.

use crate::linear::EigenError;

/// Why a ROM could not be built.
#[derive(Debug, thiserror::Error)]
pub enum RomError {
    #[error("mode selection: {0}")]
    Selection(String),
    #[error("mode {0} has no eigenvectors (infinite eigenvalue)")]
    MissingVectors(usize),
    #[error("{0} is singular: no static response can be computed")]
    SingularStatic(&'static str),
    #[error(transparent)]
    Eigen(#[from] EigenError),
    #[error("frequency grid: {0}")]
    Grid(String),
}
