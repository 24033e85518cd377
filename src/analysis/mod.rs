//! Runs an initial-value problem with its eigenanalyses (MBDyn's `initial value` problem):
//! consistent initial derivatives, fixed-step integration, eigenanalyses of `J(±c)` at the
//! requested times; observers receive each event (progress, MBDyn-compatible files). Also
//! the reference solution at a time, and the Jacobian check of a model there.
//!
//! The last module of the data line: it drives `solve`, `linear` and `output`.

mod check;
mod eigen;
mod error;
mod files;
mod history;
mod observer;
mod reference;
mod run;
mod warning;

pub use check::{check_model_jacobians, JacobianCheck, JACOBIAN_CHECK_TOLERANCE};
pub use eigen::{Eigenanalysis, DEFAULT_DCOEF};
pub use files::{eigen_file_stem, journal_path, RunFiles};
pub use history::NodeHistories;
pub use observer::{Derivatives, EigenDone, ObserverError, RunObserver, RunStart, StepDone};
pub use reference::{reference_state, reference_state_with_warnings, static_state_from, Reference};
pub use error::RunError;
pub use run::{run, EigenSummary, RunReport};
pub use warning::RunWarning;
