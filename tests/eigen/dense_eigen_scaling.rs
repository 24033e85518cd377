//! Issue 30, findings 3 (dense route) and 4: the dense eigenanalysis with its default dCoef
//! is accurate on flexible beams whatever EA/EJ, gives the same physical eigenvalues and labels
//! in any units, and never shows a mode of an extremely scaled model as a wrong "dynamic" one.

use crate::common;

use common::beam_family::{cantilever, MassStiffness};

use common::mbdyn::read;
use romdyn::c64;
use romdyn::dae::{linearize, Assembler, State};
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};

/// The default dense eigenanalysis of a model's initial configuration (the study's dense
/// path: deflation, QZ, labels; dCoef chosen by the eigenanalysis itself).
/// Also returns the linear DAE and each node's first unknown.
fn default_modes(text: &str) -> (ModalAnalysis, romdyn::linear::LinearDae, Vec<usize>) {
    let m = read(text);
    let asm = Assembler::new(&m.model);
    let st = State::initial(&m.model, &asm.dofs);
    let dae = linearize(&m.model, &st, &[], &[], None).unwrap();
    let modal = ModalAnalysis::of_dae(&dae, EigenRoute::Lambda, None).unwrap();
    (modal, dae, asm.dofs.node_first.clone())
}

/// Moduli of the lowest `count` dynamic modes (one per complex pair).
fn lowest(modal: &ModalAnalysis, count: usize) -> Vec<f64> {
    modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 0.0).map(|m| m.lambda.norm()).take(count).collect()
}

#[test]
fn beam_family_lowest_modes_match_the_mass_stiffness_problem() {
    // Reference: the undamped problem K q = ω² M q of the same cantilever at rest, with M the
    // lumped masses and inertias written into the file (diagonal, built here by hand) and K
    // the equilibrium rows' stiffness F_y[equilibrium, positions] of the free nodes (the
    // clamped node 1 removed), solved as a standard eigenproblem of M^(-1/2) K M^(-1/2):
    // no QZ, no deflation, no Λ form, no labelling. EA/EJ from 1e3 to
    // 1e7. The 20 lowest modes (bending pairs in y and z, torsion, axial) to 1e-8 relative.
    let elements = 6;
    for ea in [1e6, 1e8, 1e10] {
        let ej = 1e3;
        let (modal, dae, node_first) = default_modes(&cantilever(elements, ea, ej));
        let reference = MassStiffness::of(&dae, &node_first, elements);
        let (omega, reference_error) = (&reference.omega, |w: f64| reference.error(w));
        let got = lowest(&modal, 20);
        assert_eq!(got.len(), 20, "EA = {ea:e}");
        for (i, (g, w)) in got.iter().zip(omega).enumerate() {
            let rel = (g - w).abs() / w;
            assert!(rel < 1e-8, "EA = {ea:e}, mode {}: {g} vs {w} rad/s ({rel:.1e})", i + 1);
        }
        // The error column is honest: it covers the difference to the reference, less the
        // reference's own rounding (MassStiffness::error).
        let dynamic: Vec<_> = modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 0.0).take(20).collect();
        for (m, w) in dynamic.iter().zip(omega) {
            let off = (m.lambda - c64::new(0.0, *w)).norm();
            assert!(off <= m.error + reference_error(*w), "EA = {ea:e}: {} vs {w}: error {:e}, reference {:e}", m.lambda, m.error, reference_error(*w));
        }
    }
}

/// A deterministic xorshift generator for the property test (no dependency).
struct Rng(u64);
impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Log-uniform in [lo, hi].
    fn log(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + self.uniform() * (hi.ln() - lo.ln())).exp()
    }
}

/// A chain of `masses.len()` dynamic nodes hanging from a clamped static node by 6-D
/// deformable joints (diagonal stiffnesses `k[i]`: 3 translational [N/m], 3 rotational
/// [N m/rad]), masses `masses[i] = (m, J)` [kg, kg m²], all nodes at the origin, written in
/// units where a mass unit is `a` kg... i.e. every value multiplied by its unit factor:
/// mass `mu`, length `lu`, time `tu` (kg -> g: mu = 1e3; m -> mm: lu = 1e3; s -> ms: tu = 1e3).
fn chain(masses: &[(f64, f64)], k: &[[f64; 6]], (mu, lu, tu): (f64, f64, f64)) -> String {
    let n = masses.len();
    let mut nodes = String::from("structural: 1, static, 0., 0., 0., eye, null, null;\n");
    let mut elems = String::from("joint: 1, clamp, 1, node, node;\n");
    let (force, moment) = (mu / (tu * tu), mu * lu * lu / (tu * tu));
    for (i, ((m, j), kk)) in masses.iter().zip(k).enumerate() {
        let label = i + 2;
        nodes += &format!("structural: {label}, dynamic, 0., 0., 0., eye, null, null;\n");
        let (m, j) = (m * mu, j * mu * lu * lu);
        elems += &format!("body: {label}, {label}, {m:e}, null, diag, {j:e}, {:e}, {:e};\n", 1.3 * j, 1.7 * j);
        let s: Vec<String> = (0..6).map(|c| format!("{:e}", kk[c] * if c < 3 { force } else { moment })).collect();
        elems += &format!("joint: {label}, deformable joint, {}, null, {label}, null, linear elastic generic, diag, {};\n", label - 1, s.join(", "));
    }
    common::mbdyn::file(&format!("structural nodes: {}; rigid bodies: {n}; joints: {};", n + 1, n + 1), &nodes, &elems)
}

#[test]
fn unit_changes_leave_eigenvalues_and_labels_unchanged() {
    // Property: random well-posed spring-mass chains (2–4 nodes, masses 0.1–10 kg, inertias
    // 0.01–1 kg m², stiffnesses 1e2–1e5 in SI) give, in kg/m/s, g/m/s, kg/mm/s, kg/m/ms and
    // g/mm/ms, the same physical eigenvalues (λ times the time unit) to 1e-8 relative and the
    // same labels, mode by mode (issue 30's acceptance).
    let units = [(1.0, 1.0, 1.0), (1e3, 1.0, 1.0), (1.0, 1e3, 1.0), (1.0, 1.0, 1e3), (1e3, 1e3, 1e3)];
    let mut rng = Rng(0x5EED_1234_ABCD_0001);
    for case in 0..8 {
        let n = 2 + case % 3;
        let masses: Vec<(f64, f64)> = (0..n).map(|_| (rng.log(0.1, 10.0), rng.log(0.01, 1.0))).collect();
        let k: Vec<[f64; 6]> = (0..n).map(|_| std::array::from_fn(|_| rng.log(1e2, 1e5))).collect();
        let (si, ..) = default_modes(&chain(&masses, &k, units[0]));
        assert_eq!(si.count(ModeKind::Dynamic), 12 * n, "case {case}: every mode dynamic");
        for &(mu, lu, tu) in &units[1..] {
            let (other, ..) = default_modes(&chain(&masses, &k, (mu, lu, tu)));
            let ctx = format!("case {case}, units x({mu:e} kg, {lu:e} m, {tu:e} s)");
            assert_eq!(other.modes.len(), si.modes.len(), "{ctx}");
            for (a, b) in si.modes.iter().zip(&other.modes) {
                assert_eq!(a.kind, b.kind, "{ctx}: {} vs {}", a.lambda, b.lambda);
                if a.kind == ModeKind::Dynamic {
                    let physical = b.lambda * tu;
                    let rel = (physical - a.lambda).norm() / a.lambda.norm();
                    assert!(rel < 1e-8, "{ctx}: {physical} vs {} ({rel:.1e})", a.lambda);
                }
            }
        }
    }
}

/// Two masses of 1e-12 kg and 1e12 kg in a chain (finding 4), with direction-dependent
/// stiffnesses 1..6 so that every eigenvalue is simple.
fn extreme_two_masses() -> (String, Vec<f64>) {
    let k: Vec<[f64; 6]> = vec![[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]; 2];
    let text = chain(&[(1e-12, 1e-12), (1e12, 1e12)], &k, (1.0, 1.0, 1.0));
    // Closed form per direction: m1 m2 ω⁴ − k (2 m2 + m1) ω² + k² = 0 with M = diag(m1, m2),
    // K = k [[2, −1], [−1, 1]]; the small root from the product of the roots (no cancellation).
    let mut omegas = Vec::new();
    for (c, kk) in k[0].iter().enumerate() {
        let scale = match c {
            0..3 => 1.0,
            3 => 1.0,
            4 => 1.3,
            _ => 1.7,
        };
        let (m1, m2) = (1e-12 * scale, 1e12 * scale);
        let (b, p) = (kk * (2.0 * m2 + m1) / (m1 * m2), kk * kk / (m1 * m2));
        let big = 0.5 * (b + (b * b - 4.0 * p).sqrt());
        omegas.push(big.sqrt());
        omegas.push((p / big).sqrt());
    }
    (text, omegas)
}

#[test]
fn extremely_scaled_masses_never_show_a_wrong_dynamic_mode() {
    // Finding 4: with 1e-12 and 1e12 kg the norm-based dCoef put the 1.414e6 rad/s mode next
    // to Λ = 1 and printed it as a "dynamic" 158.75 rad/s mode. Every mode labelled dynamic
    // must lie within its own error estimate of a closed-form eigenvalue (±jω), and its
    // estimate must be below its modulus, with the default dCoef and with the norm-based
    // one forced (1e12 s).
    let (text, omegas) = extreme_two_masses();
    let m = read(&text);
    let asm = Assembler::new(&m.model);
    let st = State::initial(&m.model, &asm.dofs);
    let dae = linearize(&m.model, &st, &[], &[], None).unwrap();
    // Both the deflated route (`of_dae`) and QZ on the whole pencil (`compute_with_dcoef`,
    // the route of pencil files without their constraint structure).
    let runs = [None, Some(1e12)].into_iter().flat_map(|c| [(c, true), (c, false)]);
    for (dcoef, deflated) in runs {
        let modal = if deflated { ModalAnalysis::of_dae(&dae, EigenRoute::Lambda, dcoef) } else { ModalAnalysis::compute_with_dcoef(&dae.jacobians, EigenRoute::Lambda, dcoef) }.unwrap();
        let dcoef = (dcoef, deflated);
        let mut dynamic = 0;
        for mode in modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic) {
            dynamic += 1;
            let off = omegas.iter().map(|w| (mode.lambda - c64::new(0.0, w.copysign(mode.lambda.im))).norm()).fold(f64::INFINITY, f64::min);
            assert!(mode.error < mode.lambda.norm(), "dCoef {dcoef:?}: {} labelled dynamic with error {:e}", mode.lambda, mode.error);
            assert!(off <= mode.error, "dCoef {dcoef:?}: {} is {off:e} from the closed form, error estimate {:e}", mode.lambda, mode.error);
        }
        if dcoef == (None, true) {
            // The default dCoef resolves every one of the 24 eigenvalues, 1.414e6 rad/s included.
            assert_eq!(dynamic, 24, "{:?}", modal.modes.iter().map(|m| (m.lambda, m.kind)).collect::<Vec<_>>());
        }
    }
}
