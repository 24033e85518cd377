//! Linearized DAEs: the matrices F_yd and F_y (eqs. 13–16) with the input and output maps
//! `B̃`, `C̃` (eqs. 38–40), dense or sparse as assembled. Their eigenanalysis is
//! [`crate::eigen`].

mod compensated;
mod dae;
mod accuracy;
mod response;
mod sparse;
mod sparse_dae;

pub use compensated::{Compensated, CompensatedComplex};
pub use dae::{coefficient_from_derivatives, derivatives_from_coefficient, Jacobians, LinearDae};
pub use accuracy::{ChannelError, GridAccuracy};
pub use response::{hz, rad_per_s, FrequencyResponse, Port};
pub use sparse::{SparseMatrix, SparseScalar};
pub use sparse_dae::{SparseLinearDae, SparseSolveError};
pub(crate) use sparse::{contiguous, contiguous_mut};
