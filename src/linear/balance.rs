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
    let (mut a, mut b) = (a.clone(), b.clone());
    let (mut row, mut col) = (vec![1.0; n], vec![1.0; n]);
    let pow2 = |s: f64| if s > 0.0 && s.is_finite() { (-s.log2().round()).exp2() } else { 1.0 };
    // Column-major passes (faer stores columns contiguously); each row's sum runs over
    // j = 0..n in order, as a row-wise loop would.
    for _sweep in 0..8 {
        let mut changed = false;
        let mut rs = vec![0.0; n];
        for j in 0..n {
            for i in 0..n {
                rs[i] += a[(i, j)].powi(2) + b[(i, j)].powi(2);
            }
        }
        let fr: Vec<f64> = rs.iter().map(|s| pow2(s.sqrt())).collect();
        if fr.iter().any(|&f| f != 1.0) {
            changed = true;
            for j in 0..n {
                for i in 0..n {
                    a[(i, j)] *= fr[i];
                    b[(i, j)] *= fr[i];
                }
            }
            for i in 0..n {
                row[i] *= fr[i];
            }
        }
        for j in 0..n {
            let s = (0..n).map(|i| a[(i, j)].powi(2) + b[(i, j)].powi(2)).sum::<f64>().sqrt();
            let f = pow2(s);
            if f != 1.0 {
                changed = true;
                col[j] *= f;
                for i in 0..n {
                    a[(i, j)] *= f;
                    b[(i, j)] *= f;
                }
            }
        }
        if !changed {
            break;
        }
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
