//! NumPy `.npz` writer: an uncompressed ZIP archive of `.npy` (format 1.0) arrays —
//! float64 matrices, complex128 vectors and unicode string arrays — readable with
//! `numpy.load(path, allow_pickle=False)`.

use std::path::Path;

use faer::{c64, Mat};

use super::atomic::{write_atomic_bytes, OutputError};

/// An `.npz` archive being assembled in memory.
#[derive(Default)]
pub struct NpzWriter {
    entries: Vec<(String, Vec<u8>)>,
}

/// A `.npy` file: magic, version 1.0, header dict padded so the data starts on a
/// 64-byte boundary, then the data.
fn npy(descr: &str, shape: &[usize], data: &[u8]) -> Vec<u8> {
    npy_ordered(descr, shape, false, data)
}

/// [`npy`] with the data in column-major order when `fortran`.
fn npy_ordered(descr: &str, shape: &[usize], fortran: bool, data: &[u8]) -> Vec<u8> {
    let shape = match shape {
        [] => "()".to_string(),
        [n] => format!("({n},)"),
        s => format!("({})", s.iter().map(usize::to_string).collect::<Vec<_>>().join(", ")),
    };
    let order = if fortran { "True" } else { "False" };
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': {order}, 'shape': {shape}, }}");
    let total = 10 + header.len() + 1;
    header.push_str(&" ".repeat(total.next_multiple_of(64) - total));
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend((header.len() as u16).to_le_bytes());
    out.extend(header.as_bytes());
    out.extend(data);
    out
}

impl NpzWriter {
    pub fn new() -> Self {
        Self::default()
    }

    fn push(&mut self, name: &str, npy: Vec<u8>) -> Result<(), OutputError> {
        let file = format!("{name}.npy");
        if name.is_empty() || name.contains('/') || self.entries.iter().any(|(n, _)| *n == file) {
            return Err(OutputError::Invalid { path: name.into(), message: "array names must be unique, non-empty and contain no '/'".into() });
        }
        self.entries.push((file, npy));
        Ok(())
    }

    /// A float64 matrix (row-major, shape (rows, cols)).
    pub fn add_matrix(&mut self, name: &str, m: &Mat<f64>) -> Result<(), OutputError> {
        let data: Vec<u8> = (0..m.nrows()).flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)])).flat_map(f64::to_le_bytes).collect();
        self.push(name, npy("<f8", &[m.nrows(), m.ncols()], &data))
    }

    /// A float64 array of any rank, `data` in column-major order (first index fastest, stored
    /// with `fortran_order`): `A[:, :, k]` in NumPy is MATLAB's `A(:,:,k)`.
    pub fn add_array(&mut self, name: &str, shape: &[usize], data: &[f64]) -> Result<(), OutputError> {
        if shape.iter().product::<usize>() != data.len() {
            return Err(OutputError::Invalid { path: name.into(), message: format!("array of {} values does not have the shape {shape:?}", data.len()) });
        }
        let bytes: Vec<u8> = data.iter().flat_map(|x| x.to_le_bytes()).collect();
        self.push(name, npy_ordered("<f8", shape, true, &bytes))
    }

    /// A complex128 vector.
    pub fn add_complex_column(&mut self, name: &str, v: &[c64]) -> Result<(), OutputError> {
        let data: Vec<u8> = v.iter().flat_map(|x| [x.re, x.im]).flat_map(f64::to_le_bytes).collect();
        self.push(name, npy("<c16", &[v.len()], &data))
    }

    /// A float64 scalar (shape ()).
    pub fn add_scalar(&mut self, name: &str, x: f64) -> Result<(), OutputError> {
        self.push(name, npy("<f8", &[], &x.to_le_bytes()))
    }

    /// A unicode string array (`<U{max length}`, UTF-32LE).
    pub fn add_string_list(&mut self, name: &str, list: &[String]) -> Result<(), OutputError> {
        let width = list.iter().map(|s| s.chars().count()).max().unwrap_or(0).max(1);
        let mut data = Vec::with_capacity(list.len() * width * 4);
        for s in list {
            let n = s.chars().count();
            data.extend(s.chars().flat_map(|c| (c as u32).to_le_bytes()));
            data.extend(std::iter::repeat_n(0u8, 4 * (width - n)));
        }
        self.push(name, npy(&format!("<U{width}"), &[list.len()], &data))
    }

    /// The ZIP archive of the `.npy` members ([`super::zip::stored_archive`]).
    pub fn to_bytes(&self) -> Vec<u8> {
        super::zip::stored_archive(&self.entries)
    }

    /// Writes the archive atomically.
    pub fn write(&self, path: &Path) -> Result<(), OutputError> {
        write_atomic_bytes(path, &self.to_bytes())
    }
}

#[cfg(test)]
mod tests;
