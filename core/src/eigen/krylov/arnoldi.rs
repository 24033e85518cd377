//! The Arnoldi expansion of a Krylov–Schur basis (see [`super::iteration`]): each new
//! direction is the operator applied to the last basis vector, orthogonalized against the
//! basis by classical Gram–Schmidt twice; for a real basis the second pass of a step is
//! delayed and done together with the next step's first (one sweep over the basis instead
//! of two), and a breakdown restarts from a fresh random direction. The basis's entries
//! ([`Scalar`]: `f64` for a real operator, `c64`) choose the expansion and the real or
//! complex arithmetic of the restart.

use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{c64, Col, ColMut, ColRef, Mat, MatRef};

use super::gram_schmidt::Sweeper;
use crate::linear::{contiguous, contiguous_mut};
use super::KrylovError;

/// The entries of a Krylov basis: `f64` (real operator) or `c64`.
pub(super) trait Scalar: faer::traits::ComplexField<Real = f64> + Copy + Send + Sync + 'static {
    /// The real basis: wanted θ are counted with `Im θ ≥ 0` only (their conjugates come along).
    const REAL: bool;
    fn to_c64(self) -> c64;
    /// `z` (its real part for a real basis).
    fn from_c64(z: c64) -> Self;
    fn times(self, f: f64) -> Self;
    /// Eigenvalues and unit eigenvectors of a small dense matrix (faer's dense eigensolver).
    fn eigen(h: &Mat<Self>) -> Option<(Vec<c64>, Mat<c64>)>;
    /// An orthonormal basis of the span of the leading `keep` columns of `y` (eigenvectors
    /// or Schur vectors for the diagonal `theta`, in order), with `keep` columns (complex:
    /// their QR, so that leading columns span leading vectors) or, for a real basis, a real
    /// one of the nearest count that does not split a conjugate pair; `None` if there is
    /// none.
    fn kept_basis(y: &Mat<c64>, theta: &[c64], keep: usize) -> Option<Mat<Self>>;
    /// [`orthogonalize`]: `w` with its components along `basis` removed, the coefficients
    /// in `h`, `c` scratch; the norm left.
    fn orthogonalize(_: Sweeper, basis: MatRef<'_, Self>, w: ColMut<'_, Self>, h: ColMut<'_, Self>, c: ColMut<'_, Self>) -> f64 {
        orthogonalize(basis, w, h, c)
    }
    /// The Arnoldi expansion of `a` from column `kept` to its full size; returns the size
    /// reached (smaller when the finite spectrum is exhausted).
    fn expand(a: &mut Arnoldi<Self>, op: &mut dyn FnMut(ColRef<'_, Self>, ColMut<'_, Self>), kept: usize) -> Result<usize, KrylovError> {
        expand_classic(a, op, kept)
    }
    /// The coefficients of the Ritz vectors `V y` in the basis's arithmetic: `y` itself, or
    /// for a real basis the real and imaginary parts of each `y` as two columns.
    fn ritz_coefficients(y: &Mat<c64>) -> Mat<Self>;
    /// Entry `(r, i)` of the Ritz vectors from `V` times [`Self::ritz_coefficients`].
    fn ritz_entry(p: MatRef<'_, Self>, r: usize, i: usize) -> c64;
}

impl Scalar for c64 {
    const REAL: bool = false;
    fn to_c64(self) -> c64 {
        self
    }
    fn from_c64(z: c64) -> Self {
        z
    }
    fn times(self, f: f64) -> Self {
        self * f
    }
    fn eigen(h: &Mat<c64>) -> Option<(Vec<c64>, Mat<c64>)> {
        small_eigen_complex(h)
    }
    fn kept_basis(y: &Mat<c64>, _: &[c64], keep: usize) -> Option<Mat<c64>> {
        let qr = y.subcols(0, keep).qr();
        let r = qr.R();
        let d0 = r[(0, 0)].norm();
        (0..keep).all(|i| r[(i, i)].norm() > 1e-6 * d0).then(|| qr.compute_thin_Q())
    }
    fn ritz_coefficients(y: &Mat<c64>) -> Mat<c64> {
        y.clone()
    }
    fn ritz_entry(p: MatRef<'_, c64>, r: usize, i: usize) -> c64 {
        p[(r, i)]
    }
}

impl Scalar for f64 {
    const REAL: bool = true;
    fn to_c64(self) -> c64 {
        c64::new(self, 0.0)
    }
    fn from_c64(z: c64) -> Self {
        z.re
    }
    fn times(self, f: f64) -> Self {
        self * f
    }
    fn eigen(h: &Mat<f64>) -> Option<(Vec<c64>, Mat<c64>)> {
        small_eigen_real(h)
    }
    fn kept_basis(y: &Mat<c64>, theta: &[c64], keep: usize) -> Option<Mat<f64>> {
        // span(Y_k) of a conjugate-closed set of eigenvalues of a real matrix is the
        // complexification of a real subspace of dimension k, spanned by [Re Y_k, Im Y_k]:
        // its first k columns of a column-pivoted QR, when the rank is k (the cut does not
        // split a pair: R[k, k] ≈ 0).
        let size = y.nrows();
        // The nearest cuts first: keep, keep + 1, keep - 1, keep + 2, ...
        let cuts = (0..2 * size).map(|d| if d % 2 == 0 { keep + d / 2 } else { keep.wrapping_sub(d / 2 + 1) });
        for k in cuts {
            if k == 0 || k >= size || !closed_under_conjugation(&theta[..k], theta) {
                continue;
            }
            let parts = Mat::<f64>::from_fn(size, 2 * k, |i, j| if j < k { y[(i, j)].re } else { y[(i, j - k)].im });
            let qr = parts.col_piv_qr();
            let r = qr.R();
            let d = |i: usize| if i < r.nrows().min(r.ncols()) { r[(i, i)].abs() } else { 0.0 };
            if d(k - 1) > 1e-6 * d(0) && d(k) <= 1e-8 * d(0) {
                return Some(qr.compute_Q().subcols(0, k).to_owned());
            }
        }
        None
    }
    /// The row-blocked real kernels of `gram_schmidt.rs` (three reads of the basis, not four).
    fn orthogonalize(sweeper: Sweeper, basis: MatRef<'_, f64>, mut w: ColMut<'_, f64>, mut h: ColMut<'_, f64>, mut c: ColMut<'_, f64>) -> f64 {
        let cols = columns(basis, basis.ncols());
        match sweeper.orthogonalize(&cols, contiguous_mut(w.rb_mut()), contiguous_mut(h.rb_mut()), contiguous_mut(c.rb_mut())) {
            Some(left) => left,
            None => orthogonalize(basis, w, h, c),
        }
    }
    /// Classical Gram–Schmidt with the second pass delayed ([`expand_delayed`]): two reads
    /// of the basis per operator application instead of three.
    fn expand(a: &mut Arnoldi<f64>, op: &mut dyn FnMut(ColRef<'_, f64>, ColMut<'_, f64>), kept: usize) -> Result<usize, KrylovError> {
        expand_delayed(a, op, kept)
    }
    fn ritz_coefficients(y: &Mat<c64>) -> Mat<f64> {
        Mat::from_fn(y.nrows(), 2 * y.ncols(), |i, j| if j % 2 == 0 { y[(i, j / 2)].re } else { y[(i, j / 2)].im })
    }
    fn ritz_entry(p: MatRef<'_, f64>, r: usize, i: usize) -> c64 {
        c64::new(p[(r, 2 * i)], p[(r, 2 * i + 1)])
    }
}

/// The first `k` columns of a real matrix as slices.
pub(super) fn columns(v: MatRef<'_, f64>, k: usize) -> Vec<&[f64]> {
    (0..k).map(|j| contiguous(v.col(j))).collect()
}

fn pseudo_random<T: Scalar>(n: usize, seed: u64) -> Col<T> {
    let mut x = 0x9E37_79B9_7F4A_7C15u64 ^ seed.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    Col::from_fn(n, |_| T::from_c64(c64::new(next(), next())))
}

fn scale<T: Scalar>(w: &mut Col<T>, f: f64) {
    for x in w.iter_mut() {
        *x = x.times(f);
    }
}

/// A unit random vector with `T³` applied, so that its (index ≤ 3) components at θ = 0 of the
/// infinite eigenvalues are gone; `None` when it vanishes.
pub(super) fn purified<T: Scalar>(op: &mut dyn FnMut(ColRef<'_, T>, ColMut<'_, T>), n: usize, seed: u64, applications: &mut usize) -> Option<Col<T>> {
    let mut x = pseudo_random::<T>(n, seed);
    let mut y = Col::<T>::zeros(n);
    for _ in 0..3 {
        op(x.as_ref(), y.as_mut());
        *applications += 1;
        std::mem::swap(&mut x, &mut y);
        let nx = x.norm_l2();
        if !(nx > 0.0 && nx.is_finite()) {
            return None;
        }
        scale(&mut x, 1.0 / nx);
    }
    Some(x)
}

/// `w` with its components along the columns of `basis` removed (classical Gram–Schmidt as
/// two block projections `c = Vᴴ w`, `w ← w − V c`, a second pass when needed); the
/// coefficients removed are written to `h`, `c` is scratch of the same length; returns the
/// norm left.
fn orthogonalize<T: Scalar>(basis: MatRef<'_, T>, mut w: ColMut<'_, T>, mut h: ColMut<'_, T>, mut c: ColMut<'_, T>) -> f64 {
    use faer::linalg::matmul::matmul;
    use faer::{Accum, Par};
    let (one, minus_one) = (T::from_c64(c64::new(1.0, 0.0)), T::from_c64(c64::new(-1.0, 0.0)));
    // Sequential products: these matrix-vector products are too small to gain from threads.
    // A second pass only when the first removed most of `w` (Kahan–Parlett "twice is
    // enough": a norm kept above 1/√2 of the input is orthogonal to working accuracy).
    let mut before = w.norm_l2();
    for pass in 0..2 {
        let target = if pass == 0 { h.rb_mut() } else { c.rb_mut() };
        matmul(target.as_mat_mut(), Accum::Replace, basis.adjoint(), w.rb().as_mat(), one, Par::Seq);
        let coef = if pass == 0 { h.rb() } else { c.rb() };
        matmul(w.rb_mut().as_mat_mut(), Accum::Add, basis, coef.as_mat(), minus_one, Par::Seq);
        if pass == 1 {
            h += c.rb();
        }
        let after = w.norm_l2();
        if after > std::f64::consts::FRAC_1_SQRT_2 * before {
            return after;
        }
        before = after;
    }
    w.norm_l2()
}

/// `theta` is closed under conjugation (to `1e-8` relative, or `1e-12` of the largest: the
/// rounding of the eigenvalues near 0 is relative to the matrix).
fn closed_under_conjugation(theta: &[c64], all: &[c64]) -> bool {
    let k = theta.len();
    let top = all.iter().map(|x| x.norm()).fold(0.0, f64::max);
    let mut used = vec![false; k];
    for i in 0..k {
        if used[i] {
            continue;
        }
        let x = theta[i];
        let tol = 1e-8 * x.norm() + 1e-12 * top;
        if x.im.abs() <= tol {
            used[i] = true;
            continue;
        }
        match (i + 1..k).find(|&j| !used[j] && (theta[j] - x.conj()).norm() <= tol) {
            Some(j) => {
                used[i] = true;
                used[j] = true;
            }
            None => return false,
        }
    }
    true
}

/// The state of an Arnoldi expansion: the basis `v` (`n x (m + 1)`), the Hessenberg matrix
/// `h` (`(m + 1) x m`), the scratch of the Gram–Schmidt steps.
pub(super) struct Arnoldi<T: Scalar> {
    pub(super) n: usize,
    pub(super) m: usize,
    pub(super) v: Mat<T>,
    pub(super) h: Mat<T>,
    pub(super) coef: Col<T>,
    pub(super) scratch: Col<T>,
    pub(super) applications: usize,
    pub(super) seed: u64,
    pub(super) sweeper: Sweeper,
}

fn all_finite<T: Scalar>(w: ColRef<'_, T>) -> Result<(), KrylovError> {
    if w.iter().all(|x| x.to_c64().re.is_finite() && x.to_c64().im.is_finite()) {
        Ok(())
    } else {
        Err(KrylovError::Breakdown("the operator returned non-finite values".into()))
    }
}

/// `w ← T v_j` into column `j + 1`.
fn apply<T: Scalar>(a: &mut Arnoldi<T>, op: &mut dyn FnMut(ColRef<'_, T>, ColMut<'_, T>), j: usize) -> Result<(), KrylovError> {
    let (done, mut rest) = a.v.as_mut().split_at_col_mut(j + 1);
    op(done.rb().col(j), rest.rb_mut().col_mut(0));
    a.applications += 1;
    all_finite(rest.rb().col(0))
}

/// A fresh unit direction in column `col`, orthogonal to the columns before it: a random
/// vector purified like the start vector (coupling zero, an invariant subspace was
/// reached); `false` when the purified fresh vectors lie in the basis too (the finite
/// spectrum the operator reaches is exhausted).
fn fresh_direction<T: Scalar>(a: &mut Arnoldi<T>, op: &mut dyn FnMut(ColRef<'_, T>, ColMut<'_, T>), col: usize) -> bool {
    let j = col - 1;
    for attempt in 0..3u64 {
        let Some(mut f) = purified(op, a.n, a.seed + 1000 + 7 * j as u64 + attempt, &mut a.applications) else { continue };
        let nb = T::orthogonalize(a.sweeper, a.v.as_ref().subcols(0, col), f.as_mut(), a.coef.subrows_mut(0, col), a.scratch.subrows_mut(0, col));
        if nb > 1e-8 && nb.is_finite() {
            let mut w = a.v.col_mut(col);
            w.copy_from(&f);
            for x in w.iter_mut() {
                *x = x.times(1.0 / nb);
            }
            return true;
        }
    }
    false
}

/// Column `j + 1` holds `T v_j` (with `h[.., j]` already holding `add` of its coefficients
/// when `add`): orthogonalized against columns `0..=j` by classical Gram–Schmidt twice, its
/// coefficients added to `h[.., j]`, normalized; `Some(j + 1)` (the size reached) when the
/// finite spectrum is exhausted.
fn complete_step<T: Scalar>(a: &mut Arnoldi<T>, op: &mut dyn FnMut(ColRef<'_, T>, ColMut<'_, T>), j: usize, add: bool) -> Option<usize> {
    let zero = T::from_c64(c64::new(0.0, 0.0));
    let beta = {
        let (done, mut rest) = a.v.as_mut().split_at_col_mut(j + 1);
        T::orthogonalize(a.sweeper, done.rb(), rest.rb_mut().col_mut(0), a.coef.subrows_mut(0, j + 1), a.scratch.subrows_mut(0, j + 1))
    };
    for i in 0..=j {
        let before = if add { a.h[(i, j)] } else { zero };
        a.h[(i, j)] = before + a.coef[i];
    }
    let scale_c = (0..=j).map(|i| a.h[(i, j)].to_c64().norm_sqr()).sum::<f64>().sqrt().max(beta);
    if beta <= 1e-12 * scale_c {
        // Invariant subspace: continue with a fresh direction (coupling zero).
        a.h[(j + 1, j)] = zero;
        if !fresh_direction(a, op, j + 1) {
            return Some(j + 1);
        }
    } else {
        a.h[(j + 1, j)] = T::from_c64(c64::new(beta, 0.0));
        for x in a.v.col_mut(j + 1).iter_mut() {
            *x = x.times(1.0 / beta);
        }
    }
    None
}

/// Arnoldi with classical Gram–Schmidt twice at each step (three or four reads of the basis).
fn expand_classic<T: Scalar>(a: &mut Arnoldi<T>, op: &mut dyn FnMut(ColRef<'_, T>, ColMut<'_, T>), kept: usize) -> Result<usize, KrylovError> {
    for j in kept..a.m {
        apply(a, op, j)?;
        if let Some(size) = complete_step(a, op, j, false) {
            return Ok(size);
        }
    }
    Ok(a.m)
}

/// Column `j` holds `u`, the once-orthogonalized unit vector of step `j − 1` (`T v_{j−1} =
/// V_j h + β₁ u`, `h` in `h[0..j, j − 1]`): orthogonalized again by classical Gram–Schmidt
/// twice, `u = V_j s + α v_j`, so `T v_{j−1} = V_j (h + β₁ s) + β₁ α v_j`; `Some(j)` (the
/// size reached) when the finite spectrum is exhausted.
fn finish_delayed(a: &mut Arnoldi<f64>, op: &mut dyn FnMut(ColRef<'_, f64>, ColMut<'_, f64>), j: usize, beta1: f64) -> Option<usize> {
    let alpha = {
        let (done, mut rest) = a.v.as_mut().split_at_col_mut(j);
        f64::orthogonalize(a.sweeper, done.rb(), rest.rb_mut().col_mut(0), a.coef.subrows_mut(0, j), a.scratch.subrows_mut(0, j))
    };
    for i in 0..j {
        a.h[(i, j - 1)] += beta1 * a.coef[i];
    }
    let beta = beta1 * alpha;
    let scale_c = (0..j).map(|i| a.h[(i, j - 1)] * a.h[(i, j - 1)]).sum::<f64>().sqrt().max(beta);
    if beta <= 1e-12 * scale_c {
        a.h[(j, j - 1)] = 0.0;
        if !fresh_direction(a, op, j) {
            return Some(j);
        }
    } else {
        a.h[(j, j - 1)] = beta;
        for x in a.v.col_mut(j).iter_mut() {
            *x /= alpha;
        }
    }
    None
}

/// Arnoldi on a real basis with the second Gram–Schmidt pass delayed by one step (DCGS2:
/// Świrydowicz, Langou, Ananthan, Yang, Thomas, "Low synchronization Gram–Schmidt and
/// generalized minimal residual algorithms", Numer. Linear Algebra Appl. 28, 2021; Bielich
/// et al., "Low-synch Gram–Schmidt with delayed reorthogonalization for Krylov solvers",
/// Parallel Comput. 112, 2022). At 10⁵ unknowns every pass over the basis is a read from
/// memory, and with classical Gram–Schmidt twice nearly every step takes its second pass
/// (118 of 118 on the hanging chain): three reads a step. Here the operator is applied to
/// `u`, the vector of the previous step orthogonalized once; one sweep then gives both
/// `s = V_jᵀ u` (the delayed second pass of `u`) and `z = V_jᵀ w` for `w = T u`, and a second
/// sweep writes `v_j = (u − V_j s)/α` and `w` orthogonalized once against `[V_j, v_j]`: two
/// reads a step. With `α² = uᵀu − sᵀs`, by linearity
/// `T v_j = (w − T V_j s)/α = (w − V_{j+1} H s)/α` (the Arnoldi relation of the earlier
/// columns, `H = h[0..=j, 0..j]` once column `j − 1` is corrected as in [`finish_delayed`]),
/// so with `g = [V_j, v_j]ᵀ w = [z; (uᵀw − sᵀz)/α]` the new column of `h` is `(g − H s)/α`
/// and `T v_j − V_{j+1} (g − H s)/α = (w − V_{j+1} g)/α`. When `u` was far from orthogonal
/// (`α² < uᵀu/2`, where the Pythagorean `α` would lose digits) or nearly in the basis,
/// column `j` is finished by the classical passes and `T` applied again.
fn expand_delayed(a: &mut Arnoldi<f64>, op: &mut dyn FnMut(ColRef<'_, f64>, ColMut<'_, f64>), kept: usize) -> Result<usize, KrylovError> {
    let m = a.m;
    let sw = a.sweeper;
    let (mut s, mut z, mut g) = (vec![0.0; m + 1], vec![0.0; m + 1], vec![0.0; m + 1]);
    // β₁ of column j when it holds the once-orthogonalized u of the previous step.
    let mut pending: Option<f64> = None;
    let mut j = kept;
    while j < m {
        apply(a, op, j)?;
        let (beta1, add) = if let Some(b1) = pending {
            let (uu, uw) = {
                let cols = columns(a.v.as_ref(), j);
                sw.project_pair(&cols, contiguous(a.v.col(j)), contiguous(a.v.col(j + 1)), &mut s[..j], &mut z[..j])
            };
            let ss: f64 = s[..j].iter().map(|x| x * x).sum();
            let alpha2 = uu - ss;
            let corrected = (0..j).map(|i| (a.h[(i, j - 1)] + b1 * s[i]).powi(2)).sum::<f64>().sqrt();
            let alpha = alpha2.max(0.0).sqrt();
            if !(alpha2.is_finite() && uw.is_finite() && alpha2 >= 0.5 * uu && b1 * alpha > 1e-12 * corrected.max(b1 * alpha)) {
                if let Some(size) = finish_delayed(a, op, j, b1) {
                    return Ok(size);
                }
                pending = None;
                continue;
            }
            for i in 0..j {
                a.h[(i, j - 1)] += b1 * s[i];
            }
            a.h[(j, j - 1)] = b1 * alpha;
            g[..j].copy_from_slice(&z[..j]);
            g[j] = (uw - s[..j].iter().zip(&z[..j]).map(|(x, y)| x * y).sum::<f64>()) / alpha;
            for i in 0..=j {
                let hs: f64 = (0..j).map(|l| a.h[(i, l)] * s[l]).sum();
                a.h[(i, j)] = (g[i] - hs) / alpha;
            }
            let (done, mut rest) = a.v.as_mut().split_at_col_mut(j);
            let cols = columns(done.rb(), j);
            let (mut uc, mut wc) = rest.rb_mut().split_at_col_mut(1);
            (sw.update_pair(&cols, &s[..j], &g[..=j], alpha, contiguous_mut(uc.rb_mut().col_mut(0)), contiguous_mut(wc.rb_mut().col_mut(0))).sqrt(), true)
        } else {
            // Column j is orthonormal to the others: one pass, its second one delayed.
            let (done, mut rest) = a.v.as_mut().split_at_col_mut(j + 1);
            let cols = columns(done.rb(), j + 1);
            let w = contiguous_mut(rest.rb_mut().col_mut(0));
            if sw.project(&cols, w, &mut g[..=j]).is_finite() {
                for i in 0..=j {
                    a.h[(i, j)] = g[i];
                }
                (sw.subtract(&cols, &g[..=j], w).sqrt(), true)
            } else {
                (f64::NAN, false)
            }
        };
        if !beta1.is_finite() {
            // Overflow: the classical passes with faer's scaled norms (added to the
            // coefficients already in h[.., j] when a pass was made).
            pending = None;
            if let Some(size) = complete_step(a, op, j, add) {
                return Ok(size);
            }
            j += 1;
            continue;
        }
        let hn = (0..=j).map(|i| a.h[(i, j)] * a.h[(i, j)]).sum::<f64>().sqrt();
        if beta1 <= 1e-12 * hn.max(beta1) {
            // Invariant subspace (a second pass only makes the norm smaller).
            a.h[(j + 1, j)] = 0.0;
            pending = None;
            if !fresh_direction(a, op, j + 1) {
                return Ok(j + 1);
            }
        } else {
            for x in a.v.col_mut(j + 1).iter_mut() {
                *x /= beta1;
            }
            pending = Some(beta1);
        }
        j += 1;
    }
    if let Some(b1) = pending {
        if let Some(size) = finish_delayed(a, op, m, b1) {
            return Ok(size);
        }
    }
    Ok(m)
}

/// faer's eigendecomposition parameters with its blocked, aggressive-early-deflation QR
/// turned off: the Rayleigh-quotient matrices are at most a few hundred wide, where the
/// plain double-shift QR (LAPACK's `lahqr`) is as fast, and faer 0.24's AED did not return
/// on those of the 64-element double-bending cantilever of `tests/eigen/sparse_count.rs`
/// (`eig --solver sparse --count 20`: over 20 CPU-minutes in release, 43 % of it in
/// `schur_swap_22` under `aggressive_early_deflation`, measured with perf).
fn unblocked<T>() -> faer::Spec<faer::linalg::evd::EvdParams, T>
where
    faer::linalg::evd::EvdParams: faer::Auto<T>,
{
    let mut params = <faer::linalg::evd::EvdParams as faer::Auto<T>>::auto();
    params.schur.blocking_threshold = usize::MAX;
    faer::Spec::new(params)
}

/// Eigenvalues and right eigenvectors of a small real matrix by [`unblocked`] QR, complex
/// pairs as conjugate columns (faer's `Mat::eigen` convention).
fn small_eigen_real(h: &Mat<f64>) -> Option<(Vec<c64>, Mat<c64>)> {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::linalg::evd::{evd_real, evd_scratch, ComputeEigenvectors};
    let n = h.nrows();
    let (mut re, mut im) = (faer::diag::Diag::<f64>::zeros(n), faer::diag::Diag::<f64>::zeros(n));
    let mut u = Mat::<f64>::zeros(n, n);
    let mut buffer = MemBuffer::new(evd_scratch::<f64>(n, ComputeEigenvectors::No, ComputeEigenvectors::Yes, faer::Par::Seq, unblocked()));
    evd_real(h.as_ref(), re.as_mut(), im.as_mut(), None, Some(u.as_mut()), faer::Par::Seq, MemStack::new(&mut buffer), unblocked()).ok()?;
    let mut values = Vec::with_capacity(n);
    let mut vectors = Mat::<c64>::zeros(n, n);
    let mut j = 0;
    while j < n {
        if im[j] == 0.0 || j + 1 == n {
            values.push(c64::new(re[j], 0.0));
            for i in 0..n {
                vectors[(i, j)] = c64::new(u[(i, j)], 0.0);
            }
            j += 1;
        } else {
            values.push(c64::new(re[j], im[j]));
            values.push(c64::new(re[j], -im[j]));
            for i in 0..n {
                vectors[(i, j)] = c64::new(u[(i, j)], u[(i, j + 1)]);
                vectors[(i, j + 1)] = c64::new(u[(i, j)], -u[(i, j + 1)]);
            }
            j += 2;
        }
    }
    Some((values, vectors))
}

/// Eigenvalues and right eigenvectors of a small complex matrix by [`unblocked`] QR.
fn small_eigen_complex(h: &Mat<c64>) -> Option<(Vec<c64>, Mat<c64>)> {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::linalg::evd::{evd_cplx, evd_scratch, ComputeEigenvectors};
    let n = h.nrows();
    let mut s = faer::diag::Diag::<c64>::zeros(n);
    let mut u = Mat::<c64>::zeros(n, n);
    let params = unblocked::<c64>();
    let mut buffer = MemBuffer::new(evd_scratch::<c64>(n, ComputeEigenvectors::No, ComputeEigenvectors::Yes, faer::Par::Seq, params));
    evd_cplx(h.as_ref(), s.as_mut(), None, Some(u.as_mut()), faer::Par::Seq, MemStack::new(&mut buffer), params).ok()?;
    Some((s.column_vector().iter().copied().collect(), u))
}

#[cfg(test)]
mod small_eigen_tests {
    use super::*;

    /// The unblocked decompositions satisfy `H u = λ u` to rounding on a real matrix with a
    /// complex pair and on a complex one (a 150-wide random matrix, past faer's blocking size).
    #[test]
    fn unblocked_eigenpairs_satisfy_their_definition() {
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let n = 150;
        let h = Mat::<f64>::from_fn(n, n, |_, _| next());
        let (values, vectors) = small_eigen_real(&h).unwrap();
        let hc = Mat::<c64>::from_fn(n, n, |i, j| c64::new(h[(i, j)], 0.0));
        let g = Mat::<c64>::from_fn(n, n, |_, _| c64::new(next(), next()));
        let (gv, gu) = small_eigen_complex(&g).unwrap();
        for (m, l, u) in [(&hc, &values, &vectors), (&g, &gv, &gu)] {
            assert!(l.iter().any(|x| x.im != 0.0));
            for k in 0..n {
                let v = u.col(k);
                let mv = m * v;
                let r = Col::<c64>::from_fn(n, |i| mv[i] - v[i] * l[k]).norm_l2();
                assert!(r <= 1e-12 * m.norm_l2() * v.norm_l2(), "pair {k}: residual {r:e}");
            }
        }
    }
}
