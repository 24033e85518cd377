//! Shift-invert Krylov–Schur eigenanalysis of sparse linear DAEs (issue 13 point 2) against
//! the dense route (`ModalAnalysis::of_dae`, itself validated against QZ on the whole pencil
//! in tests/eigen/eigen_deflation.rs and against the paper's cases): same eigenvalues to 1e-9
//! relative, same labels, no spurious modes in MBDyn's constraint form (eq. 30), bands by one
//! complex shift or several shifts, none missed.

use crate::common;

use common::beams::{simply_supported, TABLE3};
use common::models::{hanging_chain, pendulum};
use faer::c64;
use romdyn::dae::{linearize, linearize_sparse, Assembler, State};
use romdyn::eigen::krylov::{sparse_modes, ModeTarget, SparseEigenSettings, SparseModalAnalysis};
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::linear::{LinearDae, SparseLinearDae};
use romdyn::model::ConstraintForm;
use romdyn::model::Model;
use romdyn::solve::{static_solution, NewtonSettings};

fn at_rest(model: &Model) -> State {
    let asm = Assembler::new(model);
    let mut st = State::initial(model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    st
}

/// The dense and the sparse linear model of the same state.
fn models(model: &Model) -> (LinearDae, SparseLinearDae) {
    let st = at_rest(model);
    (linearize(model, &st, &[], &[], None).unwrap(), linearize_sparse(model, &st, &[], &[]).unwrap())
}

/// Dynamic eigenvalues of the dense route with Im λ ≥ 0 (one per unit), by increasing |λ|.
fn dense_units(modal: &ModalAnalysis) -> Vec<c64> {
    dense_units_with_error(modal).into_iter().map(|(l, _)| l).collect()
}

/// The same with each eigenvalue's estimated error (eqs. 32–35).
fn dense_units_with_error(modal: &ModalAnalysis) -> Vec<(c64, f64)> {
    modal.of_kind(ModeKind::Dynamic).map(|i| (modal.modes[i].lambda, modal.modes[i].error)).filter(|l| l.0.im >= 0.0).collect()
}

/// Every sparse mode is dynamic (as the dense route labels it) and equals the dense
/// eigenvalue nearest to it; returns the dense units it matched. Issue 13's acceptance is
/// 1e-9 relative for the `asked` lowest units; the dense route's own error (its estimate,
/// eqs. 32–35) can exceed that on the real parts of undamped modes (1712-equation chain:
/// Re λ = 8.0e-7 on 25.1j rad/s, where the sparse route gives 4e-14 and the exact value is 0),
/// so the imaginary parts are compared to 1e-9 and the real parts to the larger of 1e-9 |λ|
/// and the dense estimate. Modes beyond the asked ones that a window also returned (far from
/// the shift, where a residual of 1e-10 bounds λ less tightly) must agree within the sum of
/// both routes' error estimates.
fn assert_matches_dense(what: &str, dense: &[(c64, f64)], sparse: &SparseModalAnalysis, asked: usize) -> Vec<c64> {
    let mut matched = Vec::new();
    let units: Vec<_> = sparse.modal.modes.iter().filter(|m| m.lambda.im >= 0.0).collect();
    for (k, m) in units.iter().enumerate() {
        let (l, kind) = (m.lambda, m.kind);
        assert_eq!(kind, ModeKind::Dynamic, "{what}: λ = {l} labelled {kind:?}");
        let (d, e) = dense.iter().copied().min_by(|a, b| (a.0 - l).norm().total_cmp(&(b.0 - l).norm())).unwrap();
        if k < asked {
            assert!((d.im - l.im).abs() <= 1e-9 * d.norm(), "{what}: sparse {l} vs dense {d}");
            assert!((d.re - l.re).abs() <= (1e-9 * d.norm()).max(e), "{what}: sparse {l} vs dense {d} (error estimate {e:e})");
        } else {
            assert!((d - l).norm() <= 1e-9 * d.norm() + e + m.error, "{what}: sparse {l} (error {:e}) vs dense {d} (error {e:e})", m.error);
        }
        matched.push(d);
    }
    // Residuals of every returned pair at the stated tolerance.
    assert!(sparse.max_residual <= 1e-10, "{what}: residual {:e}", sparse.max_residual);
    for m in &sparse.modal.modes {
        assert!(m.right.is_some() && m.left.is_some(), "{what}: vectors");
    }
    matched
}

#[test]
fn shift_at_zero_returns_only_the_pendulums_swing_in_the_form_of_eq_30() {
    // Paper Table 2: 29 equations, 2 dynamic eigenvalues ±3.1305j, 22 zero ones (eq. 30).
    let model = pendulum(0.0, false, ConstraintForm::Scaled);
    let (dense, sparse) = models(&model);
    let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
    assert_eq!(modal.count(ModeKind::Zero), 22);
    let s = sparse_modes(&sparse, ModeTarget::Lowest(1), &SparseEigenSettings::default()).unwrap();
    assert!(s.certified, "{:?}", s.note);
    // Exactly the swing pair: no zero eigenvalue of the constrained variables comes back.
    assert_eq!(s.modal.modes.len(), 2, "{:?}", s.modal.modes.iter().map(|m| m.lambda).collect::<Vec<_>>());
    let matched = assert_matches_dense("pendulum", &dense_units_with_error(&modal), &s, 1);
    // Paper §7.2: ω = sqrt(g/L (1 + J/(m L²))^-1) = 3.1305 rad/s.
    assert!((matched[0].im - 3.1305).abs() < 1e-4);
}

#[test]
fn shift_at_zero_on_chain_and_beam_returns_only_dynamic_modes() {
    for form in [ConstraintForm::Scaled, ConstraintForm::Plain] {
        // N = 6 chain: 2N = 12 dynamic eigenvalues (6 swing pairs), all asked.
        let (dense, sparse) = models(&hanging_chain(6, form));
        let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
        let units = dense_units(&modal);
        assert_eq!(units.len(), 6);
        let s = sparse_modes(&sparse, ModeTarget::Lowest(6), &SparseEigenSettings::default()).unwrap();
        assert!(s.certified, "{:?}", s.note);
        let matched = assert_matches_dense(&format!("chain {}", form.name()), &dense_units_with_error(&modal), &s, 6);
        assert_eq!(matched.len(), 6, "every swing mode once");
    }
    // 4-element simply supported beam (paper §6.2, eq. 30): the 8 lowest modes.
    let (dense, sparse) = models(&simply_supported(&TABLE3, 4, 0.0, 0.0));
    let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
    let units = dense_units(&modal);
    let s = sparse_modes(&sparse, ModeTarget::Lowest(8), &SparseEigenSettings::default()).unwrap();
    assert!(s.certified, "{:?}", s.note);
    let matched = assert_matches_dense("beam", &dense_units_with_error(&modal), &s, 8);
    assert!(matched.len() >= 8);
    for (k, d) in units.iter().take(8).enumerate() {
        assert!(matched.iter().any(|m| m == d), "beam: dense mode {k} ({d}) not found");
    }
}

/// Every mode of the 10-link chain (10 swing pairs): once the finite spectrum is exhausted
/// the two Krylov runs also converge Ritz values of the infinite eigenvalues' defective θ = 0
/// cluster (|λ| ~ 1e6 rad/s), different in each run. Those lie far beyond the 10 modes: the
/// disc short of them holds the same 10 eigenvalues in both runs, so the 10 are certified
/// there, and equal the dense route's (source: `ModalAnalysis::of_dae`, 1e-9 relative).
#[test]
fn every_mode_of_the_10_link_chain_is_certified_below_the_infinite_cluster() {
    let (dense, sparse) = models(&hanging_chain(10, ConstraintForm::Scaled));
    let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
    assert_eq!(dense_units(&modal).len(), 10);
    let s = sparse_modes(&sparse, ModeTarget::Lowest(10), &SparseEigenSettings::default()).unwrap();
    assert!(s.certified, "{:?}", s.note);
    let matched = assert_matches_dense("10-link chain", &dense_units_with_error(&modal), &s, 10);
    assert_eq!(matched.len(), 10, "every swing mode once");
    let top = matched.iter().map(|l| l.norm()).fold(0.0, f64::max);
    assert!(s.windows.iter().all(|w| w.radius >= top), "{:?}", s.windows);
}

/// A certified result returns only modes inside the discs its windows certify (issue 13:
/// "the count of modes in the band is certified ... or the result says it is not"): when the
/// two Krylov runs disagree, or a pair fails its residual test, beyond the asked modes, the
/// window shrinks to the disc short of it and the accepted pairs beyond that disc are not
/// returned (they were, before). Looser Krylov tolerances make the farther pairs fail their
/// true-residual test (1e-10) and so exercise the shrunk disc; each result is checked
/// against the dense route's eigenvalues (1e-9 relative, `assert_matches_dense`).
#[test]
fn a_certified_result_returns_only_modes_inside_its_windows() {
    for (links, count, krylov_tolerance) in [(10, 10, 1e-12), (30, 6, 1e-9), (30, 6, 1e-8), (30, 6, 1e-7)] {
        let (dense, sparse) = models(&hanging_chain(links, ConstraintForm::Scaled));
        let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
        let settings = SparseEigenSettings { krylov_tolerance, ..Default::default() };
        let s = sparse_modes(&sparse, ModeTarget::Lowest(count), &settings).unwrap();
        let what = format!("{links}-link chain, Krylov tolerance {krylov_tolerance:e}");
        if !s.certified {
            assert!(s.note.is_some(), "{what}: an uncertified result says why");
            continue;
        }
        for m in s.modal.modes.iter().filter(|m| m.lambda.im >= 0.0) {
            let inside = s.windows.iter().any(|w| (m.lambda - w.shift).norm() <= w.radius * (1.0 + 1e-9));
            assert!(inside, "{what}: λ = {} outside every certified window {:?}", m.lambda, s.windows);
        }
        let matched = assert_matches_dense(&what, &dense_units_with_error(&modal), &s, count);
        assert!(matched.len() >= count, "{what}: {} of {count} modes", matched.len());
    }
}

#[test]
fn twenty_lowest_modes_of_the_1712_equation_chain_match_the_dense_route() {
    let (dense, sparse) = models(&hanging_chain(100, ConstraintForm::Scaled));
    assert_eq!(sparse.dim(), 1712);
    let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
    let units = dense_units(&modal);
    let s = sparse_modes(&sparse, ModeTarget::Lowest(20), &SparseEigenSettings::default()).unwrap();
    assert!(s.certified, "{:?}", s.note);
    let matched = assert_matches_dense("chain N = 100", &dense_units_with_error(&modal), &s, 20);
    for (k, d) in units.iter().take(20).enumerate() {
        assert!(matched.iter().any(|m| m == d), "chain: dense mode {k} ({d}) not found");
    }
    // The chain is undamped: Re λ = 0 exactly; the sparse route's real parts are rounding.
    for m in s.modal.modes.iter().filter(|m| m.lambda.im > 0.0) {
        assert!(m.lambda.re.abs() <= 1e-12 * m.lambda.norm(), "sparse {}", m.lambda);
    }
}

/// Dense units with |λ| strictly between the midpoints around units `first..=last` (0-based),
/// and that band in Hz.
fn band_around(units: &[c64], first: usize, last: usize) -> (f64, f64) {
    let tau = 2.0 * std::f64::consts::PI;
    let lo = if first == 0 { 0.5 * units[0].norm() } else { 0.5 * (units[first - 1].norm() + units[first].norm()) };
    let hi = 0.5 * (units[last].norm() + units[last + 1].norm());
    (lo / tau, hi / tau)
}

fn assert_band(what: &str, modal: &ModalAnalysis, s: &SparseModalAnalysis, first: usize, last: usize) {
    assert!(s.certified, "{what}: {:?}", s.note);
    let units = dense_units(modal);
    let matched = assert_matches_dense(what, &dense_units_with_error(modal), s, usize::MAX);
    // Exactly the band's modes, none missed, none extra.
    assert_eq!(matched.len(), last - first + 1, "{what}: {matched:?}");
    for d in &units[first..=last] {
        assert!(matched.contains(d), "{what}: {d} missed");
    }
}

#[test]
fn a_band_in_the_middle_of_the_beam_spectrum_takes_one_complex_shift() {
    let (dense, sparse) = models(&simply_supported(&TABLE3, 4, 0.0, 0.0));
    let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
    let units = dense_units(&modal);
    // 3rd to 5th modes of the spectrum.
    let (fmin, fmax) = band_around(&units, 2, 4);
    let s = sparse_modes(&sparse, ModeTarget::Band { fmin_hz: fmin, fmax_hz: fmax }, &SparseEigenSettings::default()).unwrap();
    assert_eq!(s.windows.len(), 1, "{:?}", s.windows);
    assert!(s.windows[0].shift.im > 0.0 && s.windows[0].shift.re == 0.0, "a complex shift");
    assert_band("beam modes 3-5", &modal, &s, 2, 4);
}

#[test]
fn a_wide_band_of_the_chain_takes_several_shifts_and_misses_none() {
    let (dense, sparse) = models(&hanging_chain(30, ConstraintForm::Scaled));
    let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
    let units = dense_units(&modal);
    let (fmin, fmax) = band_around(&units, 3, 24);
    // At most 10 eigenvalues per shift: the 22 modes need several windows.
    let settings = SparseEigenSettings { per_shift: 10, ..Default::default() };
    let s = sparse_modes(&sparse, ModeTarget::Band { fmin_hz: fmin, fmax_hz: fmax }, &settings).unwrap();
    assert!(s.windows.len() >= 3, "{:?}", s.windows);
    assert_band("chain N = 30 modes 4-25", &modal, &s, 3, 24);
}

/// Right vectors only (`SparseEigenSettings::left_vectors = false`, the work scipy's `eigs`
/// does): the right Krylov run alone gives the same 20 lowest modes of the 1712-equation
/// chain as the dense route (1e-9 relative, `assert_matches_dense`) and as the two-sided
/// run (the same right vectors: |v₁ᴴ v₂| = 1 to 1e-8 for unit vectors), each right vector's
/// true residual `‖(λ F_yd + F_y) v‖ / ((|λ| ‖F_yd‖ + ‖F_y‖) ‖v‖)` recomputed here below the
/// 1e-10 tolerance, no left vectors, and the result not certified, saying why (no adjoint
/// run checked the count).
#[test]
fn right_vectors_only_give_the_same_modes_without_certifying_the_count() {
    let (dense, sparse) = models(&hanging_chain(100, ConstraintForm::Scaled));
    let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
    let both = sparse_modes(&sparse, ModeTarget::Lowest(20), &SparseEigenSettings::default()).unwrap();
    let right = sparse_modes(&sparse, ModeTarget::Lowest(20), &SparseEigenSettings { left_vectors: false, ..Default::default() }).unwrap();
    assert!(!right.certified);
    assert!(right.note.as_deref().is_some_and(|n| n.contains("right vectors only")), "{:?}", right.note);
    assert!(right.windows.iter().all(|w| !w.agreed), "{:?}", right.windows);
    // The dense route's 20 lowest units, each found (imaginary parts to 1e-9 relative, the
    // real parts to the dense error estimate, as `assert_matches_dense`, which also asks for
    // left vectors), every returned mode dynamic.
    let units: Vec<_> = right.modal.modes.iter().filter(|m| m.lambda.im >= 0.0).collect();
    assert!(units.iter().all(|m| m.kind == ModeKind::Dynamic));
    for (d, e) in dense_units_with_error(&modal).into_iter().take(20) {
        let l = units.iter().map(|m| m.lambda).min_by(|a, b| (a - d).norm().total_cmp(&(b - d).norm())).unwrap();
        assert!((d.im - l.im).abs() <= 1e-9 * d.norm() && (d.re - l.re).abs() <= (1e-9 * d.norm()).max(e), "dense {d} vs sparse {l}");
    }
    assert!(right.max_residual <= 1e-10, "{:e}", right.max_residual);
    let (nyd, ny) = (sparse.fyd.norm_l2(), sparse.fy.norm_l2());
    for m in right.modal.modes.iter().take(40) {
        assert!(m.left.is_none());
        let v = m.right.as_ref().unwrap();
        let (a, b) = (sparse.fyd.mul_complex(v), sparse.fy.mul_complex(v));
        let r = faer::Col::from_fn(v.nrows(), |i| m.lambda * a[i] + b[i]).norm_l2() / ((m.lambda.norm() * nyd + ny) * v.norm_l2());
        assert!(r <= 1e-10, "λ = {}: residual {r:e}", m.lambda);
        let twin = both.modal.modes.iter().min_by(|x, y| (x.lambda - m.lambda).norm().total_cmp(&(y.lambda - m.lambda).norm())).unwrap();
        assert!((twin.lambda - m.lambda).norm() <= 1e-9 * m.lambda.norm(), "{} vs {}", twin.lambda, m.lambda);
        let w = twin.right.as_ref().unwrap();
        let overlap = (0..v.nrows()).fold(c64::new(0.0, 0.0), |s, i| s + w[i].conj() * v[i]).norm() / (v.norm_l2() * w.norm_l2());
        assert!((overlap - 1.0).abs() <= 1e-8, "λ = {}: overlap {overlap}", m.lambda);
    }
}

/// Sparse eigenanalyses run on every worker of the global rayon pool at once (what a
/// parameter sweep's points do on a large model) finish. The adjoint Krylov run must then
/// stay on the worker: on a thread of its own, its faer products wait for the pool's
/// workers, which all wait for it (measured: `romdyn::sweep`'s pendulum test hung in
/// faer's matmul this way after the dense eigenanalysis had been given such a thread).
/// A watchdog aborts the test binary after 300 s instead of hanging CI.
#[test]
fn sparse_eigenanalyses_on_every_rayon_worker_at_once_finish() {
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;
    let (_, sparse) = models(&hanging_chain(100, ConstraintForm::Scaled));
    let done = Arc::new(AtomicBool::new(false));
    let watch = done.clone();
    std::thread::spawn(move || {
        for _ in 0..300 {
            std::thread::sleep(std::time::Duration::from_secs(1));
            if watch.load(Ordering::SeqCst) {
                return;
            }
        }
        eprintln!("sparse eigenanalyses on the rayon workers did not finish in 300 s (deadlock)");
        std::process::abort();
    });
    let jobs = 2 * rayon::current_num_threads().max(2);
    let counts: Vec<usize> = (0..jobs).into_par_iter().map(|_| sparse_modes(&sparse, ModeTarget::Lowest(4), &SparseEigenSettings::default()).unwrap().modal.modes.len()).collect();
    done.store(true, Ordering::SeqCst);
    assert!(counts.iter().all(|&c| c == counts[0] && c >= 4), "{counts:?}");
}

/// The same with right vectors only on a model large enough (5112 equations, from
/// `PARALLEL_FROM` = 4096 on) for the right run to split its sweeps, Ritz vectors and
/// restarts over two threads of the pool (`rayon::in_place_scope` from a worker: the
/// waiting worker runs other work meanwhile): every point finishes, with the same modes.
#[test]
fn right_only_eigenanalyses_with_split_sweeps_on_every_rayon_worker_at_once_finish() {
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;
    let (_, sparse) = models(&hanging_chain(300, ConstraintForm::Scaled));
    assert!(sparse.dim() >= 4096);
    let done = Arc::new(AtomicBool::new(false));
    let watch = done.clone();
    std::thread::spawn(move || {
        for _ in 0..300 {
            std::thread::sleep(std::time::Duration::from_secs(1));
            if watch.load(Ordering::SeqCst) {
                return;
            }
        }
        eprintln!("right-only sparse eigenanalyses on the rayon workers did not finish in 300 s (deadlock)");
        std::process::abort();
    });
    let settings = SparseEigenSettings { left_vectors: false, ..Default::default() };
    let alone = sparse_modes(&sparse, ModeTarget::Lowest(4), &settings).unwrap();
    let jobs = 2 * rayon::current_num_threads().max(2);
    let results: Vec<Vec<c64>> = (0..jobs).into_par_iter().map(|_| sparse_modes(&sparse, ModeTarget::Lowest(4), &settings).unwrap().modal.modes.iter().map(|m| m.lambda).collect()).collect();
    done.store(true, Ordering::SeqCst);
    let expected: Vec<c64> = alone.modal.modes.iter().map(|m| m.lambda).collect();
    assert!(expected.len() >= 8, "{expected:?}");
    assert!(results.iter().all(|r| *r == expected), "the same modes on every worker as alone");
}
