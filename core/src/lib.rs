//! romdyn's numerical core: everything between a model and its reduced-order model, without
//! files, workflows or a command line (those are the crate `romdyn`, which re-exports every
//! module here: use `romdyn::eigen`, `romdyn::element`, ...).
//!
//! ```text
//! model -> dae (assembly) -> solve -> linear (F_yd, F_y) -> eigen -> rom
//!   element (the library every model is built from), kinematics, lu, limits beside them
//! ```
//!
//! Equation numbers in doc comments refer to "Reduced order models from multibody
//! analysis" (the paper behind `shared/METHOD.md`). Units are SI throughout.

pub mod dae;
pub mod eigen;
pub mod element;
pub mod kinematics;
pub mod limits;
pub mod linear;
pub mod lu;
pub mod model;
pub mod rom;
pub mod solve;

/// Complex scalar used throughout (re-exported from faer).
pub use faer::c64;
