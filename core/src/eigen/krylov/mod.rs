//! Shift-invert Krylov–Schur eigenanalysis of a sparse linear DAE (METHOD §3, issue 13
//! point 2): the modes nearest one or several shifts, with right and left vectors, each
//! checked by its true residual; the N lowest modes proven complete by an argument-principle
//! count (`count.rs`), a band checked by two independent Krylov spaces per shift.

mod arnoldi;
mod clusters;
mod count;
mod gram_schmidt;
mod iteration;
mod operator;
mod pencil;
mod schur;
mod shifts;
mod sweep_kernels;
mod window;

pub use shifts::{sparse_modes, sparse_modes_with_progress, ModeTarget, ShiftWindow, SparseModalAnalysis};

use faer::c64;

/// Tolerances and limits of the sparse eigensolver.
#[derive(Clone, Debug)]
pub struct SparseEigenSettings {
    /// Largest true relative residual `‖(λ F_yd + F_y) v‖ / ((|λ| ‖F_yd‖ + ‖F_y‖) ‖v‖)`
    /// (and of the left vector) of a returned pair.
    pub tolerance: f64,
    /// Relative residual `‖T x − θ x‖/|θ|` at which the Krylov–Schur iteration stops.
    pub krylov_tolerance: f64,
    /// Largest number of eigenvalues asked of one shift (a wider band takes more shifts).
    pub per_shift: usize,
    pub max_restarts: usize,
    /// Route whose labels (eqs. 32–35) the modes get, as the dense eigenanalysis labels them.
    pub route: crate::eigen::EigenRoute,
    /// dCoef of the Λ route's labels; `None`: `‖F_yd‖_F / ‖F_y‖_F` as for the dense route.
    pub dcoef: Option<f64>,
    /// Left (adjoint) vectors (the default): for the lowest modes from each eigenvalue's
    /// inverse iteration, certified by the argument-principle count; for a band from the
    /// adjoint Krylov run, whose agreement with the right run is the band's check. `false`:
    /// right vectors only, from the right Krylov run alone (half the work: scipy's `eigs`
    /// does the same), each pair still checked by its true right residual; the modes have
    /// no left vectors, their error estimates take the condition number as 1 (a lower
    /// bound), and the result is never `certified` (no second Krylov space checks the
    /// count).
    pub left_vectors: bool,
}

impl Default for SparseEigenSettings {
    fn default() -> Self {
        SparseEigenSettings { tolerance: 1e-10, krylov_tolerance: 1e-12, per_shift: 40, max_restarts: 200, route: crate::eigen::EigenRoute::Lambda, dcoef: None, left_vectors: true }
    }
}

/// Failure of the sparse eigenanalysis.
#[derive(Debug, thiserror::Error)]
pub enum KrylovError {
    #[error("the shifted matrix F_y + σ F_yd is singular at σ = {0} (sparse LU failed)")]
    Singular(c64),
    #[error("the sparse LU of F_y + σ F_yd at σ = {sigma} is not accurate (relative residual {residual:e}): σ is at or next to an eigenvalue")]
    Inaccurate { sigma: c64, residual: f64 },
    #[error("the Krylov–Schur iteration broke down: {0}")]
    Breakdown(String),
    #[error("the sparse eigenanalysis needs the constraint structure: {0}")]
    Structure(String),
    #[error("{0}")]
    Request(String),
}

/// The pencil `λ E + K` in the form of eq. 29 that [`sparse_modes`] factors and iterates on
/// (MBDyn's constraint form, eq. 30, mapped as `pencil.rs` describes; other forms as they
/// are): `(E, K)`, for exporting the exact problem to other eigensolvers.
pub fn shift_invert_pencil(dae: &crate::linear::SparseLinearDae) -> Result<(crate::linear::SparseMatrix, crate::linear::SparseMatrix), KrylovError> {
    let p = pencil::Pencil::new(dae)?;
    Ok((p.e, p.k))
}
