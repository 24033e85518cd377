//! Linearized DAEs: the matrices F_yd and F_y (eqs. 13–16), generalized eigenanalysis with
//! right and adjoint vectors (eqs. 10–11, 18–23) and the labelling of eigenvalues
//! (eqs. 32–35).

mod balance;
mod certified_lu;
mod classify;
mod dae;
mod degenerate;
mod deflate;
mod dynamic_eigen;
mod eigen;
mod eigen_error;
mod route;
mod sparse;
mod sparse_dae;
pub mod krylov;

pub use classify::{Classification, ModeKind};
pub use dae::{coefficient_from_derivatives, derivatives_from_coefficient, ConstraintForm, Jacobians, LinearDae};
pub use eigen::{ModalAnalysis, Mode};
pub use eigen_error::EigenError;
pub use route::EigenRoute;
pub use sparse::{SparseMatrix, SparseScalar};
pub use sparse_dae::{SparseLinearDae, SparseSolveError};
pub(crate) use certified_lu::{certified_partial_lu, full_pivots_nonsingular};
