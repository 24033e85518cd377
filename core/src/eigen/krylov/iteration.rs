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
use faer::{c64, Col, ColMut, ColRef, Mat};

use super::arnoldi::{purified, Arnoldi, Scalar};
use super::gram_schmidt::{both, Sweeper};
use super::schur::{schur, sort_schur};
use crate::linear::contiguous_mut;
use super::KrylovError;

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

/// Restarts without a newly converged pair after which a run returns what converged.
const STALL_RESTARTS: usize = 10;

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
    /// The Ritz values of the last Rayleigh quotient not returned as pairs (unconverged,
    /// or beyond the wanted ones; a real basis's with their conjugates): approximations of
    /// the eigenvalues next beyond those returned, which the count (`count.rs`) divides out.
    pub unconverged: Vec<c64>,
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
    // Restarts since the count of converged pairs last grew, and that count.
    let (mut stalled, mut best) = (0usize, 0usize);
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
        // Residual of the Ritz pair i relative to |θᵢ|, or to the rounding floor of the
        // operator's application (ε ‖T‖ ≥ ε |θ₀|, times 100) when that is larger: a θ far
        // below the largest (an eigenvalue far from the shift: the cantilever's torsion
        // modes at 1e4 times its first bending frequency) cannot reach `tolerance |θᵢ|`, and
        // asking it made every restart up to `max_restarts` (minutes on 210 equations). The
        // pair still meets its true residual before it is accepted (window.rs).
        let floor = 100.0 * f64::EPSILON * theta.first().map_or(0.0, |t| t.norm()) / s.tolerance;
        let residual_of = |r: &Ritz, i: usize| (0..size).fold(c64::new(0.0, 0.0), |acc, l| acc + h[(size, l)].to_c64() * r.y[(l, i)]).norm() / theta[i].norm().max(floor);
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
        // A wanted Ritz value that stops converging (the second copy of a repeated
        // eigenvalue, which a single-vector Krylov space holds only through rounding: the
        // 3-D cantilever's 24 lowest stalled at 22 for the whole 200 restarts, minutes)
        // ends the run after STALL_RESTARTS restarts without progress: the pairs converged
        // so far are returned (`complete` false), and the caller's count decides.
        if converged > best {
            (best, stalled) = (converged, 0);
        } else {
            stalled += 1;
        }
        if converged >= want || restarts >= s.max_restarts || size < m || (converged > 0 && stalled > STALL_RESTARTS) {
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
            let unconverged = theta[converged..size].to_vec();
            return Ok(Run { pairs, next, complete: converged >= want, applications: a.applications, restarts, unconverged });
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
