//! String drives that read the model's state through MBDyn's `model` namespace (modelns.cc;
//! issue 12, point 3): `tests/mbdyn_files/state_drives.mbd` against closed forms and MBDyn
//! 1.7.3, the elements' Jacobians against finite differences with those drives held (their
//! derivatives are in no Jacobian, as in MBDyn), the refusal to linearize, and the errors.

use crate::common;

use common::mbdyn::{assert_jacobians_after_run, assert_not_linearized, read_test_file, test_file as path};
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{build, parse_text, read_model, MbdynModel};
use romdyn::kinematics::euler123;

fn text(name: &str) -> String {
    std::fs::read_to_string(path(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn from_text(t: &str) -> Result<MbdynModel, String> {
    parse_text(t, &path("state_drives.mbd")).and_then(|d| build(&d)).map_err(|e| e.to_string())
}

#[test]
fn state_reading_drives_give_the_closed_forms_and_mbdyns_motion() {
    let m = read_model(&path("state_drives.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = |k: usize| report.final_state.node_frame(&asm.dofs, k).kin;
    let (c, k): (f64, f64) = (0.8, 4.0);
    let w = k.sqrt();
    let zeta = c / (2.0 * w);
    let wd = w * (1.0 - zeta * zeta).sqrt();
    // Closed forms at t = 1 s (file header): drag x = x0 + v0 (1 − e^{−C t})/C, springs
    // x0 cos(√K t), the torsional spring θ = (w0/√K) sin(√K t) [deg for Euler 1-2-3], the
    // damped oscillator of the node drive callers.
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, 1727489e) on this file, `output
    // precision: 16`, last row of its .mov: x of node 1, z of node 1, x of node 2, y of
    // node 3, x of node 4, Euler 1-2-3 angle z of node 6, x of node 7.
    let cases = [
        ("node 1 x", kin(0).x[0], 2.0 * (1.0 - (-c).exp()) / c, 1.3766776455161494e+00),
        ("node 1 z", kin(0).x[2], 1.0 * (1.0 - (-c).exp()) / c, 6.8833882275807468e-01),
        ("node 2 x", kin(1).x[0], 0.3 * w.cos(), -1.2484383556973308e-01),
        ("node 3 y", kin(2).x[1], 0.2 * w.cos(), -8.3229223713156428e-02),
        ("node 4 x", kin(3).x[0], 1.0 + 0.5 * w.cos(), 7.9192694071713010e-01),
        ("node 6 θz [deg]", euler123(&kin(5).r)[2].to_degrees(), (0.5 / w * w.sin()).to_degrees(), 1.3024730932881960e+01),
        ("node 7 x", kin(6).x[0], 0.4 * (-zeta * w).exp() * (wd.cos() + zeta * w / wd * wd.sin()), -5.0993626283280628e-02),
    ];
    for (what, x, exact, mbdyn) in cases {
        eprintln!("{what}: {x:.15e}, closed form {exact:.15e}, MBDyn {mbdyn:.15e}");
        // ms with ρ∞ = 0.6 and h = 1 ms on these smooth motions: within 1e-5 relative.
        assert!((x - exact).abs() < 1e-5 * exact.abs(), "{what}: {x} against the closed form {exact}");
        // Same method and steps as MBDyn, each Newton iteration converged to a residual of
        // 1e-10 with the drive's derivatives missing from the Jacobian in both programs
        // (measured 1.1e-9 m apart on node 1, 5.1e-10 m on node 7): 5e-9 relative to the
        // value or to the largest amplitude of these motions, 0.4 m.
        assert!((x - mbdyn).abs() < 5e-9 * mbdyn.abs().max(0.4), "{what}: {x} against MBDyn {mbdyn}");
    }
    // The velocity of the drag's node: v0 e^{−C t}, MBDyn 8.9865788198730479e-01.
    assert!((kin(0).xdot[0] - 8.9865788198730479e-01).abs() < 5e-9, "{:?}", kin(0).xdot);
}

/// A follower force with an arm (its Jacobian is not zero) whose drive reads other nodes'
/// distance and velocity and its own node's rotation: the element's Jacobian equals
/// central differences of its residual with the drive held at the state checked.
#[test]
fn jacobians_hold_state_reading_drives_at_the_checked_state() {
    let t = text("state_drives.mbd")
        .replace("    forces: 8;", "    forces: 9;")
        .replace(
            "end: elements;",
            "    force: 10, follower, 1, position, 0.1, 0.2, 0.3, 1., 2., 3.,\n        string, \"2. + model::distance(4, 1)*model::xvelocity(2) + model::yangle(1)\";\nend: elements;",
        );
    let checks = assert_jacobians_after_run(&mut from_text(&t).unwrap(), Some(0.2), 1e-3);
    let force = checks.iter().find(|c| c.element == "follower force 10").unwrap();
    // The follower force depends on node 1's rotation: a non-zero block, c ∂f/∂θ with c = 1e-3 s.
    eprintln!("{force:?}");
    assert!(force.drive_held && force.analytic.abs() > 1e-4, "{force:?}");
    for c in &checks {
        // Central differences on the library's elements: about 1e-9 (analysis::check).
        assert!(c.within(1e-7), "{c:?}");
    }
}

#[test]
fn a_model_whose_drives_read_the_state_is_not_linearized() {
    let why = "the drag's damping is in no Jacobian: the linearization would be wrong";
    assert_not_linearized(&read_test_file("state_drives.mbd"), &["absolute force 1", "reads the model's state"], why);
}

#[test]
fn bad_model_namespace_calls_name_the_place_and_the_problem() {
    let base = text("state_drives.mbd");
    let cases = [
        ("-K*model::xposition(2)", "-K*model::xposition(12)", "the file declares no structural node 12"),
        ("-K*model::xposition(2)", "-K*model::xposition_prev(2)", "previous time step"),
        ("-K*model::xposition(2)", "-K*model::element::joint(5, \\\"L\\\")", "romdyn does not compute the private data \"L\" of clamp 5"),
        ("-K*model::xposition(2)", "-K*model::xposition(2, 3)", "takes 1 node label(s), found 2"),
        ("-K*model::xposition(2)", "-K*model::unitvec(2, 3)", "unknown function 'model::unitvec'"),
        ("model::node::structural(3, \\\"X[2]\\\")", "model::node::structural(3, \\\"E[2]\\\")", "Euler angles"),
        ("-K*model::drive(1, Time)", "-K*model::drive(9, Time)", "drive caller 9 is not defined"),
        ("\"XP[1]\", linear", "\"XPP[1]\", linear", "accelerations are not supported"),
        ("node, 7, structural, string, \"X[1]\"", "node, 17, structural, string, \"X[1]\"", "declares no structural node 17"),
        ("node, 7, structural, string, \"X[1]\"", "node, 7, abstract, string, \"X[1]\"", "the file declares no abstract node 7"),
    ];
    for (old, new, expected) in cases {
        assert!(base.contains(old), "{old}");
        let e = match from_text(&base.replacen(old, new, 1)) {
            Err(e) => e,
            Ok(_) => panic!("{new} must be refused"),
        };
        let line = base.lines().position(|l| l.contains(old)).unwrap() + 1;
        assert!(e.contains(&format!("state_drives.mbd:{line}:")) && e.contains(expected), "{new}: {e}");
    }
    // An imposed-motion joint whose drive reads the state is read (evaluated at the
    // iterate, as MBDyn's: tests/mbdyn/mbdyn_element_drives.rs checks one against MBDyn 1.7.3).
    let m = from_text(&base.replace("joint: 5, clamp, 5, node, node;", "joint: 5, drive displacement pin, 5, null, null, 1., 0., 0., string, \"model::xposition(2)\";")).unwrap();
    assert!(m.model.elements.iter().any(|e| e.type_name() == "drive displacement pin" && e.reads_state()));
    // `set:` while the file is read sees the nodes above it only (MBDyn reads in order).
    let line = base.lines().position(|l| l == "set: real K = 4.;").unwrap() + 1;
    let e = from_text(&base.replace("set: real K = 4.;", "set: real K = model::xposition(2);")).err().unwrap();
    assert!(e.contains(&format!("state_drives.mbd:{line}:")) && e.contains("there is no structural node 2") && e.contains("only the nodes above"), "{e}");
}
