//! MATLAB Level-5 MAT-file writer (uncompressed): real and complex double matrices,
//! character arrays and cell arrays of strings. Readable by MATLAB, Octave and
//! `scipy.io.loadmat`. Doubles are always stored as `miDOUBLE`, never narrowed to integers.

use std::path::Path;

use faer::{c64, Mat};

use super::atomic::{write_atomic_bytes, OutputError};

const MI_INT8: u32 = 1;
const MI_UINT16: u32 = 4;
const MI_INT32: u32 = 5;
const MI_UINT32: u32 = 6;
const MI_DOUBLE: u32 = 9;
const MI_MATRIX: u32 = 14;
const MX_CELL: u32 = 1;
const MX_CHAR: u32 = 4;
const MX_DOUBLE: u32 = 6;
const COMPLEX_FLAG: u32 = 0x0800;

/// A MAT-file being assembled in memory.
#[derive(Default)]
pub struct MatFile {
    body: Vec<u8>,
    names: Vec<String>,
}

/// One tagged data element, padded to 8 bytes.
fn element(out: &mut Vec<u8>, ty: u32, data: &[u8]) {
    out.extend(ty.to_le_bytes());
    out.extend((data.len() as u32).to_le_bytes());
    out.extend(data);
    out.resize(out.len().next_multiple_of(8), 0);
}

/// A miMATRIX element: flags, dimensions, name, then `parts` (already tagged).
fn matrix_element(class_flags: u32, dims: &[usize], name: &str, parts: &[u8]) -> Vec<u8> {
    let mut m = Vec::new();
    let flags: Vec<u8> = [class_flags, 0].iter().flat_map(|x| x.to_le_bytes()).collect();
    element(&mut m, MI_UINT32, &flags);
    let d: Vec<u8> = dims.iter().flat_map(|&x| (x as i32).to_le_bytes()).collect();
    element(&mut m, MI_INT32, &d);
    element(&mut m, MI_INT8, name.as_bytes());
    m.extend(parts);
    let mut out = Vec::with_capacity(m.len() + 8);
    out.extend(MI_MATRIX.to_le_bytes());
    out.extend((m.len() as u32).to_le_bytes());
    out.extend(m);
    out
}

fn doubles(values: impl Iterator<Item = f64>) -> Vec<u8> {
    let bytes: Vec<u8> = values.flat_map(f64::to_le_bytes).collect();
    let mut out = Vec::new();
    element(&mut out, MI_DOUBLE, &bytes);
    out
}

fn char_array(name: &str, s: &str) -> Vec<u8> {
    let units: Vec<u8> = s.encode_utf16().flat_map(u16::to_le_bytes).collect();
    let mut part = Vec::new();
    element(&mut part, MI_UINT16, &units);
    matrix_element(MX_CHAR, &[1, s.encode_utf16().count()], name, &part)
}

fn valid_name(name: &str) -> bool {
    let mut c = name.chars();
    c.next().is_some_and(|f| f.is_ascii_alphabetic()) && name.len() <= 63 && name.chars().all(|ch| ch.is_ascii_alphanumeric() || ch == '_')
}

impl MatFile {
    pub fn new() -> Self {
        Self::default()
    }

    fn push(&mut self, name: &str, element: Vec<u8>) -> Result<(), OutputError> {
        if !valid_name(name) || self.names.iter().any(|n| n == name) {
            return Err(OutputError::Invalid {
                path: name.into(),
                message: "a MAT-file variable name must be unique, start with a letter and hold at most 63 letters, digits or underscores".into(),
            });
        }
        self.names.push(name.to_string());
        self.body.extend(element);
        Ok(())
    }

    /// A real double matrix (stored column-major).
    pub fn add_matrix(&mut self, name: &str, m: &Mat<f64>) -> Result<(), OutputError> {
        let data = doubles((0..m.ncols()).flat_map(|j| (0..m.nrows()).map(move |i| m[(i, j)])));
        self.push(name, matrix_element(MX_DOUBLE, &[m.nrows(), m.ncols()], name, &data))
    }

    /// A real double array of any rank, `data` in column-major order (MATLAB's: the first
    /// index fastest), e.g. a sweep's `A(:,:,k)`.
    pub fn add_array(&mut self, name: &str, dims: &[usize], data: &[f64]) -> Result<(), OutputError> {
        if dims.iter().product::<usize>() != data.len() || dims.len() < 2 {
            return Err(OutputError::Invalid { path: name.into(), message: format!("array of {} values does not have the dimensions {dims:?} (at least 2)", data.len()) });
        }
        self.push(name, matrix_element(MX_DOUBLE, dims, name, &doubles(data.iter().copied())))
    }

    /// A complex column vector.
    pub fn add_complex_column(&mut self, name: &str, v: &[c64]) -> Result<(), OutputError> {
        let mut data = doubles(v.iter().map(|x| x.re));
        data.extend(doubles(v.iter().map(|x| x.im)));
        self.push(name, matrix_element(MX_DOUBLE | COMPLEX_FLAG, &[v.len(), 1], name, &data))
    }

    /// A real scalar.
    pub fn add_scalar(&mut self, name: &str, x: f64) -> Result<(), OutputError> {
        self.push(name, matrix_element(MX_DOUBLE, &[1, 1], name, &doubles(std::iter::once(x))))
    }

    /// A character row vector.
    pub fn add_string(&mut self, name: &str, s: &str) -> Result<(), OutputError> {
        self.push(name, char_array(name, s))
    }

    /// A column cell array of strings.
    pub fn add_string_list(&mut self, name: &str, list: &[String]) -> Result<(), OutputError> {
        let cells: Vec<u8> = list.iter().flat_map(|s| char_array("", s)).collect();
        self.push(name, matrix_element(MX_CELL, &[list.len(), 1], name, &cells))
    }

    /// The whole file: 128-byte header (text, subsystem offset, version 0x0100, 'IM') and body.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut text = format!("MATLAB 5.0 MAT-file, written by romdyn {} (SI units)", env!("CARGO_PKG_VERSION")).into_bytes();
        text.resize(116, b' ');
        let mut out = text;
        out.extend([0u8; 8]);
        out.extend(0x0100u16.to_le_bytes());
        out.extend(*b"IM");
        out.extend(&self.body);
        out
    }

    /// Writes the file atomically.
    pub fn write(&self, path: &Path) -> Result<(), OutputError> {
        write_atomic_bytes(path, &self.to_bytes())
    }
}

#[cfg(test)]
mod tests;
