//! Reading models and matrices: linear-DAE pencil files, Matrix Market matrices.

pub mod matrix_market;
pub mod mbdyn;
pub mod pencil;
