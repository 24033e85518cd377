//! Drives that read an element's private data or a node's degree of freedom (MBDyn's
//! `element` and `dof` drive callers; issue 12, point 3): `tests/mbdyn_files/element_drives.mbd`
//! against closed forms and MBDyn 1.7.3, the elements' Jacobians against finite differences
//! with those drives held (their derivatives are in no Jacobian, as in MBDyn), the refusal
//! to linearize, parameter nodes and `bind`, and the errors.

use crate::common;

use common::mbdyn::{assert_jacobians_after_run, assert_not_linearized, read_test_file, test_file as path};
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{build, parse_text, read_model, MbdynModel};
use romdyn::kinematics::euler123;

fn text() -> String {
    std::fs::read_to_string(path("element_drives.mbd")).unwrap_or_else(|e| panic!("element_drives.mbd: {e}"))
}

fn from_text(t: &str) -> Result<MbdynModel, String> {
    parse_text(t, &path("element_drives.mbd")).and_then(|d| build(&d)).map_err(|e| e.to_string())
}

#[test]
fn element_and_dof_drives_give_the_closed_forms_and_mbdyns_motion() {
    let m = read_model(&path("element_drives.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = |k: usize| report.final_state.node_frame(&asm.dofs, k).kin;
    let (c, k, f): (f64, f64, f64) = (0.8, 4.0, 0.5);
    let w = k.sqrt();
    let zeta = c / (2.0 * w);
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let decay = (-zeta * w).exp();
    // Closed forms at t = 1 s (file header): the torsional oscillators θ = (w0/ωd) e^{−ζωt}
    // sin(ωd t) [deg, Euler 1-2-3 z] and their spin; the forced oscillator of node 3,
    // x = x_h − F t/K + C F/K² with x_h(0) = x0 − C F/K², ẋ_h(0) = F/K.
    let theta = |w0: f64| (w0 / wd * decay * wd.sin()).to_degrees();
    let spin = |w0: f64| w0 / wd * decay * (wd * wd.cos() - zeta * w * wd.sin());
    let (a, b) = (-f / k, c * f / (k * k));
    let (x0, v0) = (0.3 - b, -a);
    let x3 = decay * (x0 * wd.cos() + (v0 + zeta * w * x0) / wd * wd.sin()) + a + b;
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, 1727489e) on this file, `output
    // precision: 16`, last row of its .mov.
    let cases = [
        ("node 2 θz [deg]", euler123(&kin(1).r)[2].to_degrees(), theta(0.5), 9.0682448938937572e+00),
        ("node 2 ωz", kin(1).omega[2], spin(0.5), -1.9035861855156702e-01),
        ("node 4 θz [deg]", euler123(&kin(3).r)[2].to_degrees(), theta(-0.3), -5.4409469345925210e+00),
        ("node 4 ωz", kin(3).omega[2], spin(-0.3), 1.1421517043033101e-01),
        ("node 3 x", kin(2).x[0], x3, -9.5490435395668066e-02),
        // The gears: node 5 free at 1 rad/s, node 6 imposed at −2 times its hinge's rz.
        ("node 5 θz [deg]", euler123(&kin(4).r)[2].to_degrees(), 1f64.to_degrees(), 5.7295782347691102e+01),
        ("node 6 θz [deg]", euler123(&kin(5).r)[2].to_degrees(), -2f64.to_degrees(), -1.1459156469538645e+02),
        ("node 6 ωz", kin(5).omega[2], -2.0, -1.9999997031273253e+00),
    ];
    for (what, x, exact, mbdyn) in cases {
        eprintln!("{what}: {x:.15e}, closed form {exact:.15e}, MBDyn {mbdyn:.15e}");
        // ms with ρ∞ = 0.6 and h = 1 ms on these smooth motions: measured 7e-7 relative
        // to the amplitude (θ of node 2: 9.06824 deg against 9.06824); 1e-5 of the value
        // or of the amplitude (0.3 m, 0.25 rad = 14 deg).
        let scale = if what.contains("θz") { 14.0 } else { 0.3 };
        assert!((x - exact).abs() < 1e-5 * scale, "{what}: {x} against the closed form {exact}");
        // Same method, steps and Newton iterations as MBDyn (each converged to 1e-10 with
        // the drives' derivatives missing from the Jacobian in both): measured to 1e-13
        // relative; 1e-10 of the amplitude.
        assert!((x - mbdyn).abs() < 1e-10 * scale, "{what}: {x} against MBDyn {mbdyn}");
    }
    // MBDyn 1.7.3's .out: 3002 Newton iterations over its 1001 "Step" rows (the
    // derivatives step's 1 included), the same count per step as romdyn: the drives held
    // in the Jacobian slow Newton down in both the same way.
    assert_eq!(report.newton_iterations + report.derivatives_iterations, 3002);
}

/// A driven element's private data are its wrapped element's, as MBDyn's `DrivenElem`
/// forwards them (romdyn refused the read before: "private data not computed"). The same
/// file with the hinge of node 2 inside `driven: 2, const, 1., …`: MBDyn 1.7.3 on that file
/// gives node 2 θz = 9.0682448938937572 deg at t = 1 s, the undriven file's value, and so
/// must romdyn (the closed form and MBDyn, tolerances as above).
#[test]
fn a_driven_elements_private_data_are_the_wrapped_elements() {
    let old = "    joint: 2, revolute hinge,\n        1, reference, node, null,";
    let t = text();
    assert!(t.contains(old));
    let m = from_text(&t.replace(old, &format!("    driven: 2, const, 1.,\n{old}"))).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let theta = euler123(&report.final_state.node_frame(&asm.dofs, 1).kin.r)[2].to_degrees();
    let (c, k): (f64, f64) = (0.8, 4.0);
    let (w, zeta) = (k.sqrt(), c / (2.0 * k.sqrt()));
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let exact = (0.5 / wd * (-zeta * w).exp() * wd.sin()).to_degrees();
    assert!((theta - exact).abs() < 1e-5 * 14.0, "θz {theta} against the closed form {exact}");
    assert!((theta - 9.0682448938937572).abs() < 1e-10 * 14.0, "θz {theta} against MBDyn");
}

/// A follower couple with the drives of the hinge's rotation and spin: the element's
/// Jacobian equals central differences of its residual with the drives held at the state
/// checked (the drives' own derivatives are in no Jacobian, as in MBDyn).
#[test]
fn jacobians_hold_element_and_dof_drives_at_the_checked_state() {
    let checks = assert_jacobians_after_run(&mut read_test_file("element_drives.mbd"), Some(0.2), 1e-3);
    for name in ["follower couple 2", "follower couple 4", "absolute force 3", "total joint 6"] {
        let c = checks.iter().find(|c| c.element == name).unwrap_or_else(|| panic!("{name}: {checks:?}"));
        assert!(c.drive_held, "{c:?}");
    }
}

#[test]
fn a_model_whose_drives_read_elements_is_not_linearized() {
    let why = "the torsional spring's stiffness is in no Jacobian: the linearization would be wrong";
    assert_not_linearized(&read_test_file("element_drives.mbd"), &["reads the model's state", "element drive callers"], why);
}

#[test]
fn bad_element_and_dof_drives_and_binds_name_the_place_and_the_problem() {
    let base = text();
    let cases = [
        // MBDyn 1.7.3 stops on this file's `dof, 1, parameter, …` ("Parameter(1) must have
        // dofs at line …", as on its own tests/joints/plane/plane).
        ("dof, 3, structural, 1, algebraic", "dof, 1, parameter", "MBDyn 1.7.3 refuses it"),
        ("dof, 3, structural, 1, algebraic", "dof, 3, structural, 4, algebraic", "orientation parameters"),
        ("dof, 3, structural, 1, algebraic", "dof, 3, structural, 7, algebraic", "1 to 6, found 7"),
        ("dof, 3, structural, 1, algebraic", "dof, 13, structural, 1, algebraic", "no structural node 13"),
        ("dof, 3, structural, 1, algebraic", "dof, 3, abstract, 1, algebraic", "abstract"),
        ("dof, 3, structural, 1, algebraic", "dof, 3, structural, 1, string", "'algebraic' (position) or 'differential'"),
        ("element, 2, joint, string, \"rz\", linear", "element, 2, joint, string, \"Fx\", linear", "does not compute the private data \"Fx\" of revolute hinge 2"),
        ("element, 2, joint, string, \"rz\", linear", "element, 12, joint, string, \"rz\", linear", "there is no joint 12"),
        ("element, 2, joint, string, \"rz\", linear", "element, 2, joint, index, 1, linear", "by name"),
        ("element, 2, joint, string, \"rz\", linear", "element, 2, body, string, \"rz\", linear", "private data \"rz\" of body 2"),
        // MBDyn 1.7.3 on this file with the drive caller card above joint 4: "unable to find
        // Joint(4) at line …".
        ("drive caller: 1, element, 4", "drive caller: 1, element, 15", "there is no joint 15"),
        ("bind: 2, joint, 1, string", "bind: 7, joint, 1, string", "no joint 7 above this statement"),
        ("bind: 2, joint, 1, string", "bind: 2, joint, 3, string", "there is no parameter node 3"),
        ("parameter: 1, element;", "parameter: 1, value, 2.;", "parameter nodes 'value' are not supported"),
        ("parameter nodes: 1;", "parameter nodes: 2;", "declares 2 parameter nodes, the model has 1"),
    ];
    for (old, new, expected) in cases {
        assert!(base.contains(old), "{old}");
        let e = match from_text(&base.replacen(old, new, 1)) {
            Err(e) => e,
            Ok(_) => panic!("{new} must be refused"),
        };
        let line = base.lines().position(|l| l.contains(old)).unwrap() + 1;
        assert!(e.contains(&format!("element_drives.mbd:{line}:")) && e.contains(expected), "{new}: {e}");
    }
    // The drive caller card above the joint it reads (MBDyn: "unable to find Joint(4)").
    let card = "    drive caller: 1, element, 4, joint, string, \"rz\", linear, 0., -K;\n";
    let moved = base.replacen(card, "", 1).replacen("begin: elements;\n", &format!("begin: elements;\n{card}"), 1);
    let line = moved.lines().position(|l| l.contains("drive caller: 1, element")).unwrap() + 1;
    let e = from_text(&moved).err().unwrap();
    assert!(e.contains(&format!("element_drives.mbd:{line}:")) && e.contains("joint 4 is not defined above it"), "{e}");
    // A parameter node bound twice (MBDyn's j2p.cc: already bound).
    let twice = base.replacen("bind: 2, joint, 1, string, \"rz\";", "bind: 2, joint, 1, string, \"rz\";\n    bind: 2, joint, 1, string, \"wz\";", 1);
    let e = from_text(&twice).err().unwrap();
    assert!(e.contains("parameter node 1 is already bound"), "{e}");
}

/// `model::sf::NAME(x)` and `model::drive(LABEL, x)` in `set:` call the cards read above
/// the statement, as MBDyn's reader does (its tests/namespaces/model: "model::drive(LABEL,
/// 2.) expected: 21" for `linear, 1., 10.`); a card below is not defined there yet.
#[test]
fn set_calls_the_scalar_function_and_drive_caller_cards_above_it() {
    let base = text();
    let cards = "scalar function: \"f\", const, 3.;\nset: real A = model::sf::f(0.);\ndrive caller: 99, linear, 1., 10.;\nset: real B = model::drive(99, 2.);\nbegin: nodes;";
    let doc = parse_text(&base.replacen("begin: nodes;", cards, 1), &path("element_drives.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let value = |name: &str| doc.variables.real(name);
    assert_eq!((value("A"), value("B")), (Some(3.0), Some(21.0)));
    let below = base.replacen("begin: nodes;", "set: real B = model::drive(99, 2.);\ndrive caller: 99, linear, 1., 10.;\nbegin: nodes;", 1);
    let e = parse_text(&below, &path("element_drives.mbd")).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(e.contains("drive caller 99 is not defined"), "{e}");
}
