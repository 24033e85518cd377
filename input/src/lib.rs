//! Reading models and matrices: MBDyn input files, linear-DAE pencil files (JSON, or the
//! eigenanalysis `.m` files MBDyn writes), Matrix Market matrices, the FEM files of MBDyn's
//! modal element.
//!
//! A crate of its own, `romdyn-input`, on the numerical core alone (`romdyn-core`), re-exported
//! by `romdyn` as `romdyn::input`, so the compiler keeps the readers off the writers and
//! workflows (issue 36 point 5: the root Cargo.toml's profiles and
//! docs/src/performance/overview.md).

// The core's modules under the names the reader's paths use (`crate::element`, ...).
use romdyn_core::{dae, element, kinematics, limits, linear, model};

mod chars;
pub mod ports_file;
pub mod eigen_pencil;
pub mod fem;
pub mod matrix_market;
pub mod mbdyn;
pub mod octave_m;
pub mod pencil;
pub mod text_file;
