//! One shift: the eigenvalues nearest σ with right and left vectors, from two independent
//! Krylov–Schur runs on the same factorization (`T` for the right vectors, its transposed
//! operator for the left ones, eq. 11), each pair checked by its true residual on the DAE's
//! own pencil.

use faer::{c64, Col};

use super::iteration::{krylov_schur, RitzPair, Run, Settings};
use super::operator::ShiftInvert;
use super::pencil::Pencil;
use super::{KrylovError, SparseEigenSettings};
use crate::linear::SparseLinearDae;

/// An eigenpair of the DAE's pencil `λ F_yd + F_y` (the DAE's own constraint form), its
/// representative with `Im λ ≥ 0`.
#[derive(Clone, Debug)]
pub(super) struct Eigenpair {
    pub lambda: c64,
    pub right: Col<c64>,
    pub left: Col<c64>,
    /// True relative residuals `‖(λ F_yd + F_y) v‖ / ((|λ| ‖F_yd‖ + ‖F_y‖) ‖v‖)`, and of `uᵀ`.
    pub residual_right: f64,
    pub residual_left: f64,
}

/// What one shift found: accepted pairs, the radius of the disc `|λ − σ| ≤ radius` in which
/// both runs found the same eigenvalues (`f64::INFINITY` when the finite spectrum was
/// exhausted), and whether they agreed.
pub(super) struct WindowResult {
    pub shift: c64,
    pub radius: f64,
    pub agreed: bool,
    pub pairs: Vec<Eigenpair>,
    /// Pairs that converged in the operator but failed the true-residual test.
    pub rejected: usize,
}

/// `‖(λ F_yd + F_y) x‖ / ((|λ| ‖F_yd‖ + ‖F_y‖) ‖x‖)`, or with the transposes.
pub(super) fn true_residual(dae: &SparseLinearDae, lambda: c64, x: &Col<c64>, transpose: bool) -> f64 {
    let (a, b) = if transpose { (dae.fyd.mul_t_complex(x), dae.fy.mul_t_complex(x)) } else { (dae.fyd.mul_complex(x), dae.fy.mul_complex(x)) };
    let r = Col::from_fn(x.nrows(), |i| lambda * a[i] + b[i]).norm_l2();
    r / ((lambda.norm() * dae.fyd.norm_l2() + dae.fy.norm_l2()) * x.norm_l2())
}

/// θ at or below this fraction of the largest are the infinite eigenvalues (θ = 0).
const NULL_THETA: f64 = 1e-8;

/// The pairs of one run with their eigenvalues λ, purified (`x ← T x / θ` removes the
/// components along the infinite eigenvalues); `exhausted` when the run reached θ ≈ 0.
fn lambdas(op: &ShiftInvert, run: &Run, transpose: bool) -> (Vec<(c64, Col<c64>)>, bool) {
    let top = run.pairs.first().map_or(0.0, |p| p.theta.norm());
    let mut out = Vec::new();
    let mut exhausted = false;
    for RitzPair { theta, x } in &run.pairs {
        if theta.norm() <= NULL_THETA * top {
            exhausted = true;
            break;
        }
        let y = op.apply(x, transpose);
        let scale = c64::new(1.0, 0.0) / (*theta * y.norm_l2() / theta.norm());
        out.push((op.lambda(*theta), Col::from_fn(y.nrows(), |i| y[i] * scale)));
    }
    // All wanted pairs converged and nothing but θ ≈ 0 (or nothing) is left.
    exhausted |= run.complete && run.next.is_none_or(|t| t <= NULL_THETA * top);
    (out, exhausted)
}

/// Runs both Krylov–Schur iterations at `sigma` for `wanted` eigenvalues.
pub(super) fn window(dae: &SparseLinearDae, pencil: &Pencil, sigma: c64, wanted: usize, s: &SparseEigenSettings, progress: &dyn Fn(&str)) -> Result<WindowResult, KrylovError> {
    let n = pencil.dim();
    let op = ShiftInvert::new(pencil, sigma)?;
    // Basis of three times the wanted count: measured on the 20 lowest modes of the hanging
    // chain (callgrind, 24 wanted), 2x+1 took 11 restart cycles per run, 3x+1 four; at
    // N = 1000 (17012 equations) 3x+1 ran in 0.65 of the time of 2x+1 (4x+1: 0.71, its
    // Schur forms of the 97-wide Rayleigh quotient cost more than the saved restarts).
    let basis = (3 * wanted + 1).max(wanted + 20).min(n);
    // A real basis holds both of each complex pair: twice the wanted count, and a basis of
    // twice that plus one as ARPACK's default (ncv = 2 nev + 1).
    let real_basis = (4 * wanted + 1).max(2 * wanted + 20).min(n);
    let real_settings = |seed| Settings { wanted, basis: real_basis, tolerance: s.krylov_tolerance, max_restarts: s.max_restarts, seed };
    let settings = |seed| Settings { wanted, basis, tolerance: s.krylov_tolerance, max_restarts: s.max_restarts, seed };
    let report = |side: &'static str| move |k: usize| progress(&format!("shift {sigma}: {side} {k}/{wanted} converged"));
    // The two runs are independent (one factorization, read only): the adjoint run goes
    // to a second thread while this one does the right run and reports progress. Its own
    // progress is not reported (the caller's callback need not be thread-safe); both take
    // about as long. A real shift of the real pencil runs in real arithmetic (the
    // eigenvalues below the real axis are the conjugates of those above).
    let run = |transpose: bool, seed: u64, progress: &dyn Fn(usize)| -> Result<Run, KrylovError> {
        if sigma.im == 0.0 {
            let apply = |x: &Col<f64>| op.apply_real(x, transpose).unwrap_or_else(|| unreachable!("a real shift has a real factorization"));
            krylov_schur::<f64>(n, &apply, &real_settings(seed), progress)
        } else {
            krylov_schur::<c64>(n, &|x| op.apply(x, transpose), &settings(seed), progress)
        }
    };
    let (right_run, left_run) = std::thread::scope(|scope| {
        let left = scope.spawn(|| run(true, 2, &|_| {}));
        let right = run(false, 1, &report("right"));
        let left = left.join().unwrap_or_else(|_| Err(KrylovError::Breakdown("the adjoint Krylov run panicked".into())));
        (right, left)
    });
    let (right_run, left_run) = (right_run?, left_run?);
    progress(&format!(
        "shift {sigma}: {} + {} operator applications, {} + {} restarts (right + adjoint run)",
        right_run.applications, left_run.applications, right_run.restarts, left_run.restarts
    ));
    let (right, right_all) = lambdas(&op, &right_run, false);
    let (left, left_all) = lambdas(&op, &left_run, true);
    // Radius of the disc each run covers: the farthest converged eigenvalue (everything
    // when the run exhausted the finite spectrum).
    let reach = |l: &[(c64, Col<c64>)], all: bool| {
        if all {
            f64::INFINITY
        } else {
            l.iter().map(|(x, _)| (x - sigma).norm()).fold(0.0, f64::max)
        }
    };
    let radius = reach(&right, right_all).min(reach(&left, left_all));
    let inside = |l: c64| (l - sigma).norm() <= radius * (1.0 + 1e-9);
    // Match each right eigenvalue with the nearest unused left one.
    let mut used = vec![false; left.len()];
    let mut pairs = Vec::new();
    let mut rejected = 0;
    let mut agreed = true;
    for (lr, v29) in &right {
        let best = left.iter().enumerate().filter(|(i, _)| !used[*i]).min_by(|a, b| (a.1 .0 - lr).norm().total_cmp(&(b.1 .0 - lr).norm()));
        let Some((i, (ll, u29))) = best else {
            agreed &= !inside(*lr);
            continue;
        };
        if (ll - lr).norm() > 1e-6 * (lr - sigma).norm().max(lr.norm() * 1e-3) {
            agreed &= !inside(*lr);
            continue;
        }
        used[i] = true;
        // Two-sided Rayleigh quotient on eq. 29: λ = −(uᵀ K v)/(uᵀ E v).
        let (kv, ev) = (pencil.k.mul_complex(v29), pencil.e.mul_complex(v29));
        let (ukv, uev) = u29.iter().zip(kv.iter().zip(ev.iter())).fold((c64::new(0.0, 0.0), c64::new(0.0, 0.0)), |(a, b), (u, (k, e))| (a + u * k, b + u * e));
        let rq = -ukv / uev;
        let candidates = [*lr, rq];
        let (lambda, v, u, rr, rl) = candidates
            .iter()
            .filter(|l| l.re.is_finite() && l.im.is_finite())
            .map(|&l| {
                let (v, u) = (pencil.to_dae(v29, l), pencil.to_dae(u29, l));
                let (rr, rl) = (true_residual(dae, l, &v, false), true_residual(dae, l, &u, true));
                (l, v, u, rr, rl)
            })
            .min_by(|a, b| a.3.max(a.4).total_cmp(&b.3.max(b.4)))
            .unwrap_or_else(|| unreachable!("the Ritz value is finite"));
        if !(rr <= s.tolerance && rl <= s.tolerance) {
            rejected += 1;
            agreed &= !inside(lambda);
            continue;
        }
        let (lambda, right, left) = if lambda.im < 0.0 { (lambda.conj(), conj(&v), conj(&u)) } else { (lambda, v, u) };
        pairs.push(Eigenpair { lambda, right, left, residual_right: rr, residual_left: rl });
    }
    // A left eigenvalue inside the disc without a right partner is a disagreement.
    for (i, (ll, _)) in left.iter().enumerate() {
        if !used[i] && inside(*ll) {
            agreed = false;
        }
    }
    Ok(WindowResult { shift: sigma, radius, agreed, pairs, rejected })
}

fn conj(v: &Col<c64>) -> Col<c64> {
    Col::from_fn(v.nrows(), |i| v[i].conj())
}
