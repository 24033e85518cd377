//! Diagonal scaling of a pencil `(A, B) -> (D_r A D_c, D_r B D_c)` by powers of two.
//!
//! Multibody pencils mix rows of very different size (constraint rows divided by dCoef,
//! stiffness next to mass); equilibrating rows and columns of `|A| + |B|` before QZ keeps
//! the backward error small relative to every row, and leaves eigenvalues unchanged. Right
//! vectors map back as `v = D_c v'`, left vectors as `u = D_r u'`.

use faer::{c64, Col, Mat};

pub(crate) struct BalancedPencil {
    pub a: Mat<f64>,
    pub b: Mat<f64>,
    pub row: Vec<f64>,
    pub col: Vec<f64>,
}

/// Alternating row/column equilibration: each sweep divides every row, then every column,
/// by the power of two nearest its 2-norm over both matrices.
pub(crate) fn balance_pencil(a: &Mat<f64>, b: &Mat<f64>) -> BalancedPencil {
    let n = a.nrows();
    let (mut row, mut col) = (vec![1.0; n], vec![1.0; n]);
    let pow2 = |s: f64| if s > 0.0 && s.is_finite() { (-s.log2().round()).exp2() } else { 1.0 };
    // The entries where A or B is not zero, column by column (the rows in increasing order):
    // every sum below runs over them in the order a dense row-wise or column-wise loop
    // would, and skipping exact zeros does not change a sum of squares, so the scaling is
    // that of the dense loops; multibody pencils are sparse (a tenth of the entries or less).
    let mut at: Vec<(usize, usize)> = Vec::new();
    let mut ab: Vec<[f64; 2]> = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (a[(i, j)], b[(i, j)]);
            if x != 0.0 || y != 0.0 {
                at.push((i, j));
                ab.push([x, y]);
            }
        }
    }
    // The 2-norm of entries whose squares overflow or underflow (1e±200): scaled by the
    // largest first. Used only where the plain sum of squares is out of range.
    let safe_norm = |xs: &mut dyn Iterator<Item = f64>| {
        let v: Vec<f64> = xs.map(f64::abs).collect();
        let m = v.iter().copied().fold(0.0, f64::max);
        if m > 0.0 && m.is_finite() { m * v.iter().map(|x| (x / m).powi(2)).sum::<f64>().sqrt() } else { m }
    };
    let out_of_range = |sum: f64| !sum.is_finite() || sum < f64::MIN_POSITIVE;
    for _sweep in 0..8 {
        let mut changed = false;
        let mut rs = vec![0.0; n];
        for (&(i, _), [x, y]) in at.iter().zip(&ab) {
            rs[i] += x * x + y * y;
        }
        let fr: Vec<f64> = (0..n)
            .map(|i| {
                let s = if out_of_range(rs[i]) {
                    safe_norm(&mut at.iter().zip(&ab).filter(|(t, _)| t.0 == i).flat_map(|(_, v)| *v))
                } else {
                    rs[i].sqrt()
                };
                pow2(s)
            })
            .collect();
        if fr.iter().any(|&f| f != 1.0) {
            changed = true;
            for (&(i, _), v) in at.iter().zip(ab.iter_mut()) {
                v[0] *= fr[i];
                v[1] *= fr[i];
            }
            for i in 0..n {
                row[i] *= fr[i];
            }
        }
        let mut k = 0;
        for j in 0..n {
            let first = k;
            let mut sum = 0.0;
            while k < at.len() && at[k].1 == j {
                sum += ab[k][0] * ab[k][0] + ab[k][1] * ab[k][1];
                k += 1;
            }
            let s = if out_of_range(sum) { safe_norm(&mut ab[first..k].iter().flat_map(|v| *v)) } else { sum.sqrt() };
            let f = pow2(s);
            if f != 1.0 {
                changed = true;
                col[j] *= f;
                for v in &mut ab[first..k] {
                    v[0] *= f;
                    v[1] *= f;
                }
            }
        }
        if !changed {
            break;
        }
    }
    let (mut a, mut b) = (Mat::zeros(n, n), Mat::zeros(n, n));
    for (&(i, j), [x, y]) in at.iter().zip(&ab) {
        a[(i, j)] = *x;
        b[(i, j)] = *y;
    }
    BalancedPencil { a, b, row, col }
}

impl BalancedPencil {
    pub fn unscale_right(&self, v: &Col<c64>) -> Col<c64> {
        Col::from_fn(v.nrows(), |i| v[i] * self.col[i])
    }
    pub fn unscale_left(&self, u: &Col<c64>) -> Col<c64> {
        Col::from_fn(u.nrows(), |i| u[i] * self.row[i])
    }
}
