//! Writing results: MATLAB v5 `.mat`, NumPy `.npz`, JSON, CSV, Bode plots, and MBDyn's
//! run files (`.out` step log, `.mov` motion, `.log` model log, eigenanalysis `.m`); every
//! file is written atomically (temporary file, then rename).

pub mod atomic;
pub mod beam_sections;
pub mod cleanup;
pub mod bode;
pub mod figure;
pub mod frequency_plot;
pub mod hydraulic_elements;
pub mod line_plot;
pub mod eigen_file;
pub mod eigen_json;
pub mod eigen_m;
pub mod fem_file;
pub mod fmu;
pub mod mat5;
pub mod jacobian_check;
pub mod matrix_market;
pub mod mimo_plot;
pub mod modal;
pub mod model_log;
pub mod plates;
pub mod modal_coordinates;
pub mod motion;
pub mod npz;
pub(crate) mod zip;
pub mod report;
pub mod response_csv;
pub mod rom_export;
pub mod rom_file;
pub mod rom_script;
pub mod scientific;
pub mod scalar_nodes;
pub mod step_log;
pub mod sweep_plot;

use std::path::{Path, PathBuf};

/// `PREFIX.ext`: a file named after an output prefix (the prefix may contain dots).
pub fn prefixed_path(prefix: &Path, ext: &str) -> PathBuf {
    let mut s = prefix.as_os_str().to_owned();
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}
