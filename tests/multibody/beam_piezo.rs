//! MBDyn's `piezoelectric actuator` on `beam3` and `beam2` (docs/src/mbdyn/beams.md; issue
//! 38): the sections' voltage-driven forces `T_s V`, the voltages the values of abstract
//! nodes. MBDyn 1.7.3's numbers on the same files, a closed form (a uniform actuation moment
//! bends a cantilever into an arc), the voltage columns of the Jacobian against central
//! differences, a ROM with the voltage as its input, and bad cards refused at their place.
//!
//! MBDyn 1.7.3 (built by shared/tools/build-mbdyn.sh), run on 2026-12-07: `mbdyn -f
//! tests/mbdyn_files/FILE.mbd -o out`, rows of `out.mov` and `out.act` (the files ask for
//! 16 digits).

#![allow(clippy::excessive_precision)] // MBDyn's numbers as it prints them (17 digits)

use crate::common;
use common::cli::{romdyn_at, temp_dir};
use common::mbdyn::{assert_model_jacobians, assert_refused, test_file as file};

use romdyn::analysis::run;
use romdyn::dae::{Assembler, Coefficients};
use romdyn::input::mbdyn::{read_model_text, BeamUpdateRule, ReadOptions, SetOverrides};
use romdyn::kinematics::{euler123, rotation_vector, Vec3};
use romdyn::model::{ConstraintForm, ScalarNodeId, ScalarNodeKind};

/// Node `label`'s position and Euler angles 123 (MBDyn's `.mov` orientation) at `final_time` (the file's own when `None`)
/// with the file's `set:` variables `overrides`, the beams with MBDyn 1.7.3's incremental
/// rotation update (`romdyn run`'s default, `--beam-update auto`); the run has no warning.
fn node_at(name: &str, final_time: Option<f64>, overrides: &[(&str, f64)], label: u32) -> (Vec3, Vec3) {
    let path = file(name);
    let text = std::fs::read_to_string(&path).unwrap();
    let overrides: SetOverrides = overrides.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    let options = ReadOptions { overrides: &overrides, beam_update: BeamUpdateRule::IncrementalWherePossible };
    let mut m = read_model_text(&text, &path, options).unwrap_or_else(|e| panic!("{e}"));
    if let Some(t) = final_time {
        m.problem.final_time = t;
    }
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    assert!(report.warnings().is_empty(), "{name}: {:?}", report.warnings().iter().map(|w| w.to_string()).collect::<Vec<_>>());
    let asm = Assembler::new(&m.model);
    let slot = m.model.nodes.iter().position(|n| n.label == label).unwrap();
    let k = report.final_state.node_frame(&asm.dofs, slot).kin;
    (k.x, euler123(&k.r))
}

/// `got` within `relative` of `expected`, component by component (relative to the
/// vector's largest component).
fn assert_close(what: &str, got: &Vec3, expected: &Vec3, relative: f64) {
    let scale = expected.amax();
    assert!((got - expected).amax() <= relative * scale, "{what}: {got:?} against {expected:?} (relative {:e})", (got - expected).amax() / scale);
}

#[test]
fn a_three_node_piezoelectric_cantilever_follows_mbdyn_s_trajectory() {
    // piezo_beam_cantilever.mbd: one electrode, 0 → 100 V in 1 ms, 1e-3 N m/V about axis 3;
    // the undamped beam swings. MBDyn 1.7.3, node 3 (position; Euler angles 123 in degrees)
    // at t = 0.005 s and 0.01 s. Agreement measured 2e-13 relative on the tip deflection and
    // 6e-13 on the rotations (the beams with MBDyn's incremental update); asserted 1e-6.
    let mbdyn = [
        (0.005, Vec3::new(9.9999999892537084e-01, -1.3493673482765798e-05, 0.0), Vec3::new(0.0, 0.0, -8.9030931171645775e-03)),
        (0.01, Vec3::new(9.9999998842957183e-01, -4.8707517061819250e-05, 0.0), Vec3::new(0.0, 0.0, -2.8549298596248968e-02)),
    ];
    for (t, x, phi_deg) in mbdyn {
        let (got_x, got_phi) = node_at("piezo_beam_cantilever.mbd", Some(t), &[], 3);
        assert_close(&format!("t = {t} s, node 3 position"), &got_x, &x, 1e-6);
        assert!((got_x.y - x.y).abs() < 1e-6 * x.y.abs(), "t = {t} s: tip y {} against MBDyn's {}", got_x.y, x.y);
        assert_close(&format!("t = {t} s, node 3 rotation"), &got_phi.map(f64::to_degrees), &phi_deg, 1e-6);
    }
}

#[test]
fn a_two_node_piezoelectric_cantilever_with_two_electrodes_follows_mbdyn_s_trajectory() {
    // piezo_beam2_cantilever.mbd: two beam2, electrodes 10 (0 → 100 V, 1e-3 N m/V about axis
    // 3) and 11 (0 → 50 V, 0.1 N/V axial and 8e-4 N m/V about axis 2), the matrix by rows
    // after `matr` with `scale`. MBDyn 1.7.3, node 3 (position; Euler angles 123 in
    // degrees) at t = 0.005 s and 0.01 s; measured
    // agreement 1.3e-13 (deflections) and 3.5e-13 (rotations) relative; asserted 1e-6.
    let mbdyn = [
        (0.005, Vec3::new(9.9999949627963802e-01, -1.1857041049358011e-05, 4.7428164197432046e-06), Vec3::new(-2.0307592455970124e-07, -3.0509530750493794e-03, -7.6273827173609244e-03)),
        (0.01, Vec3::new(9.9999949228586626e-01, -4.3810207151703610e-05, 1.7524082860681448e-05), Vec3::new(-2.0549634571077533e-06, -9.7052862486242605e-03, -2.4263216578804373e-02)),
    ];
    for (t, x, phi_deg) in mbdyn {
        let (got_x, got_phi) = node_at("piezo_beam2_cantilever.mbd", Some(t), &[], 3);
        assert_close(&format!("t = {t} s, node 3 position"), &got_x, &x, 1e-6);
        for c in 1..3 {
            assert!((got_x[c] - x[c]).abs() < 1e-6 * x[c].abs(), "t = {t} s: tip component {c} {} against MBDyn's {}", got_x[c], x[c]);
        }
        assert_close(&format!("t = {t} s, node 3 rotation"), &got_phi.map(f64::to_degrees), &phi_deg, 1e-6);
    }
}

#[test]
fn the_act_rows_carry_the_actuation_as_mbdyn_s_do() {
    // MBDyn adds T V to the section's forces before it writes them (pzbeam2.cc,
    // AddInternalForces): beam2 1 of piezo_beam2_cantilever.mbd at t = 0.01 s, MBDyn 1.7.3's
    // row `1 -9.6088984491871088e-04 5.2369191496291290e-01 -2.0947676598516513e-01 ~0
    // 4.9887698402065063e-02 1.2471924600516267e-01`: the axial force is the law's EA ε
    // plus 0.1 N/V × 50 V, nearly balanced (without the actuator it would read −5 N).
    let dir = temp_dir("beam-piezo-act");
    let (ok, _, err) = romdyn_at(&dir, &["run", file("piezo_beam2_cantilever.mbd").to_str().unwrap(), "-o", "p"]);
    assert!(ok, "{err}");
    let body = std::fs::read_to_string(dir.join("p.act")).unwrap();
    let rows: Vec<Vec<f64>> = body.lines().rev().take(2).map(|l| l.split_whitespace().map(|c| c.parse().unwrap()).collect()).collect();
    let first = rows.iter().find(|r| r[0] == 1.0).unwrap_or_else(|| panic!("{body}"));
    let mbdyn = [1.0, -9.6088984491871088e-04, 5.2369191496291290e-01, -2.0947676598516513e-01, 0.0, 4.9887698402065063e-02, 1.2471924600516267e-01];
    for (a, b) in first.iter().zip(mbdyn) {
        // The file's 13 digits; the forces balance 5 N, so 1e-9 N is 2e-10 of the terms.
        assert!((a - b).abs() < 1e-9, "row {first:?} against MBDyn's {mbdyn:?}");
    }
}

#[test]
fn a_uniform_actuation_moment_bends_the_cantilever_into_its_closed_form_arc() {
    // piezo_beam_static.mbd: static nodes, four beam3, L = 1 m, EJ = 100 N m², t = 1e-3 N
    // m/V (read in the `anba` layout). With no load from outside each section's moment
    // EJ κ + t V vanishes: κ = −t V / EJ everywhere, an arc of tip rotation θ = κ L and tip
    // (sin θ, −(1 − cos θ)) / |κ|.
    let (l, ej, t) = (1.0_f64, 100.0, 1e-3);
    let arc = |v: f64| {
        let theta = t * v * l / ej;
        (Vec3::new(theta.sin(), -(1.0 - theta.cos()), 0.0) * (l / theta), theta)
    };
    // V = 100 V: the small-rotation closed forms M L²/(2 EJ) = 5e-4 m and M L / EJ = 1e-3
    // rad (M = t V = 0.1 N m) hold within θ²/12 = 8e-8 of the arc; romdyn's tip is 1.2e-12 m
    // from the arc (2.4e-9 relative, as its rotation: Newton's tolerance 1e-7 over EJ), so
    // the deflection is 8.6e-8 from the linear formula and the rotation 2.2e-9.
    let (x, phi) = node_at("piezo_beam_static.mbd", None, &[], 9);
    let m = t * 100.0;
    assert!((x.y + m * l * l / (2.0 * ej)).abs() < 1e-6 * 5e-4, "tip deflection {} against -M L²/(2 EJ) = {}", x.y, -m * l * l / (2.0 * ej));
    assert!((phi.z + m * l / ej).abs() < 1e-6 * 1e-3, "tip rotation {} against -M L / EJ", phi.z);
    // MBDyn 1.7.3 on the same file: node 9 at (9.9999983333334175e-01, -4.9999995832726379e-04)
    // m, rotation -5.7295779513082325e-02 deg (1.2e-11 from the arc).
    assert!((x.y - -4.9999995832726379e-04).abs() < 1e-6 * 5e-4 && (x.x - 9.9999983333334175e-01).abs() < 1e-12, "{x:?} against MBDyn's");
    assert!((phi.z.to_degrees() - -5.7295779513082325e-02).abs() < 1e-6 * 5.73e-2, "{} deg against MBDyn's", phi.z.to_degrees());
    // V = 5e4 V: θ = 0.5 rad in one load step. romdyn's four elements are 3.5e-7 m from the
    // arc (mesh error; 9e-8 relative on θ). MBDyn 1.7.3 does not converge on this step (its
    // incremental beam from the straight state); at 1e4 V (θ = 0.1 rad) it is 4e-10 from the
    // arc, romdyn 5e-10.
    let (x, phi) = node_at("piezo_beam_static.mbd", None, &[("V", 5e4)], 9);
    let (tip, theta) = arc(5e4);
    assert!((x - tip).norm() < 1e-6, "tip {x:?} against the arc's {tip:?} ({:e} m)", (x - tip).norm());
    assert!((phi.z + theta).abs() < 1e-6 * theta, "tip rotation {} against -{theta}", phi.z);
}

/// The abstract node 10's index among the unknowns.
fn voltage_index(m: &romdyn::input::mbdyn::MbdynModel, asm: &Assembler) -> usize {
    asm.dofs.scalar_first + m.model.scalar_index(ScalarNodeId { kind: ScalarNodeKind::Abstract, label: 10 }).unwrap()
}

#[test]
fn the_voltage_columns_of_the_jacobian_are_the_residual_s_central_differences() {
    // Every element of the two dynamic files (beams, electrodes, springs) at a random state
    // (all unknowns and rates moved by 0.5, the voltages too), both constraint forms:
    // analytic Jacobian against central differences of the residual, 1e-6 (the library's
    // check, `common::mbdyn::assert_model_jacobians`).
    for name in ["piezo_beam_cantilever.mbd", "piezo_beam2_cantilever.mbd"] {
        let m = common::mbdyn::read_test_file(name);
        let compared = assert_model_jacobians(
            |form| {
                let mut model = common::mbdyn::read_test_file(name).model;
                model.constraint_form = form;
                model
            },
            7,
            1e-6,
        );
        assert!(compared >= m.model.elements.len(), "{name}: {compared} elements compared");
        // The voltage column alone, in the whole model's Newton matrix J(c) = F_/ẏ + c F_/y
        // (a value's column holds c ∂F/∂V): against c times the central difference of the
        // residual in V, at the file's end state, where the beam is bent and the voltage 100 V
        // (measured 4.8e-12 of the column's largest entry, asserted 1e-8).
        let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
        let asm = Assembler::new(&m.model);
        let j = voltage_index(&m, &asm);
        let c = 0.37;
        let jac = asm.jacobian(&report.final_state, Coefficients::newton(c, ConstraintForm::Plain));
        let mut column = vec![0.0; jac.n];
        for k in 0..jac.values.len() {
            if jac.cols[k] == j {
                column[jac.rows[k]] += jac.values[k];
            }
        }
        let h = 1e-3;
        let moved = |dv: f64| {
            let mut st = report.final_state.clone();
            st.y[j] += dv;
            asm.residual(&st, ConstraintForm::Plain, c)
        };
        let (plus, minus) = (moved(h), moved(-h));
        let scale = column.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(scale > 1e-4, "{name}: the voltage column is empty");
        let structural = (0..jac.n).filter(|&i| i != j && column[i].abs() > 0.0).count();
        // A moment about axis 3 alone moves the moment rows of the beam's end nodes (the
        // middle node's two volumes cancel); the beam2 file's axial force moves more.
        assert!(structural >= 2, "{name}: the voltage moves {structural} structural equations");
        for i in 0..jac.n {
            let fd = c * (plus[i] - minus[i]) / (2.0 * h);
            assert!((column[i] - fd).abs() < 1e-8 * scale, "{name}: row {i}: analytic {:e}, central difference {fd:e}", column[i]);
        }
    }
}

#[test]
fn a_rom_with_the_voltage_as_input_has_the_closed_form_static_gain() {
    // piezo_beam_rom.mbd: the cantilever of piezo_beam_static.mbd with masses; the voltage
    // node held by a unit spring, so the input on its equation is the voltage [V]. Linear
    // theory at rest: tip deflection per volt −t L²/(2 EJ) = −5e-6 m/V, rotation −t L / EJ =
    // −1e-5 rad/V (four beam3: exact for a uniform moment; measured 7e-12 relative, the
    // ROM's 5e-12).
    use romdyn::study::{Residualization, RomRequest, Study, StudySource};
    let study = Study::builder(StudySource::model_file(file("piezo_beam_rom.mbd")))
        .node_ports(vec!["10:abstract".parse().unwrap()], vec!["9:y".parse().unwrap(), "9:rz".parse().unwrap()])
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let (deflection, rotation) = (-5e-6, -1e-5);
    let full = study.full_static_gain().unwrap_or_else(|e| panic!("{e}"));
    assert!((full[(0, 0)] - deflection).abs() < 1e-9 * 5e-6, "full model: {} m/V", full[(0, 0)]);
    assert!((full[(1, 0)] - rotation).abs() < 1e-9 * 1e-5, "full model: {} rad/V", full[(1, 0)]);
    // The ROM of the two lowest modes (the bending pair at 5.58 Hz) with the dropped modes
    // residualized keeps the gain; the modes alone carry 89 % of the deflection's.
    let rom = study.reduce(&RomRequest::new(romdyn::rom::ModeSelection::Lowest(2)).residualize(Residualization::Dropped)).unwrap_or_else(|e| panic!("{e}"));
    let gain = rom.static_gains.rom.as_ref().unwrap_or_else(|e| panic!("{e}"));
    assert!((gain[(0, 0)] - deflection).abs() < 1e-8 * 5e-6, "ROM: {} m/V", gain[(0, 0)]);
    assert!((gain[(1, 0)] - rotation).abs() < 1e-8 * 1e-5, "ROM: {} rad/V", gain[(1, 0)]);
    let modal = study.reduce(&RomRequest::new(romdyn::rom::ModeSelection::Lowest(2))).unwrap_or_else(|e| panic!("{e}"));
    let modal_gain = modal.static_gains.rom.as_ref().unwrap_or_else(|e| panic!("{e}"))[(0, 0)];
    assert!((modal_gain / deflection - 0.892).abs() < 1e-3, "modes alone: {modal_gain} m/V");
}

#[test]
fn bad_piezoelectric_actuators_are_refused_at_their_place() {
    let name = "piezo_beam_cantilever.mbd";
    let original = std::fs::read_to_string(file(name)).unwrap();
    let card = "piezoelectric actuator, 1, 10,\n            0., 0., 0., 0., 0., 1.e-3,\n            same;";
    assert!(original.contains(card));
    let with = |new: &str| original.replace(card, new);
    let mut algebraic = original.replace("abstract: 10, differential;", "abstract: 10, algebraic;");
    for line in ["    genels: 1;\n", "    forces: 1;\n", "    genel: 1, spring support, 10, abstract, algebraic, linear elastic, 1.;\n", "    force: 10, abstract, 10, abstract, cosine, 0., pi/1.e-3, 50., half, 0.;\n"] {
        assert!(algebraic.contains(line), "{line}");
        algebraic = algebraic.replace(line, "");
    }
    assert_refused(
        name,
        &original,
        &[
            (with("piezoelectric actuator, 0, 0., 0., 0., 0., 0., 1.e-3, same;"), "beam3 1, piezoelectric actuator: the number of electrodes must be at least 1"),
            (with("piezoelectric actuator, 1, 11, 0., 0., 0., 0., 0., 1.e-3, same;"), "beam3 1, piezoelectric actuator, electrode 1: abstract node 11 is not defined (MBDyn 1.7.3 reads the electrodes among the abstract nodes)"),
            (with("piezoelectric actuator, 1, 10, 0., 0., 0., 0., 0., 1.e-3;"), "expected beam3 1, piezoelectric actuator: actuation matrix of section II ('same' or 6x1 values)"),
            (with("piezoelectric actuator, 1, 10, 0., 0., 0., 0., 0.;"), "actuation matrix of section I"),
            // MBDyn 1.7.3: "DataManager::ReadNode: unable to cast Abstract(10) to
            // \"22ScalarDifferentialNode\"" (the genel and the force removed: a spring
            // support on it is refused first, by both).
            (algebraic, "abstract node 10 is algebraic, and MBDyn 1.7.3 takes differential abstract nodes only"),
        ],
    );
    // Where: the electrode's label (line 61, column 39 of the card's second line).
    let e = romdyn::input::mbdyn::parse_text(&with("piezoelectric actuator, 1, 11, 0., 0., 0., 0., 0., 1.e-3, same;"), &file(name)).and_then(|d| romdyn::input::mbdyn::build(&d)).err().unwrap().to_string();
    let line = original.lines().position(|l| l.contains("piezoelectric actuator")).unwrap() + 1;
    assert!(e.contains(&format!("{name}:{line}:")), "{e}");
}

#[test]
fn the_initial_assembly_keeps_the_piezoelectric_beam_with_its_voltages_held() {
    // piezo_beam_cantilever.mbd with 100 V on from the start (a genel clamp on the node's
    // initial value) and the initial assembly run. MBDyn 1.7.3 keeps the beam there, its
    // actuation read from the node (pzbeam.cc): "Initial assembly iterations reached maximum
    // number 1; aborting..." (and with 20 or 1000 iterations too). romdyn left every element
    // on scalar nodes out of its assembly, the beam with them, and passed; it now stops
    // where MBDyn stops, and with 20 iterations converges.
    let text = std::fs::read_to_string(file("piezo_beam_cantilever.mbd")).unwrap();
    let changed = |iterations: &str| {
        let mut t = text.clone();
        for (old, new) in [
            ("    skip initial joint assembly;\n", iterations),
            ("abstract: 10, differential;", "abstract: 10, differential, value, 100.;"),
            ("genel: 1, spring support, 10, abstract, algebraic, linear elastic, 1.;", "genel: 1, clamp, 10, abstract, algebraic, const, 100.;"),
            ("    force: 10, abstract, 10, abstract, cosine, 0., pi/1.e-3, 50., half, 0.;\n", ""),
            ("    forces: 1;\n", ""),
        ] {
            assert!(t.contains(old), "{old}");
            t = t.replace(old, new);
        }
        romdyn::input::mbdyn::read_model_text(&t, &file("piezo_beam_cantilever.mbd"), &SetOverrides::default()).unwrap_or_else(|e| panic!("{e}"))
    };
    let m = changed("");
    let asm = Assembler::new(&m.model);
    let mut st = romdyn::dae::State::initial(&m.model, &asm.dofs);
    let e = romdyn::solve::initial_assembly(&m.model, &mut st, &m.problem.assembly).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(e.contains("initial assembly did not converge in 1 iteration"), "{e}");
    // With 20 iterations: the 100 V bend the beam against the assembly's unit springs on the
    // positions and rotations of nodes 2 and 3. Linear theory (a cantilever EJ = 100 N m²
    // under the uniform moment 0.1 N m and the springs' forces −y and moments −θ at x = 0.5
    // and 1 m, flexibilities from the closed forms): y2 = −1.225923e-4 m, y3 = −4.914688e-4
    // m, θ3 = −9.850854e-4 rad. romdyn: 3.6e-4, 2.2e-4 and 2.4e-5 from them (one three-node
    // element under point loads: the mesh error); asserted 1e-3.
    let m = changed("    max iterations: 20;\n");
    let mut st = romdyn::dae::State::initial(&m.model, &asm.dofs);
    romdyn::solve::initial_assembly(&m.model, &mut st, &m.problem.assembly).unwrap_or_else(|e| panic!("{e}"));
    let at = |label: u32| st.node_frame(&asm.dofs, m.model.nodes.iter().position(|n| n.label == label).unwrap()).kin;
    let (n2, n3) = (at(2), at(3));
    for (got, linear) in [(n2.x.y, -1.225923349e-4), (n3.x.y, -4.914687987e-4), (rotation_vector(&n3.r).z, -9.850854352e-4)] {
        assert!((got - linear).abs() < 1e-3 * linear.abs(), "{got} against linear theory's {linear}");
    }
}

#[test]
fn an_actuator_that_does_not_fit_its_beam_is_an_error() {
    use nalgebra::DMatrix;
    use romdyn::element::{Beam2, BeamNode, PiezoActuator, SectionLaw, SectionOrientation};
    use romdyn::kinematics::Mat3;
    let electrode = vec![ScalarNodeId { kind: ScalarNodeKind::Abstract, label: 10 }];
    let nodes = [BeamNode::new(1, Vec3::zeros(), Mat3::identity(), Vec3::zeros()), BeamNode::new(2, Vec3::x(), Mat3::identity(), Vec3::zeros())];
    let beam = Beam2::new(7, nodes, SectionOrientation::Given(Mat3::identity()), SectionLaw::diagonal(1e6, 1e6, 1e6, 1e2, 1e2, 1e2)).unwrap();
    let two = PiezoActuator::new(7, electrode.clone(), vec![DMatrix::zeros(6, 1); 2]).unwrap();
    let e = beam.with_piezo(two).expect_err("two matrices on beam2").to_string();
    assert_eq!(e, "beam 7: the piezoelectric actuator has 2 actuation matrices, the beam 1 evaluation points");
    let e = PiezoActuator::new(7, electrode.clone(), vec![DMatrix::zeros(6, 2)]).expect_err("6x2 for one electrode").to_string();
    assert_eq!(e, "beam 7: actuation matrix 1 is 6x2, expected 6x1 (one column per electrode)");
    let e = PiezoActuator::new(7, electrode, vec![DMatrix::from_element(6, 1, f64::NAN)]).expect_err("NaN").to_string();
    assert_eq!(e, "beam 7: actuation matrix 1 has a value that is not finite");
    let e = PiezoActuator::new(7, Vec::new(), vec![DMatrix::zeros(6, 0)]).expect_err("no electrode").to_string();
    assert_eq!(e, "beam 7: a piezoelectric actuator needs at least one electrode");
}
