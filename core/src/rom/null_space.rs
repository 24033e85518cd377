//! The direction a singular static matrix leaves free: rigid-body motion of an
//! unrestrained model.

use faer::Mat;

use super::dense::{equilibration, free_direction};

/// When `m` is numerically singular (the smallest pivot of the full-pivoting LU of the
/// equilibrated matrix at or below `n ε` times the largest, the test of
/// [`super::dense::solve_nonsingular`]), a direction it leaves free, in `m`'s unknowns
/// (largest entry 1).
pub fn null_direction(m: &Mat<f64>) -> Option<Vec<f64>> {
    let n = m.nrows();
    if n == 0 {
        return None;
    }
    let (dr, dc) = equilibration(m);
    let scaled = Mat::from_fn(n, n, |i, j| dr[i] * m[(i, j)] * dc[j]);
    free_direction(&scaled.full_piv_lu(), &dc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rank-deficient matrix with a known null vector (closed form): the direction found
    /// is that vector (up to its sign and scale) to rounding, and a nonsingular matrix has
    /// none.
    #[test]
    fn the_free_direction_of_a_singular_matrix_is_its_null_vector() {
        // M = [[2, -1, 0], [-1, 2, -1], [0, -1, 1]] * stiffness-like scales: rows sum to
        // zero after the scaling below, so M x = 0 for x = D⁻¹ (1, 1, 1) with D = diag(s).
        let s = [1e3, 1.0, 1e-4];
        let k = Mat::from_fn(3, 3, |i, j| match (i, j) {
            (0, 0) => 1.0,
            (0, 1) | (1, 0) => -1.0,
            (1, 1) => 2.0,
            (1, 2) | (2, 1) => -1.0,
            (2, 2) => 1.0,
            _ => 0.0,
        });
        let m = Mat::from_fn(3, 3, |i, j| 7.0 * k[(i, j)] * s[j]);
        let x = null_direction(&m).expect("singular");
        let exact: Vec<f64> = s.iter().map(|v| 1.0 / v).collect();
        let top = exact.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let sign = x[2].signum();
        for i in 0..3 {
            assert!((sign * x[i] - exact[i] / top).abs() <= 1e-12, "{x:?}");
        }
        let regular = Mat::from_fn(3, 3, |i, j| if i == j { 2.0 } else { 1.0 });
        assert!(null_direction(&regular).is_none());
    }
}
