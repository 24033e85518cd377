//! The LU factorizations the solvers share, below every user: faer's general sparse LU of
//! one pattern ([`PatternLu`]: Newton, the sparse DAE, the Krylov shift-invert operator), the
//! banded LU after a reverse Cuthill–McKee renumbering ([`BandLu`]: Newton's narrow-band
//! path), and the dense partial-pivoting LU that proves its matrix nonsingular
//! ([`certified_partial_lu`]: the pencil checks and the ROM).

mod band;
mod certified;
pub(crate) mod prefetch;
mod sparse;

pub(crate) use band::{BandLu, BandOrdering};
pub(crate) use certified::{certified_partial_lu, full_pivots_nonsingular};
pub use sparse::{PatternLu, SparseLuError};
