//! The paper's validation cases in one place (CASES C1–C6) and the linear ROM method they
//! validate. C1, two rigidly connected masses: `two_masses`. C2 and C3, the simple and the
//! inverted pendulum: `multibody_pendulum`, and C2's periods in `multibody_dynamics`. C4, the
//! simply supported beam: `beam_simply_supported`. C5, the cantilever: `beam_cantilever`. C4
//! and C5 read from MBDyn files: `beam_examples`. C6, the HAM-SAS-like isolator: `ham_sas`.
//! The ROM built on them: eigenvectors (eqs. 10–11), a mass chain, the `Study` type, and the
//! ROM's checks and messages (`rom_trust`, `rom_checks`).

#[path = "../common/mod.rs"]
mod common;

mod beam_cantilever;
mod beam_examples;
mod beam_simply_supported;
mod eigenvectors;
mod ham_sas;
mod mass_chain;
mod multibody_dynamics;
mod multibody_pendulum;
mod rom_checks;
mod rom_trust;
mod study;
mod two_masses;
