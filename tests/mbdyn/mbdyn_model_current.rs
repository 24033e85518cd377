//! MBDyn's `model::current` (the data an element card publishes while part of it is read:
//! a distance joint's `"L"` in its drive, a rod's `"L0"` and `"L"` in its law; joint.cc,
//! modelns.cc) and `model::element::TYPE(LABEL, "NAME")` while the file is read (an
//! element's private data, modelns.cc `model_elem`), issue 12: the motion of
//! `tests/mbdyn_files/model_current.mbd` against MBDyn 1.7.3 and closed forms, the values
//! MBDyn's `tests/namespaces/model` expects, and the errors.

use crate::common;

use common::mbdyn::{file, test_file as path, variables};
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{build, parse_text, read_model};

fn error(text: &str) -> String {
    match parse_text(text, std::path::Path::new("m.mbd")).and_then(|d| build(&d)) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn distance_and_rod_read_model_current_as_mbdyn() {
    let m = read_model(&path("model_current.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let x = |k: usize| report.final_state.node_frame(&asm.dofs, k).kin.x;
    let (bob, mass) = (x(1), x(2));
    // The distance's drive took model::current("L") = 1 (the written length): the length is
    // DESIRED_DISTANCE = 1.5 from t = 0.5 s on.
    assert!((bob.norm() - 1.5).abs() < 1e-9, "{bob:?}");
    // The rod's law took EA = K L0 with L0 = 0.9 (its length as input) and the viscosity
    // C L with L = 1 (the distance as written): a mass m = 2 on a spring k = EA/L0 = 200 N/m
    // with damping c = C L/L0 under gravity, from rest at l = 1: the closed form of the
    // damped oscillator about l = L0 + m g/k at t = 1 s, -1.0971440434872501 m (the
    // integrator's error with h = 1 ms, measured 6.7e-8 m, inside 2e-7).
    let (m2, k, c, g) = (2.0f64, 200.0f64, 2.0 / 0.9, 9.81);
    let leq = 0.9 + m2 * g / k;
    let (w, zeta) = ((k / m2).sqrt(), c / (2.0 * (k * m2).sqrt()));
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let l = leq + (1.0 - leq) * (-zeta * w).exp() * (wd.cos() + zeta * w / wd * wd.sin());
    assert!((mass[1] - (-0.1 - l)).abs() < 2e-7, "{mass:?} against {}", -0.1 - l);
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, 1727489e) on
    // tests/mbdyn_files/model_current.mbd, `output precision: 16`, last row of its .mov:
    // node 2 x, y and node 3 y. Same method, steps and tolerance: measured 4e-14 m apart;
    // 1e-11 m.
    let mbdyn = [(bob[0], -9.6256775873598432e-01), (bob[1], -1.1504187541247686e+00), (mass[1], -1.0971439763635706e+00)];
    for (got, expected) in mbdyn {
        assert!((got - expected).abs() < 1e-11, "{got} against MBDyn {expected}");
    }
}

/// A name the card does not publish, or `model::current` where no card publishes: a clean
/// error at the call (MBDyn: "model::current(NAME) not defined").
#[test]
fn model_current_outside_what_a_card_publishes_is_a_clean_error() {
    let nodes = "structural: 1, static, null, eye, null, null;\nstructural: 2, dynamic, 1., 0., 0., eye, null, null;";
    let control = "structural nodes: 2; joints: 2; rigid bodies: 1;";
    let elements = |joint: &str| format!("joint: 1, clamp, 1, node, node;\nbody: 2, 2, 1., null, eye;\n{joint}");
    let cases = [
        ("joint: 2, distance, 1, 2,\n  const, model::current(\"L0\");", 11, 10, "model::current(\"L0\") is not defined: this part of the card publishes \"L\""),
        ("joint: 2, rod, 1, 2, 1.,\n  linear elastic, model::current(\"X\");", 11, 19, "model::current(\"X\") is not defined: this part of the card publishes \"L0\" and \"L\""),
        ("joint: 2, rod, 1, 2,\n  model::current(\"L\"), linear elastic, 1.;", 11, 3, "model::current(\"L\") is not defined here"),
        ("joint: 2, distance, 1, position,\n  model::current(\"L\"), 0., 0., 2, from nodes;", 11, 3, "is not defined here"),
        ("joint: 2, distance, 1, 2,\n  const, model::current(1.);", 11, 10, "takes the name of a datum in double quotes"),
    ];
    for (joint, line, column, expected) in cases {
        let e = error(&file(control, nodes, &elements(joint)));
        assert!(e.contains(&format!("m.mbd:{line}:{column}:")) && e.contains(expected), "{joint}: {e}");
    }
    // In `set:`, read while no card publishes anything.
    let text = format!("set: real x = model::current(\"L\");\n{}", file(control, nodes, &elements("joint: 2, distance, 1, 2, from nodes;")));
    let e = error(&text);
    assert!(e.contains("m.mbd:1:15:") && e.contains("is not defined here"), "{e}");
    // An assignment inside an argument that waits for the card is refused.
    let e = error(&file(control, nodes, &elements("joint: 2, distance, 1, 2,\n  const, (real y = model::current(\"L\")) + 1.;")));
    assert!(e.contains("m.mbd:11:10:") && e.contains("cannot declare or assign"), "{e}");
}

/// What MBDyn's `tests/namespaces/model` expects of `model::element::body(2, "V")` while
/// the file is read (its remark: "expected: 0", MBDyn 1.7.3 prints 0: the gravity element
/// is linked to the bodies after all elements are read), with the kinetic energy and mass
/// of the same body (body.cc `Body::dGetPrivData`: ½ m v·v = ½ 0.01 · 14).
#[test]
fn model_element_reads_a_body_written_above() {
    let nodes = "structural: 1, static, null, eye, null, null;\nstructural: 2, dynamic, 1., 2., 3., eye, -1., -2., -3., null;";
    let elements = "joint: 1, clamp, 1, node, node;\nbody: 2, 2, 1.e-2, null, eye;\n\
        set: (model::node::structural(2, \"X[1]\"); x = -999);\n\
        set: real V = model::element::body(2, \"V\");\n\
        set: real E = model::element::body(2, \"E\");\n\
        set: real M = model::element::body(2, \"m\");\n\
        gravity: uniform, 0., 0., -1., const, 9.81;";
    let text = format!("set: real x = 0.;\n{}", file("structural nodes: 2; joints: 1; rigid bodies: 1; gravity;", nodes, elements));
    let v = variables(&text);
    assert_eq!(v.real("x"), Some(-999.0));
    assert_eq!(v.real("V"), Some(0.0));
    assert!((v.real("E").unwrap() - 0.5 * 0.01 * 14.0).abs() < 1e-15, "{:?}", v.real("E"));
    assert_eq!(v.real("M"), Some(0.01));
    // With an offset centre of mass and a spin (body.cc): v_G = v + ω × R x_G =
    // (−1, −1, −3), E = ½ (m v_G·v_G + Ωᵀ J Ω) = ½ (0.01 · 11 + 3 · 2²) = 6.055; MBDyn
    // 1.7.3 remarks "E", 6.055 on the same lines (measured 2026-12-03).
    let spinning = "structural: 1, static, null, eye, null, null;\nstructural: 2, dynamic, 1., 2., 3., eye, -1., -2., -3., 0., 0., 2.;";
    let body = "joint: 1, clamp, 1, node, node;\nbody: 2, 2, 1.e-2, 0.5, 0., 0., diag, 1., 2., 3.;\nset: real E = model::element::body(2, \"E\");";
    let v = variables(&file("structural nodes: 2; joints: 1; rigid bodies: 1;", spinning, body));
    assert!((v.real("E").unwrap() - 6.055).abs() < 1e-13, "{:?}", v.real("E"));
    // In a card's numbers: a force of the body's mass times 100.
    let force = "force: 2, absolute, 2, position, null, 0., 0., 1., const, 100.*model::element::body(2, \"m\");";
    let m = common::mbdyn::read(&file("structural nodes: 2; joints: 1; rigid bodies: 1; forces: 1;", nodes, &format!("joint: 1, clamp, 1, node, node;\nbody: 2, 2, 1.e-2, null, eye;\n{force}")));
    assert_eq!(m.model.elements.len(), 3);
}

#[test]
fn model_element_errors_name_the_element_and_the_datum() {
    let nodes = "structural: 1, static, null, eye, null, null;\nstructural: 2, dynamic, 1., 2., 3., eye, null, null;";
    let control = "structural nodes: 2; joints: 1; rigid bodies: 1; forces: 1;";
    let head = "joint: 1, clamp, 1, node, node;\nbody: 2, 2, 1.e-2, null, eye;\n";
    let cases = [
        ("set: real x = model::element::body(3, \"E\");", "there is no body 3 above this statement"),
        ("set: real x = model::element::body(2, \"Q\");", "does not compute the private data \"Q\" of body 2"),
        ("set: real x = model::element::aerodynamic(2, \"E\");", "romdyn reads the private data of bodies and joints"),
        // In a string drive the element may be anywhere in the elements block (read during
        // the run, tests/mbdyn/mbdyn_string_element_reads.rs), but must exist.
        ("force: 2, absolute, 2, position, null, 0., 0., 1., string, \"model::element::body(3, \\\"E\\\")\";", "there is no body 3 in the elements block"),
    ];
    for (statement, expected) in cases {
        let e = error(&file(control, nodes, &format!("{head}{statement}")));
        assert!(e.contains("m.mbd:10:") && e.contains(expected), "{statement}: {e}");
    }
}
