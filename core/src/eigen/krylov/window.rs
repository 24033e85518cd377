//! One shift: the eigenvalues nearest σ with right and left vectors, from two independent
//! Krylov–Schur runs on the same factorization (`T` for the right vectors, its transposed
//! operator for the left ones, eq. 11), each pair checked by its true residual on the DAE's
//! own pencil.

use faer::{c64, Col};

use super::clusters::pair_clusters;
use super::iteration::{krylov_schur, RitzPair, Run, Settings};
use super::operator::ShiftInvert;
use super::pencil::Pencil;
use super::{KrylovError, SparseEigenSettings};
use crate::eigen::Classification;
use crate::eigen::route::EigenRoute;
use crate::linear::{contiguous, contiguous_mut, SparseLinearDae};

/// An eigenpair of the DAE's pencil `λ F_yd + F_y` (the DAE's own constraint form), its
/// representative with `Im λ ≥ 0`.
#[derive(Clone, Debug)]
pub(super) struct Eigenpair {
    pub lambda: c64,
    pub right: Col<c64>,
    /// `None` when only right vectors were asked ([`SparseEigenSettings::left_vectors`]).
    pub left: Option<Col<c64>>,
    /// True relative residuals `‖(λ F_yd + F_y) v‖ / ((|λ| ‖F_yd‖ + ‖F_y‖) ‖v‖)`, and of `uᵀ`
    /// (0 without a left vector).
    pub residual_right: f64,
    pub residual_left: f64,
    /// The label of eqs. 32–35 and the error estimate of λ it gives.
    pub classification: Classification,
    pub error: f64,
}

/// What one shift found: accepted pairs, the radius of the disc `|λ − σ| ≤ radius` in which
/// both runs found the same eigenvalues (`f64::INFINITY` when the finite spectrum was
/// exhausted), and whether they agreed.
pub(super) struct WindowResult {
    pub shift: c64,
    pub radius: f64,
    pub agreed: bool,
    /// The adjoint run was made (the agreement is a check); `false` for right vectors only.
    pub checked: bool,
    /// Radius of the largest disc `|λ − σ| < clean` (at most `radius`) holding no
    /// disagreement and no rejected pair: where the two runs' check holds when `agreed` is
    /// false (disagreements far out, e.g. Ritz values of the infinite eigenvalues' defective
    /// θ = 0 cluster once the finite spectrum is exhausted).
    pub clean: f64,
    pub pairs: Vec<Eigenpair>,
    /// Pairs that converged in the operator but failed the true-residual test.
    pub rejected: usize,
}

/// θ at or below this fraction of the largest are the infinite eigenvalues (θ = 0).
const NULL_THETA: f64 = 1e-8;

/// The pairs of one run with their eigenvalues λ (the run purified the vectors);
/// `exhausted` when the run reached θ ≈ 0.
fn lambdas(op: &ShiftInvert, run: Run) -> (Vec<(c64, Col<c64>)>, bool) {
    let top = run.pairs.first().map_or(0.0, |p| p.theta.norm());
    let mut out = Vec::new();
    let mut exhausted = false;
    for RitzPair { theta, x } in run.pairs {
        if theta.norm() <= NULL_THETA * top {
            exhausted = true;
            break;
        }
        out.push((op.lambda(theta), x));
    }
    // All wanted pairs converged and nothing but θ ≈ 0 (or nothing) is left.
    exhausted |= run.complete && run.next.is_none_or(|t| t <= NULL_THETA * top);
    (out, exhausted)
}

/// Runs both Krylov–Schur iterations at `sigma` for `wanted` eigenvalues.
pub(super) fn window(dae: &SparseLinearDae, pencil: &Pencil, sigma: c64, wanted: usize, s: &SparseEigenSettings, progress: &dyn Fn(&str)) -> Result<WindowResult, KrylovError> {
    let scales = Scales::new(dae, s);
    let op = ShiftInvert::new(pencil, sigma)?;
    if !s.left_vectors {
        let run = krylov_run(pencil, &op, wanted, s, false, Placement::RightOnly, 1, progress)?;
        return right_only(dae, pencil, &op, run, s, &scales, progress);
    }
    let sides = krylov_sides(dae, pencil, &op, wanted, s, 0, true, progress)?;
    // Radius of the disc each run covers: the farthest converged eigenvalue (everything
    // when the run exhausted the finite spectrum).
    let radius = sides.reach(sigma);
    let inside = |l: c64| (l - sigma).norm() <= radius * (1.0 + 1e-9);
    let mut agreed = true;
    let mut rejected = sides.rejected;
    // Nearest distance to σ of a disagreement or a rejected pair.
    let mut trouble = sides.trouble;
    if trouble.is_finite() && inside(sigma + trouble) {
        agreed = false;
    }
    let mut flag = |l: c64, agreed: &mut bool| {
        if inside(l) {
            *agreed = false;
        }
        trouble = trouble.min((l - sigma).norm());
    };
    let clusters = pair_clusters(pencil, sigma, &sides.right, &sides.left, 1);
    for l in &clusters.unmatched {
        flag(*l, &mut agreed);
    }
    let mut pairs = Vec::new();
    for e in evaluate(dae, pencil, &scales, s, clusters.pairs) {
        match e {
            Ok(p) => pairs.push(p),
            Err(lambda) => {
                rejected += 1;
                flag(lambda, &mut agreed);
            }
        }
    }
    let clean = radius.min(trouble * (1.0 - 1e-6));
    Ok(WindowResult { shift: sigma, radius, agreed, checked: true, clean, pairs, rejected })
}

/// How a run shares the machine and how wide its real basis is.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Placement {
    /// Beside the adjoint run, a core each.
    BesideAdjoint,
    /// Alone (its sweeps on both cores): the right run of [`SparseEigenSettings::left_vectors`]
    /// false, tuned as scipy's `eigs` is asked.
    RightOnly,
    /// Alone, for the counted lowest modes (`shifts.rs`), whose left vectors come from the
    /// clusters' inverse iteration: a wider basis ([`COUNTED_EXTRA`]).
    Counted,
}

/// Columns beyond 2 nev of the counted route's right run (basis beyond the second-level
/// cache). Measured (2026-12-07, release, CPU s of `sparse_pencil solve DIR 20`, 24
/// wanted, load 10-12): the 96,024-equation spring chain 2 nev + 20 / 40 / 60 / 80: 293 /
/// 197 / 141 / 131 applications, 20 / 5 / 1 / 0 restarts, 5.62 / 4.96 / 4.36 / 4.43 s;
/// the 102,012-equation hanging chain 121 / 131 / 111 applications, 5.57 / 5.70 / 5.43 s
/// (20 / 40 / 60), the 17,012-equation one 0.68 / 0.68 / 0.65 s.
const COUNTED_EXTRA: usize = 60;

/// One Krylov–Schur run on `T` (`transpose` false: right vectors) or `Tᵀ` (left vectors)
/// with the start vector of `seed`, placed as `placement` says.
#[allow(clippy::too_many_arguments)]
pub(super) fn krylov_run(pencil: &Pencil, op: &ShiftInvert, wanted: usize, s: &SparseEigenSettings, transpose: bool, placement: Placement, seed: u64, progress: &dyn Fn(&str)) -> Result<Run, KrylovError> {
    let n = pencil.dim();
    let sigma = op.sigma;
    // Basis of three times the wanted count: measured on the 20 lowest modes of the hanging
    // chain (callgrind, 24 wanted), 2x+1 took 11 restart cycles per run, 3x+1 four; at
    // N = 1000 (17012 equations) 3x+1 ran in 0.65 of the time of 2x+1 (4x+1: 0.71, its
    // Schur forms of the 97-wide Rayleigh quotient cost more than the saved restarts).
    let basis = (3 * wanted + 1).max(wanted + 20).min(n);
    // A real basis holds both of each complex pair: twice the wanted count, and 20 columns
    // more. Measured on the 20 lowest modes of the hanging chain (24 wanted, N = 1000 and
    // 6000): ARPACK's default 2 nev + 1 (97 columns) takes 125 applications and 1 restart
    // per run, 6878 basis columns orthogonalized against; 2 nev + 20 (68 columns) 121
    // applications, 5 restarts, 5521 columns: the Gram–Schmidt sweeps, which are memory
    // bound at 10⁵ unknowns, read 20 % less (N = 6000: 0.8 of the wall time). Re-measured
    // with the delayed reorthogonalization (2026-12-02, N = 1000, columns swept per run):
    // 24 wanted (both runs) 2 nev + 10 / 20 / 30 / 40: 133 / 121 / 113 / 131 applications,
    // 12 / 5 / 2 / 2 restarts, 5577 / 5403 / 5227 / 6928 columns; 20 wanted (the right run
    // alone) 2 nev + 20 / 30: 103 / 105 applications, 4 / 2 restarts, 3950 / 4383 columns;
    // 5 and 10 modes favour 2 nev + 20 over 30 as well. Kept at 20 more. Keeping fewer
    // Ritz vectors at a restart (the wanted ones and a third or a quarter of the rest, or
    // none of the rest) took more applications and columns. When the basis fits in the
    // second-level cache (2 MiB a core here) its sweeps cost little and the restarts' dense
    // work (the Rayleigh quotient's eigenvectors, the basis rotation) dominates: there 20
    // columns more again, fewer restarts (callgrind, the whole 1712-equation chain solve:
    // right only 192 M -> 142 M instructions, 4 -> 1 restart, 103 applications; right +
    // left 525 M -> 413 M, 5 -> 2 restarts, 121 -> 131 applications each). At 17012
    // equations (11 MB) the instructions fell too (right only 1.02e9 -> 0.93e9) but the
    // sweeps read 22 % more of a basis beyond that cache: not taken there.
    let roomy = 2 * wanted + 40;
    let extra = if n * roomy * std::mem::size_of::<f64>() <= 2 << 20 { 40 } else if placement == Placement::Counted { COUNTED_EXTRA } else { 20 };
    let real_basis = (2 * wanted + extra).min(n);
    // A run alone has both cores: its sweeps over the basis go on two threads.
    let parallel = placement != Placement::BesideAdjoint && n >= PARALLEL_FROM && rayon::current_num_threads() > 1;
    let real_settings = |seed| Settings { wanted, basis: real_basis, tolerance: s.krylov_tolerance, max_restarts: s.max_restarts, seed, parallel };
    let settings = |seed| Settings { wanted, basis, tolerance: s.krylov_tolerance, max_restarts: s.max_restarts, seed, parallel };
    let side = if transpose { "adjoint" } else { "right" };
    let report = move |k: usize| progress(&format!("shift {sigma}: {side} {k}/{wanted} converged"));
    // A real shift of the real pencil runs in real arithmetic (the eigenvalues below the
    // real axis are the conjugates of those above).
    let mut ws = op.workspace();
    if sigma.im == 0.0 {
        krylov_schur::<f64>(n, &mut |x, out| op.apply_into(x, out, transpose, &mut ws), &real_settings(seed), &report)
    } else {
        krylov_schur::<c64>(n, &mut |x, out| op.apply_into(x, out, transpose, &mut ws), &settings(seed), &report)
    }
}

/// The converged pairs of both runs at one shift as eigenpairs of eq. 29 (`Im λ ≥ 0`), each
/// checked by its own true residual (right: `(λ E + K) v`, left: `uᵀ (λ E + K)`).
pub(super) struct Sides {
    pub right: Vec<(c64, Col<c64>)>,
    pub left: Vec<(c64, Col<c64>)>,
    right_reach: f64,
    left_reach: f64,
    /// Pairs that converged in the operator but failed their true residual.
    pub rejected: usize,
    /// Nearest distance to σ of a rejected pair.
    pub trouble: f64,
    /// The right run's last Ritz values not returned as pairs, as λ (with their
    /// conjugates): the eigenvalues next beyond those found, roughly (the counted route
    /// divides those outside its circle out of the count; empty for two runs).
    pub unconverged: Vec<c64>,
}

impl Sides {
    /// Radius of the disc about σ both runs covered.
    pub fn reach(&self, _sigma: c64) -> f64 {
        self.right_reach.min(self.left_reach)
    }
}

/// Both runs at the factored shift (`adjoint` false: the right run alone, placed as
/// [`Placement::Counted`], no left pairs), with the start vectors of `round` (each round
/// its own).
#[allow(clippy::too_many_arguments)]
pub(super) fn krylov_sides(dae: &SparseLinearDae, pencil: &Pencil, op: &ShiftInvert, wanted: usize, s: &SparseEigenSettings, round: u64, adjoint: bool, progress: &dyn Fn(&str)) -> Result<Sides, KrylovError> {
    let sigma = op.sigma;
    let (seed_right, seed_left) = (2 * round + 1, 2 * round + 2);
    if !adjoint {
        let run = krylov_run(pencil, op, wanted, s, false, Placement::Counted, seed_right, progress)?;
        progress(&format!("shift {sigma}: {} operator applications, {} restarts (right run)", run.applications, run.restarts));
        let top = run.pairs.first().map_or(0.0, |p| p.theta.norm());
        let unconverged: Vec<c64> = run.unconverged.iter().filter(|t| t.norm() > NULL_THETA * top).map(|&t| op.lambda(t)).filter(|l| l.re.is_finite() && l.im.is_finite()).collect();
        let (right, right_all) = lambdas(op, run);
        let mut sides = checked_sides(dae, pencil, sigma, s, (right, right_all), (Vec::new(), true));
        sides.unconverged = unconverged;
        return Ok(sides);
    }
    // The two runs are independent (one factorization, read only): the adjoint run goes
    // to a second thread while this one does the right run and reports progress. Its own
    // progress is not reported (the caller's callback need not be thread-safe); both take
    // about as long. On a worker of the rayon pool (a sweep's point) both runs stay on it:
    // a thread of its own would call faer's parallel products from outside the pool and
    // wait for its workers, which all wait for it (tests/eigen/sparse_eigen.rs, the rayon-workers
    // test).
    let (right_run, left_run) = if rayon::current_thread_index().is_some() {
        (krylov_run(pencil, op, wanted, s, false, Placement::BesideAdjoint, seed_right, progress), krylov_run(pencil, op, wanted, s, true, Placement::BesideAdjoint, seed_left, &|_| {}))
    } else {
        std::thread::scope(|scope| {
            let left = scope.spawn(|| krylov_run(pencil, op, wanted, s, true, Placement::BesideAdjoint, seed_left, &|_| {}));
            let right = krylov_run(pencil, op, wanted, s, false, Placement::BesideAdjoint, seed_right, progress);
            let left = left.join().unwrap_or_else(|_| Err(KrylovError::Breakdown("the adjoint Krylov run panicked".into())));
            (right, left)
        })
    };
    let (right_run, left_run) = (right_run?, left_run?);
    progress(&format!(
        "shift {sigma}: {} + {} operator applications, {} + {} restarts (right + adjoint run)",
        right_run.applications, left_run.applications, right_run.restarts, left_run.restarts
    ));
    Ok(checked_sides(dae, pencil, sigma, s, lambdas(op, right_run), lambdas(op, left_run)))
}

/// The runs' pairs (with whether each run exhausted the finite spectrum) checked by their
/// true residuals, as [`Sides`].
fn checked_sides(dae: &SparseLinearDae, pencil: &Pencil, sigma: c64, s: &SparseEigenSettings, (right, right_all): (Vec<(c64, Col<c64>)>, bool), (left, left_all): (Vec<(c64, Col<c64>)>, bool)) -> Sides {
    let reach = |l: &[(c64, Col<c64>)], all: bool| if all { f64::INFINITY } else { l.iter().map(|(x, _)| (x - sigma).norm()).fold(0.0, f64::max) };
    let (right_reach, left_reach) = (reach(&right, right_all), reach(&left, left_all));
    let norms = (dae.fyd.norm_l2(), dae.fy.norm_l2());
    let mut rejected = 0;
    let mut trouble = f64::INFINITY;
    let mut keep = |list: Vec<(c64, Col<c64>)>, transpose: bool| -> Vec<(c64, Col<c64>)> {
        let mut out = Vec::new();
        for (l, x) in list {
            let r = if transpose { DaeProducts::new(dae, pencil.moved(), &x, true, norms).residual(l) } else { right_residual(dae, pencil.moved(), &x, l, norms) };
            if r <= s.tolerance {
                out.push(if l.im < 0.0 { (l.conj(), Col::from_fn(x.nrows(), |i| x[i].conj())) } else { (l, x) });
            } else {
                rejected += 1;
                trouble = trouble.min((l - sigma).norm());
            }
        }
        out
    };
    let right = keep(right, false);
    let left = keep(left, true);
    Sides { right, left, right_reach, left_reach, rejected, trouble, unconverged: Vec::new() }
}

/// Each pair's residuals, vectors and label, one after the other (on the pool's threads
/// they took 5 % less time at N = 6000 but the threads' glibc arenas kept what the pairs'
/// vectors had used: peak over three solves 254 -> 422 MB). `Err(λ)`: the pair failed the
/// true-residual test.
pub(super) fn evaluate(dae: &SparseLinearDae, pencil: &Pencil, scales: &Scales, s: &SparseEigenSettings, matched: Vec<(c64, Col<c64>, Col<c64>)>) -> Vec<Result<Eigenpair, c64>> {
    map_pairs(false, matched, |(lr, v29, u29)| {
        // Two-sided Rayleigh quotient on eq. 29: λ = −(uᵀ K v)/(uᵀ E v), its sums compensated
        // (a stiff beam's uᵀ K v cancels EA = 1e10 N down to the bending value: plain sums
        // left the lowest pair 1.4e-7 off at EA/EJ = 1e7, 64 elements; now 2e-11). It is
        // taken whenever its true residuals pass, else whichever of it and the Ritz value has
        // the smaller (the residuals' own rounding cannot rank two values this close).
        let rq = pencil.k.two_sided_quotient(&pencil.e, &u29, &v29);
        // The DAE's products of both vectors, split by the moved entries, serve every
        // candidate λ, the labels and the normalization.
        let norms = (scales.nyd, scales.ny);
        let (right_products, left_products) = (DaeProducts::new(dae, pencil.moved(), &v29, false, norms), DaeProducts::new(dae, pencil.moved(), &u29, true, norms));
        let candidates: Vec<_> = rq.into_iter().chain([lr]).filter(|l| l.re.is_finite() && l.im.is_finite()).map(|l| (l, right_products.residual(l), left_products.residual(l))).collect();
        let (lambda, rr, rl) = candidates
            .iter()
            .copied()
            .find(|c| c.1 <= s.tolerance && c.2 <= s.tolerance)
            .or_else(|| candidates.iter().copied().min_by(|a, b| a.1.max(a.2).total_cmp(&b.1.max(b.2))))
            .unwrap_or_else(|| unreachable!("the Ritz value is finite"));
        if !(rr <= s.tolerance && rl <= s.tolerance) {
            return Err(lambda);
        }
        let (v, u) = (pencil.to_dae(&v29, lambda), pencil.to_dae(&u29, lambda));
        drop((v29, u29));
        let ((fydv, fyv), (ufyd, ufy)) = (right_products.at(lambda), left_products.at(lambda));
        drop((right_products, left_products));
        let vectors = PairVectors { v, u, fydv, fyv, ufyd, ufy };
        // The residuals against the scale of the entries they sum (`(|λ| |F_yd| + |F_y|) |v|`,
        // and from the left): the norm-wise test above lets the largest stiffness (a beam's
        // EA = 1e8 N) hide a wrong pair, which this one does not (the 64-element cantilever's
        // spurious 4.3 + 14296j rad/s, made of an axial mode's refined subspace, passed the
        // norm-wise test and failed this one).
        let (right_entrywise, right_magnitude) = entrywise_residual(dae, lambda, &vectors.v, &vectors.fydv, &vectors.fyv, false);
        let (left_entrywise, left_magnitude) = entrywise_residual(dae, lambda, &vectors.u, &vectors.ufyd, &vectors.ufy, true);
        if !(right_entrywise <= s.tolerance && left_entrywise <= s.tolerance) {
            return Err(lambda);
        }
        let mut vectors = vectors;
        let lambda = if lambda.im < 0.0 {
            vectors.map(|x| x.conj());
            lambda.conj()
        } else {
            lambda
        };
        // The conjugation keeps the moduli: the products of |v| and |u| serve the error
        // estimate as they are.
        Ok(Eigenpair::new(dae, lambda, vectors, rr, rl, rq.map_or(f64::INFINITY, |q| (lr - q).norm()), scales, Some(Magnitudes { right: right_magnitude, left: left_magnitude })))
    })
}

/// The window of the right run alone ([`SparseEigenSettings::left_vectors`] false): every
/// pair checked by its true right residual at the Ritz value; the disc is the run's reach,
/// `agreed` since nothing disagrees, but not `checked`.
fn right_only(dae: &SparseLinearDae, pencil: &Pencil, op: &ShiftInvert, run: Run, s: &SparseEigenSettings, scales: &Scales, progress: &dyn Fn(&str)) -> Result<WindowResult, KrylovError> {
    let sigma = op.sigma;
    progress(&format!("shift {sigma}: {} operator applications, {} restarts (right run only)", run.applications, run.restarts));
    let (right, all) = lambdas(op, run);
    let radius = if all { f64::INFINITY } else { right.iter().map(|(x, _)| (x - sigma).norm()).fold(0.0, f64::max) };
    // On the pool's threads (the right run alone has both cores): 6 % less time at
    // N = 6000, for 38 MB more at the peak over three solves (170 -> 208 MB; the threads'
    // arenas keep what the pairs' vectors used).
    let evaluated = map_pairs(pencil.dim() >= PARALLEL_FROM, right, |(lr, v29)| {
        let rr = right_residual(dae, pencil.moved(), &v29, lr, (scales.nyd, scales.ny));
        if !(rr <= s.tolerance) {
            return Err(lr);
        }
        let v = pencil.to_dae(&v29, lr);
        drop(v29);
        let (v, lambda) = if lr.im < 0.0 { (Col::from_fn(v.nrows(), |i| v[i].conj()), lr.conj()) } else { (v, lr) };
        Ok(Eigenpair::right_only(lambda, v, rr, scales))
    });
    let mut pairs = Vec::new();
    let mut rejected = 0;
    let mut trouble = f64::INFINITY;
    for e in evaluated {
        match e {
            Ok(p) => pairs.push(p),
            Err(lr) => {
                rejected += 1;
                trouble = trouble.min((lr - sigma).norm());
            }
        }
    }
    let clean = radius.min(trouble * (1.0 - 1e-6));
    Ok(WindowResult { shift: sigma, radius, agreed: true, checked: false, clean, pairs, rejected })
}

/// `‖(λ F_yd + F_y) x‖ / ‖(|λ| |F_yd| + |F_y|) |x|‖` (transposed for a left vector), from the
/// products `F_yd x`, `F_y x` already formed; with the products `|F_yd| |x|`, `|F_y| |x|` it
/// took (the error estimate, `shifts.rs`' `residual_error`, needs the same ones).
fn entrywise_residual(dae: &SparseLinearDae, lambda: c64, x: &Col<c64>, dx: &Col<c64>, yx: &Col<c64>, transpose: bool) -> (f64, (Vec<f64>, Vec<f64>)) {
    let ax: Vec<f64> = x.iter().map(|&e| crate::eigen::route::modulus(e)).collect();
    let (d, k) = (dae.fyd.abs_mul(&ax, transpose), dae.fy.abs_mul(&ax, transpose));
    let r = (0..dx.nrows()).map(|i| (lambda * dx[i] + yx[i]).norm_sqr()).sum::<f64>().sqrt();
    let scale = (0..dx.nrows()).map(|i| (lambda.norm() * d[i] + k[i]).powi(2)).sum::<f64>().sqrt();
    (r / scale, (d, k))
}

/// `(|F_yd| |v|, |F_y| |v|)` and `(|F_ydᵀ| |u|, |F_yᵀ| |u|)` of a pair's vectors as
/// [`entrywise_residual`] formed them, for the error estimate of [`Eigenpair::new`] (the
/// same products of the same vectors: computed once, not twice).
pub(super) struct Magnitudes {
    pub right: (Vec<f64>, Vec<f64>),
    pub left: (Vec<f64>, Vec<f64>),
}

/// Vectors from this length on are long enough for the hand-over to other threads to pay
/// (measured on the hanging chain: at 1712 equations two threads were slower than one, at
/// 17012 faster).
pub(super) const PARALLEL_FROM: usize = 4096;

/// `f` of every item (taken by value, so what it holds is freed as it goes), in order: on
/// the rayon pool's threads when `parallel` (from the calling thread outside the pool rayon
/// waits for its workers, which wait for nothing here; on a worker, the items may be
/// stolen or run on it).
fn map_pairs<I: Send, R: Send>(parallel: bool, items: Vec<I>, f: impl Fn(I) -> R + Sync + Send) -> Vec<R> {
    use rayon::prelude::*;
    if parallel && items.len() > 1 && rayon::current_num_threads() > 1 {
        items.into_par_iter().with_max_len(1).map(f).collect()
    } else {
        items.into_iter().map(f).collect()
    }
}

/// `F_yd x` and `F_y x` (or `F_ydᵀ x`, `F_yᵀ x`) of the DAE's vector of an eq. 29 vector
/// `x29` at any λ: the moved entries are `x29/λ` (eq. 30, see `pencil.rs`), so each product
/// is `a + b/λ` with `a`, `b` the products of the unmoved and moved parts.
struct DaeProducts {
    fyd: (Col<c64>, Col<c64>),
    fy: (Col<c64>, Col<c64>),
    /// `‖x29‖²` on the unmoved and the moved entries.
    norm2: (f64, f64),
    norms: (f64, f64),
}

/// `‖x29‖²` on the unmoved and the moved entries.
fn split_norms(x29: &Col<c64>, moved: &[bool]) -> (f64, f64) {
    x29.iter().zip(moved).fold((0.0, 0.0), |(a, b), (x, &m)| if m { (a, b + x.norm_sqr()) } else { (a + x.norm_sqr(), b) })
}

/// [`DaeProducts::residual`] of the right vector of an eq. 29 vector at λ, row by row in one
/// pass over the matrices, no product kept (the same sums in the same order; the right run
/// alone needs nothing else). `norms`: `(‖F_yd‖_F, ‖F_y‖_F)`.
fn right_residual(dae: &SparseLinearDae, moved: &[bool], x29: &Col<c64>, lambda: c64, norms: (f64, f64)) -> f64 {
    let x = crate::linear::contiguous(x29.as_ref());
    assert!(x.len() == dae.fyd.ncols() && x.len() == dae.fy.ncols() && moved.len() == x.len() && dae.fyd.nrows() == dae.fy.nrows(), "residual: sizes");
    let norm2 = split_norms(x29, moved);
    let inv = c64::new(1.0, 0.0) / lambda;
    let r2 = (0..dae.fyd.nrows())
        .map(|i| {
            let ((da, db), (ya, yb)) = (dae.fyd.row_split(i, x, moved), dae.fy.row_split(i, x, moved));
            (lambda * da + db + ya + yb * inv).norm_sqr()
        })
        .sum::<f64>();
    let nx = (norm2.0 + norm2.1 * inv.norm_sqr()).sqrt();
    r2.sqrt() / ((lambda.norm() * norms.0 + norms.1) * nx)
}

impl DaeProducts {
    fn new(dae: &SparseLinearDae, moved: &[bool], x29: &Col<c64>, transpose: bool, norms: (f64, f64)) -> Self {
        DaeProducts { fyd: dae.fyd.mul_split(x29, moved, transpose), fy: dae.fy.mul_split(x29, moved, transpose), norm2: split_norms(x29, moved), norms }
    }

    /// `(F_yd x, F_y x)` at λ.
    fn at(&self, lambda: c64) -> (Col<c64>, Col<c64>) {
        let inv = c64::new(1.0, 0.0) / lambda;
        // On the columns' slices (the same sums as entry by entry).
        let part = |(a, b): &(Col<c64>, Col<c64>)| {
            let mut out = a.clone();
            if self.norm2.1 != 0.0 {
                for (o, bi) in contiguous_mut(out.as_mut()).iter_mut().zip(contiguous(b.as_ref())) {
                    *o = *o + bi * inv;
                }
            }
            out
        };
        (part(&self.fyd), part(&self.fy))
    }

    /// The true relative residual `‖(λ F_yd + F_y) x‖ / ((|λ| ‖F_yd‖ + ‖F_y‖) ‖x‖)` at λ.
    fn residual(&self, lambda: c64) -> f64 {
        let inv = c64::new(1.0, 0.0) / lambda;
        let ((da, db), (ya, yb)) = (&self.fyd, &self.fy);
        let r2 = (0..da.nrows()).map(|i| (lambda * da[i] + db[i] + ya[i] + yb[i] * inv).norm_sqr()).sum::<f64>();
        let nx = (self.norm2.0 + self.norm2.1 * inv.norm_sqr()).sqrt();
        r2.sqrt() / ((lambda.norm() * self.norms.0 + self.norms.1) * nx)
    }
}

/// A pair's vectors of the DAE's pencil and their products: `F_yd v`, `F_y v`, `F_ydᵀ u`,
/// `F_yᵀ u`.
pub(super) struct PairVectors {
    pub v: Col<c64>,
    pub u: Col<c64>,
    pub fydv: Col<c64>,
    pub fyv: Col<c64>,
    pub ufyd: Col<c64>,
    pub ufy: Col<c64>,
}

impl PairVectors {
    /// Every vector mapped entrywise by `f` (a conjugation, or a phase: the matrices are real).
    pub fn map(&mut self, f: impl Fn(c64) -> c64) {
        for x in [&mut self.v, &mut self.u, &mut self.fydv, &mut self.fyv, &mut self.ufyd, &mut self.ufy] {
            for e in x.iter_mut() {
                *e = f(*e);
            }
        }
    }
}

/// The norms and scales the labels (eqs. 32–35) use: `‖F_yd‖_F`, `‖F_y‖_F`, the Direct
/// route's `μ = λ/σ` scale and the Λ route's dCoef.
pub(super) struct Scales {
    pub nyd: f64,
    pub ny: f64,
    pub mu_scale: f64,
    pub dcoef: f64,
    pub route: EigenRoute,
}

impl Scales {
    pub fn new(dae: &SparseLinearDae, s: &SparseEigenSettings) -> Self {
        let (nyd, ny) = (dae.fyd.norm_l2(), dae.fy.norm_l2());
        let dcoef = s.dcoef.unwrap_or(if nyd > 0.0 && ny > 0.0 && (nyd / ny).is_finite() { nyd / ny } else { 1.0 });
        let mu_scale = if nyd > 0.0 && ny > 0.0 { ny / nyd } else { 1.0 };
        Scales { nyd, ny, mu_scale, dcoef, route: s.route }
    }
}
