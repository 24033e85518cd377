//! Small dense helpers shared by the ROM code.

use faer::linalg::solvers::Solve;
use faer::{c64, Mat};

/// `M⁻¹ R` by LU with full pivoting, or `None` when `M` is numerically singular
/// (smallest pivot below `n ε` times the largest).
pub(crate) fn solve_nonsingular(m: &Mat<f64>, r: &Mat<f64>) -> Option<Mat<f64>> {
    let n = m.nrows();
    if n == 0 {
        return Some(Mat::zeros(0, r.ncols()));
    }
    let lu = m.full_piv_lu();
    let u = lu.U();
    let (big, small) = (0..n).map(|i| u[(i, i)].abs()).fold((0.0f64, f64::INFINITY), |(b, s), x| (b.max(x), s.min(x)));
    if !(small > big * n as f64 * f64::EPSILON) {
        return None;
    }
    Some(lu.solve(r))
}

/// Complex copy of a real matrix.
pub(crate) fn to_complex(m: &Mat<f64>) -> Mat<c64> {
    Mat::from_fn(m.nrows(), m.ncols(), |i, j| c64::new(m[(i, j)], 0.0))
}

/// `jω P + Q` for real `P`, `Q`.
pub(crate) fn shifted(omega: f64, p: &Mat<f64>, q: &Mat<f64>) -> Mat<c64> {
    Mat::from_fn(p.nrows(), p.ncols(), |i, j| c64::new(q[(i, j)], omega * p[(i, j)]))
}

/// `C (jω P + Q)⁻¹ B + D` for one frequency (LU with partial pivoting).
pub(crate) fn transfer(omega: f64, p: &Mat<f64>, q: &Mat<f64>, b: &Mat<f64>, c: &Mat<f64>, d: Option<&Mat<f64>>) -> Mat<c64> {
    let x = shifted(omega, p, q).partial_piv_lu().solve(&to_complex(b));
    let mut h = &to_complex(c) * &x;
    if let Some(d) = d {
        h += &to_complex(d);
    }
    h
}
