//! Small dense helpers shared by the ROM code.

use faer::linalg::solvers::{FullPivLu, Solve};
use faer::{c64, Mat};

/// Row and column scale factors (powers of two) that bring every row's and column's largest
/// entry of `m` near 1 (alternating sweeps).
pub(crate) fn equilibration(m: &Mat<f64>) -> (Vec<f64>, Vec<f64>) {
    let n = m.nrows();
    let (mut row, mut col) = (vec![1.0; n], vec![1.0; n]);
    let pow2 = |s: f64| if s > 0.0 && s.is_finite() { (-s.log2().round()).exp2() } else { 1.0 };
    // Zeros change no maximum: the sweeps run over the non-zeros (a static matrix has few).
    let entries: Vec<(usize, usize, f64)> = (0..m.ncols()).flat_map(|j| (0..n).map(move |i| (i, j))).map(|(i, j)| (i, j, m[(i, j)])).filter(|e| e.2 != 0.0).collect();
    let mut big = vec![0.0f64; n];
    for _ in 0..4 {
        big.iter_mut().for_each(|b| *b = 0.0);
        for &(i, j, v) in &entries {
            big[i] = big[i].max((row[i] * v * col[j]).abs());
        }
        row.iter_mut().zip(&big).for_each(|(r, &b)| *r *= pow2(b));
        big.iter_mut().for_each(|b| *b = 0.0);
        for &(i, j, v) in &entries {
            big[j] = big[j].max((row[i] * v * col[j]).abs());
        }
        col.iter_mut().zip(&big).for_each(|(c, &b)| *c *= pow2(b));
    }
    (row, col)
}

/// `M⁻¹ R` by LU of the equilibrated `D_r M D_c`, or `None` when it is numerically singular
/// (smallest pivot of an LU with full pivoting below `n ε` times the largest; a
/// partial-pivoting LU that proves the matrix nonsingular answers first). Equilibration
/// matters for multibody static matrices: a saddle point `[K Φᵀ; Φ 0]` with stiffness
/// `K ~ 1e7` and unit constraint gradients has singular values near `1/K` while being
/// perfectly determined.
pub(crate) fn solve_nonsingular(m: &Mat<f64>, r: &Mat<f64>) -> Option<Mat<f64>> {
    solve_or_free_direction(m, r).ok()
}

/// [`solve_nonsingular`], or when `m` is numerically singular the direction it leaves free
/// from the same factorization ([`free_direction`]; `None` inside when
/// it could not be formed).
pub(crate) fn solve_or_free_direction(m: &Mat<f64>, r: &Mat<f64>) -> Result<Mat<f64>, Option<Vec<f64>>> {
    let n = m.nrows();
    if n == 0 {
        return Ok(Mat::zeros(0, r.ncols()));
    }
    let (dr, dc) = equilibration(m);
    let scaled = Mat::from_fn(n, n, |i, j| dr[i] * m[(i, j)] * dc[j]);
    // M x = R  ⇔  (D_r M D_c)(D_c⁻¹ x) = D_r R. A partial-pivoting LU that proves `D_r M D_c`
    // nonsingular (blocked: 10 times faster at n = 1712) answers; only a doubtful matrix
    // goes to full pivoting's rank test.
    let rhs = Mat::from_fn(n, r.ncols(), |i, j| dr[i] * r[(i, j)]);
    let x = match crate::lu::certified_partial_lu(scaled.as_ref(), n as f64 * f64::EPSILON, 0.0) {
        Some(lu) => lu.solve(rhs),
        None => {
            let lu = scaled.full_piv_lu();
            if !crate::lu::full_pivots_nonsingular(&lu, n as f64 * f64::EPSILON) {
                return Err(free_direction(&lu, &dc));
            }
            lu.solve(rhs)
        }
    };
    Ok(Mat::from_fn(n, r.ncols(), |i, j| dc[i] * x[(i, j)]))
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

/// `(C + jω C_v) (jω P + Q)⁻¹ B + D` for one frequency: outputs with rate rows `C_v`.
pub(crate) fn transfer_with_rates(omega: f64, p: &Mat<f64>, q: &Mat<f64>, b: &Mat<f64>, c: &Mat<f64>, c_rate: Option<&Mat<f64>>, d: Option<&Mat<f64>>) -> Mat<c64> {
    let x = shifted(omega, p, q).partial_piv_lu().solve(&to_complex(b));
    let cc = match c_rate {
        Some(cv) => shifted(omega, cv, c),
        None => to_complex(c),
    };
    let mut h = &cc * &x;
    if let Some(d) = d {
        h += &to_complex(d);
    }
    h
}

/// A null direction of `D_r M D_c = Pᵀ L U Qᵀ` from its factors, mapped back to `M`'s
/// unknowns by `D_c`; `None` when no pivot is at or below `n ε` times the largest.
///
/// With full pivoting every pivot after the first negligible one `u_kk` is at most `|u_kk|`
/// and the trailing block `U[k.., k..]` is negligible: `y = (−U₁₁⁻¹ U[..k, k], 1, 0, …)`
/// gives `U y ≈ 0`, and `x = D_c Q y` the free direction (one of them when `M` has a
/// larger null space: rigid-body motion of a free model).
pub(crate) fn free_direction(lu: &FullPivLu<f64>, dc: &[f64]) -> Option<Vec<f64>> {
    let u = lu.U();
    let n = u.nrows();
    let big = (0..n).map(|i| u[(i, i)].abs()).fold(0.0f64, f64::max);
    let tiny = big * n as f64 * f64::EPSILON;
    let k = (0..n).find(|&i| !(u[(i, i)].abs() > tiny))?;
    let mut y = vec![0.0; n];
    y[k] = 1.0;
    for i in (0..k).rev() {
        let s: f64 = (i + 1..=k).map(|j| u[(i, j)] * y[j]).sum();
        y[i] = -s / u[(i, i)];
    }
    // (L U)[a, b] = (D_r M D_c)[P[a], Q[b]] (faer's reconstruction), so x[Q[b]] = y[b].
    let q = lu.Q().arrays().0;
    let mut x = vec![0.0; n];
    for (b, &yb) in y.iter().enumerate() {
        x[q[b]] = dc[q[b]] * yb;
    }
    let top = x.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    (top > 0.0 && top.is_finite()).then(|| x.iter().map(|e| e / top).collect())
}
