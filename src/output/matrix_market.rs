//! Matrices as Matrix Market files (read back by `input::matrix_market`).

use std::path::Path;

use faer::Mat;

use super::atomic::{write_atomic_bytes, OutputError};
use crate::linear::SparseMatrix;

/// Writes a matrix as `coordinate real general` (nonzeros only), atomically.
pub fn write_matrix(path: &Path, m: &Mat<f64>) -> Result<(), OutputError> {
    let mut entries = Vec::new();
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            if m[(i, j)] != 0.0 {
                entries.push(format!("{} {} {:e}", i + 1, j + 1, m[(i, j)]));
            }
        }
    }
    let text = format!("%%MatrixMarket matrix coordinate real general\n% written by romdyn\n{} {} {}\n{}\n", m.nrows(), m.ncols(), entries.len(), entries.join("\n"));
    write_atomic_bytes(path, text.as_bytes())
}

/// Writes a sparse matrix as `coordinate real general` (its stored entries, row by row,
/// each value in the shortest digits that read back to the same double), atomically.
pub fn write_sparse_matrix(path: &Path, m: &SparseMatrix) -> Result<(), OutputError> {
    use std::fmt::Write;
    let mut text = format!("%%MatrixMarket matrix coordinate real general\n% written by romdyn\n{} {} {}\n", m.nrows(), m.ncols(), m.nnz());
    for (i, j, v) in m.triplets() {
        let _ = writeln!(text, "{} {} {:e}", i + 1, j + 1, v);
    }
    write_atomic_bytes(path, text.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::matrix_market::{read_matrix, read_sparse_matrix};

    #[test]
    fn sparse_write_then_read_round_trips_bit_for_bit() {
        let dir = std::env::temp_dir().join(format!("romdyn-mm-sparse-{}", std::process::id()));
        let entries = [(0, 2, 0.1), (1, 0, -1.0 / 3.0), (2, 2, 6.02214076e23), (2, 1, -5e-324)];
        let Some(m) = SparseMatrix::from_triplets(3, 4, entries) else { unreachable!("indices in range") };
        write_sparse_matrix(&dir.join("s.mtx"), &m).unwrap();
        let back = read_sparse_matrix(&dir.join("s.mtx")).unwrap();
        assert_eq!((back.nrows(), back.ncols()), (3, 4));
        assert_eq!(back.triplets().collect::<Vec<_>>(), m.triplets().collect::<Vec<_>>());
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn write_then_read_round_trips() {
        let dir = std::env::temp_dir().join(format!("romdyn-mm-{}", std::process::id()));
        let m = Mat::from_fn(3, 2, |i, j| if i == j { 0.0 } else { (i + 10 * j) as f64 + 0.25 });
        write_matrix(&dir.join("m.mtx"), &m).unwrap();
        assert_eq!(read_matrix(&dir.join("m.mtx")).unwrap(), m);
        std::fs::remove_dir_all(&dir).ok();
    }
}
