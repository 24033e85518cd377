//! LU factorizations shared by the solvers: the dense partial-pivoting LU that proves its
//! matrix nonsingular ([`certified_partial_lu`]), used by the pencil checks and the ROM.

mod certified;

pub(crate) use certified::{certified_partial_lu, full_pivots_nonsingular};
