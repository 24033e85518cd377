//! The direction a singular static matrix leaves free: rigid-body motion of an
//! unrestrained model.

use faer::Mat;

use super::dense::equilibration;

/// When `m` is numerically singular (smallest singular value of the equilibrated matrix
/// below `n ε` times the largest), the null direction in `m`'s unknowns (largest entry 1).
pub fn null_direction(m: &Mat<f64>) -> Option<Vec<f64>> {
    let n = m.nrows();
    if n == 0 {
        return None;
    }
    let (dr, dc) = equilibration(m);
    let scaled = Mat::from_fn(n, n, |i, j| dr[i] * m[(i, j)] * dc[j]);
    let svd = scaled.svd().ok()?;
    let s = svd.S();
    let (big, small) = (s[0], s[n - 1]);
    if small > big * n as f64 * f64::EPSILON * 16.0 {
        return None;
    }
    let v = svd.V();
    let x: Vec<f64> = (0..n).map(|i| dc[i] * v[(i, n - 1)]).collect();
    let top = x.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    (top > 0.0).then(|| x.iter().map(|e| e / top).collect())
}
