//! Matrices as Matrix Market files (read back by `input::matrix_market`).

use std::path::Path;

use faer::Mat;

use super::atomic::{write_atomic_bytes, OutputError};

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::matrix_market::read_matrix;

    #[test]
    fn write_then_read_round_trips() {
        let dir = std::env::temp_dir().join(format!("romdyn-mm-{}", std::process::id()));
        let m = Mat::from_fn(3, 2, |i, j| if i == j { 0.0 } else { (i + 10 * j) as f64 + 0.25 });
        write_matrix(&dir.join("m.mtx"), &m).unwrap();
        assert_eq!(read_matrix(&dir.join("m.mtx")).unwrap(), m);
        std::fs::remove_dir_all(&dir).ok();
    }
}
