//! MBDyn's `modal` joint read from a file (issue 35): `tests/mbdyn_files/modal_spring_mass.mbd`
//! and its FEM file, against the closed form written in the file, and bad cards refused
//! with the file, line and column.

use crate::common;

use common::mbdyn::{assert_refused, test_file};
use romdyn::analysis::Reference;
use romdyn::eigen::ModeKind;
use romdyn::study::{StudySource, Study};

const FILE: &str = "modal_spring_mass.mbd";

#[test]
fn an_attached_multibody_node_moves_with_its_fem_node() {
    let study = Study::builder(StudySource::model_file(&test_file(FILE))).reference(Reference::Initial).build().unwrap_or_else(|e| panic!("{e}"));
    let im: Vec<f64> = study.modal().modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 1e-6).map(|m| m.lambda.im).collect();
    // The file's closed form: ω² = k (1/(mb + m2) + 1/ma + l²/Jz) with Jz = 0.3 + 0.01 kg m².
    let expected = (1000.0f64 * (1.0 / 2.0 + 1.0 / 2.0 + 0.64 / 0.31)).sqrt();
    assert_eq!(im.len(), 1, "{im:?}");
    // 1e-9 relative: one QZ on 36 unknowns with entries from 1e-2 to 1e3.
    assert!(common::rel(im[0], expected) < 1e-9, "{} rad/s against the closed form {expected} rad/s", im[0]);
    // MBDyn 1.7.3 on this file (built here 2026-12-06) prints 55.3581 rad/s: within its 6
    // digits.
    assert!(common::rel(im[0], 55.3581) < 2e-6, "{} rad/s against MBDyn's 55.3581", im[0]);
}

#[test]
fn bad_modal_joint_cards_are_refused_with_their_place() {
    let original = std::fs::read_to_string(test_file(FILE)).unwrap();
    let with = |from: &str, to: &str| original.replace(from, to);
    assert_refused(
        FILE,
        &original,
        &[
            (with("structural: 1, modal,", "structural: 1, dynamic,"), "is not a 'modal' node"),
            (with("        1,                        # modes", "        2, list, 1, 1,"), "mode number 1: expected"),
            (with("        1,                        # modes", "        2, list, 1, 3,"), "mode 3 asked for, the FEM file"),
            (with("        1,                        # modes", "        2,"), "mode 2 asked for, the FEM file"),
            (with("from file,                # FEM node count", "3,"), "3 FEM nodes given, the FEM file"),
            (with("\"B\", 2, null;", "\"Z\", 2, null;"), "FEM node \"Z\" is not in the FEM file"),
            (with("origin node, \"A\",", "origin node, \"Q\","), "origin node: FEM node \"Q\""),
            (with("\"modal_spring_mass.fem\"", "\"no_such_file.fem\""), "the FEM file cannot be used"),
            (with("no damping,", "diag damping, 1, 2, 0.01,"), "damped mode index 2"),
            (with("origin node, \"A\",", "use invariant 9, origin node, \"A\","), "'use invariant 9' comes after the interface nodes"),
            (with("\"B\", 2, null;", "\"B\", 2, null, orientation, euler123, 0.1, 0., 0.;"), "an interface orientation other than the identity"),
        ],
    );
}

#[test]
fn a_bad_fem_file_is_refused_with_its_own_place() {
    // The FEM file's error (file:line:col of the .fem) comes through the card's.
    let dir = common::cli::temp_dir("modal-bad-fem");
    let fem = std::fs::read_to_string(test_file("modal_spring_mass.fem")).unwrap().replace("0.5 0.5 0.5 0. 0. 0.", "0.5 0.5 0.5 0. 0. nan");
    common::cli::write_file(&dir, "modal_spring_mass.fem", &fem);
    let mbd = common::cli::write_file(&dir, FILE, &std::fs::read_to_string(test_file(FILE)).unwrap());
    let err = romdyn::input::mbdyn::read_model(std::path::Path::new(&mbd)).err().expect("a NaN in record 11 is refused").to_string();
    assert!(err.contains(&format!("{FILE}:")) && err.contains("modal_spring_mass.fem:28:19:"), "{err}");
    assert!(err.contains("expected a finite real number, found 'nan'"), "{err}");
}

/// Runs `name` of `tests/mbdyn_files/` and returns, at its final time, each node's position
/// [m] and velocity [m/s] by label and the modal coordinates and their rates by mode.
fn final_state(name: &str) -> (Vec<(u32, [f64; 6])>, Vec<(f64, f64)>) {
    let m = common::mbdyn::read_test_file(name);
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = romdyn::dae::Assembler::new(&m.model);
    let st = &report.final_state;
    let nodes = m.model.nodes.iter().enumerate().map(|(i, n)| {
        let k = st.node_frame(&asm.dofs, i).kin;
        (n.label, [k.x[0], k.x[1], k.x[2], k.xdot[0], k.xdot[1], k.xdot[2]])
    });
    let e = m.model.elements.iter().position(|e| e.type_name() == "modal").expect("a modal joint");
    let names = m.model.elements[e].multipliers();
    let q = names.iter().enumerate().filter(|(_, n)| n.starts_with("modal coordinate")).map(|(k, _)| {
        let j = asm.dofs.element_first[e] + k;
        (st.y[j], st.yp[j])
    });
    (nodes.collect(), q.collect())
}

/// `computed` against MBDyn's printed `expected`: each within `rel` of the largest.
fn assert_as_mbdyn(what: &str, computed: &[f64], expected: &[f64], rel: f64) {
    let scale = expected.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (k, (c, e)) in computed.iter().zip(expected).enumerate() {
        assert!((c - e).abs() <= rel * scale, "{what}[{k}]: romdyn {c}, MBDyn 1.7.3 {e} (allowed {:.1e})", rel * scale);
    }
}

#[test]
fn a_clamped_modal_body_under_gravity_moves_as_in_mbdyn() {
    // MBDyn 1.7.3 on tests/mbdyn_files/modal_clamped_gravity.mbd (built here, 2026-12-06),
    // at t = 1 s: node 2's .mov row and the .mod rows (7 digits). romdyn agrees to all of
    // them: 1e-6 of each group's largest value is MBDyn's print rounding (5e-7) with margin.
    let (nodes, q) = final_state("modal_clamped_gravity.mbd");
    assert_as_mbdyn("node 2", &nodes[0].1, &[9.384915e-02, -2.032134e-01, 2.896675e-01, 3.837623e-02, 1.119896e-02, 8.024533e-02], 1e-6);
    assert_as_mbdyn("q", &[q[0].0, q[1].0], &[-8.168098e-03, -1.475026e-02], 1e-6);
    assert_as_mbdyn("q rates", &[q[0].1, q[1].1], &[1.773037e-02, 1.009455e-01], 1e-6);
}

#[test]
fn a_floating_modal_body_shaken_at_an_interface_moves_as_in_mbdyn() {
    // MBDyn 1.7.3 on tests/mbdyn_files/modal_floating_force.mbd (built here, 2026-12-06),
    // t = 1 s, 7 digits. With `use invariant 9` and point masses (no nodal rotational
    // inertia) MBDyn's equations of motion are romdyn's; they integrate different unknowns
    // (MBDyn q and q̇, romdyn q and p = ∂T/∂q̇; its modal node velocities, romdyn momenta), so
    // the steps' truncation errors part them: at h = 1e-3 q2 differed by 3.4e-6 relative, at
    // the file's 2.5e-4 every printed digit agrees (measured within 3e-7 of each group's
    // largest value).
    let (nodes, q) = final_state("modal_floating_force.mbd");
    assert_as_mbdyn("node 1", &nodes[0].1, &[9.459115e-02, -1.144112e-01, 3.433838e-01, 7.083164e-02, 1.360663e-01, 1.648950e-01], 1e-6);
    assert_as_mbdyn("node 2", &nodes[1].1, &[9.615091e-02, -1.135499e-01, 3.453592e-01, -1.001088e-01, 1.291364e-01, -2.000449e-01], 1e-6);
    assert_as_mbdyn("q", &[q[0].0, q[1].0], &[2.737466e-03, 3.220877e-03], 1e-6);
    assert_as_mbdyn("q rates", &[q[0].1, q[1].1], &[2.210764e-02, -4.341876e-01], 1e-6);
}

/// The last `.mod` rows `romdyn run` writes for `name`: `(label.mode, q, q̇, q̈)`.
fn last_mod_rows(name: &str, rows: usize) -> Vec<(String, [f64; 3])> {
    let dir = common::cli::temp_dir(&format!("modal-mod-{name}"));
    let prefix = dir.join("run");
    let (ok, _, err) = common::cli::romdyn(&["run", test_file(name).to_str().unwrap(), "-o", prefix.to_str().unwrap()]);
    assert!(ok, "{err}");
    let text = std::fs::read_to_string(dir.join("run.mod")).expect("romdyn run writes PREFIX.mod for a model with a modal joint");
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len() - rows..].iter().map(|l| {
        let f: Vec<&str> = l.split_whitespace().collect();
        assert_eq!(f.len(), 4, "{l}");
        (f[0].to_string(), [f[1].parse().unwrap(), f[2].parse().unwrap(), f[3].parse().unwrap()])
    }).collect()
}

#[test]
fn the_mod_file_holds_mbdyns_rows() {
    // MBDyn 1.7.3's .mod rows at t = 1 s on the same files (built here, 2026-12-06):
    // `label.mode q q̇ q̈`, 7 digits. q̈ is no unknown of romdyn's (it integrates the modal
    // momenta): it comes from the momentum definitions differentiated along the motion
    // (dae::modal_coordinates); measured within 4e-7 relative of MBDyn's bPrime.
    let cases: [(&str, [(&str, [f64; 3]); 2]); 2] = [
        ("modal_clamped_gravity.mbd", [("10.1", [-8.168098e-03, 1.773037e-02, 9.960250e-01]), ("10.2", [-1.475026e-02, 1.009455e-01, 2.184097e+00])]),
        ("modal_floating_force.mbd", [("10.1", [2.737466e-03, 2.210764e-02, -1.689899e+00]), ("10.2", [3.220877e-03, -4.341876e-01, -3.226761e+00])]),
    ];
    for (name, expected) in cases {
        let rows = last_mod_rows(name, 2);
        for ((label, got), (mode, want)) in rows.iter().zip(expected) {
            assert_eq!(label, mode, "{name}");
            assert_as_mbdyn(&format!("{name} {mode}"), got, &want, 2e-6);
        }
    }
}

#[test]
fn drives_read_the_modal_coordinates_private_data() {
    // tests/mbdyn_files/modal_private_data.mbd: q = Q0 cos ωt (ω² = 1000/0.5) drives a force
    // along y on a free 1 kg node (q[1]) and q̇ one along z (qP[#1]), so the node is at
    // y = Q0 (1 − cos ωt)/ω², z − 1 = Q0 (sin ωt/ω − t) at t = 0.1 s (the file's closed form).
    let m = common::mbdyn::read_test_file("modal_private_data.mbd");
    let e = m.model.elements.iter().find(|e| e.type_name() == "modal").expect("a modal joint");
    let outputs = e.outputs().expect("outputs");
    assert!(outputs.private_data("q[1]").is_some() && outputs.private_data("qP[#1]").is_some());
    assert!(outputs.private_data("q[2]").is_none() && outputs.private_data("qPP[1]").is_none() && outputs.private_data("q[#0]").is_none());
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = romdyn::dae::Assembler::new(&m.model);
    let x = report.final_state.node_frame(&asm.dofs, 0).kin.x;
    // (The run's last time, 0.1 s up to the steps' sum.)
    let (q0, w, t) = (1e-2f64, 2000f64.sqrt(), report.final_state.t);
    assert!((t - 0.1).abs() < 2e-5, "{t}");
    let (y, z) = (q0 * (1.0 - (w * t).cos()) / (w * w), q0 * ((w * t).sin() / w - t));
    // Crank–Nicolson at h = 1e-5 s, ωh = 4.5e-4: phase error ~ (ωh)² ωt/12 = 7e-8, so 1e-6
    // of the motion's amplitude.
    assert!((x[1] - y).abs() < 1e-6 * q0 / (w * w) * 2.0, "y = {} against {y}", x[1]);
    assert!((x[2] - 1.0 - z).abs() < 1e-6 * q0 * t, "z − 1 = {} against {z}", x[2] - 1.0);
}

#[test]
fn a_floating_modal_body_has_mbdyns_eigenvalues() {
    // MBDyn 1.7.3 (built here) on tests/mbdyn_files/modal_floating_force.mbd (a free modal
    // node, point masses, `use invariant 9`, Rayleigh damping, a 0.5 kg body on FEM node B;
    // its force is sin 0 = 0 at t = 0) with final time 2.5e-4 and `eigenanalysis: 0., output
    // eigenvectors, results output precision, 16, parameter, 1.e-4, use lapack, balance, no;`
    // (2026-12-07): the `alpha` rows of its two flexible pairs, λ by MBDyn's formula (dCoef
    // 5e-5); its other eigenvalues are the rigid motions' (λ = 0). 1e-9 relative: two QZ on
    // 40-odd unknowns (measured below 1e-11).
    let mbdyn_alpha = [[7.9049106374521105e-01, 1.6078112508054682e-03, 7.9053032989470740e-01], [5.0026114830912105e-01, 1.4542659128019713e-03, 5.0030767763925321e-01]];
    let study = Study::builder(StudySource::model_file(test_file("modal_floating_force.mbd"))).reference(Reference::Initial).build().unwrap_or_else(|e| panic!("{e}"));
    let mut pairs: Vec<faer::c64> = study.modal().modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 1e-6).map(|m| m.lambda).collect();
    pairs.sort_by(|a, b| a.im.total_cmp(&b.im));
    assert_eq!(pairs.len(), 2, "{pairs:?}");
    for (l, row) in pairs.iter().zip(mbdyn_alpha) {
        let (re, im) = common::lambda_of_alpha(row, 5e-5);
        let m = faer::c64::new(re, im);
        eprintln!("romdyn {l}, MBDyn {m}: {:.1e}", (l - m).norm() / m.norm());
        assert!((l - m).norm() <= 1e-9 * m.norm(), "romdyn {l} rad/s, MBDyn 1.7.3 {m} rad/s");
    }
}
