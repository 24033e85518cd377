//! Issue 30's acceptance for finding 3 on the beam family (tests/common/beam_family.rs: a
//! beam3 cantilever of N elements with a tip mass, every node dynamic, EJ = 1e3 N m²,
//! EA = GA = EJ · 1e3 … 1e7, 1 kg/m; round section: every bending eigenvalue double):
//! `romdyn eig` with its defaults finishes, and the sparse route's `--count 20` returns the
//! 20 lowest modes, each copy of a double one, certified by the argument-principle count,
//! all within 1e-8 of an independent solve (the mass–stiffness problem of the same beam,
//! `MassStiffness`: no Krylov space, no pencil). 128 elements (3090 equations) are measured
//! in benches/dense_beam_family.rs, not here (debug build time).

use crate::common;
use crate::sparse_count::units;

use common::beam_family::{cantilever, MassStiffness};
use common::cli::{romdyn, temp_dir, write_file};
use common::mbdyn::read;
use romdyn::dae::{linearize, linearize_sparse, Assembler, State};
use romdyn::eigen::krylov::{sparse_modes, ModeTarget, SparseEigenSettings};
use romdyn::eigen::ModeKind;

/// Relative agreement asked of every mode (issue 30's acceptance line), whatever EA/EJ.
/// Measured beyond the reference's 1e-13 (sparse `--count 20` / default `eig`): nothing up
/// to EA/EJ = 1e5; at 1e7 1.7e-10, 6.0e-10, 2.2e-11 on the sparse route at 16, 32, 64
/// elements and nothing on the dense one, since both routes take a dynamic mode's eigenvalue
/// as its two-sided Rayleigh quotient summed in twice the working precision
/// (`romdyn::linear::Compensated`). Before
/// that the lowest bending pair at EA/EJ = 1e7 was off by up to 1.4e-7 (sparse, 64
/// elements) against the refined reference, and the double-precision reference itself by
/// 2.2e-7: the sums of `uᵀ K v` cancel axial and shear stiffness of EA = 1e10 N down to
/// the bending value, losing ε EA/EJ per term.
const AGREE: f64 = 1e-8;

/// The family's members of `elements` elements, EA/EJ = 1e3, 1e5, 1e7.
fn members(elements: usize) {
    let dir = temp_dir(&format!("beam-family-{elements}"));
    for ea in [1e6, 1e8, 1e10] {
        let ej = 1e3;
        let text = cantilever(elements, ea, ej);
        let m = read(&text);
        let asm = Assembler::new(&m.model);
        let st = State::initial(&m.model, &asm.dofs);
        let reference = MassStiffness::of(&linearize(&m.model, &st, &[], &[], None).unwrap(), &asm.dofs.node_first, elements);
        // Source: the mass–stiffness problem (MassStiffness, its lowest 20 refined to the
        // stored matrices' exact eigenvalues), less its own error bound; the largest relative
        // difference of each route, checked at the end.
        let off = |got: f64, k: usize| {
            let w = reference.omega[k];
            ((got - w).abs() - reference.error(w)).max(0.0) / w
        };
        // The sparse route's 20 lowest (the library call behind `eig --solver sparse
        // --count 20`): certified, each copy of a double eigenvalue with its own vector.
        let dae = linearize_sparse(&m.model, &st, &[], &[]).unwrap();
        let found = sparse_modes(&dae, ModeTarget::Lowest(20), &SparseEigenSettings::default()).unwrap();
        assert!(found.certified, "{elements} elements, EA/EJ = {:e}: {:?}", ea / ej, found.note);
        let upper: Vec<_> = found.modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 0.0).collect();
        // The 20 lowest, and the second copy of a double eigenvalue that is the 20th (the
        // count's circle is drawn in a gap of the spectrum, never between two copies).
        let last = reference.omega[19];
        let expected = reference.omega.iter().filter(|&&w| w <= last * (1.0 + 1e-6)).count();
        assert_eq!(upper.len(), expected, "{elements} elements, EA/EJ = {:e}", ea / ej);
        let sparse = upper.iter().enumerate().map(|(k, mode)| off(mode.lambda.norm(), k)).fold(0.0, f64::max);
        // The error column is honest: it covers each difference to the reference.
        for (k, mode) in upper.iter().enumerate() {
            let w = reference.omega[k];
            assert!((mode.lambda.norm() - w).abs() <= mode.error + reference.error(w), "{elements} elements, EA/EJ = {:e}, mode {}: {} vs {w} rad/s, error estimate {:e}", ea / ej, k + 1, mode.lambda, mode.error);
        }
        // A double eigenvalue's two copies have independent right vectors (not one found
        // twice): |v₁ᴴ v₂| / (‖v₁‖ ‖v₂‖) well below 1.
        for pair in upper.windows(2).filter(|p| (p[0].lambda - p[1].lambda).norm() <= 1e-8 * p[0].lambda.norm()) {
            let (a, b) = (pair[0].right.as_ref().unwrap(), pair[1].right.as_ref().unwrap());
            let cos = a.iter().zip(b.iter()).fold(romdyn::c64::new(0.0, 0.0), |s, (x, y)| s + x.conj() * y).norm() / (a.norm_l2() * b.norm_l2());
            assert!(cos < 0.9, "{elements} elements, EA/EJ = {:e}: the copies of {} have parallel vectors ({cos})", ea / ej, pair[0].lambda);
        }
        // `romdyn eig` with its defaults (the dense route below 400 equations, the sparse
        // route's 10 lowest above) finishes and lists the reference's lowest modes.
        let file = write_file(&dir, &format!("beam_{elements}_{ea:e}.mbd"), &text);
        let (ok, json, err) = romdyn(&["eig", &file, "--json"]);
        assert!(ok, "{elements} elements, EA/EJ = {:e}: {err}", ea / ej);
        let (listed, _) = units(&json);
        assert!(listed.len() >= 10, "{elements} elements, EA/EJ = {:e}: {} modes", ea / ej, listed.len());
        let default = listed.iter().take(20).enumerate().map(|(k, (re, im, _))| off(re.hypot(*im), k)).fold(0.0, f64::max);
        eprintln!("{elements} elements, EA/EJ = {:e}: largest relative difference to the mass–stiffness problem: sparse --count 20 {sparse:.1e}, default eig {default:.1e}", ea / ej);
        assert!(sparse <= AGREE && default <= AGREE, "{elements} elements, EA/EJ = {:e}: sparse {sparse:.1e}, default {default:.1e}", ea / ej);
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn beam_family_of_8_elements() {
    members(8);
}

#[test]
fn beam_family_of_16_elements() {
    members(16);
}

#[test]
fn beam_family_of_32_elements() {
    members(32);
}

#[test]
fn beam_family_of_64_elements() {
    members(64);
}


/// Issue 30 point 3: the family's beam with no torsional inertia (`J_x = 0` on every node,
/// the tip mass's too): every torsion direction is massless, each an infinite eigenvalue of
/// index 2 (`L_x = 0` from the momentum definition, its derivative in the moment balance).
/// Source: the mass–stiffness problem with those directions massless (`M^(1/2) = 0` there,
/// exactly `K` condensed on them), refined ([`MassStiffness::with_inertia`]).
/// - The sparse route deflates them like the constrained variables (shift-invert maps ∞ to
///   θ = 0): its `--count 20` agrees to 1e-8 (measured ≤ 3e-16 at EA/EJ = 1e3 and 1e7).
/// - The dense route's deflation (`eigen::dense::deflate`, step 3) takes index-1 infinite
///   parts only, so it falls back to QZ on the whole pencil (`ModalAnalysis::deflated_size`
///   is `None`, 192 of 210 with `J_x ≠ 0`), whose own eigenvalues are 1.2e-9 (EA/EJ = 1e3)
///   and 1.5e-6 (1e7) off. Its compensated two-sided quotients (as on the deflated route)
///   are not: measured 2.7e-16 and 2.2e-11, asserted 1e-8. The error column (QZ's estimate,
///   at least the quotient's distance to QZ's value) covers the difference. The fallback is
///   asserted, so that a deflation of index-2 parts shows here.
#[test]
fn beam_without_torsional_inertia() {
    use common::beam_family::{beam_inertia, cantilever_with_inertia};
    use romdyn::eigen::{EigenRoute, ModalAnalysis};
    let elements = 8;
    let inertia: Vec<[f64; 4]> = beam_inertia(elements).into_iter().map(|[m, _, jy, jz]| [m, 0.0, jy, jz]).collect();
    for ea in [1e6, 1e10] {
        let m = read(&cantilever_with_inertia(elements, ea, 1e3, &inertia));
        let asm = Assembler::new(&m.model);
        let st = State::initial(&m.model, &asm.dofs);
        let lin = linearize(&m.model, &st, &[], &[], None).unwrap();
        let reference = MassStiffness::with_inertia(&lin, &asm.dofs.node_first, elements, &inertia);
        let found = sparse_modes(&linearize_sparse(&m.model, &st, &[], &[]).unwrap(), ModeTarget::Lowest(20), &SparseEigenSettings::default()).unwrap();
        assert!(found.certified, "EA = {ea:e}: {:?}", found.note);
        let sparse: Vec<f64> = found.modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 0.0).map(|m| m.lambda.norm()).collect();
        assert!(sparse.len() >= 20, "EA = {ea:e}: {} modes", sparse.len());
        let off = sparse.iter().take(20).zip(&reference.omega).map(|(s, w)| ((s - w).abs() - reference.error(*w)).max(0.0) / w).fold(0.0, f64::max);
        assert_eq!(ModalAnalysis::deflated_size(&lin), None, "EA = {ea:e}: the dense deflation now takes the massless directions: assert its accuracy here");
        let dense = ModalAnalysis::of_dae(&lin, EigenRoute::Lambda, None).unwrap();
        let upper: Vec<_> = dense.modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 0.0).take(20).collect();
        let dense_off = upper.iter().zip(&reference.omega).map(|(m, w)| (m.lambda.norm() - w).abs() / w).fold(0.0, f64::max);
        eprintln!("no torsional inertia, EA/EJ = {:e}: largest relative difference to the mass–stiffness problem: sparse --count 20 {off:.1e}, dense {dense_off:.1e}", ea / 1e3);
        assert!(off <= AGREE && dense_off <= AGREE, "EA = {ea:e}: sparse {off:.1e}, dense {dense_off:.1e}");
        for (k, (mode, w)) in upper.iter().zip(&reference.omega).enumerate() {
            assert!((mode.lambda.norm() - w).abs() <= mode.error + reference.error(*w), "EA = {ea:e}, mode {}: {} vs {w} rad/s, error estimate {:e}", k + 1, mode.lambda, mode.error);
        }
    }
}

/// Issue 30 point 4: the family's beam without its tip mass converges to the continuum's
/// closed forms as the mesh is refined (8 → 16 → 32 → 64 elements), at the order of beam3's
/// discretisation. EA = GA = 1e10 N (EA/EJ = 1e7: shear deformation moves the first bending
/// frequency by ~EJ/(GA L²) = 1e-7, below the discretisation error, so Euler–Bernoulli is the
/// continuum), EJ = GJ = 1e3 N m², ρA = 1 kg/m, torsional inertia 1e-3 kg m, L = 1 m.
/// Closed forms: first bending `ω = (β₁L)² √(EJ/(ρA L⁴))`, `β₁L = 1.87510406871196` the first
/// root of the clamped–free frequency equation `1 + cos βL cosh βL = 0`; first torsion, the
/// clamped–free shaft's quarter wave `ω = (π/2L) √(GJ/ρJ_p)`. beam3 is a three-node finite-volume element with the masses lumped
/// at the nodes (each node's segment, its rotary inertia `ρA l³/12` an O(h²) term): second
/// order, the error falling by 4 per halving. Measured (sparse `--count 20`): bending
/// −2.58e-3, −6.49e-4, −1.63e-4, −4.10e-5 relative, torsion −2.40e-4, −6.01e-5, −1.50e-5,
/// −3.75e-6; observed orders 1.988, 1.993, 1.992 (bending) and 2.001, 2.000, 2.000
/// (torsion), asserted within 0.05 of 2.
#[test]
fn beam_family_converges_to_the_continuum_at_second_order() {
    use common::beam_family::{beam_inertia, cantilever_with_inertia};
    let (ej, gj, rho_a, rho_jp) = (1e3_f64, 1e3_f64, 1.0_f64, 1e-3_f64);
    let bending = 1.875_104_068_711_96_f64.powi(2) * (ej / rho_a).sqrt();
    let torsion = std::f64::consts::FRAC_PI_2 * (gj / rho_jp).sqrt();
    let mut errors = Vec::new();
    for elements in [8, 16, 32, 64] {
        // The family's lumped inertia without the tip mass.
        let mut inertia = beam_inertia(elements);
        let n = inertia.len();
        let dl = 1.0 / (n - 1) as f64;
        inertia[n - 1] = [dl / 2.0, 1e-3 * dl / 2.0, (dl / 2.0).powi(3) / 12.0, (dl / 2.0).powi(3) / 12.0];
        let m = read(&cantilever_with_inertia(elements, 1e10, ej, &inertia));
        let asm = Assembler::new(&m.model);
        let st = State::initial(&m.model, &asm.dofs);
        let found = sparse_modes(&linearize_sparse(&m.model, &st, &[], &[]).unwrap(), ModeTarget::Lowest(20), &SparseEigenSettings::default()).unwrap();
        assert!(found.certified, "{elements} elements: {:?}", found.note);
        let w: Vec<f64> = found.modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 0.0).map(|m| m.lambda.norm()).collect();
        // The first bending pair (y and z) is the lowest; torsion is the simple eigenvalue
        // (no copy within 1e-6) nearest its closed form.
        let simple = |k: usize| w.iter().enumerate().all(|(j, x)| j == k || (x - w[k]).abs() > 1e-6 * w[k]);
        let t = (0..w.len()).filter(|&k| simple(k)).min_by(|&a, &b| (w[a] - torsion).abs().total_cmp(&(w[b] - torsion).abs())).unwrap();
        errors.push(((w[0] - bending) / bending, (w[t] - torsion) / torsion));
        eprintln!("{elements} elements: first bending {} rad/s ({:+.2e}), first torsion {} rad/s ({:+.2e})", w[0], errors.last().unwrap().0, w[t], errors.last().unwrap().1);
    }
    for pair in errors.windows(2) {
        let orders = ((pair[0].0 / pair[1].0).abs().log2(), (pair[0].1 / pair[1].1).abs().log2());
        eprintln!("observed orders: bending {:.3}, torsion {:.3}", orders.0, orders.1);
        assert!((orders.0 - 2.0).abs() <= 0.05 && (orders.1 - 2.0).abs() <= 0.05, "{errors:?}");
    }
    // And the finest mesh is close: 64 elements within 5e-5 (bending) and 5e-6 (torsion).
    let (b, t) = errors[3];
    assert!(b.abs() <= 5e-5 && t.abs() <= 5e-6, "{errors:?}");
}
