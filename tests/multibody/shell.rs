//! MBDyn's 4-node EAS shell `shell4eas` (docs/src/mbdyn/plates.md): a cantilever strip
//! against beam theory and MBDyn 1.7.3, a simply supported square plate's modes against
//! Kirchhoff's closed form and MBDyn 1.7.3, and its exact derivatives (hyper-dual numbers)
//! against central differences of the residual at a deformed state.
//!
//! MBDyn 1.7.3 (built by shared/tools/build-mbdyn.sh): `mbdyn -f tests/mbdyn_files/FILE.mbd
//! -o out`; positions from `out.mov` at t = 1 s (16 digits), eigenvalues from `out_0.m`
//! (`alpha`, `dCoef` = 0.5 s: `λ = (z − 1)/((z + 1) dCoef)`, `z = (αr + i αi)/β`).

use crate::common;
use common::mbdyn::{assert_model_jacobians, read_test_file, test_file};

use romdyn::analysis::{run, Reference};
use romdyn::dae::Assembler;
use romdyn::eigen::ModeKind;
use romdyn::kinematics::{rotation_vector, Vec3};
use romdyn::study::{Study, StudySource};

/// The position and rotation vector of node `label` at the end of the run of `name`.
pub(crate) fn final_node(name: &str, label: u32) -> (Vec3, Vec3) {
    let m = read_test_file(name);
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let slot = m.model.nodes.iter().position(|n| n.label == label).unwrap();
    let k = report.final_state.node_frame(&asm.dofs, slot).kin;
    (k.x, rotation_vector(&k.r))
}

#[test]
fn a_cantilever_strip_of_shells_bends_as_beam_theory_and_as_mbdyn() {
    // tests/mbdyn_files/shell4eas_cantilever.mbd: L = 1 m, b = 0.1 m, h = 0.01 m, E = 70 GPa,
    // ν = 0 (no anticlastic stiffening), 10 × 2 elements, tip load P = 1 N.
    // MBDyn 1.7.3 on the same file, node 111: x 9.9999980570339353e-01 m, z
    // 5.7002838173384157e-04 m, Euler angle about y −4.9110655054081943e-02 deg.
    assert_cantilever_tip("shell4eas_cantilever.mbd", [9.9999980570339353e-01, 5.7002838173384157e-04, -4.9110655054081943e-02]);
}

/// The tip node 111 of a cantilever strip file against beam theory and against MBDyn's
/// `[x [m], z [m], Euler angle about y [deg]]` on the same file.
pub(crate) fn assert_cantilever_tip(name: &str, mbdyn: [f64; 3]) {
    let (x, phi) = final_node(name, 111);
    // Euler–Bernoulli: P L³/(3 EI) = 5.7143e-4 m, P L²/(2 EI) = 8.5714e-4 rad (EI = E b h³/12);
    // the shear term P L/(G A a_s) is 4e-8 of it. Ten bilinear elements along the span are
    // 0.245 % stiffer (measured: 5.70028e-4 m); the slope 0.012 % off.
    let ei = 70e9 * 0.1 * 0.01_f64.powi(3) / 12.0;
    let deflection = 1.0 / (3.0 * ei);
    assert!((x.z - deflection).abs() < 3e-3 * deflection, "{name}: tip z {} against {deflection}", x.z);
    assert!((-phi.y - 1.0 / (2.0 * ei)).abs() < 2e-4 / (2.0 * ei), "{name}: tip rotation {} against {}", -phi.y, 1.0 / (2.0 * ei));
    // MBDyn: same element, same discretization: 1e-9 relative (Newton's tolerance 1e-6 N on
    // stiffnesses of 1e9 N).
    assert!((x.x - mbdyn[0]).abs() < 1e-12, "{name}: tip x {} against MBDyn's {}", x.x, mbdyn[0]);
    assert!((x.z - mbdyn[1]).abs() < 1e-9 * mbdyn[1].abs(), "{name}: tip z {} against MBDyn's {}", x.z, mbdyn[1]);
    assert!((phi.y.to_degrees() - mbdyn[2]).abs() < 1e-9 * mbdyn[2].abs(), "{name}: tip rotation {} deg against MBDyn's {}", phi.y.to_degrees(), mbdyn[2]);
}

/// The dynamic eigenvalues' positive imaginary parts [rad/s], ascending.
pub(crate) fn frequencies(name: &str) -> Vec<f64> {
    frequencies_of(StudySource::model_file(&test_file(name)))
}

/// The same for any study source.
pub(crate) fn frequencies_of(source: StudySource) -> Vec<f64> {
    let study = Study::builder(source).reference(Reference::Initial).build().unwrap_or_else(|e| panic!("{e}"));
    let mut im: Vec<f64> = study.modal().modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 1e-6).map(|m| m.lambda.im).collect();
    im.sort_by(f64::total_cmp);
    im
}

#[test]
fn a_simply_supported_plate_of_shells_has_kirchhoff_s_modes_and_mbdyn_s() {
    // tests/mbdyn_files/shell4eas_plate.mbd: a = 1 m, h = 0.01 m (a/h = 100: a thin plate,
    // where shear locking would stiffen bilinear elements by orders of magnitude; the
    // enhanced strains keep it out), E = 70 GPa, ν = 0.3, ρ = 2700 kg/m³, 4 × 4 elements,
    // masses lumped at the nodes, edges held at z = 0.
    let w = frequencies("shell4eas_plate.mbd");
    // Kirchhoff: ω_mn = π² (m² + n²)/a² √(D/(ρ h)), D = E h³/(12 (1 − ν²)) = 6410.3 N m:
    // ω_11 = 304.10 rad/s, ω_12 = ω_21 = 760.25 rad/s.
    let d = 70e9 * 0.01_f64.powi(3) / (12.0 * (1.0 - 0.09));
    let omega = |m: f64, n: f64| std::f64::consts::PI.powi(2) * (m * m + n * n) * (d / (2700.0 * 0.01)).sqrt();
    // Measured mesh convergence of ω_11 (this file with N = 4, 8): 287.11, 299.91 rad/s
    // (−5.6 %, −1.38 %: second order; Richardson's extrapolation 304.18 rad/s, 0.03 % from
    // the closed form). The 4 × 4 mesh is asserted within its measured error.
    assert!((w[0] / omega(1.0, 1.0) - 1.0).abs() < 0.06, "ω_11 {} against {}", w[0], omega(1.0, 1.0));
    assert!((w[1] / omega(1.0, 2.0) - 1.0).abs() < 0.025, "ω_12 {} against {}", w[1], omega(1.0, 2.0));
    assert!((w[1] - w[2]).abs() < 1e-9 * w[1], "ω_12 and ω_21 are one double eigenvalue: {} {}", w[1], w[2]);
    // MBDyn 1.7.3 on the same file (its LAPACK eigenanalysis, dCoef 0.5 s): 287.1085420927675,
    // 774.7689575365259 and 774.7690195188901 (its QZ splits the double pair by 8e-8),
    // 1112.2777297646855 rad/s. Same element, same discretization: 1e-6 relative.
    let mbdyn = [287.1085420927675, 0.5 * (774.7689575365259 + 774.7690195188901), 1112.2777297646855];
    for (k, (ours, theirs)) in [w[0], w[1], w[3]].iter().zip(mbdyn).enumerate() {
        assert!((ours - theirs).abs() < 1e-6 * theirs, "mode {k}: {ours} against MBDyn's {theirs}");
    }
}

#[test]
fn shell_derivatives_match_finite_differences_at_a_deformed_state() {
    let compared = assert_patch_jacobians("shell4eas", "h-shell-jacobian");
    assert!(compared >= 2, "both shells compared: {compared}");
}

/// A 2 × 1 patch of the cantilever strip's elements of type `card` moved far from its
/// initial state (every position, rotation and enhanced-strain parameter perturbed by noise
/// of amplitude 0.5: large rotations, large stresses, so the geometric stiffness counts),
/// its Jacobian against central differences of the residual in both constraint forms (1e-6
/// relative); the number of entries compared.
pub(crate) fn assert_patch_jacobians(card: &str, dir_name: &str) -> usize {
    let text = "begin: data; problem: initial value; end: data;\n\
        begin: initial value; initial time: 0.; final time: 1.; time step: 1.; end: initial value;\n\
        begin: control data; structural nodes: 6; plates: 2; end: control data;\n\
        begin: nodes;\n\
        structural: 1, static, 0., 0., 0., eye, null, null;\n\
        structural: 2, static, 0.5, 0., 0., eye, null, null;\n\
        structural: 3, static, 1.1, 0.1, 0.05, eye, null, null;\n\
        structural: 4, static, 0., 0.4, 0., eye, null, null;\n\
        structural: 5, static, 0.5, 0.45, -0.02, 1, 0., 0., 1., 2, 0., 1., 0.2, null, null;\n\
        structural: 6, static, 1.05, 0.5, 0., eye, null, null;\n\
        end: nodes;\n\
        begin: elements;\n\
        CARD: 1, 5, 4, 1, 2, isotropic, E, 2.e3, nu, 0.3, thickness, 0.05, prestress, 1., 2., 0., 2., 3., 0., 0., 0., 0., 0., 0., 0.;\n\
        CARD: 2, 6, 5, 2, 3, diag, 10., 8., 5., 8., 10., 5., 1., 2., 0.1, 2., 1., 0.1;\n\
        end: elements;\n"
        .replace("CARD", card);
    assert_text_jacobians(&text, dir_name, 38)
}

/// The Jacobian of the MBDyn file `text` at its initial state perturbed by noise (`seed`)
/// against central differences in both constraint forms, 1e-6 relative; the number of
/// entries compared.
pub(crate) fn assert_text_jacobians(text: &str, dir_name: &str, seed: u64) -> usize {
    let dir = common::cli::temp_dir(dir_name);
    let path = common::cli::write_file(&dir, "patch.mbd", text);
    assert_model_jacobians(
        |form| {
            let mut m = romdyn::input::mbdyn::read_model(std::path::Path::new(&path)).unwrap_or_else(|e| panic!("{e}"));
            m.model.constraint_form = form;
            m.model
        },
        seed,
        1e-6,
    )
}

#[test]
fn bad_plate_laws_are_refused_with_their_place() {
    // A law missing its thickness or given a datum twice, a Poisson's ratio out of range,
    // the orthotropic law's data missing or inconsistent, its fiber angle (MBDyn 1.7.3:
    // "fiber angle "beta" not supported yet"), a membrane law with the shells' factors: each
    // refused at its place.
    let text = std::fs::read_to_string(test_file("shell4eas_cantilever.mbd")).unwrap();
    let card = "shell4eas: 1, 102, 101, 1, 2, isotropic, E, E, nu, NU, thickness, H;";
    assert!(text.contains(card));
    let orthotropic = "plane stress orthotropic, E_l, E, E_t, E/2, nu_lt, NU, G, E/3";
    let cases = [
        (card.replace(", thickness, H", ""), "shell isotropic law: the 'thickness' is missing"),
        (card.replace("nu, NU", "E, 1."), "Young's modulus E [Pa] given twice"),
        (card.replace("nu, NU", "nu, .5"), "must be in [0, 0.5)"),
        (card.replace("isotropic, E, E, nu, NU", orthotropic).replace(", thickness, H", ""), "shell plane stress orthotropic law: the 'thickness' is missing"),
        (card.replace("isotropic, E, E, nu, NU", &orthotropic.replace(", E_t, E/2", "")), "the transverse Young's modulus 'E_t' is missing"),
        (card.replace("isotropic, E, E, nu, NU", &format!("{orthotropic}, nu_tl, 0.2")), "are inconsistent (nu_tl E_l must equal nu_lt E_t)"),
        (card.replace("isotropic, E, E, nu, NU", &format!("{orthotropic}, beta, 30.")), "the fiber angle 'beta' is not supported (MBDyn 1.7.3 refuses it too"),
        (card.replace("shell4eas:", "membrane4eas:").replace(", thickness, H", ""), "membrane isotropic law: the 'thickness' is missing"),
        (card.replace("shell4eas:", "membrane4eas:").replace("thickness, H", "thickness, H, as, 1."), "'as'"),
    ];
    for (changed, expected) in cases {
        let err = romdyn::input::mbdyn::read_model_text(&text.replace(card, &changed), &test_file("shell4eas_cantilever.mbd"), &Default::default()).err().unwrap_or_else(|| panic!("accepted: {changed}"));
        let message = err.to_string();
        assert!(message.contains(expected), "{message}");
        assert!(message.contains("shell4eas_cantilever.mbd:"), "no place: {message}");
    }
}

#[test]
fn the_plate_file_holds_mbdyn_s_stress_resultants() {
    // `romdyn run` writes MBDyn's `.pla`: a line per shell and output instant, the label and
    // the 12 resultants of each of the four Gauss points. MBDyn 1.7.3 on
    // shell4eas_cantilever.mbd, out.pla, element 1 at t = 1 s (n₁₃ = P = 10 N/m of shear
    // flux over b = .1 m, m₁₂ = −9.5 N: the bending moment per unit width at the root
    // element's points). The large components agree to 1e-12 relative; the ones that should
    // be zero are rounding, up to the membrane stiffness times the strains' rounding, E h ·
    // 2.2e-16 = 1.6e-7 N/m (measured: 1.6e-7 against MBDyn's 1e-24): 1e-9 relative plus
    // 1e-6 N/m or N.
    let mbdyn = [
        8.1426532183704117e-04, -1.3374058538935133e-08, 9.9999999779021707e+00, -1.4130115760814125e-08,
        2.1390053880437770e-25, -1.2721575963990543e-11, -9.8370818016902076e-15, -9.4999980592451116e+00,
        -1.9098446127334110e-14, 5.7445483927382012e-16, 2.5298050691328435e-15, -5.4217773843623211e-15,
        8.1426532183436970e-04, -1.8505285686656312e-08, 9.9999999779116564e+00, -4.0593709197827889e-08,
        -9.9282880632843924e-25, -1.4534812218653150e-11, -9.8370818016902076e-15, -9.4999980592451116e+00,
        -1.9098446127334113e-14, 1.9536399738605617e-15, 1.0119220276531374e-14, -2.0234349134449365e-14,
        8.1426532183625317e-04, -4.4865176003473927e-09, 9.9999999779069135e+00, -4.5724935003129294e-08,
        9.9282880632843924e-25, -1.4609434922656695e-11, -9.0268726054793792e-15, -9.4999980592451099e+00,
        -2.6504731699789145e-14, 1.9536399738605617e-15, 1.0119220276531374e-14, -2.0234349134449365e-14,
        8.1426532183515770e-04, -9.6177409871706643e-09, 9.9999999779021707e+00, -8.9988910226777223e-09,
        -2.1390053880437770e-25, -1.2741571062566454e-11, -9.0268726054793792e-15, -9.4999980592451099e+00,
        -2.6504731699789138e-14, 5.7445483927382012e-16, 2.5298050691328435e-15, -5.4217773843623211e-15,
    ];
    assert_last_pla_row("shell4eas_cantilever.mbd", "h-shell-pla", 40, &mbdyn);
}

/// `romdyn run FILE` writes `lines` lines to `.pla` (every plate at t = 0 and t = 1 s), and
/// element 1's last row holds `mbdyn` (1e-9 relative plus 1e-6 N/m or N).
pub(crate) fn assert_last_pla_row(name: &str, dir_name: &str, lines: usize, mbdyn: &[f64]) {
    let dir = common::cli::temp_dir(dir_name);
    let (ok, _, err) = common::cli::romdyn_at(&dir, &["run", test_file(name).to_str().unwrap(), "-o", "c"]);
    assert!(ok, "{err}");
    let body = std::fs::read_to_string(dir.join("c.pla")).unwrap();
    assert_eq!(body.lines().count(), lines, "{name}: every plate at t = 0 and t = 1 s");
    let row: Vec<f64> = body.lines().rev().find(|l| l.split_whitespace().next() == Some("1")).unwrap().split_whitespace().skip(1).map(|v| v.parse().unwrap()).collect();
    assert_eq!(row.len(), mbdyn.len());
    for (k, (ours, theirs)) in row.iter().zip(mbdyn).enumerate() {
        assert!((ours - theirs).abs() < 1e-9 * theirs.abs() + 1e-6, "{name}: component {k}: {ours} against MBDyn's {theirs}");
    }
}
