//! Linear-DAE pencil files (JSON): `{"Fyd", "Fy"}` or `{"J", "Jstar", "dcoef"}`, plus `"B"`,
//! `"C"` and optional `"input_names"`, `"output_names"`, `"unknown_names"`, `"dcoef"`.
//!
//! A matrix is a dense row-major array of rows, or a path (string, relative to the JSON
//! file) to a Matrix Market file, or `{"matrix_market": "path"}`.
//!
//! [`read_pencil_file`] also takes MBDyn's eigenanalysis `.m` files (by the extension; see
//! [`super::eigen_pencil`]).

use std::path::{Path, PathBuf};

use faer::Mat;
use serde_json::Value;

use super::text_file::{read_text_file, TextFileError};
use super::eigen_pencil::{read_eigen_pencil, EigenPencilError, PencilPorts};
use crate::linear::{Jacobians, LinearDae};

/// A malformed pencil file.
#[derive(Debug, thiserror::Error)]
pub enum PencilError {
    #[error(transparent)]
    Read(#[from] TextFileError),
    #[error("{file}:{line}:{column}: invalid JSON: {message}")]
    Json { file: PathBuf, line: usize, column: usize, message: String },
    #[error("{file}: field \"{field}\": {message}")]
    Field { file: PathBuf, field: String, message: String },
    #[error("{file}: {message}")]
    Shape { file: PathBuf, message: String },
    #[error(transparent)]
    EigenFile(#[from] EigenPencilError),
}

struct Reader<'a> {
    file: &'a Path,
    root: serde_json::Map<String, Value>,
}

impl Reader<'_> {
    fn err(&self, field: &str, message: impl Into<String>) -> PencilError {
        PencilError::Field { file: self.file.to_path_buf(), field: field.into(), message: message.into() }
    }

    fn matrix(&self, field: &str) -> Result<Option<Mat<f64>>, PencilError> {
        let Some(v) = self.root.get(field) else { return Ok(None) };
        let mm_path = match v {
            Value::String(p) => Some(p.as_str()),
            Value::Object(o) => match o.get("matrix_market") {
                Some(Value::String(p)) => Some(p.as_str()),
                _ => return Err(self.err(field, "expected an array of rows, a path string, or {\"matrix_market\": \"path\"}")),
            },
            _ => None,
        };
        if let Some(p) = mm_path {
            let path = self.file.parent().unwrap_or(Path::new(".")).join(p);
            return crate::matrix_market::read_matrix(&path)
                .map(Some)
                .map_err(|e| self.err(field, e.to_string()));
        }
        let rows = v.as_array().ok_or_else(|| self.err(field, format!("expected an array of rows of numbers, found {}", kind(v))))?;
        let mut out: Vec<Vec<f64>> = Vec::with_capacity(rows.len());
        for (i, row) in rows.iter().enumerate() {
            let row = row.as_array().ok_or_else(|| self.err(field, format!("row {}: expected an array of numbers, found {}", i + 1, kind(row))))?;
            let mut r = Vec::with_capacity(row.len());
            for (j, x) in row.iter().enumerate() {
                let x = x.as_f64().ok_or_else(|| self.err(field, format!("row {}, column {}: expected a number, found {}", i + 1, j + 1, kind(x))))?;
                r.push(x);
            }
            if let Some(first) = out.first() {
                if first.len() != r.len() {
                    return Err(self.err(field, format!("row {} has {} entries, row 1 has {}", i + 1, r.len(), first.len())));
                }
            }
            out.push(r);
        }
        let ncols = out.first().map_or(0, Vec::len);
        Ok(Some(Mat::from_fn(out.len(), ncols, |i, j| out[i][j])))
    }

    fn require(&self, field: &str) -> Result<Mat<f64>, PencilError> {
        self.matrix(field)?.ok_or_else(|| self.err(field, "missing"))
    }

    fn names(&self, field: &str, n: usize, default: impl Fn(usize) -> String) -> Result<Vec<String>, PencilError> {
        match self.root.get(field) {
            None => Ok((0..n).map(default).collect()),
            Some(Value::Array(a)) => {
                let names: Option<Vec<String>> = a.iter().map(|x| x.as_str().map(String::from)).collect();
                let names = names.ok_or_else(|| self.err(field, "expected an array of strings"))?;
                if names.len() != n {
                    return Err(self.err(field, format!("expected {n} names, found {}", names.len())));
                }
                Ok(names)
            }
            Some(v) => Err(self.err(field, format!("expected an array of strings, found {}", kind(v)))),
        }
    }

    fn dcoef(&self) -> Result<Option<f64>, PencilError> {
        match self.root.get("dcoef") {
            None => Ok(None),
            Some(v) => match v.as_f64() {
                Some(c) if c > 0.0 && c.is_finite() => Ok(Some(c)),
                _ => Err(self.err("dcoef", "expected a positive number")),
            },
        }
    }
}

fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// A pencil file's content.
#[derive(Clone, Debug)]
pub struct PencilFile {
    pub dae: LinearDae,
    /// The file's `"dcoef"`: with J/J* it is part of the Jacobians; with F_yd/F_y it only
    /// sets the coefficient of the Λ form.
    pub dcoef: Option<f64>,
}

/// Reads a pencil file: an MBDyn eigenanalysis `.m` file (inputs and outputs from `ports`)
/// or a JSON pencil (inputs and outputs in the file; `ports` must be empty).
pub fn read_pencil_file(file: &Path, ports: &PencilPorts) -> Result<PencilFile, PencilError> {
    if file.extension().is_some_and(|e| e.eq_ignore_ascii_case("m")) {
        let (dae, dcoef) = read_eigen_pencil(file, ports)?;
        return Ok(PencilFile { dae, dcoef: Some(dcoef) });
    }
    if !ports.is_empty() {
        return Err(PencilError::Shape { file: file.to_path_buf(), message: "input rows and output columns select ports of an MBDyn .m pencil; a JSON pencil carries its own B and C".into() });
    }
    read_pencil(file)
}

/// Reads a JSON pencil file.
pub fn read_pencil(file: &Path) -> Result<PencilFile, PencilError> {
    let text = read_text_file(file)?;
    parse_pencil(&text, file)
}

/// Parses the text of a pencil file (`file` names it in errors and anchors relative paths).
pub fn parse_pencil(text: &str, file: &Path) -> Result<PencilFile, PencilError> {
    // Every number becomes a JSON value (32 bytes) before it is a matrix entry: bound their
    // count by the dense-matrix budget before parsing.
    let separators = text.bytes().filter(|b| *b == b',').count();
    if separators > crate::limits::MAX_DENSE_ENTRIES {
        return Err(PencilError::Shape {
            file: file.to_path_buf(),
            message: format!("{separators} values: more than romdyn's budget of {} numbers for a JSON pencil (use Matrix Market files for large matrices)", crate::limits::MAX_DENSE_ENTRIES),
        });
    }
    let json_error = |e: serde_json::Error| PencilError::Json { file: file.to_path_buf(), line: e.line(), column: e.column(), message: e.to_string() };
    let value: Value = serde_json::from_str(text).map_err(json_error)?;
    if !value.is_object() {
        return Err(PencilError::Shape { file: file.to_path_buf(), message: "expected a JSON object at the top level".into() });
    }
    // JSON leaves duplicate keys undefined and serde keeps the last: refuse them, at the key.
    let UniqueFields(root) = serde_json::from_str(text).map_err(json_error)?;
    let r = Reader { file, root };
    let shape = |message: String| PencilError::Shape { file: file.to_path_buf(), message };
    let jacobians = match (r.matrix("Fyd")?, r.matrix("Fy")?, r.matrix("J")?, r.matrix("Jstar")?) {
        (Some(fyd), Some(fy), None, None) => Jacobians::Derivatives { fyd, fy },
        (None, None, Some(j), Some(jstar)) => {
            let dcoef = r.dcoef()?.ok_or_else(|| r.err("dcoef", "missing (required with J and Jstar)"))?;
            Jacobians::Coefficient { j, jstar, dcoef }
        }
        _ => return Err(shape("expected either \"Fyd\" and \"Fy\", or \"J\", \"Jstar\" and \"dcoef\"".into())),
    };
    let (names_a, names_b) = match &jacobians {
        Jacobians::Derivatives { .. } => ("Fyd", "Fy"),
        Jacobians::Coefficient { .. } => ("J", "Jstar"),
    };
    let (a, b_) = match &jacobians {
        Jacobians::Derivatives { fyd, fy } => (fyd, fy),
        Jacobians::Coefficient { j, jstar, .. } => (j, jstar),
    };
    let n = a.nrows();
    if a.ncols() != n || b_.nrows() != n || b_.ncols() != n {
        return Err(shape(format!(
            "\"{names_a}\" is {}x{} and \"{names_b}\" is {}x{}: both must be square and of the same size",
            a.nrows(),
            a.ncols(),
            b_.nrows(),
            b_.ncols()
        )));
    }
    let b = r.require("B")?;
    let c = r.require("C")?;
    if b.nrows() != n {
        return Err(r.err("B", format!("has {} rows, expected {n} (one per equation)", b.nrows())));
    }
    if c.ncols() != n {
        return Err(r.err("C", format!("has {} columns, expected {n} (one per unknown)", c.ncols())));
    }
    let dae = LinearDae {
        unknown_names: r.names("unknown_names", n, |i| format!("y{}", i + 1))?,
        input_names: r.names("input_names", b.ncols(), |i| format!("u{}", i + 1))?,
        output_names: r.names("output_names", c.nrows(), |i| format!("z{}", i + 1))?,
        jacobians,
        b,
        c,
        constraint_form: None,
        multipliers: Vec::new(),
        c_rate: None,
    };
    Ok(PencilFile { dae, dcoef: r.dcoef()? })
}

/// The top-level object of a pencil file, refusing a key that appears twice.
struct UniqueFields(serde_json::Map<String, Value>);

impl<'de> serde::Deserialize<'de> for UniqueFields {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Fields;
        impl<'de> serde::de::Visitor<'de> for Fields {
            type Value = UniqueFields;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a JSON object")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<UniqueFields, A::Error> {
                let mut out = serde_json::Map::new();
                while let Some(key) = map.next_key::<String>()? {
                    if out.contains_key(&key) {
                        return Err(serde::de::Error::custom(format!("field \"{key}\" appears twice")));
                    }
                    let value: Value = map.next_value()?;
                    out.insert(key, value);
                }
                Ok(UniqueFields(out))
            }
        }
        d.deserialize_map(Fields)
    }
}
