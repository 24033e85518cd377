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
//!
//! Three crates: `romdyn-core` (core/: model, element, dae, solve, linear, eigen, rom,
//! kinematics, lu, limits; no files, workflows or command line), re-exported here module by
//! module; `romdyn-input` (input/: the readers, on the core alone), re-exported as
//! `input`; and this one (output, analysis, study, cms, sweep, validate, and the command
//! line in src/cli).

pub mod analysis;
pub mod cms;
pub use romdyn_core::dae;
pub use romdyn_core::eigen;
pub use romdyn_core::element;
pub use romdyn_input as input;
pub use romdyn_core::kinematics;
pub use romdyn_core::limits;
pub use romdyn_core::linear;
pub use romdyn_core::lu;
pub use romdyn_core::model;
pub mod output;
pub use romdyn_core::rom;
pub use romdyn_core::solve;
pub mod study;
pub mod sweep;
pub mod validate;

/// Complex scalar used throughout (re-exported from faer).
pub use faer::c64;
