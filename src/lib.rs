//! romdyn: linear reduced-order models (ROMs) extracted from nonlinear multibody models.
//!
//! Data flows one way along the modules:
//!
//! ```text
//! input -> model -> dae (assembly) -> solve -> linear (F_yd, F_y) -> eigen -> rom -> output
//!   -> analysis (runs an initial-value problem with its eigenanalyses)
//!   -> study (the ROM workflow: reference, linearization, modes, ROM, checks)
//! ```
//!
//! Equation numbers in doc comments refer to "Reduced order models from multibody
//! analysis" (the paper behind `shared/METHOD.md`). Units are SI throughout.

pub mod analysis;
pub mod cms;
pub mod dae;
pub mod eigen;
pub mod element;
pub mod input;
pub mod kinematics;
pub mod limits;
pub mod linear;
pub mod lu;
pub mod model;
pub mod output;
pub mod rom;
pub mod solve;
pub mod study;
pub mod sweep;
pub mod validate;

/// Complex scalar used throughout (re-exported from faer).
pub use faer::c64;
