//! Krylov–Schur iteration (Stewart, "A Krylov–Schur algorithm for large eigenproblems",
//! SIAM J. Matrix Anal. Appl. 23, 2001) for the eigenvalues θ of largest modulus of an
//! operator applied to vectors: Arnoldi expansion with full reorthogonalization (classical
//! Gram–Schmidt twice), Schur form of the Rayleigh quotient sorted by |θ|, truncation to the
//! wanted Schur vectors, and locking of the converged leading ones (their coupling to the
//! residual vector is set to zero once below the tolerance).

use faer::{c64, Col, Mat};

use super::schur::{schur, sort_schur};
use super::KrylovError;

/// What one run is asked for.
pub(super) struct Settings {
    /// Number of wanted θ (largest |θ|).
    pub wanted: usize,
    /// Largest basis size.
    pub basis: usize,
    /// Relative residual `‖T x − θ x‖ / |θ|` at which a Ritz pair is converged.
    pub tolerance: f64,
    pub max_restarts: usize,
    /// Seed of the start vector.
    pub seed: u64,
    /// Want only θ with `Im θ ≥ 0` (`Im λ ≥ 0`): for a real operator the others are their
    /// conjugates, so the basis need not hold them.
    pub upper_half: bool,
}

/// A converged Ritz pair of the operator, `x` of unit norm.
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
}

fn pseudo_random(n: usize, seed: u64) -> Col<c64> {
    let mut x = 0x9E37_79B9_7F4A_7C15u64 ^ seed.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    Col::from_fn(n, |_| c64::new(next(), next()))
}

/// `w` with its components along `v[:, 0..cols]` removed (classical Gram–Schmidt, a
/// second pass when needed); the coefficients removed and the norm left.
fn orthogonalize(v: &Mat<c64>, cols: usize, w: &mut Col<c64>) -> (Col<c64>, f64) {
    use faer::linalg::matmul::matmul;
    use faer::{Accum, Par};
    let basis = v.subcols(0, cols);
    let mut h = Col::<c64>::zeros(cols);
    let mut c = Col::<c64>::zeros(cols);
    let (one, minus_one) = (c64::new(1.0, 0.0), c64::new(-1.0, 0.0));
    // Sequential products: these matrix-vector products are too small to gain from threads.
    // A second pass only when the first removed most of `w` (Kahan–Parlett "twice is
    // enough": a norm kept above 1/√2 of the input is orthogonal to working accuracy).
    let mut before = w.norm_l2();
    for _ in 0..2 {
        matmul(c.as_mat_mut(), Accum::Replace, basis.adjoint(), w.as_mat(), one, Par::Seq);
        matmul(w.as_mat_mut(), Accum::Add, basis, c.as_mat(), minus_one, Par::Seq);
        h += &c;
        let after = w.norm_l2();
        if after > std::f64::consts::FRAC_1_SQRT_2 * before {
            return (h, after);
        }
        before = after;
    }
    (h, w.norm_l2())
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

/// Runs Krylov–Schur on `op` (dimension `n`); `progress` is told the number of converged
/// pairs after each restart.
pub(super) fn krylov_schur(n: usize, op: &dyn Fn(&Col<c64>) -> Col<c64>, s: &Settings, progress: &dyn Fn(usize)) -> Result<Run, KrylovError> {
    let m = s.basis.min(n).max(1);
    let wanted = s.wanted.min(m.saturating_sub(1)).max(1).min(n);
    let mut v = Mat::<c64>::zeros(n, m + 1);
    let mut h = Mat::<c64>::zeros(m + 1, m);
    // Start vector: random, then T³ applied so the (index ≤ 3) components at θ = 0 of the
    // infinite eigenvalues are gone before the Krylov space is built.
    let mut x = pseudo_random(n, s.seed);
    for _ in 0..3 {
        x = op(&x);
        let nx = x.norm_l2();
        if !(nx > 0.0 && nx.is_finite()) {
            return Err(KrylovError::Breakdown("the start vector is in the operator's null space".into()));
        }
        x /= nx;
    }
    v.col_mut(0).copy_from(&x);
    let mut kept = 0;
    let mut restarts = 0;
    loop {
        // Arnoldi expansion from column `kept`.
        let mut size = m;
        for j in kept..m {
            let mut w = op(&v.col(j).to_owned());
            if !w.iter().all(|x| x.re.is_finite() && x.im.is_finite()) {
                return Err(KrylovError::Breakdown("the operator returned non-finite values".into()));
            }
            let (c, mut beta) = orthogonalize(&v, j + 1, &mut w);
            for i in 0..=j {
                h[(i, j)] = c[i];
            }
            let scale = c.norm_l2().max(beta);
            if beta <= 1e-12 * scale {
                // Invariant subspace: continue with a fresh direction (coupling zero), purified
                // like the start vector. When the purified fresh vectors lie in the basis
                // too, the finite spectrum the operator reaches is exhausted: stop there.
                h[(j + 1, j)] = c64::new(0.0, 0.0);
                let mut fresh = None;
                for attempt in 0..3u64 {
                    let mut f = pseudo_random(n, s.seed + 1000 + 7 * j as u64 + attempt);
                    for _ in 0..3 {
                        f = op(&f);
                        let nf = f.norm_l2();
                        if nf > 0.0 {
                            f /= nf;
                        }
                    }
                    let nb = orthogonalize(&v, j + 1, &mut f).1;
                    if nb > 1e-8 && nb.is_finite() {
                        fresh = Some((f, nb));
                        break;
                    }
                }
                match fresh {
                    Some((f, nb)) => {
                        w = f;
                        beta = nb;
                    }
                    None => {
                        size = j + 1;
                        break;
                    }
                }
            } else {
                h[(j + 1, j)] = c64::new(beta, 0.0);
            }
            let col = &w / beta;
            v.col_mut(j + 1).copy_from(&col);
        }
        let square = h.submatrix(0, 0, size, size).to_owned();
        let (mut t, mut z) = schur(&square).ok_or_else(|| KrylovError::Breakdown("the Schur form of the Rayleigh quotient did not converge".into()))?;
        // Wanted first (by decreasing |θ|), then the others (by decreasing |θ|).
        let upper = s.upper_half;
        sort_schur(&mut t, &mut z, |x| {
            let m = x.norm() / (1.0 + x.norm());
            if !upper || x.im >= -1e-8 * x.norm() { 1.0 + m } else { m }
        });
        // Residual row bᵀ = h[size, :] Z.
        let b: Vec<c64> = (0..size).map(|j| (0..size).fold(c64::new(0.0, 0.0), |acc, i| acc + h[(size, i)] * z[(i, j)])).collect();
        let residual_of = |i: usize| {
            let y = triangular_eigenvector(&t, i);
            let r = (0..=i).fold(c64::new(0.0, 0.0), |acc, l| acc + b[l] * y[l]).norm();
            r / (y.norm_l2() * t[(i, i)].norm())
        };
        let want = wanted.min(size);
        let converged = (0..want).take_while(|&i| residual_of(i) <= s.tolerance).count();
        progress(converged);
        if converged >= want || restarts >= s.max_restarts || size < m {
            let basis = v.subcols(0, size) * &z;
            let pairs = (0..converged)
                .map(|i| {
                    let y = triangular_eigenvector(&t, i);
                    let x = &basis * &y;
                    let nx = x.norm_l2();
                    RitzPair { theta: t[(i, i)], x: x / nx }
                })
                .collect();
            let next = (size > want).then(|| t[(want, want)].norm());
            return Ok(Run { pairs, next, complete: converged >= want });
        }
        // Restart: keep the leading Schur vectors (wanted plus half the rest).
        let keep = (want + (size - want) / 2).min(size - 1).max(want);
        let new_basis = v.subcols(0, size) * z.subcols(0, keep);
        let last = v.col(size).to_owned();
        v.subcols_mut(0, keep).copy_from(&new_basis);
        v.col_mut(keep).copy_from(&last);
        h.fill(c64::new(0.0, 0.0));
        for j in 0..keep {
            for i in 0..=j {
                h[(i, j)] = t[(i, j)];
            }
            // Locking: a converged leading Schur vector no longer couples to the residual.
            let locked = j < converged && b[j].norm() <= s.tolerance * t[(j, j)].norm();
            h[(keep, j)] = if locked { c64::new(0.0, 0.0) } else { b[j] };
        }
        kept = keep;
        restarts += 1;
    }
}
