//! MBDyn's 4-node EAS membrane `membrane4eas` (docs/src/mbdyn/plates.md): a strip in
//! uniaxial tension against the closed form of plane stress in Green–Lagrange strains, an
//! in-plane cantilever against Timoshenko's beam, both against MBDyn 1.7.3 on the same file,
//! its `.pla` rows against MBDyn's, and its exact derivatives against central differences.
//!
//! MBDyn 1.7.3 (built by shared/tools/build-mbdyn.sh): `mbdyn -f tests/mbdyn_files/FILE.mbd
//! -o out`; positions from `out.mov`, resultants from `out.pla` at t = 1 s (16 digits).

use super::shell::{assert_last_pla_row, assert_text_jacobians, final_node};

/// The stretch λ of a strip of Saint Venant–Kirchhoff plane stress under the dead load `n`
/// per unit initial width: `n = λ E h (λ² − 1)/2` (first Piola–Kirchhoff `λ S`, `S = E h E₁₁`
/// when the transverse resultant vanishes), by Newton's method from λ = 1.
fn stretch(n: f64, eh: f64) -> f64 {
    let mut l: f64 = 1.0;
    for _ in 0..50 {
        l -= (l * eh * (l * l - 1.0) / 2.0 - n) / (eh * (3.0 * l * l - 1.0) / 2.0);
    }
    l
}

#[test]
fn a_membrane_strip_in_tension_stretches_as_plane_stress_and_as_mbdyn() {
    // tests/mbdyn_files/membrane4eas_tension.mbd: LX = 1 m, LY = 0.5 m, h = 1 mm, E = 70 GPa,
    // ν = 0.3, 2 × 2 elements, P = 3.5e6 N along x (a 9 % strain: the Green–Lagrange terms
    // count). Closed form: λ = 1.0880339 from n = P/LY; the transverse stretch from
    // E₂₂ = −ν E₁₁: λ₂ = √(1 − ν (λ² − 1)). A uniform state: the bilinear element is exact
    // (the patch test), so the nodes are asserted to 1e-12 relative.
    let l = stretch(3.5e6 / 0.5, 70e9 * 1e-3);
    let l2 = (1.0 - 0.3 * (l * l - 1.0)).sqrt();
    let (x3, _) = final_node("membrane4eas_tension.mbd", 3);
    let (x203, _) = final_node("membrane4eas_tension.mbd", 203);
    assert!((x3.x - l).abs() < 1e-12 * l, "node 3 x {} against {l}", x3.x);
    assert!((x203.x - l).abs() < 1e-12 * l && (x203.y - 0.5 * l2).abs() < 1e-12, "node 203 {x203:?} against ({l}, {})", 0.5 * l2);
    // MBDyn 1.7.3 on the same file: node 3 x 1.0880339146912923 m, node 203 (1.0880339146912921,
    // 0.48601817356567634) m: 1e-12.
    for (ours, theirs) in [(x3.x, 1.0880339146912923), (x203.x, 1.0880339146912921), (x203.y, 0.48601817356567634)] {
        assert!((ours - theirs).abs() < 1e-12, "{ours} against MBDyn's {theirs}");
    }
}

#[test]
fn an_in_plane_cantilever_of_membranes_bends_as_timoshenko_and_as_mbdyn() {
    // tests/mbdyn_files/membrane4eas_cantilever.mbd: L = 1 m, c = 0.1 m deep, h = 1 cm, E = 70
    // GPa, ν = 0.3, 8 × 2 elements, tip load P = 100 N along y. Timoshenko: P L³/(3 E I) +
    // P L/(k G A) = 5.7590e-4 m (I = h c³/12, k = 5/6, G = E/(2 (1 + ν))). Measured
    // 5.6702e-4 m (−1.5 %: the mesh, and the clamped edge holding the Poisson contraction):
    // asserted within 2 %.
    let (x, _) = final_node("membrane4eas_cantilever.mbd", 9);
    let (i, g) = (1e-2 * 0.1_f64.powi(3) / 12.0, 70e9 / 2.6);
    let timoshenko = 100.0 / (3.0 * 70e9 * i) + 100.0 / (5.0 / 6.0 * g * 1e-3);
    assert!((x.y / timoshenko - 1.0).abs() < 0.02, "tip y {} against {timoshenko}", x.y);
    // MBDyn 1.7.3 on the same file, node 9: x 1.0000424606655505 m, y 5.6701580866069887e-04
    // m. Same element, same discretization: 1e-9 relative (Newton's tolerance 1e-5 N on
    // stiffnesses of 1e8 N/m).
    assert!((x.y - 5.6701580866069887e-04).abs() < 1e-9 * 5.67e-4, "tip y {} against MBDyn's", x.y);
    assert!((x.x - 1.0000424606655505).abs() < 1e-12, "tip x {} against MBDyn's", x.x);
}

#[test]
fn the_plate_file_holds_mbdyn_s_membrane_resultants() {
    // MBDyn 1.7.3's out.pla on membrane4eas_cantilever.mbd, element 1 (at the clamped edge)
    // at t = 1 s: n₁₁, n₂₂, n₁₂ [N/m] at each Gauss point. 1e-9 relative plus 1e-6 N/m.
    let mbdyn = [
        4.4178491932798024e+04, 6.3266068480028443e+03, 9.9988194236332879e+02, 4.4178491932739293e+04, 3.6112277557862581e+02, 9.9988194244214935e+02,
        1.2570628980512489e+04, 3.6112277563311545e+02, 9.9988194245307363e+02, 1.2570628980571213e+04, 6.3266068480573358e+03, 9.9988194237428604e+02,
    ];
    assert_last_pla_row("membrane4eas_cantilever.mbd", "h-shell2-membrane-pla", 32, &mbdyn);
}

#[test]
fn membrane_derivatives_match_finite_differences_at_a_deformed_state() {
    // A 2 × 1 patch, one membrane on displacement nodes with an isotropic law and a
    // prestress, one on structural nodes with a full 3×3 law, moved far from its initial
    // state (noise of amplitude 0.5 on every position and enhanced-strain parameter: large
    // strains and stresses, so the geometric stiffness counts: without it the test fails,
    // measured 0.1 relative): central differences, both constraint forms, 1e-6 relative.
    let text = "begin: data; problem: initial value; end: data;\n\
        begin: initial value; initial time: 0.; final time: 1.; time step: 1.; end: initial value;\n\
        begin: control data; structural nodes: 6; plates: 2; end: control data;\n\
        begin: nodes;\n\
        structural: 1, static displacement, 0., 0., 0., null;\n\
        structural: 2, static, 0.5, 0., 0., eye, null, null;\n\
        structural: 3, static, 1.1, 0.1, 0.05, eye, null, null;\n\
        structural: 4, static displacement, 0., 0.4, 0., null;\n\
        structural: 5, static displacement, 0.5, 0.45, -0.02, null;\n\
        structural: 6, static, 1.05, 0.5, 0., eye, null, null;\n\
        end: nodes;\n\
        begin: elements;\n\
        membrane4eas: 1, 5, 4, 1, 2, isotropic, E, 2.e3, nu, 0.3, thickness, 0.05, prestress, 1., 2., 0.5;\n\
        membrane4eas: 2, 6, 5, 2, 3, matr, 10., 3., 1., 3., 8., 0.5, 1., 0.5, 4.;\n\
        end: elements;\n";
    let compared = assert_text_jacobians(text, "h-shell2-membrane-jacobian", 41);
    assert!(compared >= 2, "both membranes compared: {compared}");
}

#[test]
fn a_prestressed_membrane_drum_has_the_wave_equation_s_modes_and_mbdyn_s() {
    // tests/mbdyn_files/membrane4eas_drum.mbd: a = 1 m, tension T = 1000 N/m as prestress,
    // ρh = 1 kg/m², 4 × 4 elements, the interior nodes dynamic displacement nodes with lumped
    // masses, the edges clamped. Out of plane only the prestress holds it (the geometric
    // stiffness at rest): ω_mn = π √(T/(ρh)) √(m² + n²)/a, ω_11 = 140.50 rad/s. Measured with
    // MBDyn 1.7.3 on this mesh and on 8 × 8: 130.06, 137.81 rad/s (−7.4 %, −1.9 %: second
    // order, Richardson's extrapolation 140.40 rad/s): the 4 × 4 mesh within its error.
    let w = super::shell::frequencies("membrane4eas_drum.mbd");
    let exact = std::f64::consts::PI * 1000.0_f64.sqrt() * 2.0_f64.sqrt();
    assert!((w[0] / exact - 1.0).abs() < 0.08, "ω_11 {} against {exact}", w[0]);
    assert!((w[1] - w[2]).abs() < 1e-9 * w[1], "ω_12 and ω_21 are one double eigenvalue: {} {}", w[1], w[2]);
    // MBDyn 1.7.3 on the same file (its LAPACK eigenanalysis, dCoef 0.5 s): 130.05788897043254,
    // 187.41450172298948 and 187.41453731123465 (the double pair split by 1.9e-7),
    // 206.55910267166448 rad/s: 1e-6 relative.
    let mbdyn = [130.05788897043254, 0.5 * (187.41450172298948 + 187.41453731123465), 206.55910267166448];
    for (k, (ours, theirs)) in [w[0], w[1], w[3]].iter().zip(mbdyn).enumerate() {
        assert!((ours - theirs).abs() < 1e-6 * theirs, "mode {k}: {ours} against MBDyn's {theirs}");
    }
}
