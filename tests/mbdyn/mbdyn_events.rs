//! Events of issue 12 (elements whose data change at an instant of the run, latched once per
//! step after the predictor: `Element::latch`): the `linear viscoelastic bistop` law on a
//! rod, and driven elements' hints. Each: the analytic Jacobian against central finite
//! differences of the residual in the changed state (1e-6 relative to the element's largest
//! entry, as tests/multibody/multibody_jacobians.rs), closed forms, and MBDyn 1.7.3's output on the
//! same file of `tests/mbdyn_files/` (written for romdyn in MBDyn's style, recorded here
//! with `output precision: 16`; MBDyn is never run by the tests).

use crate::common;
use common::mbdyn::test_file as path;

use common::mbdyn::rewritten_test_file as rewritten;

use std::sync::Arc;

use common::fixtures::Noise;
use romdyn::analysis::run;
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::drive::Drive;
use romdyn::element::{Anchor, BistopRod, BistopStatus, NodeKinematics, Rod, RodViscosity};
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};
use romdyn::kinematics::Mat3;
use romdyn::model::ConstraintForm;
use romdyn::model::ModelBuilder;


/// The model of `name` run to `final_time` (its `final time:` line replaced): the final
/// state's kinematics of each node by label, the state, and the model.
fn run_to(name: &str, final_time: &str, old: &str) -> (impl Fn(u32) -> NodeKinematics, State, MbdynModel) {
    let m = rewritten(name, &[(old, &format!("final time: {final_time};"))]);
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let nodes: std::collections::HashMap<u32, NodeKinematics> = m.model.nodes.iter().enumerate().map(|(i, n)| (n.label, report.final_state.node_frame(&asm.dofs, i).kin)).collect();
    (move |label: u32| nodes[&label].clone(), report.final_state, m)
}

const G: f64 = 9.81;

#[test]
fn bistop_rod_acts_from_its_activation_strain_as_the_closed_form_and_mbdyn() {
    // bistop_rod.mbd: node 2 falls from rest 1 m below the ground node; the rod's law
    // (EA = 100 N, C = 2 N s, L = 1 m, mass 1 kg) activates for t > 0.3 s and lets go for
    // t > 0.7 s. MBDyn 1.7.3 (1727489e) on the same file, node 2 (.mov):
    //   t = 0.3 s: z = −1.4414484079732324 m;  t = 0.7 s: z = −1.4411666456692063 m,
    //   ż = 1.6637800759148045 m/s;  t = 1 s: z = −1.3835028849335551 m, ż = −1.2792875720327297 m/s.
    let old = "final time: 1.;";
    let (kin, _, _) = run_to("bistop_rod.mbd", "1.", old);
    // Against MBDyn: the same discrete equations; 1e-9 m and m/s (measured 8e-12 m, 1.3e-10 m/s).
    assert!((kin(2).x.z - -1.3835028849335551).abs() < 1e-9, "z(1) = {}", kin(2).x.z);
    assert!((kin(2).xdot.z - -1.2792875720327297).abs() < 1e-9, "ż(1) = {}", kin(2).xdot.z);

    // Before the activation, free fall (exact for the integrator): z = −1 − g t²/2.
    let (kin, st, _) = run_to("bistop_rod.mbd", "0.299", old);
    // 1e-8 m: the derivatives phase (dCoef 1e-9 s, MBDyn's) starts the fall at ż = −g dCoef,
    // 2.9e-9 m at 0.3 s (MBDyn's run the same).
    assert!((kin(2).x.z - (-1.0 - 0.5 * G * st.t * st.t)).abs() < 1e-8, "z({}) = {}", st.t, kin(2).x.z);
    // The step at t = 0.3 s already has the law on (its viscous force), as MBDyn's.
    let (kin, _, _) = run_to("bistop_rod.mbd", "0.3", old);
    assert!((kin(2).x.z - -1.4414484079732324).abs() < 1e-9, "z(0.3) = {}", kin(2).x.z);

    // Active: u = z − z_ref obeys m ü = −m g − k u − c u̇ (k = EA/L, c = C/L, the viscous
    // part on MBDyn's strain rate l̇/L) from u = 0, u̇ = −g t_a at t_a = 0.3 s. The ms
    // formula's two-step memory straddles the jump of the viscous force (c g t_a = 5.9 N)
    // at the activation: an error oscillating at 2.3e-4 m measured (2.6e-5 m at t = 0.6 s);
    // MBDyn's the same.
    let (k, c, ta) = (100.0, 2.0, 0.3);
    let closed = |t: f64| {
        let (up, wd, s) = (-G / k, (k - c * c / 4.0f64).sqrt(), -c / 2.0);
        let (a, b) = (-up, (-G * ta - s * -up) / wd);
        let tt = t - ta;
        -1.0 - 0.5 * G * ta * ta + up + (s * tt).exp() * (a * (wd * tt).cos() + b * (wd * tt).sin())
    };
    let (kin, st, m) = run_to("bistop_rod.mbd", "0.6", old);
    // The law activated at the step t = 0.3 s (the time sums to just above 0.3): its
    // reference strain is the strain of the free fall there at the predicted state, which
    // the ms predictor gives exactly for a quadratic motion, ε_ref = g t²/2 / L.
    // (At the step before, the fall is the closed form: checked below.) (Once
    // deactivated, the law re-activates and deactivates at every step, both drives being
    // non-zero, as MBDyn's wrapper falls through: ε_ref then follows the strain, unused.)
    let e = m.model.elements.iter().position(|e| e.label() == 2 && e.type_name() == "rod").unwrap();
    let status = st.latched[e].as_ref().and_then(|l| l.downcast_ref::<BistopStatus>()).copied().unwrap();
    assert!(status.active, "active at t = 0.6 s");
    // 1e-8: the derivatives phase's ż(0) = −g dCoef (below), 2.9e-9 m at 0.3 s.
    assert!((status.reference_strain - 0.5 * G * 0.09).abs() < 1e-8, "ε_ref = {}", status.reference_strain);
    assert!((kin(2).x.z - closed(st.t)).abs() < 3e-4, "z(0.6) = {} against {}", kin(2).x.z, closed(st.t));
    // The step at t = 0.7 s (just above 0.7) has the law off again, as MBDyn's.
    let (kin, _, _) = run_to("bistop_rod.mbd", "0.7", old);
    assert!((kin(2).x.z - -1.4411666456692063).abs() < 1e-9 && (kin(2).xdot.z - 1.6637800759148045).abs() < 1e-9, "z(0.7) against MBDyn");

    // Inactive again: free fall from the state at 0.8 s to the end (exact for the integrator).
    let (kin8, st8, _) = run_to("bistop_rod.mbd", "0.8", old);
    let (kin1, st1, _) = run_to("bistop_rod.mbd", "1.", old);
    let dt = st1.t - st8.t;
    let z = kin8(2).x.z + kin8(2).xdot.z * dt - 0.5 * G * dt * dt;
    assert!((kin1(2).x.z - z).abs() < 1e-9 && (kin1(2).xdot.z - (kin8(2).xdot.z - G * dt)).abs() < 1e-9, "free fall after 0.7 s");
}

#[test]
fn bistop_rod_jacobian_matches_finite_differences_in_each_status() {
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let mut n = Noise(4242);
        let mut b = ModelBuilder::new();
        b.static_node(1, n.vec(), n.rotation()).dynamic_node(2, n.vec(), n.rotation(), n.vec(), n.vec());
        let rod = Rod { label: 1, a: Anchor::Node { label: 1, offset: n.vec(), orientation: Mat3::identity() }, b: Anchor::Node { label: 2, offset: n.vec(), orientation: Mat3::identity() }, axial_stiffness: 300.0, length: 0.7, viscous: Some(RodViscosity { coefficient: 4.0, length: 0.8 }), elastic: None };
        b.element(BistopRod { rod, strain_length: 0.8, initially_active: false, activate: Drive::Const(1.0), deactivate: Drive::Const(0.0) });
        b.constraint_form(form);
        let model = b.build().unwrap();
        let asm = Assembler::new(&model);
        let mut st = State::initial(&model, &asm.dofs);
        let mut noise = Noise(99);
        for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
            *x += 0.5 * noise.next();
        }
        // Inactive (the state as read), active from a reference strain, and the latch itself:
        // with its activating drive on, the element latches the state's strain.
        let before = st.clone();
        let mut latched = st.clone();
        asm.latch_events(&mut latched, &before);
        let status = latched.latched[0].as_ref().and_then(|l| l.downcast_ref::<BistopStatus>()).copied().unwrap();
        assert!(status.active && status.reference_strain != 0.0);
        let mut active = st.clone();
        active.latched[0] = Some(Arc::new(BistopStatus { active: true, reference_strain: 0.13 }));
        for (what, s) in [("inactive", &st), ("latched", &latched), ("active", &active)] {
            for w in check_jacobians(&asm, s, 0.37, form) {
                assert!(w.within(1e-6), "{form:?} {what}: {} d({})/d({}): analytic {:e}, fd {:e}", w.element, w.equation, w.unknown, w.analytic, w.finite_difference);
            }
        }
        // Latched, the law adds its force (inactive, none).
        let r_on = asm.residual(&latched, ConstraintForm::Plain, 1.0);
        let r_off = asm.residual(&st, ConstraintForm::Plain, 1.0);
        assert!(r_on.iter().zip(&r_off).any(|(a, b)| a != b), "the activated law adds its viscous force");
    }
}

#[test]
fn hints_reset_drives_from_the_state_at_the_switch_on_as_closed_forms_and_mbdyn() {
    // driven_hints.mbd. MBDyn 1.7.3 (1727489e) on the same file at t = 3.001 s (its last
    // step): node 2 x = 1.2005000000008966e+01 m; node 4 Euler angle z = 4.6294989850763649e+01
    // deg; node 6 at t = 0.501 s: x = 2.5088373551556553e-01 m, z = 2.9995293141058439 m.
    let old = "final time: 3.;";
    let (kin, st, _) = run_to("driven_hints.mbd", "3.", old);
    let t = st.t;
    // Total pin joint 2, on for 1 ≤ t ≤ 2: the hint's ramp starts where the node is (x = 2 m,
    // 2 m/s) with slope 2 + 3 m/s, so x(2) = 7 m; then the node keeps 5 m/s (1e-9 m: the
    // integrator is exact for a linear motion).
    assert!((kin(2).x.x - (7.0 + 5.0 * (t - 2.0))).abs() < 1e-9, "node 2 x = {} at {t}", kin(2).x.x);
    assert!((kin(2).x.x - 1.2005000000008966e+01).abs() < 1e-10, "node 2 against MBDyn");
    // Drive hinge 4, on for t > 0.2 s: θ_z(0.2) = α t²/2 with α = 0.2/0.5 rad/s², held and
    // ramped by 1 rad/s until t = 1 s: 0.008 + 0.8 rad (1e-9 rad: the predicted rotation at
    // the switch-on); against MBDyn 1e-12 rad.
    let theta = nalgebra::Rotation3::from_matrix_unchecked(kin(4).r).scaled_axis();
    assert!((theta.z - 0.808).abs() < 1e-9 && theta.xy().norm() < 1e-12, "node 4 rotation {theta}");
    assert!((theta.z.to_degrees() - 4.6294989850763649e+01).abs() < 1e-10, "node 4 against MBDyn");
    // Distance 6, on for t ≥ 0.5 s: the distance of the step before the switch-on, the
    // free flight under 2 N on 1 kg, x = t², at t = 0.499 s: √(1 + 0.499⁴), held to the end.
    let d = (kin(6).x - kin(5).x).norm();
    assert!((d - (1.0 + 0.499f64.powi(4)).sqrt()).abs() < 1e-9, "distance {d}");
    // Against MBDyn until t = 0.501 s. From t = 0.502 s MBDyn's run (whose direction unknowns
    // were held at zero while the joint was off) jumps node 6 to the mirror point through
    // node 5 at velocities of 4e3 m/s, as in MBDyn's own tests/joints/distance/
    // distance_driven_stringdrive_error; romdyn's does not (its direction starts from the
    // written one), so the comparison stops there.
    let (kin, _, _) = run_to("driven_hints.mbd", "0.501", old);
    assert!((kin(6).x.x - 2.5088373551556553e-01).abs() < 1e-10 && (kin(6).x.z - 2.9995293141058439).abs() < 1e-10, "node 6 at 0.501 s: {}", kin(6).x);
}

#[test]
fn hinted_elements_jacobians_match_finite_differences_after_the_switch_on() {
    // All three driven elements on at t = 1.5 s, with the drives their hints built.
    let (_, st, m) = run_to("driven_hints.mbd", "1.5", "final time: 3.;");
    assert!(st.latched.iter().filter(|l| l.is_some()).count() == 3);
    let asm = Assembler::new(&m.model);
    let mut moved = st.clone();
    let mut noise = Noise(7);
    for x in moved.y.iter_mut().chain(moved.yp.iter_mut()) {
        *x += 1e-2 * noise.next();
    }
    for w in check_jacobians(&asm, &moved, 1e-3, m.model.constraint_form) {
        assert!(w.within(1e-6), "{} d({})/d({}): analytic {:e}, fd {:e}", w.element, w.equation, w.unknown, w.analytic, w.finite_difference);
    }
}

#[test]
fn hints_romdyn_cannot_build_are_refused_at_the_hint() {
    let cases = [
        ("\"drive{model::distance_prev(5, 6)}\"", "\"offset{1}\"", "hint \"offset{1}\" is not supported by romdyn"),
        ("\"drive3{0., 0., 1., ramp, 1., .2, 1., model::zanglerel(3, 4)}\"", "\"drive{1.}\"", "hint 1 does not apply to a drive hinge"),
        ("model::distance_prev(5, 6)", "model::distance_prev(5, 9)", "no structural node 9"),
        // A hint reading the state, on an element it does not apply to (checked with each
        // `model::` read 0).
        ("\"drive{model::distance_prev(5, 6)}\"", "\"position-drive3{1., 0., 0., model::xposition(6)}\"", "hint 1 does not apply to a distance"),
    ];
    for (old, new, expected) in cases {
        let t = std::fs::read_to_string(path("driven_hints.mbd")).unwrap().replace(old, new);
        let e = parse_text(&t, &path("driven_hints.mbd")).and_then(|d| build(&d)).err().unwrap_or_else(|| panic!("{new} accepted"));
        assert!(e.message.contains(expected) && e.line > 0, "{new}: {}:{}: {}", e.line, e.column, e.message);
    }
    // A bistop law elsewhere than on a rod.
    let t = std::fs::read_to_string(path("bistop_rod.mbd")).unwrap().replace("joint: 2, rod, 1, 2, L,", "joint: 2, deformable axial joint, 1, 2,");
    let e = parse_text(&t, &path("bistop_rod.mbd")).and_then(|d| build(&d)).err().unwrap();
    assert!(e.message.contains("bistop") && e.line > 0, "{}", e.message);
    // A driven joint with friction: its friction state would have to be frozen while off
    // (before this refusal the run failed at the switch-on, in the friction state's row).
    let t = std::fs::read_to_string(path("revolute_hinge_friction.mbd")).unwrap().replacen("\tjoint: 2, revolute hinge,", "\tdriven: 2, string, \"Time > .1\",\n\tjoint: 2, revolute hinge,", 1);
    assert!(t.contains("driven: 2"));
    let e = parse_text(&t, &path("revolute_hinge_friction.mbd")).and_then(|d| build(&d)).err().unwrap();
    assert!(e.message.contains("states of its own (joint friction)") && e.line > 0, "{}", e.message);
}

/// A hint whose drive cannot be built when its element switches on (here `asin` of the
/// distance, 1 m or more, out of its domain at t = 0.5 s; the read-time check, with each
/// `model::` read 0, cannot see it) stops the run with the hint's own reason: before, the
/// element's residual was NaN and the failure said only "the residual is not finite".
#[test]
fn a_hint_that_fails_at_the_switch_on_is_named_in_the_failure() {
    let m = rewritten("driven_hints.mbd", &[("\"drive{model::distance_prev(5, 6)}\"", "\"drive{asin(model::distance_prev(5, 6))}\"")]);
    let e = run(&m.model, &m.problem, &mut ()).err().expect("the run must fail at the switch-on").to_string();
    assert!(e.contains("distance 6: hint 1") && e.contains("asin(") && e.contains("out of domain"), "{e}");
}

/// A driven total joint with hints that is also regularized (MBDyn's
/// tests/joints/total/totalhint does this): the regularization must keep the driven
/// element's events. Joint 20 lifts node 2 by a half cosine to z = 1 m and tilts it to
/// 0.4 rad (about y) by t = 0.4 s and holds it until t = 0.5 s; joint 30 switches on then, its hints taking node 2's
/// position and relative rotation at that instant, with a Tikhonov compliance of 1e-6. The
/// node must stay where it was put (closed form: nothing else acts on it; 1e-9). Before
/// the fix the hints never applied, the joint held its written null drive through the
/// 1e6 N/m regularization spring and node 2 oscillated about the origin (z = 0.066 m at
/// t = 1 s, measured). MBDyn 1.7.3 on totalhint, which differs only in numbers: z = 1.000000 at 1 s.
#[test]
fn a_regularized_driven_joint_applies_its_hints_when_it_switches_on() {
    let text = r#"
begin: data; problem: initial value; end: data;
begin: initial value;
    initial time: 0.; final time: 1.; time step: 1.e-3;
    tolerance: 1.e-9; max iterations: 10; method: ms, .6;
end: initial value;
begin: control data;
    structural nodes: 2; rigid bodies: 1; joints: 3; joint regularizations: 1;
end: control data;
begin: nodes;
    structural: 1, static, null, eye, null, null;
    structural: 2, dynamic, null, eye, null, null;
end: nodes;
begin: elements;
    joint: 10, clamp, 1, node, node;
    body: 2, 2, 2., null, diag, 1., 1., 1.;
    driven: 20, string, "Time <= .5",
    joint: 20, total joint,
        1, position, reference, node, null,
           position orientation, reference, node, eye, rotation orientation, reference, node, eye,
        2, position, reference, node, null,
           position orientation, reference, node, eye, rotation orientation, reference, node, eye,
        position constraint, active, active, active, 0., 0., 1., cosine, 0., pi/.4, .5, half, 0.,
        orientation constraint, active, active, active, 0., 1., 0., cosine, 0., pi/.4, .2, half, 0.;
    driven: 30, string, "Time > .5",
        hint, "position-drive3{model::xposition(2), model::yposition(2), model::zposition(2), const, 1.}",
        hint, "orientation-drive3{model::xanglerel(1, 2), model::yanglerel(1, 2), model::zanglerel(1, 2), const, 1.}",
    joint: 30, total joint,
        1, position, reference, node, null,
           position orientation, reference, node, eye, rotation orientation, reference, node, eye,
        2, position, reference, node, null,
           position orientation, reference, node, eye, rotation orientation, reference, node, eye,
        position constraint, active, active, active, null,
        orientation constraint, active, active, active, null;
    joint regularization: 30, tikhonov, 1e-6;
end: elements;
"#;
    let file = path("regularized_hints.mbd");
    let m = parse_text(text, &file).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let k = report.final_state.node_frame(&asm.dofs, 1).kin;
    assert!((k.x[2] - 1.0).abs() < 1e-9 && k.x[0].abs() < 1e-9 && k.x[1].abs() < 1e-9, "node 2 at {:?}", k.x);
}
