//! Eigenanalysis of a linearized DAE `λ F_yd + F_y` (eqs. 10–11): the eigenvalues with right
//! and adjoint vectors, each labelled dynamic, zero or infinite (eqs. 32–35), and what the
//! modes are read as afterwards (kinetic-energy shares, degenerate clusters).
//!
//! - [`dense`]: QZ on the whole pencil or on its dynamic part after the exact deflation of the
//!   constraint structure (eqs. 29–30), by either route ([`EigenRoute`], eqs. 18–23);
//! - [`krylov`]: shift-invert Krylov–Schur on the sparse pencil, for the modes in a band;
//! - [`ModalAnalysis`] / [`Mode`]: the result either solver gives, sorted and normalized alike;
//! - [`kinetic_energy_shares`], [`degenerate_clusters`]: which node and component a mode
//!   moves, and the labels of (nearly) repeated modes;
//! - [`dense_modes`], [`energy_shares`]: the dense eigenanalysis and the modes' shares as
//!   `romdyn run` and a `romdyn::study::Study` both take them.
//!
//! The linear DAE's types themselves live in [`crate::linear`].

mod classify;
mod cluster;
pub mod componentwise;
pub mod dense;
mod energy;
mod error;
pub mod krylov;
mod modes;
mod pipeline;
mod route;

pub use classify::{Classification, ModeKind};
pub use cluster::{cluster_label, degenerate_clusters, CLUSTER_RELATIVE_GAP};
pub use energy::{describe, kinetic_energy_shares, mode_label, real_mode_label, EnergyShare, ModalEnergy};
pub use error::EigenError;
pub use modes::{ModalAnalysis, Mode};
pub use pipeline::{dense_modes, energy_shares};
pub use route::EigenRoute;
pub use route::{dot_t, mul_real_complex};
