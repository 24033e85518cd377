//! Exporting a ROM: JSON, MATLAB v5 `.mat` or NumPy `.npz`, chosen by the file extension.
//! All three formats carry the same content (names as cell arrays of strings in `.mat`,
//! str arrays in `.npz`):
//!
//! | name | content |
//! | --- | --- |
//! | `E A B C D` | `E ẋ = A x + B u`, `z = C x + D u` |
//! | `kind` | `"ordinary"` (E = I) or `"descriptor"` (D = 0, E possibly singular) |
//! | `eigenvalues` | the ROM's own eigenvalues (finite eigenvalues of `(A, E)`) [rad/s] |
//! | `full_eigenvalues` | the full model's kept eigenvalues [rad/s] |
//! | `inputs outputs states` | names |
//! | `input_units output_units state_units` | SI units |
//! | `state_modes state_freq_hz` | each state's mode (1-based modal-table index, 0 for a static state) and its frequency Im λ/2π [Hz] |
//! | `reference_time dcoef` | where the model was linearized [s] (NaN: a pencil file) and the dCoef of its eigenanalysis [s] |
//! | `full_static_gain rom_static_gain` | outputs × inputs (NaN when not available) |
//! | `sample_time discretization` | discrete time: `x[k+1] = A x[k] + B u[k]` at this sampling time [s], by `"zoh"`, `"tustin"` (prewarped at F Hz) or `"matched"`; continuous: NaN (JSON null) and `"continuous"` |
//! | `hankel_singular_values error_bound` | a balanced ROM's stable part's Hankel singular values and its bound `2 Σ dropped σ` on `‖G − G_r‖∞` (empty, NaN: not balanced) |
//!
//! A `.m` file is an Octave/MATLAB script with the same content that builds `sys` with
//! `ss`/`dss` (names and units set, `Ts` when discrete): `run('rom.m')`.

use std::path::Path;

use faer::{c64, Mat};
use serde_json::{json, Value};

pub use super::rom_export::RomExport;


fn rows(m: &Mat<f64>) -> Value {
    Value::Array((0..m.nrows()).map(|i| Value::Array((0..m.ncols()).map(|j| json!(m[(i, j)])).collect())).collect())
}

/// The SI unit in a port name's brackets ("node 5 y [m]" → "m"), or "" when it has none.
pub fn unit_of_name(name: &str) -> String {
    crate::linear::Port::from_label(name).unit
}

/// Why a ROM could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error("{0}: unknown ROM file format (the extension must be .json, .mat, .npz, .m or .fmu)")]
    UnknownFormat(String),
    #[error("{0}: is a directory; give a ROM file name ending in .json, .mat, .npz, .m or .fmu")]
    IsDirectory(String),
    #[error("{0}: {1}")]
    Fmu(String, super::fmu::FmuError),
    #[error(transparent)]
    Output(#[from] super::atomic::OutputError),
}

#[derive(Clone, Copy)]
enum Format {
    Json,
    Mat,
    Npz,
    MScript,
    Fmu,
}

fn format_of(path: &Path) -> Result<Format, ExportError> {
    if path.is_dir() {
        return Err(ExportError::IsDirectory(path.display().to_string()));
    }
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("json") => Ok(Format::Json),
        Some("mat") => Ok(Format::Mat),
        Some("npz") => Ok(Format::Npz),
        Some("m") => Ok(Format::MScript),
        Some("fmu") => Ok(Format::Fmu),
        _ => Err(ExportError::UnknownFormat(path.display().to_string())),
    }
}

fn nan_matrix(m: &Option<Mat<f64>>, rows: usize, cols: usize) -> Mat<f64> {
    m.clone().unwrap_or_else(|| Mat::from_fn(rows, cols, |_, _| f64::NAN))
}

impl RomExport {
    /// Checks that `path` names a file in a known format (before any computation).
    pub fn check_path(path: &Path) -> Result<(), ExportError> {
        format_of(path).map(|_| ())
    }

    /// The JSON document (matrices as arrays of rows; complex numbers as {re, im}).
    pub fn to_json(&self) -> Value {
        let complex = |v: &[c64]| v.iter().map(|l| json!({"re": l.re, "im": l.im})).collect::<Vec<_>>();
        let gain = |g: &Option<Mat<f64>>| g.as_ref().map_or(Value::Null, rows);
        json!({
            "kind": self.kind,
            "time": self.time_domain(),
            "units": self.units_line(),
            "E": rows(&self.e),
            "A": rows(&self.a),
            "B": rows(&self.b),
            "C": rows(&self.c),
            "D": rows(&self.d),
            "eigenvalues": complex(&self.eigenvalues),
            "full_eigenvalues": complex(&self.full_eigenvalues),
            "inputs": self.inputs,
            "outputs": self.outputs,
            "states": self.states,
            "input_units": self.input_units,
            "output_units": self.output_units,
            "state_units": self.state_units,
            "state_modes": self.state_modes,
            "state_freq_hz": self.state_freq_hz.iter().map(|f| if f.is_finite() { json!(f) } else { Value::Null }).collect::<Vec<_>>(),
            "reference_time": self.reference_time,
            "dcoef": self.dcoef,
            "full_static_gain": gain(&self.full_static_gain),
            "rom_static_gain": gain(&self.rom_static_gain),
            "sample_time": self.sample_time,
            "discretization": self.discretization,
            "hankel_singular_values": self.hankel_singular_values,
            "error_bound": self.error_bound,
        })
    }

    fn matrices(&self) -> Vec<(&'static str, Mat<f64>)> {
        let (no, ni) = (self.c.nrows(), self.b.ncols());
        vec![
            ("E", self.e.clone()),
            ("A", self.a.clone()),
            ("B", self.b.clone()),
            ("C", self.c.clone()),
            ("D", self.d.clone()),
            ("state_modes", Mat::from_fn(self.state_modes.len(), 1, |i, _| self.state_modes[i] as f64)),
            ("state_freq_hz", Mat::from_fn(self.state_freq_hz.len(), 1, |i, _| self.state_freq_hz[i])),
            ("full_static_gain", nan_matrix(&self.full_static_gain, no, ni)),
            ("rom_static_gain", nan_matrix(&self.rom_static_gain, no, ni)),
            ("hankel_singular_values", Mat::from_fn(self.hankel_singular_values.len(), 1, |i, _| self.hankel_singular_values[i])),
        ]
    }

    fn names(&self) -> [(&'static str, &Vec<String>); 6] {
        [
            ("inputs", &self.inputs),
            ("outputs", &self.outputs),
            ("states", &self.states),
            ("input_units", &self.input_units),
            ("output_units", &self.output_units),
            ("state_units", &self.state_units),
        ]
    }

    /// Writes the ROM atomically; the format follows the extension of `path`.
    pub fn write(&self, path: &Path) -> Result<(), ExportError> {
        let reference_time = self.reference_time.unwrap_or(f64::NAN);
        match format_of(path)? {
            Format::Json => {
                let text = serde_json::to_string_pretty(&self.to_json()).unwrap_or_default() + "\n";
                super::atomic::write_atomic_bytes(path, text.as_bytes())?;
            }
            Format::Mat => {
                let mut f = super::mat5::MatFile::new();
                for (name, m) in self.matrices() {
                    f.add_matrix(name, &m)?;
                }
                f.add_complex_column("eigenvalues", &self.eigenvalues)?;
                f.add_complex_column("full_eigenvalues", &self.full_eigenvalues)?;
                for (name, list) in self.names() {
                    f.add_string_list(name, list)?;
                }
                f.add_string("kind", self.kind)?;
                f.add_string("time", &self.time_domain())?;
                f.add_string("units", &self.units_line())?;
                f.add_string("discretization", &self.discretization)?;
                f.add_scalar("reference_time", reference_time)?;
                f.add_scalar("dcoef", self.dcoef)?;
                f.add_scalar("sample_time", self.sample_time.unwrap_or(f64::NAN))?;
                f.add_scalar("error_bound", self.error_bound.unwrap_or(f64::NAN))?;
                f.write(path)?;
            }
            Format::Npz => {
                let mut f = super::npz::NpzWriter::new();
                for (name, m) in self.matrices() {
                    f.add_matrix(name, &m)?;
                }
                f.add_complex_column("eigenvalues", &self.eigenvalues)?;
                f.add_complex_column("full_eigenvalues", &self.full_eigenvalues)?;
                for (name, list) in self.names() {
                    f.add_string_list(name, list)?;
                }
                f.add_string_list("kind", &[self.kind.to_string()])?;
                f.add_string_list("time", &[self.time_domain()])?;
                f.add_string_list("units", &[self.units_line()])?;
                f.add_string_list("discretization", std::slice::from_ref(&self.discretization))?;
                f.add_scalar("reference_time", reference_time)?;
                f.add_scalar("dcoef", self.dcoef)?;
                f.add_scalar("sample_time", self.sample_time.unwrap_or(f64::NAN))?;
                f.add_scalar("error_bound", self.error_bound.unwrap_or(f64::NAN))?;
                f.write(path)?;
            }
            Format::MScript => {
                super::atomic::write_atomic_bytes(path, super::rom_script::script(self).as_bytes())?;
            }
            Format::Fmu => {
                // The model identifier is the file's name as a C identifier.
                let bytes = super::fmu::fmu_bytes(self, &super::fmu::model_identifier(path)).map_err(|e| ExportError::Fmu(path.display().to_string(), e))?;
                super::atomic::write_atomic_bytes(path, &bytes)?;
            }
        }
        Ok(())
    }
}
