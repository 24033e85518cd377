//! `model::element::TYPE(LABEL, "NAME")` inside `string` drives, read during the run
//! (MBDyn's modelns.cc `model_elem`: the element's `dGetPrivData` when the expression is
//! evaluated): `tests/mbdyn_files/string_element_reads.mbd` against closed forms and MBDyn
//! 1.7.3, the Jacobians with those drives held, the refusal to linearize, and the errors.

use crate::common;

use common::mbdyn::{assert_jacobians_after_run, assert_not_linearized, read_test_file, test_file as path};
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{build, parse_text};
use romdyn::kinematics::euler123;

const FILE: &str = "string_element_reads.mbd";

#[test]
fn string_drives_of_private_data_give_the_closed_forms_and_mbdyns_motion() {
    let m = read_test_file(FILE);
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let kin = |k: usize| report.final_state.node_frame(&asm.dofs, k).kin;
    let (c, k, d, ks, l0): (f64, f64, f64, f64, f64) = (0.8, 4.0, 0.5, 1.0, 2.0);
    let w = k.sqrt();
    let zeta = c / (2.0 * w);
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let decay = (-zeta * w).exp();
    // Closed forms at t = 1 s (file header).
    let theta2 = (0.5 / wd * decay * wd.sin()).to_degrees();
    let spin2 = 0.5 / wd * decay * (wd * wd.cos() - zeta * w * wd.sin());
    let (x3, v3) = (0.3 + 2.0 / d * (1.0 + d).ln(), 2.0 / (1.0 + d));
    let theta4 = (-0.3 / w * w.sin()).to_degrees();
    let w5 = (3.0 + ks).sqrt();
    let (x5, v5) = (l0 + 0.1 * w5.cos(), -0.1 * w5 * w5.sin());
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, 1727489e) on this file, `output
    // precision: 16`, last row of its .mov (`mbdyn -f string_element_reads.mbd`).
    let cases = [
        ("node 2 θz [deg]", euler123(&kin(1).r)[2].to_degrees(), theta2, 9.0682448938937572e+00, 14.0),
        ("node 2 ωz", kin(1).omega[2], spin2, -1.9035861855156702e-01, 0.5),
        ("node 3 x", kin(2).x[0], x3, 1.9218604537574699e+00, 2.0),
        ("node 3 vx", kin(2).xdot[0], v3, 1.3333332889122100e+00, 2.0),
        ("node 4 θz [deg]", euler123(&kin(3).r)[2].to_degrees(), theta4, -7.8148385614801885e+00, 14.0),
        ("node 4 ωz", kin(3).omega[2], -0.3 * w.cos(), 1.2484383587679825e-01, 0.3),
        ("node 5 x", kin(4).x[0], x5, 1.9583853881434703e+00, 0.1),
        ("node 5 vx", kin(4).xdot[0], v5, -1.8185955106989157e-01, 0.2),
    ];
    for (what, x, exact, mbdyn, scale) in cases {
        eprintln!("{what}: {x:.15e}, closed form {exact:.15e}, MBDyn {mbdyn:.15e}");
        // ms with ρ∞ = 0.6 and h = 1 ms on these smooth motions: 1e-5 of the amplitude
        // `scale` (measured: at most 7.2e-7 of it, node 5's x, 1.9583853881 against
        // 1.9583853163 m).
        assert!((x - exact).abs() < 1e-5 * scale, "{what}: {x} against the closed form {exact}");
        // Same method, steps and Newton iterations as MBDyn, each converged to 1e-10 with
        // the drives' derivatives missing from the Jacobian in both: measured 1e-13 of the
        // amplitude at most (node 5's vx, 9.7e-15 m/s); 1e-10 of it.
        assert!((x - mbdyn).abs() < 1e-10 * scale, "{what}: {x} against MBDyn {mbdyn}");
    }
    // MBDyn 1.7.3's .out on this file: "total Jacobian matrices: 3002", one per Newton
    // iteration over its 1000 steps and the derivatives phase; romdyn iterates as often.
    assert_eq!(report.newton_iterations + report.derivatives_iterations, 3002);
}

/// The elements' Jacobians equal central differences of their residuals with the string
/// drives held at the checked state (their reads are in no Jacobian, as in MBDyn).
#[test]
fn jacobians_hold_the_string_drives_at_the_checked_state() {
    let checks = assert_jacobians_after_run(&mut read_test_file(FILE), Some(0.2), 1e-3);
    let held: Vec<&str> = checks.iter().filter(|c| c.drive_held).map(|c| c.element.as_str()).collect();
    for name in ["follower couple 2", "absolute force 3", "follower couple 4", "absolute force 5"] {
        assert!(held.contains(&name), "{name} not among the elements with drives held: {held:?}");
    }
}

#[test]
fn a_model_whose_string_drives_read_elements_is_not_linearized() {
    let why = "the torsional springs' stiffness is in no Jacobian: the linearization would be wrong";
    assert_not_linearized(&read_test_file(FILE), &["reads the model's state"], why);
}

/// An element that does not exist, a datum romdyn does not compute, and a type it does not
/// read: the place of the string drive, the call, the element. MBDyn 1.7.3 stops on the
/// first at the drive's first evaluation ("model::element: unable to find Joint(12)"),
/// romdyn once the elements block is read.
#[test]
fn bad_element_reads_in_string_drives_name_the_place_and_the_problem() {
    let base = std::fs::read_to_string(path(FILE)).unwrap_or_else(|e| panic!("{e}"));
    let from_text = |t: &str| parse_text(t, &path(FILE)).and_then(|d| build(&d)).err().map(|e| e.to_string());
    let old = "string, \"-D*model::element::body(3, \\\"E\\\")\"";
    let cases = [
        ("body(3, \\\"E\\\")", "joint(12, \\\"E\\\")", "model::element::joint(12, \"E\"): there is no joint 12 in the elements block"),
        ("body(3, \\\"E\\\")", "body(3, \\\"Q\\\")", "romdyn does not compute the private data \"Q\" of body 3"),
        ("body(3, \\\"E\\\")", "joint(1, \\\"rz\\\")", "romdyn does not compute the private data \"rz\" of clamp 1"),
        ("body(3, \\\"E\\\")", "aerodynamic(3, \\\"E\\\")", "romdyn reads the private data of bodies and joints"),
        ("body(3, \\\"E\\\")", "body(-3, \\\"E\\\")", "expected a element label"),
    ];
    let line = base.lines().position(|l| l.contains(old)).unwrap() + 1;
    let column = base.lines().nth(line - 1).and_then(|l| l.find('"')).unwrap() + 1;
    for (from, to, expected) in cases {
        let changed = base.replacen(&old.to_string(), &old.replace(from, to), 1);
        assert_ne!(changed, base);
        let e = from_text(&changed).unwrap_or_else(|| panic!("{to} must be refused"));
        assert!(e.contains(&format!("{FILE}:{line}:{column}:")) && e.contains(expected), "{to}: {e}");
    }
}

/// A body's potential energy "V" read during the run includes the gravity field (MBDyn
/// links the gravity element to the bodies after the elements block; while the file is read
/// "V" is 0, tests/mbdyn/mbdyn_model_current.rs): a 2 kg body falling from z = 1 m, pushed along
/// x by `V = m g z`: ẍ = g z = g (1 − g t²/2), x(1 s) = g (1/2 − g/24).
#[test]
fn a_bodys_potential_energy_read_during_the_run_includes_gravity() {
    let text = "begin: data; problem: initial value; end: data;\n\
        begin: initial value; initial time: 0.; final time: 1.; time step: 1.e-3; method: ms, .6;\n\
        tolerance: 1.e-10; max iterations: 50; derivatives tolerance: 1.e-6; end: initial value;\n\
        begin: control data; structural nodes: 1; rigid bodies: 1; forces: 1; gravity; end: control data;\n\
        begin: nodes; structural: 1, dynamic, 0., 0., 1., eye, null, null; end: nodes;\n\
        begin: elements;\n\
        body: 1, 1, 2., null, diag, 1., 1., 1.;\n\
        gravity: uniform, 0., 0., -1., const, 9.81;\n\
        force: 1, absolute, 1, position, null, 1., 0., 0., string, \"model::element::body(1, \\\"V\\\")\";\n\
        end: elements;\n";
    let m = common::mbdyn::read(text);
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let x = report.final_state.node_frame(&Assembler::new(&m.model).dofs, 0).kin.x[0];
    let g = 9.81;
    let exact = g * (0.5 - g / 24.0);
    // ms, h = 1 ms: measured 1.1e-5 relative (0.8951529719 against 0.8951625 m).
    assert!((x - exact).abs() < 1e-4 * exact, "x {x} against the closed form {exact}");
    // MBDyn 1.7.3 on this text with `output precision: 16` added (last .mov row):
    // 8.9515297193002552e-01 m; measured 1.6e-14 m apart; 1e-10 m.
    assert!((x - 8.9515297193002552e-01).abs() < 1e-10, "x {x} against MBDyn");
}

/// MBDyn counts the turns of a hinge's `rz` (planej.cc `NTheta`) and of a total pin joint's
/// `rz` (totalj.cc `Unwrap`) across the accepted steps: bodies spun at 10 and −7 rad/s,
/// each pushing a free 1 kg body along x by its joint's `rz = ω t` (10 rad after 1 s, past
/// π): x = ω t³/6 (romdyn gave the wrapped angle before).
#[test]
fn a_hinges_and_a_total_pin_joints_rz_count_the_turns() {
    let text = "\
        begin: data; problem: initial value; end: data;\n\
        begin: initial value; initial time: 0.; final time: 1.; time step: 1.e-3; method: ms, .6;\n\
        tolerance: 1.e-10; max iterations: 50; derivatives tolerance: 1.e-6; end: initial value;\n\
        begin: control data; structural nodes: 5; rigid bodies: 4; joints: 3; forces: 2; end: control data;\n\
        begin: nodes;\n\
        structural: 1, static, null, eye, null, null;\n\
        structural: 2, dynamic, null, eye, null, 0., 0., 10.;\n\
        structural: 3, dynamic, 0., 3., 0., eye, null, null;\n\
        structural: 4, dynamic, 0., 0., 4., eye, null, 0., 0., -7.;\n\
        structural: 5, dynamic, 0., 5., 0., eye, null, null;\n\
        end: nodes;\n\
        begin: elements;\n\
        joint: 1, clamp, 1, node, node;\n\
        joint: 2, revolute hinge,\n\
            1, reference, node, null, hinge, reference, node, eye,\n\
            2, reference, node, null, hinge, reference, node, eye;\n\
        joint: 4, total pin joint, 4, position, reference, node, null, position orientation, reference, node, eye, rotation orientation, reference, node, eye,\n\
            position, 0., 0., 4., position orientation, eye, rotation orientation, eye,\n\
            position constraint, active, active, active, null, orientation constraint, active, active, inactive, null;\n\
        body: 2, 2, 1., null, diag, 1., 1., 1.;\n\
        body: 3, 3, 1., null, diag, 1., 1., 1.;\n\
        body: 4, 4, 1., null, diag, 1., 1., 1.;\n\
        body: 5, 5, 1., null, diag, 1., 1., 1.;\n\
        force: 3, absolute, 3, position, null, 1., 0., 0., string, \"model::element::joint(2, \\\"rz\\\")\";\n\
        force: 5, absolute, 5, position, null, 1., 0., 0., string, \"model::element::joint(4, \\\"rz\\\")\";\n\
        end: elements;\n";
    let m = common::mbdyn::read(text);
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let dofs = Assembler::new(&m.model).dofs;
    let x = |k: usize| report.final_state.node_frame(&dofs, k).kin.x[0];
    // MBDyn 1.7.3 on this text with `output precision: 16` added (last .mov rows of nodes
    // 3 and 5).
    for (what, x, omega, mbdyn) in [("node 3", x(2), 10.0, 1.6666758989752248e+00), ("node 5", x(4), -7.0, -1.1666701867212506e+00)] {
        let exact = omega / 6.0;
        // ms, h = 1 ms: measured 5.5e-6 relative (1.6666759 against 1.6666667 m).
        assert!((x - exact).abs() < 1e-4 * exact.abs(), "{what}: x {x} against the closed form {exact}");
        // Measured 4.4e-15 m apart; 1e-10 m.
        assert!((x - mbdyn).abs() < 1e-10, "{what}: x {x} against MBDyn {mbdyn}");
    }
    // MBDyn 1.7.3's log on this text: "total Jacobian matrices: 2000".
    assert_eq!(report.newton_iterations + report.derivatives_iterations, 2000);
}
