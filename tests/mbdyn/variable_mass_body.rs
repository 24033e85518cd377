//! Variable-mass rigid bodies (`body: …, variable mass`, body_vm.cc) and the template drive
//! caller cards of dimension 1, 6, "3x3", "6x6" (issue 12, "MBDyn files unchanged"):
//! `tests/mbdyn_files/variable_mass_body.mbd` against closed forms and MBDyn 1.7.3, the
//! element's Jacobian against finite differences, and the reader's errors.
//!
//! MBDyn numbers: MBDyn 1.7.3 (built from github:alex-marinov/mbdyn), `mbdyn -f
//! variable_mass_body.mbd -o out`, its .mov at t = 1 s (`output precision: 16`).

use crate::common;

use common::mbdyn::{assert_jacobians, read_test_file, test_file};
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::element::VariableBody;
use romdyn::element::drive::Drive;
use romdyn::input::mbdyn::{build, parse_text};
use romdyn::kinematics::{Mat3, Vec3};

const G: f64 = 9.81;

#[test]
fn a_body_losing_mass_moves_as_the_closed_forms_and_as_mbdyn() {
    let m = read_test_file("variable_mass_body.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    assert!((report.final_state.t - 1.0).abs() < 1e-12);
    let asm = Assembler::new(&m.model);
    let (n1, n2) = (report.final_state.node_frame(&asm.dofs, 0).kin, report.final_state.node_frame(&asm.dofs, 1).kin);

    // Node 1: m(t) = 2 − t, F = 1 N along x, gravity along −z. d(m v)/dt = F + m g + ṁ v,
    // so m v̇ = F + m g: v_x = (F/k) ln(m0/m), x = (F/k)(t − (m/k) ln(m0/m)), z = −g t²/2.
    let (t, m0, k, f): (f64, f64, f64, f64) = (1.0, 2.0, 1.0, 1.0);
    let mass = m0 - k * t;
    let (x, vx) = ((f / k) * (t - (mass / k) * (m0 / mass).ln()), (f / k) * (m0 / mass).ln());
    // The ms integration error on the logarithm (h = 1 ms): 3.8e-8 m, 3.7e-8 m/s.
    assert!((n1.x[0] - x).abs() < 5e-8, "x = {}, closed form {x}", n1.x[0]);
    assert!((n1.xdot[0] - vx).abs() < 5e-8, "ẋ = {}, closed form {vx}", n1.xdot[0]);
    // z and ż: the derivatives phase's dCoef g (1e-8) in the momenta, exact integration.
    for n in [&n1, &n2] {
        assert!((n.x[2] + G * t * t / 2.0).abs() < 2e-8 && (n.xdot[2] + G * t).abs() < 2e-8, "z = {}, ż = {}", n.x[2], n.xdot[2]);
    }
    // Node 2: J_zz = J_m + J_g = (1 − t/4) + (1 + t); only J_g's rate acts on the spin,
    // J ω̇ = −J̇_g ω: ω = (1 + 3t/8)^(−4/3), angle 8 (1 − (1 + 3t/8)^(−1/3)).
    let omega = (1.0 + 3.0 * t / 8.0_f64).powf(-4.0 / 3.0);
    let angle = 8.0 * (1.0 - (1.0 + 3.0 * t / 8.0_f64).powf(-1.0 / 3.0));
    let turned = n2.r[(1, 0)].atan2(n2.r[(0, 0)]);
    assert!((n2.omega[2] - omega).abs() < 5e-9, "ω = {}, closed form {omega}", n2.omega[2]);
    // The angle carries the integration error, 5.1e-8 rad (MBDyn's too).
    assert!((turned - angle).abs() < 1e-7, "angle {turned}, closed form {angle}");

    // MBDyn 1.7.3 on the same file, t = 1 s: node 1 x, ẋ, z, ż; node 2 angle (deg), ω_z.
    let mbdyn1 = [3.0685285703895820e-01, 6.9314714394731225e-01, -4.9050000098076199e+00, -9.8100000098127520e+00];
    let ours1 = [n1.x[0], n1.xdot[0], n1.x[2], n1.xdot[2]];
    for (a, b) in ours1.iter().zip(mbdyn1) {
        assert!((a - b).abs() < 1e-11, "node 1: romdyn {a}, MBDyn {b}");
    }
    let (mbdyn_angle, mbdyn_omega) = (4.6162696357605903e+01_f64.to_radians(), 6.5402808936388612e-01);
    assert!((turned - mbdyn_angle).abs() < 1e-12, "angle {turned}, MBDyn {mbdyn_angle}");
    assert!((n2.omega[2] - mbdyn_omega).abs() < 1e-11, "ω {}, MBDyn {mbdyn_omega}", n2.omega[2]);
}

/// A body with every drive varying: mass, centre of mass, both inertias.
fn varying_body(mbdyn_frames: bool) -> VariableBody {
    let sine = |w: f64, a: f64, v0: f64| Drive::Sine { t0: 0.0, omega: w, amplitude: a, cycles: None, v0 };
    let cosine = |w: f64, a: f64, v0: f64| Drive::Cosine { t0: 0.0, omega: w, amplitude: a, cycles: None, v0 };
    VariableBody {
        label: 7,
        node: 2,
        mass: Drive::Polynomial(vec![3.0, -1.5, 0.4]),
        offset: vec![(Vec3::new(0.2, -0.1, 0.3), sine(3.0, 0.5, 1.0)), (Vec3::new(0.0, 0.4, 0.0), Drive::Time)],
        inertia_mass: vec![(Mat3::new(2.0, 0.1, 0.0, 0.1, 1.5, 0.2, 0.0, 0.2, 1.0), cosine(2.0, 0.3, 1.0)), (Mat3::from_diagonal(&Vec3::new(0.1, 0.3, 0.2)), Drive::Time)],
        inertia_geometry: vec![(Mat3::new(1.0, 0.0, 0.3, 0.0, 2.0, 0.0, 0.3, 0.0, 1.0), Drive::Polynomial(vec![1.0, 0.7]))],
        mbdyn_frames,
    }
}

#[test]
fn the_variable_body_jacobian_matches_finite_differences_of_its_residual() {
    // Random node state (position, rotation, velocities, momenta perturbed), t = 0.3 s,
    // romdyn's frames and MBDyn 1.7.3's.
    for mbdyn_frames in [false, true] {
        assert_jacobians(|_| vec![Box::new(varying_body(mbdyn_frames))]);
    }
}

/// variable_mass_body.mbd with node 2 turned and tumbling, its body's mass a parabola and
/// its centre of mass moving (a cosine: MBDyn's derivatives phase does not start with a
/// nonzero rate, body_vm.cc `SetValue`), run to 0.4 s.
fn offset_and_spin() -> romdyn::input::mbdyn::MbdynModel {
    let text = std::fs::read_to_string(test_file("variable_mass_body.mbd")).unwrap();
    let text = text
        .replace("final time: 1.;", "final time: 0.4;")
        .replace("structural: 2, dynamic, null, eye, null, 0., 0., 1.;", "structural: 2, dynamic, null, euler, 10., 20., 30., null, 0.3, -0.5, 1.;")
        .replace("        1.,\n        null,\n        reference, 31,", "        parabolic, 1., -.2, .05,\n        single, .1, -.2, .3, cosine, 0., 3., .5, forever, 1.,\n        reference, 31,");
    assert!(text.contains("parabolic, 1., -.2, .05") && text.contains("final time: 0.4;") && text.contains("euler, 10."));
    parse_text(&text, &test_file("variable_mass_body.mbd")).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn the_variable_body_jacobian_holds_along_a_run_with_offsets_and_spin() {
    common::mbdyn::assert_jacobians_after_run(&mut offset_and_spin(), None, 0.37);
}

#[test]
fn with_mbdyn_frames_the_tumbling_body_with_moving_offset_follows_mbdyn() {
    // MBDyn 1.7.3 on offset_and_spin()'s text, node 2 at t = 0.4 s: position, velocity,
    // angular velocity.
    let mbdyn = [
        [-1.0567866959250933e-02, -9.0146622072396293e-02, -7.5790165796684639e-01],
        [6.0090433323590244e-02, -4.2974057155095369e-01, -3.8978992572242284e+00],
        [4.6016018775233392e-01, -5.6364822916352841e-01, 1.0033713712105305e+00],
    ];
    let node2 = |mbdyn_frames: bool| {
        let mut m = offset_and_spin();
        let k = m.model.elements.iter().position(|e| e.type_name() == "variable body" && e.label() == 2).unwrap();
        // Body 2 of the text, by hand, with the chosen frames.
        let e = |i: usize| {
            let mut u = Mat3::zeros();
            u[(i, i)] = 1.0;
            u
        };
        let cosine = Drive::Cosine { t0: 0.0, omega: 3.0, amplitude: 0.5, cycles: None, v0: 1.0 };
        m.model.elements[k] = Box::new(VariableBody {
            label: 2,
            node: 2,
            mass: Drive::Polynomial(vec![1.0, -0.2, 0.05]),
            offset: vec![(Vec3::new(0.1, -0.2, 0.3), cosine)],
            inertia_mass: vec![(e(0), Drive::Const(1.0)), (e(1), Drive::Const(1.0)), (e(2), Drive::Polynomial(vec![1.0, -0.25]))],
            inertia_geometry: vec![(e(0), Drive::Const(1.0)), (e(1), Drive::Const(1.0)), (e(2), Drive::Polynomial(vec![1.0, 1.0]))],
            mbdyn_frames,
        });
        let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
        let kin = report.final_state.node_frame(&Assembler::new(&m.model).dofs, 1).kin;
        [kin.x, kin.xdot, kin.omega]
    };
    let worst = |got: [Vec3; 3]| (0..3).flat_map(|i| (0..3).map(move |j| (i, j))).map(|(i, j)| (got[i][j] - mbdyn[i][j]).abs()).fold(0.0, f64::max);
    // The same residual as body_vm.cc: MBDyn to 4.9e-11 (m, m/s, rad/s).
    let same = worst(node2(true));
    assert!(same < 2e-10, "MBDyn's frames: {same:e} from MBDyn");
    // romdyn's frames (the inertia of the offset about the node turned with the node): the
    // motion differs by 2.4e-2 (m, m/s, rad/s).
    let own = worst(node2(false));
    eprintln!("node 2 from MBDyn 1.7.3: {same:e} with its frames, {own:e} with romdyn's");
    assert!(own > 1e-3, "romdyn's frames: {own:e} from MBDyn");
}

fn error(text: &str) -> String {
    match parse_text(text, std::path::Path::new("m.mbd")).and_then(|d| build(&d)) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.to_string(),
    }
}

fn with(cards: &str, body: &str) -> String {
    common::mbdyn::file(
        "structural nodes: 2; rigid bodies: 1;",
        "structural: 1, dynamic, null, eye, null, null;\nstructural: 2, static, null, eye, null, null;",
        &format!("{cards}\n{body}"),
    )
}

#[test]
fn bad_cards_and_bodies_are_refused_with_their_place() {
    let ok_body = "body: 1, 1, variable mass, 1., null, null, null;";
    let cases = [
        ("template drive caller: 5, 4, single, 1., const, 1.;", ok_body, "m.mbd:8:27: error: template drive caller 5: unsupported dimension 4 (MBDyn 1.7.3 reads 1, 3, 6, \"3x3\", \"6x6\")"),
        ("template drive caller: 5, \"2x2\", null;", ok_body, "m.mbd:8:27: error: template drive caller 5: unsupported dimension 2x2"),
        ("template drive caller: 5, 6, component, sym, 1., 1., 1., 1., 1., 1.;", ok_body, "'sym' and 'diag' apply to matrix template drive callers"),
        ("template drive caller: 5, \"6x6\", single, anba, 1.;", ok_body, "the 'anba' layout of a 6x6 matrix is not supported"),
        ("template drive caller: 5, 1, array, 0;", ok_body, "needs at least one drive"),
        ("template drive caller: 5, \"3x3\", null;\ntemplate drive caller: 5, \"3x3\", null;", ok_body, "template drive caller 5 of dimension 3x3 is defined twice (first at line 8)"),
        ("template drive caller: 5, 3, null;", "body: 1, 1, variable mass, 1., null, reference, 5, null;", "m.mbd:9:49: error: template drive caller 5 of dimension 3x3 is not defined (there is one of dimension 3)"),
        ("", "body: 1, 1, variable mass, piecewise linear, 2, 0., 1., 1., 0., null, null, null;", "m.mbd:9:28: error: variable body 1: the mass drive must be differentiable in time"),
        ("", "body: 1, 2, variable mass, 1., null, null, null;", "m.mbd:9:10: error: variable body 1: structural node 2 is not a dynamic node"),
    ];
    for (cards, body, needle) in cases {
        let e = error(&with(cards, body));
        assert!(e.contains(needle), "{needle:?} not in: {e}");
    }
}

#[test]
fn cards_of_every_dimension_are_read_and_a_label_may_name_one_of_each() {
    // The file defines label 31 in dimensions "3x3" and 1, and cards of dimension 6 and 6x6.
    let m = read_test_file("variable_mass_body.mbd");
    assert_eq!(m.model.elements.iter().filter(|e| e.type_name() == "variable body").count(), 2);
}
