//! Generalized eigenanalysis of a linear DAE with right and adjoint (left) vectors.
//!
//! Right problem `(λ F_yd + F_y) Y = 0` (eq. 10), adjoint problem with the transposed
//! matrices (eq. 11). Two routes give the same finite eigenvalues:
//! - [`EigenRoute::Direct`]: QZ on the pencil `F_y v = μ (−F_yd) v`, `λ = μ`;
//! - [`EigenRoute::Lambda`]: QZ on `J* v = Λ (−J) v` (eq. 18), `λ = (1/c)(Λ+1)/(Λ−1)` (eq. 23).

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::evd::ComputeEigenvectors;
use faer::linalg::gevd::{gevd_real, gevd_scratch, GevdParams};
use faer::Spec;
use faer::diag::Diag;
use faer::{c64, Col, Mat, Par};

use super::balance::balance_pencil;
use crate::eigen::classify::{classify, classify_without_vectors, resolved_kind, ModeKind};
use crate::eigen::modes::{conjugate_mode, normalize, sort_units};
use crate::eigen::route::{mul_real_complex, EigenRoute, EigenVectors};
use crate::eigen::{EigenError, ModalAnalysis, Mode};
use crate::linear::{coefficient_from_derivatives, Jacobians, SparseMatrix};

/// Raw output of QZ on a (balanced) pencil `A v = μ B v`. The products `A V`, `B V`,
/// `Uᵀ A`, `Uᵀ B` the error estimates need are formed once for all vectors (four matrix
/// products, [`Products::All`]) or per requested vector ([`Products::PerVector`]).
/// faer stores a complex pair's `re, im` parts in two consecutive columns.
pub(super) struct RawEigen {
    pub alpha_re: Vec<f64>,
    pub alpha_im: Vec<f64>,
    pub beta: Vec<f64>,
    right: Mat<f64>,
    left: Mat<f64>,
    products: Option<[Mat<f64>; 4]>,
    a: Mat<f64>,
    b: Mat<f64>,
}

/// Whether [`qz`] forms the error estimates' products for every vector at once (when every
/// eigenvalue is labelled from them) or leaves them to each [`RawEigen::vectors`] call.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Products {
    All,
    PerVector,
}

/// QZ with left and right vectors. faer's QZ iteration can fail to converge within its
/// `30 n` sweeps without reporting it (measured on a prestressed beam pencil, n = 138):
/// eigenvalues it did not reach are left untouched, so they are initialized to NaN and a
/// NaN afterwards means failure. The pencil is then retried after a left multiplication by
/// a (deterministic) random orthogonal `Q`: `Qᵀ A v = μ Qᵀ B v` has the same eigenvalues
/// and right vectors, and left vectors `u = Q u′`.
pub(super) fn qz(a: &Mat<f64>, b: &Mat<f64>, products: Products) -> Result<RawEigen, EigenError> {
    let n = a.nrows();
    if let Some(raw) = qz_attempt(a, b, a, b, None, products) {
        return Ok(raw);
    }
    for seed in 1..=3u64 {
        let q = random_orthogonal(n, seed);
        let qt = q.transpose();
        if let Some(raw) = qz_attempt(a, b, &(qt * a), &(qt * b), Some(&q), products) {
            return Ok(raw);
        }
    }
    Err(EigenError::NoConvergence(n))
}

/// An orthogonal matrix: the Q factor of a matrix with entries from xorshift64.
fn random_orthogonal(n: usize, seed: u64) -> Mat<f64> {
    let mut x = 0x9E37_79B9_7F4A_7C15u64 ^ seed;
    let m = Mat::<f64>::from_fn(n, n, |_, _| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    });
    m.qr().compute_Q()
}

/// QZ on `(h, t)` (the pencil `(a, b)` or its left rotation by `qᵀ`); `None` when the
/// iteration did not converge.
fn qz_attempt(a: &Mat<f64>, b: &Mat<f64>, h: &Mat<f64>, t: &Mat<f64>, q: Option<&Mat<f64>>, products: Products) -> Option<RawEigen> {
    let n = a.nrows();
    let (mut h, mut t) = (h.clone(), t.clone());
    let (mut ar, mut ai, mut be) = (Diag::<f64>::zeros(n), Diag::<f64>::zeros(n), Diag::<f64>::zeros(n));
    for i in 0..n {
        (ar[i], ai[i], be[i]) = (f64::NAN, f64::NAN, f64::NAN);
    }
    let (mut ul, mut ur) = (Mat::<f64>::zeros(n, n), Mat::<f64>::zeros(n, n));
    let par = Par::Seq;
    let mut params: Spec<GevdParams, f64> = Default::default();
    // faer 0.24.4's blocked (multishift, aggressive-early-deflation) QZ stalls on some
    // structured pencils (measured on a tridiagonal pencil with B = I: 1.9 s against
    // 13 ms at n = 101; over a minute against 2.6 s at n = 600), so the unblocked sweep
    // is always used.
    params.schur.blocking_threshold = usize::MAX;
    let scratch = gevd_scratch::<f64>(n, ComputeEigenvectors::Yes, ComputeEigenvectors::Yes, par, params);
    // faer 0.24.4's gevd_scratch omits the eigenvector back-substitution's workspace
    // (column norms and a few n x 2 blocks); give it room for them.
    let scratch = scratch.and(StackReq::new::<f64>(16 * n + 1024));
    let mut buf = MemBuffer::new(scratch);
    gevd_real(
        h.as_mut(),
        t.as_mut(),
        ar.as_mut(),
        ai.as_mut(),
        be.as_mut(),
        Some(ul.as_mut()),
        Some(ur.as_mut()),
        par,
        MemStack::new(&mut buf),
        params,
    )
    .ok()?;
    if (0..n).any(|i| ar[i].is_nan() || ai[i].is_nan() || be[i].is_nan()) {
        return None;
    }
    if let Some(q) = q {
        ul = q * &ul;
    }
    // Columns of infinite eigenvalues come back as NaN; mark the whole column so
    // `vectors` reports none, and use zeros in the products.
    for m in [&mut ul, &mut ur] {
        for j in 0..n {
            if (0..n).any(|i| !m[(i, j)].is_finite()) {
                for i in 0..n {
                    m[(i, j)] = f64::NAN;
                }
            }
        }
    }
    let products = (products == Products::All).then(|| {
        let clean = |m: &Mat<f64>| Mat::from_fn(n, n, |i, j| if m[(i, j)].is_finite() { m[(i, j)] } else { 0.0 });
        let (urc, ulc) = (clean(&ur), clean(&ul));
        [a * &urc, b * &urc, ulc.transpose() * a, ulc.transpose() * b]
    });
    Some(RawEigen {
        alpha_re: (0..n).map(|i| ar[i]).collect(),
        alpha_im: (0..n).map(|i| ai[i]).collect(),
        beta: (0..n).map(|i| be[i]).collect(),
        products,
        a: a.clone(),
        b: b.clone(),
        right: ur,
        left: ul,
    })
}

impl RawEigen {
    /// Vectors of the eigenvalue stored at column `j` (with `j + 1` holding the imaginary
    /// parts when `im`); `None` when QZ returned NaN vectors (β = 0).
    pub(super) fn vectors(&self, j: usize, im: bool) -> Option<EigenVectors> {
        let n = self.right.nrows();
        if (0..n).any(|i| !self.right[(i, j)].is_finite() || !self.left[(i, j)].is_finite()) {
            return None;
        }
        let col = |m: &Mat<f64>| Col::<c64>::from_fn(n, |i| c64::new(m[(i, j)], if im { m[(i, j + 1)] } else { 0.0 }));
        let row = |m: &Mat<f64>| Col::<c64>::from_fn(n, |i| c64::new(m[(j, i)], if im { m[(j + 1, i)] } else { 0.0 }));
        let (v, u) = (col(&self.right), col(&self.left));
        let (av, bv, ua, ub) = match &self.products {
            Some([ar, br, la, lb]) => (col(ar), col(br), row(la), row(lb)),
            None => {
                let t = |m: &Mat<f64>| m.transpose().to_owned();
                (mul_real_complex(&self.a, &v), mul_real_complex(&self.b, &v), mul_real_complex(&t(&self.a), &u), mul_real_complex(&t(&self.b), &u))
            }
        };
        Some(EigenVectors { v, u, av, bv, ua, ub })
    }

    /// The right and left vectors alone (no products), as [`RawEigen::vectors`].
    pub(super) fn bare_vectors(&self, j: usize, im: bool) -> Option<(Col<c64>, Col<c64>)> {
        let n = self.right.nrows();
        if (0..n).any(|i| !self.right[(i, j)].is_finite() || !self.left[(i, j)].is_finite()) {
            return None;
        }
        let col = |m: &Mat<f64>| Col::<c64>::from_fn(n, |i| c64::new(m[(i, j)], if im { m[(i, j + 1)] } else { 0.0 }));
        Some((col(&self.right), col(&self.left)))
    }
}

impl ModalAnalysis {
    /// Eigenanalysis of a linear DAE by the chosen route, with the Jacobians' own dCoef.
    pub fn compute(jacobians: &Jacobians, route: EigenRoute) -> Result<Self, EigenError> {
        Self::compute_with_dcoef(jacobians, route, None)
    }

    /// Eigenanalysis with an explicit dCoef for the Λ form (ignored when the Jacobians were
    /// given as J/J*, whose own dCoef is part of them).
    pub fn compute_with_dcoef(jacobians: &Jacobians, route: EigenRoute, dcoef: Option<f64>) -> Result<Self, EigenError> {
        if jacobians.dim() == 0 {
            return Err(EigenError::Empty);
        }
        let prepared = super::degenerate::prepare(jacobians, dcoef)?;
        let jacobians = &prepared.jacobians;
        let (fyd, fy) = jacobians.derivatives();
        let dcoef = match (jacobians, dcoef) {
            (Jacobians::Derivatives { .. }, Some(c)) => c,
            (Jacobians::Derivatives { .. }, None) => balanced_dcoef(&fyd, &fy).unwrap_or_else(|| jacobians.dcoef()),
            _ => jacobians.dcoef(),
        };
        // Pencil A v = μ B v in the route's variable μ.
        let (a, b, mu_scale) = match route {
            EigenRoute::Direct => {
                let (fyd, fy) = jacobians.derivatives();
                // Scale B so ‖A‖ = ‖B‖: the chordal metric used by the labelling then
                // weighs both matrices alike (μ = λ / σ).
                let (na, nb) = (fy.norm_l2(), fyd.norm_l2());
                let sigma = if na > 0.0 && nb > 0.0 { na / nb } else { 1.0 };
                (fy, &fyd * faer::Scale(-sigma), sigma)
            }
            EigenRoute::Lambda => {
                let (j, jstar) = match jacobians {
                    Jacobians::Coefficient { j, jstar, .. } => (j.clone(), jstar.clone()),
                    Jacobians::Derivatives { fyd, fy } => coefficient_from_derivatives(fyd, fy, dcoef),
                };
                (jstar, &j * faer::Scale(-1.0), 1.0)
            }
        };
        let balanced = balance_pencil(&a, &b);
        let raw = qz(&balanced.a, &balanced.b, Products::All)?;
        let norms = (balanced.a.norm_l2(), balanced.b.norm_l2());

        let n = a.nrows();
        let fyd_sparse = SparseMatrix::from_dense(&fyd);
        let fy_sparse = SparseMatrix::from_dense(&fy);
        let mut units: Vec<Vec<Mode>> = Vec::with_capacity(n);
        let mut k = 0;
        while k < n {
            let pair = raw.alpha_im[k] != 0.0 && k + 1 < n;
            let alpha = c64::new(raw.alpha_re[k], raw.alpha_im[k]);
            let vectors = raw.vectors(k, pair);
            let class = match &vectors {
                Some(w) => classify(alpha, raw.beta[k], Some(w), norms, route),
                None => classify_without_vectors(alpha, raw.beta[k], route),
            };
            let (mut lambda, error) = class.lambda_and_error(route, mu_scale, dcoef);
            let error = if vectors.is_none() { f64::INFINITY } else { error };
            if !(lambda.re.is_finite() && lambda.im.is_finite()) {
                lambda = c64::new(f64::INFINITY, 0.0);
            }
            // The two-sided Rayleigh quotient on the unbalanced pencil of eq. 10 bounds the
            // error from below whatever the route and dCoef: independent of dCoef and of row
            // and column scaling, second-order accurate in the vectors (an eigenvalue that
            // eq. 23 moved off its own vectors, Λ rounded next to ±1, shows here).
            // Its sums compensated: a dynamic mode's eigenvalue is that quotient, as on the
            // deflated route (`super::deflated_qz`).
            let quotient = match &vectors {
                Some(w) if class.kind == ModeKind::Dynamic && lambda.re.is_finite() && lambda.im.is_finite() => {
                    let (v, u) = (balanced.unscale_right(&w.v), balanced.unscale_left(&w.u));
                    Some(fy_sparse.two_sided_quotient(&fyd_sparse, &u, &v))
                }
                _ => None,
            };
            let error = match quotient {
                Some(Some(q)) => error.max((q - lambda).norm()),
                Some(None) => f64::INFINITY,
                None => error,
            };
            let kind = resolved_kind(&class, lambda, error, dcoef);
            if let (Some(Some(q)), ModeKind::Dynamic) = (quotient, kind) {
                lambda = q;
            }
            let (right, left) = match vectors {
                Some(w) if kind != ModeKind::Infinite => {
                    let (v, u) = normalize(&balanced.unscale_right(&w.v), &balanced.unscale_left(&w.u), |x| mul_real_complex(&fyd, x), |a, b| fyd_sparse.abs_bilinear(a, b));
                    (Some(v), Some(u))
                }
                _ => (None, None),
            };
            let mode = Mode { lambda, kind, error, classification: class, right, left, partner: None };
            if pair {
                let partner = conjugate_mode(&mode);
                units.push(vec![mode, partner]);
                k += 2;
            } else {
                units.push(vec![mode]);
                k += 1;
            }
        }
        finish(ModalAnalysis { route, dcoef, modes: sort_units(units, dcoef) }, prepared.scale)
    }

}


/// The Λ form's default dCoef for a pencil without its constraint structure:
/// `‖F_yd‖/‖F_y‖` after the rows and columns of `(F_y, F_yd)` are equilibrated (powers of two,
/// [`balance_pencil`]), so that units and the stiffest entry do not decide it. `None` when
/// either norm vanishes.
fn balanced_dcoef(fyd: &Mat<f64>, fy: &Mat<f64>) -> Option<f64> {
    let b = balance_pencil(fy, fyd);
    let c = b.b.norm_l2() / b.a.norm_l2();
    (c.is_normal() && c > 0.0).then_some(c)
}



/// Undoes [`super::degenerate::prepare`]'s scaling on the left vectors (normalized with the scaled F_yd) and
/// refuses a result whose labels cannot be trusted (a non-finite λ labelled dynamic or zero).
fn finish(mut modal: ModalAnalysis, scale: f64) -> Result<ModalAnalysis, EigenError> {
    for m in &mut modal.modes {
        if let Some(u) = m.left.as_mut() {
            for i in 0..u.nrows() {
                u[i] *= scale;
            }
        }
        if m.kind != ModeKind::Infinite && !(m.lambda.re.is_finite() && m.lambda.im.is_finite() && !m.error.is_nan()) {
            return Err(EigenError::NonFinite(format!("QZ gave λ = {} labelled {}", m.lambda, m.kind.name())));
        }
    }
    Ok(modal)
}
