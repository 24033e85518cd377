//! Exporting a ROM: JSON, MATLAB v5 `.mat` or NumPy `.npz`, chosen by the file extension.

use std::path::Path;

use faer::{c64, Mat};
use serde_json::{json, Value};

use crate::rom::{DescriptorRom, OrdinaryRom};

/// A ROM in exportable form: `E ẋ = A x + B u`, `z = C x + D u`.
#[derive(Clone, Debug)]
pub struct RomExport {
    /// `"descriptor"` (D = 0, E possibly singular) or `"ordinary"` (E = I).
    pub kind: &'static str,
    pub e: Mat<f64>,
    pub a: Mat<f64>,
    pub b: Mat<f64>,
    pub c: Mat<f64>,
    pub d: Mat<f64>,
    pub eigenvalues: Vec<c64>,
    pub inputs: Vec<String>,
    pub outputs: Vec<String>,
}

impl From<&DescriptorRom> for RomExport {
    fn from(r: &DescriptorRom) -> Self {
        RomExport {
            kind: "descriptor",
            e: r.e.clone(),
            a: r.a.clone(),
            b: r.b.clone(),
            c: r.c.clone(),
            d: Mat::zeros(r.c.nrows(), r.b.ncols()),
            eigenvalues: r.eigenvalues.clone(),
            inputs: r.input_names.clone(),
            outputs: r.output_names.clone(),
        }
    }
}

impl From<&OrdinaryRom> for RomExport {
    fn from(r: &OrdinaryRom) -> Self {
        let n = r.a.nrows();
        RomExport {
            kind: "ordinary",
            e: Mat::identity(n, n),
            a: r.a.clone(),
            b: r.b.clone(),
            c: r.c.clone(),
            d: r.d.clone(),
            eigenvalues: r.eigenvalues.clone(),
            inputs: r.input_names.clone(),
            outputs: r.output_names.clone(),
        }
    }
}

fn rows(m: &Mat<f64>) -> Value {
    Value::Array((0..m.nrows()).map(|i| Value::Array((0..m.ncols()).map(|j| json!(m[(i, j)])).collect())).collect())
}

/// Why a ROM could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error("{0}: unknown output format (use .json, .mat or .npz)")]
    UnknownFormat(String),
    #[error(transparent)]
    Output(#[from] super::atomic::OutputError),
}

impl RomExport {
    /// The JSON document (keys E, A, B, C, D as arrays of rows).
    pub fn to_json(&self) -> Value {
        json!({
            "kind": self.kind,
            "units": "SI: inputs and outputs in the units of the model's forces/moments and displacements/rotations; eigenvalues in rad/s",
            "E": rows(&self.e),
            "A": rows(&self.a),
            "B": rows(&self.b),
            "C": rows(&self.c),
            "D": rows(&self.d),
            "eigenvalues": self.eigenvalues.iter().map(|l| json!({"re": l.re, "im": l.im})).collect::<Vec<_>>(),
            "inputs": self.inputs,
            "outputs": self.outputs,
        })
    }

    fn matrices(&self) -> [(&'static str, &Mat<f64>); 5] {
        [("E", &self.e), ("A", &self.a), ("B", &self.b), ("C", &self.c), ("D", &self.d)]
    }

    /// Writes the ROM atomically; the format follows the extension of `path`.
    pub fn write(&self, path: &Path) -> Result<(), ExportError> {
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("json") => {
                let text = serde_json::to_string_pretty(&self.to_json()).unwrap_or_default() + "\n";
                super::atomic::write_atomic_bytes(path, text.as_bytes())?;
            }
            Some("mat") => {
                let mut f = super::mat5::MatFile::new();
                for (name, m) in self.matrices() {
                    f.add_matrix(name, m)?;
                }
                f.add_complex_column("eigenvalues", &self.eigenvalues)?;
                f.add_string_list("inputs", &self.inputs)?;
                f.add_string_list("outputs", &self.outputs)?;
                f.add_string("kind", self.kind)?;
                f.write(path)?;
            }
            Some("npz") => {
                let mut f = super::npz::NpzWriter::new();
                for (name, m) in self.matrices() {
                    f.add_matrix(name, m)?;
                }
                f.add_complex_column("eigenvalues", &self.eigenvalues)?;
                f.add_string_list("inputs", &self.inputs)?;
                f.add_string_list("outputs", &self.outputs)?;
                f.add_string_list("kind", &[self.kind.to_string()])?;
                f.write(path)?;
            }
            _ => return Err(ExportError::UnknownFormat(path.display().to_string())),
        }
        Ok(())
    }
}
