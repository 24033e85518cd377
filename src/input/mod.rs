//! Reading models and matrices: MBDyn input files, linear-DAE pencil files (JSON, or the
//! eigenanalysis `.m` files MBDyn writes), Matrix Market matrices, the FEM files of MBDyn's
//! modal element.

mod chars;
pub mod ports_file;
pub mod eigen_pencil;
pub mod fem;
pub mod matrix_market;
pub mod mbdyn;
pub mod octave_m;
pub mod pencil;
pub mod text_file;
