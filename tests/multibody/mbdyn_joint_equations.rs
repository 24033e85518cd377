//! Joints whose equations are more than a holonomic constraint with its reaction (issue 12):
//! the `total equation` with its `total internal reaction` (MBDyn's
//! tests/joints/total/totaleq), the Tikhonov `joint regularization` (tests/stiff/pendulum_reg)
//! the `angular acceleration` (tests/joints/angularacceleration) and the `viscous body`
//! (tests/joints/viscousbody):
//! analytic Jacobians against central finite differences of the residual (1e-6 relative, as
//! tests/multibody/mbdyn_joints.rs), test files of `tests/mbdyn_files/` in MBDyn's style checked
//! against closed forms and against MBDyn 1.7.3's output on the same files (recorded here
//! with the file's name; MBDyn is never run by the tests), and the errors of bad cards.

use crate::common;
use common::mbdyn::{read_test_file as read, test_file as path};

use std::path::Path;

use common::fixtures::Noise;
use common::mbdyn::assert_jacobians;
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::element::drive::Drive;
use romdyn::element::{Anchor, AngularAcceleration, ViscousBody, DrivenJoint, Joint, Tikhonov, TotalEquation, TotalReaction, VectorDrive};
use romdyn::input::mbdyn::{build, parse_text, read_model_text, MbdynModel, SetOverrides};
use romdyn::kinematics::Vec3;



fn node(label: u32, n: &mut Noise) -> Anchor {
    Anchor::Node { label, offset: n.vec(), orientation: n.rotation() }
}

/// A total equation between `a` and `b` locking position x, z and rotation y, x and z
/// imposed by drives in time.
fn equation(label: u32, a: Anchor, b: Anchor) -> DrivenJoint {
    let mut j = DrivenJoint::new(Joint::total(label, a, b, [true, false, true], [false, true, false]), "total joint");
    j.position = VectorDrive(vec![(Vec3::new(0.2, 0.0, -0.1), Drive::Ramp { slope: 0.4, t0: 0.0, t1: 9.0, v0: 0.1 })]);
    j
}

/// A reaction reading three multipliers: position y, rotations x and z of its frames.
fn reaction(label: u32, a: Anchor, b: Anchor, n: &mut Noise) -> TotalReaction {
    let a_rotation = match &a {
        Anchor::Node { label, offset, .. } => Anchor::Node { label: *label, offset: *offset, orientation: n.rotation() },
        Anchor::Ground { position, .. } => Anchor::Ground { position: *position, orientation: n.rotation() },
    };
    TotalReaction { label, a_position: a, a_rotation, b, position_active: [false, true, false], rotation_active: [true, false, true] }
}

#[test]
fn total_equation_jacobian_matches_finite_differences() {
    // The equation on nodes 2–3 with its reactions on 1–2 and 3–1 (nodes shared between
    // the parts), and one on the ground and node 3 with its reaction on 2–3.
    assert_jacobians(|n| {
        let eq = equation(10, node(2, n), node(3, n));
        let reactions = vec![reaction(11, node(1, n), node(2, n), n), reaction(12, node(3, n), node(1, n), n)];
        let ground = Anchor::Ground { position: n.vec(), orientation: n.rotation() };
        let eq2 = equation(20, ground, node(3, n));
        let r2 = vec![reaction(21, node(2, n), node(3, n), n)];
        vec![Box::new(TotalEquation::new(eq, reactions)), Box::new(TotalEquation::new(eq2, r2))]
    });
}

#[test]
fn tikhonov_regularization_jacobian_matches_finite_differences() {
    // A spherical hinge and a driven total joint, each equation relaxed by its own C.
    assert_jacobians(|n| {
        let hinge = Joint::spherical_hinge(1, node(2, n), node(3, n));
        let total = equation(2, node(1, n), node(2, n));
        vec![Box::new(Tikhonov { inner: Box::new(hinge), c: vec![1e-3, 2e-2, 0.5] }), Box::new(Tikhonov { inner: Box::new(total), c: vec![0.3, 1e-4, 7e-2] })]
    });
}

#[test]
fn total_equation_moves_the_end_mass_as_the_closed_form_and_mbdyn() {
    // total_equation_two_masses.mbd at t = 0.8 s: node 2 at L + A sin(W t) (imposed), node 1
    // at A (1 − M2 W²/K) sin(W t) with K = EA/L = 100 N/m (closed form, see the file);
    // the actuator force, the equation's multiplier, is −(M1 x1'' + M2 x2'') on node 1 (the
    // reaction applies −λ to D, as a total joint's) = W² (M1 x1 + M2 A sin(W t)).
    let m = read("total_equation_two_masses.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let x = |i: usize| report.final_state.node_frame(&asm.dofs, i).kin.x;
    let (a, w, m1, m2, k, t) = (0.1, 2.0 * std::f64::consts::PI, 1.0, 0.5, 100.0, 0.8);
    let (x1, x2) = (a * (1.0 - m2 * w * w / k) * (w * t).sin(), 1.0 + a * (w * t).sin());
    // Integration error of ms(0.6) with h = 1 ms on the imposed motion: 1.5e-7 m measured.
    assert!((x(1)[0] - x1).abs() < 1e-6, "node 1 x {} against the closed form {x1}", x(1)[0]);
    assert!((x(2)[0] - x2).abs() < 1e-12, "node 2 x {} against the imposed {x2}", x(2)[0]);
    assert!(x(1)[1].abs() + x(1)[2].abs() + x(2)[1].abs() + x(2)[2].abs() < 1e-12);
    // MBDyn 1.7.3 (1727489e) on the same file, .mov at t = 0.8 s: node 1 x =
    // -7.6332401728358271e-02 m, node 2 x = 9.0489434837048477e-01 m (agreement measured
    // 9.3e-12 m and 0).
    assert!((x(1)[0] - -7.6332401728358271e-02).abs() < 1e-10, "node 1 x {} against MBDyn", x(1)[0]);
    assert!((x(2)[0] - 9.0489434837048477e-01).abs() < 1e-12, "node 2 x {} against MBDyn", x(2)[0]);
    let force = w * w * (m1 * x1 + m2 * a * (w * t).sin());
    let lambda = multiplier(&m, &report);
    // The multiplier is the fourth discrete derivative of the imposed motion: λ = M1 x1'' +
    // M2 x2'' with x1 = x2 − L + (M2/K) x2'', taken through four inversions of ms(0.6)'s
    // derivative recursion, whose gain at the step frequency is (1 + a1 − a2)/((b0 − b1 +
    // b2) h) = 16/h (its poles: a double one at −0.6).
    // The rounding of the positions (1 ulp = 2.2e-16 m at 1 m) so becomes a step-to-step
    // oscillation of λ about the closed form, the same in both programs and uncorrelated
    // between them (measured over 0.4–0.8 s, /tmp runs of the file and copies, 2026-12-03):
    // rms 6.3e-3 N in romdyn, 6.7e-3 N in MBDyn 1.7.3, their difference rms 6.2e-3 N and at
    // most 2.0e-2 N after the start; it grows ×15 per halving of h (9.8e-2, 1.5, 27 N rms at
    // h/2, h/4, h/8, both programs alike) and shrinks ×6 with the coordinates' magnitude (L
    // = 0.125 m, same K). The integration error of λ, 3.7e-4 N rms at h = 4 ms (test
    // below), is below 3e-5 N here (O(h²) or faster). So at h = 1 ms λ is compared within
    // that round-off band only.
    // romdyn 3.7e-3 N from the closed form at t = 0.8 s, 2.6e-2 N at most after 0.08 s.
    assert!((lambda - force).abs() < 4e-2, "actuator force {lambda} N against the closed form {force} N");
    // MBDyn 1.7.3 (1727489e), .jnt of the total internal reaction 1 at t = 0.8 s: F_x =
    // -4.8958843318644103e+00 N (the multiplier as the last residual read it, in node
    // GROUND's frame: here the global one). Measured 1.4e-3 N apart, 2.0e-2 N at most after
    // 0.08 s (round-off, above).
    assert!((lambda - -4.8958843318644103).abs() < 4e-2, "actuator force {lambda} N against MBDyn's");
}

/// The total equation's multiplier (the actuator force) at the end of a run.
fn multiplier(m: &MbdynModel, report: &romdyn::analysis::RunReport) -> f64 {
    let asm = Assembler::new(&m.model);
    let e = m.model.elements.iter().position(|e| e.type_name() == "total equation").unwrap();
    report.final_state.y[asm.dofs.element_first[e]]
}

#[test]
fn total_equation_multiplier_is_mbdyns_where_round_off_is_small() {
    // total_equation_two_masses.mbd with `time step: 4.e-3;`: the round-off that hides the
    // multiplier's integration error at 1 ms (test above) is 15² times smaller, and λ's own
    // integration error shows: the same in both programs.
    let text = std::fs::read_to_string(path("total_equation_two_masses.mbd")).unwrap();
    assert!(text.contains("time step: 1.e-3;"));
    let text = text.replace("time step: 1.e-3;", "time step: 4.e-3;");
    let m = read_model_text(&text, Path::new("total_equation_two_masses.mbd"), &SetOverrides::new()).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let lambda = multiplier(&m, &report);
    let (a, w, m1, m2, k, t) = (0.1, 2.0 * std::f64::consts::PI, 1.0, 0.5, 100.0, 0.8);
    let x1 = a * (1.0 - m2 * w * w / k) * (w * t).sin();
    let force = w * w * (m1 * x1 + m2 * a * (w * t).sin());
    // ms(0.6) with h = 4 ms: 5.0e-4 N from the closed form measured (both programs; 3.7e-4
    // N rms over 0.4–0.8 s, 2.7e-3 N at h = 8 ms).
    assert!((lambda - force).abs() < 1e-3, "actuator force {lambda} N against the closed form {force} N");
    // MBDyn 1.7.3 (1727489e) on the same text, .jnt of the total internal reaction 1 at t =
    // 0.8 s: F_x = -4.8913097357172584e+00 N; measured 6.8e-6 N apart (1.4e-6 relative),
    // 5.1e-5 N at most over 0.4–0.8 s (the round-off above, 15² times smaller).
    assert!((lambda - -4.8913097357172584).abs() < 1e-4, "actuator force {lambda} N against MBDyn's");
    // Node 1 x: MBDyn -7.6330200549922303e-02 m, measured 6.4e-12 m apart at most in the run.
    let asm = Assembler::new(&m.model);
    let x = report.final_state.node_frame(&asm.dofs, 1).kin.x[0];
    assert!((x - -7.6330200549922303e-02).abs() < 1e-10, "node 1 x {x} against MBDyn");
}

#[test]
fn total_joint_at_the_actuator_gives_the_force_as_mbdyn() {
    // total_joint_two_masses.mbd: the same motion imposed at node 1 by a total joint; its
    // multiplier, the same actuator force, is a second discrete derivative of the imposed
    // motion (the total equation's a fourth one): the round-off that dominates the total
    // equation's multiplier at h = 1 ms goes through two inversions of gain 16/h fewer
    // here, and the multiplier converges as O(h²): 1.7e-5, 4.3e-6, 1.1e-6, 2.6e-7 N from
    // the closed form at h = 1, 0.5, 0.25, 0.125 ms in both programs (measured 2026-12-03).
    let m = read("total_joint_two_masses.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let e = m.model.elements.iter().position(|e| e.type_name() == "total joint").unwrap();
    let lambda = report.final_state.y[asm.dofs.element_first[e]];
    let (a, w, m1, m2, k, t) = (0.1, 2.0 * std::f64::consts::PI, 1.0, 0.5, 100.0, 0.8);
    let x1 = a * (1.0 - m2 * w * w / k) * (w * t).sin();
    let force = w * w * (m1 * x1 + m2 * a * (w * t).sin());
    assert!((lambda - force).abs() < 5e-5, "actuator force {lambda} N against the closed form {force} N");
    // MBDyn 1.7.3 (1727489e) on the same file at t = 0.8 s: .jnt of the total joint 1, F_x
    // = -4.8908157583113114e+00 N; .mov, node 2 x = 9.0489441167433249e-01 m. Measured
    // 1.1e-10 N (at most 1.5e-9 N in the run) and 2.2e-15 m apart.
    assert!((lambda - -4.8908157583113114).abs() < 1e-8, "actuator force {lambda} N against MBDyn's");
    let x2 = report.final_state.node_frame(&asm.dofs, 2).kin.x[0];
    assert!((x2 - 9.0489441167433249e-01).abs() < 1e-13, "node 2 x {x2} against MBDyn");
}

#[test]
fn tikhonov_pin_is_a_spring_of_stiffness_one_over_c_as_the_closed_form_and_mbdyn() {
    // tikhonov_pin.mbd: a total pin joint relaxed by C = 1e-4 holds M = 2 kg under g:
    // z(t) = −M g C (1 − cos ω t), ω = 1/√(M C) = 70.71 rad/s; at t = 0.1 s, z =
    // −5.781074e-4 m (closed form; ms(0.6) with h = 0.1 ms: 4.9e-8 m of phase error measured).
    let m = read("tikhonov_pin.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, 0).kin;
    let (mass, c, g) = (2.0, 1e-4, 9.81);
    let omega = 1.0 / (mass * c as f64).sqrt();
    let z = -mass * g * c * (1.0 - (omega * 0.1).cos());
    assert!((kin.x[2] - z).abs() < 1e-7, "z {} against the closed form {z}", kin.x[2]);
    // MBDyn 1.7.3 (1727489e) on the same file, .mov at t = 0.1 s: z = -5.7805877868313241e-04
    // m, ż = -9.8339987313415020e-02 m/s (agreement measured 8.7e-18 m, 8.6e-16 m/s).
    assert!((kin.x[2] - -5.7805877868313241e-04).abs() < 1e-14, "z {} against MBDyn", kin.x[2]);
    assert!((kin.xdot[2] - -9.8339987313415020e-02).abs() < 1e-12, "ż {} against MBDyn", kin.xdot[2]);
    // The eigenanalysis at t = 0 sees the joint as springs 1/C: three translations at
    // 1/√(M C) and three rotations at 1/√(J C) = 100 rad/s (J = 1 kg m²), undamped. MBDyn
    // 1.7.3's own eigenanalysis of this file (tikhonov_pin_0.m, its J(±dCoef) pencil: the
    // regularization's −C/dCoef changes sign with dCoef) has only zero and infinite
    // eigenvalues; romdyn linearizes a regularized model in the form of eq. 29 instead.
    let dynamic = &report.eigenanalyses[0].dynamic;
    assert_eq!(dynamic.len(), 12, "{dynamic:?}");
    let mut im: Vec<f64> = dynamic.iter().map(|l| l.im.abs()).collect();
    im.sort_by(f64::total_cmp);
    for (k, expected) in [(0, omega), (6, 100.0)] {
        for v in &im[k..k + 6] {
            assert!((v - expected).abs() < 1e-9 * expected, "|Im λ| {v} against {expected}: {im:?}");
        }
    }
    assert!(dynamic.iter().all(|l| l.re.abs() < 1e-9), "{dynamic:?}");
}

fn error_of(text: &str) -> String {
    match parse_text(text, Path::new("m.mbd")).and_then(|d| build(&d)) {
        Ok(_) => "accepted".into(),
        Err(e) => e.to_string().lines().next().unwrap_or("").to_string(),
    }
}

const EQUATION: &str = "joint: 2, total equation, 1, 2, position constraint, active, inactive, inactive, null;";
const REACTION: &str = "joint: 3, total internal reaction, 1, 2, position constraint, active, inactive, inactive, total equation, 2;";

fn text(joints: usize, regs: usize, elements: &str) -> String {
    let regs = if regs > 0 { format!("joint regularizations: {regs};") } else { String::new() };
    common::mbdyn::file(
        &format!("structural nodes: 2; rigid bodies: 1; joints: {joints}; {regs}"),
        "structural: 1, static, null, eye, null, null; structural: 2, dynamic, 1., 0., 0., eye, null, null;",
        &format!("joint: 1, clamp, 1, node, node; body: 2, 2, 1., null, eye; {elements}"),
    )
}

#[test]
fn bad_total_equation_and_regularization_cards_are_named() {
    let cases = [
        (text(3, 0, &format!("{REACTION} {EQUATION}")), "m.mbd:7:"),
        (text(2, 0, EQUATION), "m.mbd:7:"),
        (text(3, 0, &format!("{EQUATION} {}", REACTION.replace("active, inactive, inactive, total", "active, active, inactive, total"))), "m.mbd:7:"),
        (text(3, 0, &format!("{EQUATION} {}", REACTION.replace(", total equation, 2", ""))), "m.mbd:7:"),
        (text(1, 1, "joint regularization: 1, dynamic, 1e-6;"), "m.mbd:7:"),
        (text(1, 1, "joint regularization: 1, tikhonov, list, 1e-6, 1e-6;"), "m.mbd:7:"),
        (text(1, 1, "joint regularization: 7, tikhonov;"), "m.mbd:7:"),
        (text(2, 0, "joint: 2, angular acceleration, 2, 0., 0., 0., const, 1.;"), "m.mbd:7:"),
        (text(2, 0, "joint: 2, angular acceleration, 2, 0., 0., 1., const, 1.;").replace("1., 0., 0., eye, null, null", "1., 0., 0., eye, null, 0., 0., 2."), "m.mbd:7:"),
    ];
    let wants = [
        "total equation 2 is not defined above",
        "no total internal reaction applies its multipliers",
        "2 active components, but total equation 2 has 1 equations",
        "expected 'total equation, LABEL'",
        "joint regularization 'dynamic' is not supported by romdyn",
        "'list' gives 2 values, clamp 1 has 6 equations",
        "there is no joint 7 above",
        "angular acceleration: the direction is null",
        "angular acceleration: node 2 starts with an angular velocity of 2e0 rad/s about the direction",
    ];
    for ((t, at), want) in cases.iter().zip(wants) {
        let got = error_of(t);
        assert!(got.starts_with(at) && got.contains(want), "got: {got}\nwant: {at}… {want}");
    }
}

#[test]
fn tikhonov_default_compliance_is_mbdyns_and_the_card_is_counted() {
    // jointreg.cc: without a value, C = 1e-6 on every equation (the same residual as with
    // 1e-6 written, another than with 2e-6); the card is counted in control data as 'joint
    // regularizations'.
    let res = |card: &str| common::mbdyn::residual(&common::mbdyn::read(&text(1, 1, card)).model, 0.2, 7);
    let default = res("joint regularization: 1, tikhonov;");
    assert_eq!(default, res("joint regularization: 1, tikhonov, 1e-6;"));
    assert_ne!(default, res("joint regularization: 1, tikhonov, 2e-6;"));
    assert_eq!(default, res("joint regularization: 1, tikhonov, list, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6;"));
    assert!(error_of(&text(1, 0, "joint regularization: 1, tikhonov;")).contains("joint regularizations"));
}

#[test]
fn angular_acceleration_jacobian_matches_finite_differences() {
    assert_jacobians(|n| {
        let sine = Drive::Sine { t0: 0.0, omega: 3.0, amplitude: 2.0, cycles: None, v0: 0.4 };
        vec![Box::new(AngularAcceleration::new(1, 2, n.vec().normalize(), sine)), Box::new(AngularAcceleration::new(2, 3, n.vec().normalize(), Drive::Const(0.7)))]
    });
}

#[test]
fn angular_acceleration_spins_the_body_up_as_the_closed_form_and_mbdyn() {
    // angular_acceleration.mbd at t = 0.95 s: α = A sin(W t) about z from rest, W = π/0.1:
    // ω_z = A/W (1 − cos W t) = 2 A/W = 0.3183099 rad/s, angle A/W (t − sin(W t)/W)
    // (closed form; ms(0.6) with h = 1 ms: 3.1e-5 rad/s and 3.2e-5 rad measured), and the
    // moment the joint applies, −m about z with m = −J α = 10 N m (J = 1 kg m²).
    let m = read("angular_acceleration.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, 0).kin;
    let (a, w, t) = (10.0, std::f64::consts::PI / 0.1, 0.95);
    let (omega, angle) = (a / w * (1.0 - (w * t).cos()), a / w * (t - (w * t).sin() / w));
    let turned = kin.r[(1, 0)].atan2(kin.r[(0, 0)]);
    assert!((kin.omega[2] - omega).abs() < 1e-4 * omega, "ω_z {} against the closed form {omega}", kin.omega[2]);
    assert!((turned - angle).abs() < 1e-4, "angle {turned} against the closed form {angle}");
    // MBDyn 1.7.3 (1727489e) on the same file, t = 0.95 s: .mov ω_z = 3.1827875932615102e-01
    // rad/s, Euler 1-2-3 angle z = 1.7904644619001118e+01 deg; .jnt of joint 2: m =
    // 1.0000000000000078e+01 N m (agreement measured 2.5e-15 rad/s, 2.2e-10 deg).
    assert!((kin.omega[2] - 3.1827875932615102e-01).abs() < 1e-12, "ω_z {} against MBDyn", kin.omega[2]);
    assert!((turned.to_degrees() - 1.7904644619001118e+01).abs() < 1e-8, "angle {} deg against MBDyn", turned.to_degrees());
    let e = m.model.elements.iter().position(|e| e.type_name() == "angular acceleration").unwrap();
    let moment = report.final_state.y[asm.dofs.element_first[e] + 1];
    assert!((moment - 1.0000000000000078e+01).abs() < 1e-6, "moment {moment} N m against MBDyn's and −J α = 10");
}

#[test]
fn viscous_body_jacobian_matches_finite_differences() {
    assert_jacobians(|n| {
        let c = nalgebra::Matrix6::from_fn(|_, _| n.next());
        vec![Box::new(ViscousBody { label: 1, node: 2, offset: n.vec(), orientation: n.rotation(), viscosity: c }), Box::new(ViscousBody { label: 2, node: 3, offset: n.vec(), orientation: n.rotation(), viscosity: c.transpose() })]
    });
}

#[test]
fn viscous_body_damps_the_body_as_the_closed_form_and_mbdyn() {
    // viscous_body.mbd at t = 1 s: v_x = V0 exp(−C t/M), x = V0 M/C (1 − exp(−C t/M)),
    // ω_z = W0 exp(−CW t/J) (closed form; ms(0.6) with h = 1 ms: 3.2e-7 m/s measured).
    let m = read("viscous_body.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, 0).kin;
    let (mass, j, c, cw, v0, w0) = (2.0f64, 0.5f64, 4.0f64, 0.25f64, 3.0f64, 1.0f64);
    let (v, x, w) = (v0 * (-c / mass).exp(), v0 * mass / c * (1.0 - (-c / mass).exp()), w0 * (-cw / j).exp());
    assert!((kin.xdot[0] - v).abs() < 1e-6 && (kin.x[0] - x).abs() < 1e-6 && (kin.omega[2] - w).abs() < 1e-6, "{} {} {} against {v} {x} {w}", kin.xdot[0], kin.x[0], kin.omega[2]);
    // MBDyn 1.7.3 (1727489e) on the same file, .mov at t = 1 s: x = 1.2969972332586004e+00
    // m, v_x = 4.0600552748913277e-01 m/s, ω_z = 6.0653065190748090e-01 rad/s (agreement
    // measured 7e-15 m, 3e-15 m/s, 2e-15 rad/s).
    assert!((kin.x[0] - 1.2969972332586004e+00).abs() < 1e-12, "x {} against MBDyn", kin.x[0]);
    assert!((kin.xdot[0] - 4.0600552748913277e-01).abs() < 1e-12, "v_x {} against MBDyn", kin.xdot[0]);
    assert!((kin.omega[2] - 6.0653065190748090e-01).abs() < 1e-12, "ω_z {} against MBDyn", kin.omega[2]);
}

/// The initial assembly leaves a viscous body alone: it is not a constraint, and its force
/// on the written velocity (C V0 = 12 N here) was balanced by the assembly's 1 N/m position
/// springs, which moved the node 12 m and reported only the move. Without the file's
/// `skip initial joint assembly` the run must be the one with it (MBDyn 1.7.3 cannot run
/// this variant: its viscous body's initial-assembly Jacobian is not implemented).
#[test]
fn the_initial_assembly_leaves_a_viscous_body_where_it_is_written() {
    let text = std::fs::read_to_string(path("viscous_body.mbd")).unwrap();
    assert!(text.contains("skip initial joint assembly;"));
    let dir = std::env::temp_dir().join(format!("romdyn-vb-assembly-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("viscous_body_assembled.mbd");
    std::fs::write(&file, text.replace("skip initial joint assembly;", "")).unwrap();
    let finals: Vec<[f64; 3]> = [path("viscous_body.mbd"), file].iter().map(|f| {
        let m = romdyn::input::mbdyn::read_model(f).unwrap();
        let report = run(&m.model, &m.problem, &mut ()).unwrap();
        let kin = report.final_state.node_frame(&Assembler::new(&m.model).dofs, 0).kin;
        [kin.x[0], kin.xdot[0], kin.omega[2]]
    }).collect();
    for k in 0..3 {
        assert!((finals[0][k] - finals[1][k]).abs() <= 1e-12, "{:?} with the assembly vs {:?} without", finals[1], finals[0]);
    }
    std::fs::remove_dir_all(&dir).ok();
}
