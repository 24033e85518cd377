//! The two pencils the eigenanalysis can run on, and the small complex-vector algebra shared
//! by the eigen solver and the labelling.

use faer::{c64, Col, Mat};

/// Which pencil the QZ algorithm is run on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EigenRoute {
    /// `(λ F_yd + F_y) Y = 0` (eq. 10).
    Direct,
    /// `(Λ J + J*) Y = 0` (eq. 18), mapped back with eq. 23.
    Lambda,
}

/// One eigenvalue's vectors and the products the error estimate needs.
pub(crate) struct EigenVectors {
    pub v: Col<c64>,
    pub u: Col<c64>,
    pub av: Col<c64>,
    pub bv: Col<c64>,
    pub ua: Col<c64>,
    pub ub: Col<c64>,
}

pub(crate) fn conj(v: &Col<c64>) -> Col<c64> {
    Col::from_fn(v.nrows(), |i| v[i].conj())
}

/// `M v` for real `M` and complex `v`.
pub fn mul_real_complex(m: &Mat<f64>, v: &Col<c64>) -> Col<c64> {
    let re = Col::<f64>::from_fn(v.nrows(), |i| v[i].re);
    let im = Col::<f64>::from_fn(v.nrows(), |i| v[i].im);
    let (r, s) = (m * &re, m * &im);
    Col::from_fn(m.nrows(), |i| c64::new(r[i], s[i]))
}

/// `uᵀ w` (no conjugation).
pub fn dot_t(u: &Col<c64>, w: &Col<c64>) -> c64 {
    u.iter().zip(w.iter()).fold(c64::new(0.0, 0.0), |s, (a, b)| s + a * b)
}

pub(crate) fn norm(v: &Col<c64>) -> f64 {
    v.iter().map(|x| x.norm_sqr()).sum::<f64>().sqrt()
}

