//! MBDyn's EAS-ANS shell `shell4easans` (docs/src/mbdyn/plates.md): the transverse shear
//! strains sampled at the edges' midpoints, 7 enhanced membrane strains. The simply
//! supported square plate against Kirchhoff's closed form and MBDyn 1.7.3 (also thin, beside
//! `shell4eas`), the cantilever strip's tip against MBDyn 1.7.3, and its exact derivatives
//! against central differences.
//!
//! MBDyn 1.7.3 (built by shared/tools/build-mbdyn.sh): `mbdyn -f tests/mbdyn_files/FILE.mbd
//! -o out`; positions from `out.mov` at t = 1 s (16 digits), eigenvalues from `out_0.m`
//! (`alpha`, `dCoef` = 0.5 s: `λ = (z − 1)/((z + 1) dCoef)`, `z = (αr + i αi)/β`).

use romdyn::input::mbdyn::SetOverrides;
use romdyn::study::StudySource;

use super::shell::{assert_cantilever_tip, assert_last_pla_row, assert_patch_jacobians, final_node, frequencies, frequencies_of};
use crate::common::mbdyn::test_file;

/// Kirchhoff's ω_mn of the simply supported square plate of shell4eas_plate.mbd (a = 1 m,
/// E = 70 GPa, ν = 0.3, ρ = 2700 kg/m³) of thickness `h`: π² (m² + n²)/a² √(D/(ρ h)),
/// D = E h³/(12 (1 − ν²)).
fn kirchhoff(m: f64, n: f64, h: f64) -> f64 {
    let d = 70e9 * h.powi(3) / (12.0 * (1.0 - 0.09));
    std::f64::consts::PI.powi(2) * (m * m + n * n) * (d / (2700.0 * h)).sqrt()
}

#[test]
fn a_simply_supported_plate_of_ans_shells_has_kirchhoff_s_modes_and_mbdyn_s() {
    // tests/mbdyn_files/shell4easans_plate.mbd: shell4eas_plate.mbd with shell4easans
    // elements (a/h = 100, 4 × 4 elements, masses lumped at the nodes).
    let w = frequencies("shell4easans_plate.mbd");
    // Kirchhoff: ω_11 = 304.15 rad/s, ω_12 = 760.37 rad/s. Measured: ω_11 295.61 rad/s
    // (−2.8 %; shell4eas on the same mesh −5.6 %), ω_12 784.43 rad/s (+3.2 %): the 4 × 4
    // mesh is asserted within its measured error.
    assert!((w[0] / kirchhoff(1.0, 1.0, 0.01) - 1.0).abs() < 0.03, "ω_11 {} against {}", w[0], kirchhoff(1.0, 1.0, 0.01));
    assert!((w[1] / kirchhoff(1.0, 2.0, 0.01) - 1.0).abs() < 0.035, "ω_12 {} against {}", w[1], kirchhoff(1.0, 2.0, 0.01));
    assert!((w[1] - w[2]).abs() < 1e-9 * w[1], "ω_12 and ω_21 are one double eigenvalue: {} {}", w[1], w[2]);
    // MBDyn 1.7.3 on the same file (its LAPACK eigenanalysis, dCoef 0.5 s): 295.6137884640098,
    // 784.4271904258267 and 784.4276287096903 (its QZ splits the double pair by 6e-7),
    // 1114.6854333903823 rad/s. Same element, same discretization, but MBDyn's pencil of
    // shell4easans is not the linearization: its AssJac divides the enhanced-strain rows by
    // dCoef, and the eigenanalysis assembles A = J(−h/2), B = J(h/2), so those rows change
    // sign between A and B and the eigenvalues depend on the `parameter` h (measured on
    // this file: ω_11 = 325.90 rad/s at h = 1e-2, 1967.1 at h = 1e-4; shell4eas's do not
    // move, 287.10854 at both). At the default h = 1 the error is small: the first two
    // agree to 1e-6 relative, the fourth to 5e-6 (measured 3.3e-6: romdyn 1114.68906, MBDyn
    // 1114.68543; at h = 10 MBDyn gives 1114.68979, 6.5e-7). romdyn's enhanced-strain rows
    // are algebraic equations of the configuration, as shell4eas's.
    let mbdyn = [(295.6137884640098, 1e-6), (0.5 * (784.4271904258267 + 784.4276287096903), 1e-6), (1114.6854333903823, 5e-6)];
    for (k, (ours, (theirs, tolerance))) in [w[0], w[1], w[3]].iter().zip(mbdyn).enumerate() {
        assert!((ours - theirs).abs() < tolerance * theirs, "mode {k}: {ours} against MBDyn's {theirs}");
    }
}

/// The plate's dynamic frequencies with `set: H` overridden and the cards of `card`.
fn plate_frequencies(card: &str, h: f64) -> Vec<f64> {
    let overrides: SetOverrides = [("H".to_string(), h)].into();
    frequencies_of(StudySource::ModelFile { path: test_file(&format!("{card}_plate.mbd")), overrides })
}

#[test]
fn on_a_thin_plate_the_ans_shell_converges_faster_than_the_eas_shell() {
    // The two plate files with h = 1 mm (a/h = 1000; `set: H` overridden). Kirchhoff: ω_11 =
    // 30.415 rad/s. Neither element locks (measured with MBDyn 1.7.3 down to a/h = 10⁴: the
    // errors do not depend on h), but on the 4 × 4 mesh shell4easans is twice as close:
    // −2.75 % against shell4eas's −5.55 %.
    let exact = kirchhoff(1.0, 1.0, 0.001);
    let eas = plate_frequencies("shell4eas", 0.001)[0];
    let ans = plate_frequencies("shell4easans", 0.001)[0];
    assert!((ans / exact - 1.0).abs() < 0.03, "shell4easans ω_11 {ans} against {exact}");
    assert!((eas / exact - 1.0).abs() < 0.06, "shell4eas ω_11 {eas} against {exact}");
    assert!((ans - exact).abs() < 0.6 * (eas - exact).abs(), "shell4easans {ans} is not closer than shell4eas {eas} to {exact}");
    // MBDyn 1.7.3 on the same files with `set: const real H = 0.001;`: 28.725835183668803
    // (shell4eas) and 29.57674053206762 rad/s (shell4easans): 1e-6 relative.
    for (ours, theirs) in [(eas, 28.725835183668803), (ans, 29.57674053206762)] {
        assert!((ours - theirs).abs() < 1e-6 * theirs, "{ours} against MBDyn's {theirs}");
    }
}

#[test]
fn a_cantilever_strip_of_ans_shells_bends_as_mbdyn_s() {
    // tests/mbdyn_files/shell4easans_cantilever.mbd: shell4eas_cantilever.mbd with
    // shell4easans elements (L = 1 m, b = 0.1 m, h = 0.01 m, ν = 0, 10 × 2 elements, P = 1 N).
    // The same tip as shell4eas's (beam theory within 0.245 %, the mesh error): on
    // rectangles in pure bending the tying points see the same transverse shear as the Gauss
    // points. MBDyn 1.7.3 on the same file, node 111: x 9.9999980570339353e-01 m, z
    // 5.7002838173379506e-04 m, Euler angle about y −4.9110655054079903e-02 deg.
    assert_cantilever_tip("shell4easans_cantilever.mbd", [9.9999980570339353e-01, 5.7002838173379506e-04, -4.9110655054079903e-02]);
}

#[test]
fn ans_shell_derivatives_match_finite_differences_at_a_deformed_state() {
    let compared = assert_patch_jacobians("shell4easans", "h-shell2-ans-jacobian");
    assert!(compared >= 2, "both shells compared: {compared}");
}

#[test]
fn the_plate_file_holds_mbdyn_s_ans_stress_resultants() {
    // MBDyn 1.7.3's out.pla on shell4easans_cantilever.mbd, element 1 at t = 1 s: the 12
    // resultants at each Gauss point (n₁₃ = 10 N/m of shear flux from the tying points,
    // m₁₂ = −9.5 N). 1e-9 relative plus 1e-6 N/m or N (the zeros are rounding, as shell4eas's).
    let mbdyn = [
        8.1426532183561328e-04, -1.1589536392513361e-08, 9.9999999668490815e+00, -1.4714283457134911e-08,
        2.0309295028766976e-25, -8.1697316269707195e-13, -7.1319624954175926e-15, -9.4999980592447280e+00,
        -2.0693777982377109e-14, 3.7014969379687679e-16, 2.5298050691328435e-15, -5.1473172536261000e-15,
        8.1426532183579759e-04, -1.6461010498950105e-08, 9.9999999668490815e+00, -4.3388428217620481e-08,
        -8.7126360132157135e-25, -3.0489853516057079e-12, -7.1319624954175926e-15, -9.4999980592447280e+00,
        -2.0693777982377112e-14, 1.2007938258485428e-15, 1.0119220276531374e-14, -1.9210049804444352e-14,
        8.1426532183592683e-04, -3.1518977183649671e-09, 9.9999999668463424e+00, -4.8259902354810652e-08,
        8.7126360132157135e-25, -3.0489853516057079e-12, -6.6021296318939516e-15, -9.4999980592447226e+00,
        -2.7725144067969861e-14, 1.2007938258485428e-15, 1.0119220276531374e-14, -1.9210049804444352e-14,
        8.1426532183548404e-04, -8.0233703949136208e-09, 9.9999999668463424e+00, -9.8428108160176744e-09,
        -2.0309295028766976e-25, -8.1697316269707195e-13, -6.6021296318939500e-15, -9.4999980592447226e+00,
        -2.7725144067969861e-14, 3.7014969379687679e-16, 2.5298050691328435e-15, -5.1473172536261000e-15,
    ];
    assert_last_pla_row("shell4easans_cantilever.mbd", "h-shell2-ans-pla", 40, &mbdyn);
}

#[test]
fn on_a_thin_skewed_mesh_the_ans_shell_locks_where_the_eas_shell_does_not() {
    // tests/mbdyn_files/shell4eas_skewed_cantilever.mbd and shell4easans_skewed_cantilever.mbd:
    // the cantilever strip with h = 1 mm (L/h = 1000), trapezoidal elements (the middle row's
    // interior nodes moved by ±0.03 m along x), P = 1 mN. Beam theory: P L³/(3 EI) =
    // 5.714e-4 m. Measured: shell4eas +1.37 % (5.7925e-4 m), shell4easans 4.128e-6 m, 138
    // times too stiff, and stiffer as h falls (with MBDyn 1.7.3: 3.14e-5, 7.80e-6, 4.13e-6 m
    // at h = 10, 3, 1 mm, where shell4eas stays within 1.5 %): shear locking. MBDyn's ANS
    // samples the transverse shears as components in each tying point's Cartesian frame
    // (t₁ along ∂x/∂ξ₁, t₂ ⟂ t₁), not as covariant components along ∂x/∂ξ₂; on a skewed
    // element ε₂₃ at B and D then carries part of the ε₁₃ shear (our reading of the cause).
    // romdyn follows MBDyn.
    let ei = 70e9 * 0.1 * 0.001_f64.powi(3) / 12.0;
    let beam = 1e-3 / (3.0 * ei);
    let (eas, _) = final_node("shell4eas_skewed_cantilever.mbd", 111);
    let (ans, _) = final_node("shell4easans_skewed_cantilever.mbd", 111);
    assert!((eas.z / beam - 1.0).abs() < 0.02, "shell4eas tip {} against {beam}", eas.z);
    assert!(ans.z > 0.0 && ans.z < 0.02 * beam, "shell4easans tip {} does not lock against {beam}", ans.z);
    // MBDyn 1.7.3 on the same files, node 111's z: 5.7925370422790359e-04 and
    // 4.1278233715921420e-06 m: 1e-9 relative.
    for (ours, theirs) in [(eas.z, 5.7925370422790359e-04), (ans.z, 4.1278233715921420e-06)] {
        assert!((ours - theirs).abs() < 1e-9 * theirs, "{ours} against MBDyn's {theirs}");
    }
}
