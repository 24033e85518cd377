//! Krylov–Schur iteration (Stewart, "A Krylov–Schur algorithm for large eigenproblems",
//! SIAM J. Matrix Anal. Appl. 23, 2001) for the eigenvalues θ of largest modulus of an
//! operator applied to vectors: Arnoldi expansion with full reorthogonalization (classical
//! Gram–Schmidt twice; for a real basis with the second pass delayed to the next step, below),
//! Schur form
//! of the Rayleigh quotient sorted by |θ|, truncation to the wanted Schur vectors, and
//! locking of the converged leading ones (their coupling to the residual vector is set to
//! zero once below the tolerance).
//!
//! The basis is complex for a complex operator and real for a real one (a real shift of
//! the real pencil): a real basis holds each complex pair with its conjugate, at a quarter
//! of the arithmetic per entry and one real solve per operator application instead of
//! two. Its restart keeps a real orthonormal basis of the wanted invariant subspace of the
//! Rayleigh quotient (conjugate pairs kept whole) in place of the complex Schur vectors.

use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{c64, Col, ColMut, ColRef, Mat, MatRef};

use super::arnoldi::{expand_classic, expand_delayed, Arnoldi};
use super::gram_schmidt::{both, Sweeper};
use super::schur::{schur, sort_schur};
use crate::linear::sparse::{contiguous, contiguous_mut};
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
        let e = h.eigen().ok()?;
        Some((e.S().column_vector().iter().copied().collect(), e.U().to_owned()))
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
        let e = h.eigen().ok()?;
        Some((e.S().column_vector().iter().copied().collect(), e.U().to_owned()))
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

/// The Ritz values of the Rayleigh quotient `square` sorted by `key` (decreasing, stable),
/// their unit eigenvectors, and the sorted Schur vectors when the Schur form was used.
struct Ritz {
    theta: Vec<c64>,
    y: Mat<c64>,
    schur: Option<Mat<c64>>,
}

/// Eigenvectors by faer's dense eigensolver (its Hessenberg QR with aggressive early
/// deflation), or from the sorted Schur form of `schur.rs` when `schur_form` (or when that
/// fails).
fn ritz<T: Scalar>(square: &Mat<T>, key: &dyn Fn(c64) -> f64, schur_form: bool) -> Result<Ritz, KrylovError> {
    let size = square.nrows();
    if !schur_form {
        if let Some((theta, y)) = T::eigen(square) {
            if theta.iter().all(|x| x.re.is_finite() && x.im.is_finite()) {
                let mut order: Vec<usize> = (0..size).collect();
                order.sort_by(|&a, &b| key(theta[b]).total_cmp(&key(theta[a])));
                let y = Mat::<c64>::from_fn(size, size, |i, j| y[(i, order[j])]);
                return Ok(Ritz { theta: order.iter().map(|&i| theta[i]).collect(), y, schur: None });
            }
        }
    }
    let complex = Mat::<c64>::from_fn(size, size, |i, j| square[(i, j)].to_c64());
    let (mut t, mut z) = schur(&complex).ok_or_else(|| KrylovError::Breakdown("the Schur form of the Rayleigh quotient did not converge".into()))?;
    sort_schur(&mut t, &mut z, key);
    let mut y = Mat::<c64>::zeros(size, size);
    for i in 0..size {
        let e = &z * triangular_eigenvector(&t, i);
        let ne = e.norm_l2();
        y.col_mut(i).copy_from(&(e / ne));
    }
    Ok(Ritz { theta: (0..size).map(|i| t[(i, i)]).collect(), y, schur: Some(z) })
}

/// What one run is asked for.
pub(super) struct Settings {
    /// Number of wanted θ (largest |θ|); for a real basis, of those with `Im θ ≥ 0`
    /// (`Im λ ≥ 0`: the others are their conjugates).
    pub wanted: usize,
    /// Largest basis size.
    pub basis: usize,
    /// Relative residual `‖T x − θ x‖ / |θ|` at which a Ritz pair is converged.
    pub tolerance: f64,
    pub max_restarts: usize,
    /// Seed of the start vector.
    pub seed: u64,
    /// The real basis's sweeps, the Ritz vectors and the restarts' rotations on two rayon
    /// threads (one run alone; see `gram_schmidt.rs`'s `Sweeper`).
    pub parallel: bool,
}

/// A converged Ritz pair of the operator, `x` of unit norm and purified (`T x / θ`).
pub(super) struct RitzPair {
    pub theta: c64,
    pub x: Col<c64>,
}

/// The result of one run: the wanted pairs in decreasing |θ| and the largest |θ| of the
/// Ritz values not returned (the next candidate), when known.
pub(super) struct Run {
    pub pairs: Vec<RitzPair>,
    pub next: Option<f64>,
    /// Every wanted pair converged.
    pub complete: bool,
    /// Operator applications and restarts of the run.
    pub applications: usize,
    pub restarts: usize,
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

/// `V[:, 0..k] ← V[:, 0..size] Q` (`k` = Q's columns) and `V[:, k] ← V[:, size]`, in place:
/// by blocks of rows through a `rows x k` scratch, not an `n x k` copy of the new basis (at
/// 10⁵ unknowns that copy was 59 MB per run); the two halves of the rows on two threads when
/// `parallel`.
fn restart_basis<T: Scalar>(v: &mut Mat<T>, size: usize, q: &Mat<T>, parallel: bool) {
    use faer::linalg::matmul::matmul;
    use faer::{Accum, Par};
    const ROWS: usize = 512;
    let (n, keep) = (v.nrows(), q.ncols());
    let one = T::from_c64(c64::new(1.0, 0.0));
    let half = |mut v: faer::MatMut<'_, T>| {
        let rows_all = v.nrows();
        let mut block = Mat::<T>::zeros(ROWS.min(rows_all), keep);
        for r0 in (0..rows_all).step_by(ROWS) {
            let rows = ROWS.min(rows_all - r0);
            let mut b = block.as_mut().submatrix_mut(0, 0, rows, keep);
            matmul(b.rb_mut(), Accum::Replace, v.rb().submatrix(r0, 0, rows, size), q.as_ref(), one, Par::Seq);
            v.rb_mut().submatrix_mut(r0, 0, rows, keep).copy_from(b.rb());
            for i in r0..r0 + rows {
                let x = v[(i, size)];
                v[(i, keep)] = x;
            }
        }
    };
    let (top, bottom) = v.as_mut().split_at_row_mut(Sweeper::mid(n));
    both(parallel, || half(top), || half(bottom));
}

/// Eigenvector `y` of the upper triangular `t` for its diagonal entry `i` (`y[i] = 1`).
fn triangular_eigenvector(t: &Mat<c64>, i: usize) -> Col<c64> {
    let mut y = Col::<c64>::zeros(t.nrows());
    y[i] = c64::new(1.0, 0.0);
    let theta = t[(i, i)];
    let tiny = f64::EPSILON * t.norm_l2().max(f64::MIN_POSITIVE);
    for j in (0..i).rev() {
        let s = (j + 1..=i).fold(c64::new(0.0, 0.0), |s, l| s + t[(j, l)] * y[l]);
        let mut d = t[(j, j)] - theta;
        if d.norm() < tiny {
            d = c64::new(tiny, 0.0);
        }
        y[j] = -s / d;
    }
    y
}

/// The purified unit Ritz vectors `x_i = V y_i + v_size g_i` (`V` the first `size` columns
/// of `v`, `y_i` the columns of `y`), all in one sweep over the basis: row block by row
/// block, `V`'s block times the coefficients (faer's product), the two halves of the rows
/// on two threads when `parallel`. (One matrix–vector product per vector read the whole
/// basis again for each: 48 reads of 55 MB at 10⁵ unknowns.)
fn ritz_vectors<T: Scalar>(v: &Mat<T>, size: usize, y: &Mat<c64>, g: &[c64], parallel: bool) -> Vec<Col<c64>> {
    use faer::linalg::matmul::matmul;
    use faer::{Accum, Par};
    const ROWS: usize = 512;
    let (n, q) = (v.nrows(), y.ncols());
    let coef = T::ritz_coefficients(y);
    let one = T::from_c64(c64::new(1.0, 0.0));
    let mut out: Vec<Col<c64>> = (0..q).map(|_| Col::zeros(n)).collect();
    let mid = Sweeper::mid(n);
    // Each half: its rows of every vector, and the partial squared norms.
    let fill = |r0: usize, parts: &mut [&mut [c64]]| {
        let rows_all = parts.first().map_or(0, |p| p.len());
        let mut block = Mat::<T>::zeros(ROWS.min(rows_all), coef.ncols());
        let mut norm2 = vec![0.0; q];
        for b0 in (0..rows_all).step_by(ROWS) {
            let rows = ROWS.min(rows_all - b0);
            let mut p = block.as_mut().submatrix_mut(0, 0, rows, coef.ncols());
            matmul(p.rb_mut(), Accum::Replace, v.as_ref().submatrix(r0 + b0, 0, rows, size), coef.as_ref(), one, Par::Seq);
            for (i, part) in parts.iter_mut().enumerate() {
                for r in 0..rows {
                    let x = T::ritz_entry(p.rb(), r, i) + v[(r0 + b0 + r, size)].to_c64() * g[i];
                    part[b0 + r] = x;
                    norm2[i] += x.norm_sqr();
                }
            }
        }
        norm2
    };
    let scale = |parts: &mut [&mut [c64]], inv: &[f64]| {
        for (part, &f) in parts.iter_mut().zip(inv) {
            part.iter_mut().for_each(|x| *x *= f);
        }
    };
    let (mut top, mut bottom): (Vec<&mut [c64]>, Vec<&mut [c64]>) = out.iter_mut().map(|x| contiguous_mut(x.as_mut()).split_at_mut(mid)).unzip();
    let (a, b) = both(parallel, || fill(0, &mut top), || fill(mid, &mut bottom));
    let inv: Vec<f64> = a.iter().zip(&b).map(|(x, y)| 1.0 / (x + y).sqrt()).collect();
    both(parallel, || scale(&mut top, &inv), || scale(&mut bottom, &inv));
    out
}

/// Runs Krylov–Schur on `op` (dimension `n`); `progress` is told the number of converged
/// pairs after each restart.
pub(super) fn krylov_schur<T: Scalar>(n: usize, op: &mut dyn FnMut(ColRef<'_, T>, ColMut<'_, T>), s: &Settings, progress: &dyn Fn(usize)) -> Result<Run, KrylovError> {
    let m = s.basis.min(n).max(1);
    let wanted = s.wanted.min(m.saturating_sub(1)).max(1).min(n);
    let zero = T::from_c64(c64::new(0.0, 0.0));
    let mut a = Arnoldi { n, m, v: Mat::<T>::zeros(n, m + 1), h: Mat::<T>::zeros(m + 1, m), coef: Col::zeros(m + 1), scratch: Col::zeros(m + 1), applications: 0, seed: s.seed, sweeper: Sweeper::new(s.parallel) };
    let Some(x) = purified(op, n, s.seed, &mut a.applications) else {
        return Err(KrylovError::Breakdown("the start vector is in the operator's null space".into()));
    };
    a.v.col_mut(0).copy_from(&x);
    drop(x);
    let mut kept = 0;
    let mut restarts = 0;
    loop {
        // Arnoldi expansion from column `kept`.
        let size = T::expand(&mut a, op, kept)?;
        let (v, h) = (&mut a.v, &mut a.h);
        let square = h.submatrix(0, 0, size, size).to_owned();
        // Wanted first (by decreasing |θ|), then the others (by decreasing |θ|). A real
        // basis keeps both of a pair, the one with Im θ ≥ 0 first.
        let key = |x: c64| {
            let m = x.norm() / (1.0 + x.norm());
            if T::REAL { m + if x.im >= -1e-8 * x.norm() { 1e-14 } else { 0.0 } } else { 1.0 + m }
        };
        let mut r = ritz(&square, &key, false)?;
        let theta = r.theta.clone();
        // Residual of the Ritz pair i: |h[size, :] yᵢ| / |θᵢ| (‖yᵢ‖ = 1).
        let residual_of = |r: &Ritz, i: usize| (0..size).fold(c64::new(0.0, 0.0), |acc, l| acc + h[(size, l)].to_c64() * r.y[(l, i)]).norm() / theta[i].norm();
        // The wanted leading entries: `wanted` of them, or for a real basis as many as hold
        // `wanted` with Im θ ≥ 0, a pair whole.
        let upper = |i: usize| theta[i].im >= -1e-8 * theta[i].norm();
        let want = if T::REAL {
            let mut count = 0;
            let mut k = 0;
            while k < size && count < wanted {
                count += usize::from(upper(k));
                k += 1;
            }
            if k < size && k > 0 && theta[k - 1].im.abs() > 1e-8 * theta[k - 1].norm() && (theta[k] - theta[k - 1].conj()).norm() <= 1e-8 * theta[k].norm() {
                k += 1;
            }
            k
        } else {
            wanted.min(size)
        };
        let converged = (0..want).take_while(|&i| residual_of(&r, i) <= s.tolerance).count();
        progress((0..converged).filter(|&i| !T::REAL || upper(i)).count());
        if converged >= want || restarts >= s.max_restarts || size < m {
            // x = V y purified, x ← T x / θ, by the Krylov relation T V = V H +
            // v_size h[size, :]: T x / θ = x + v_size (h[size, :] y) / θ, without applying T
            // (it removes the components along θ = 0, the infinite eigenvalues, as an
            // application would).
            let chosen: Vec<usize> = (0..converged).filter(|&i| !T::REAL || upper(i)).collect();
            let y = Mat::<c64>::from_fn(size, chosen.len(), |l, c| r.y[(l, chosen[c])]);
            let g: Vec<c64> = chosen.iter().map(|&i| (0..size).fold(c64::new(0.0, 0.0), |acc, l| acc + h[(size, l)].to_c64() * r.y[(l, i)]) / theta[i]).collect();
            let xs = ritz_vectors(v, size, &y, &g, s.parallel);
            let pairs = chosen.iter().zip(xs).map(|(&i, x)| RitzPair { theta: theta[i], x }).collect();
            let next = (size > want).then(|| theta[want].norm());
            return Ok(Run { pairs, next, complete: converged >= want, applications: a.applications, restarts });
        }
        // Restart: keep the leading Ritz vectors (wanted plus half the rest) as an
        // orthonormal basis Q of their invariant subspace, checked: ‖H Q − Q S‖ small with
        // S = Qᴴ H Q; else the sorted Schur vectors (complex QR iteration of schur.rs).
        let keep = (want + (size - want) / 2).min(size - 1).max(want);
        let invariant = |q: &Mat<T>| {
            let hq = &square * q;
            let s = q.adjoint() * &hq;
            let e = (&hq - q * &s).norm_l2();
            (e <= 1e-12 * square.norm_l2()).then_some(s)
        };
        let mut q = T::kept_basis(r.schur.as_ref().unwrap_or(&r.y), &theta, keep);
        let mut rq = q.as_ref().and_then(|q| invariant(q));
        if rq.is_none() && r.schur.is_none() {
            r = ritz(&square, &key, true)?;
            q = T::kept_basis(r.schur.as_ref().unwrap_or(&r.y), &r.theta, keep);
            rq = q.as_ref().map(|q| q.adjoint() * (&square * q));
        }
        let (Some(q), Some(rq)) = (q, rq) else {
            return Err(KrylovError::Breakdown("no basis of the kept Ritz vectors (a conjugate pair split at every cut)".into()));
        };
        let keep = q.ncols();
        restart_basis(v, size, &q, s.parallel);
        // The Rayleigh quotient S = Qᴴ H Q and the residual row h[size, :] Q.
        let bq = h.submatrix(size, 0, 1, size) * &q;
        h.fill(zero);
        for j in 0..keep {
            for i in 0..keep {
                h[(i, j)] = rq[(i, j)];
            }
            // Locking (complex basis, whose S is triangular): a converged leading Schur
            // vector no longer couples to the residual.
            let locked = !T::REAL && j < converged && bq[(0, j)].to_c64().norm() <= s.tolerance * rq[(j, j)].to_c64().norm();
            h[(keep, j)] = if locked { zero } else { bq[(0, j)] };
        }
        kept = keep;
        restarts += 1;
    }
}
