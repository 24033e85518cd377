//! Joints and deformable elements of issue 12, point 3 (axial rotation, …): each one's
//! analytic Jacobian against central finite differences of its residual (1e-6 relative to
//! the element's largest entry, as tests/multibody/multibody_jacobians.rs), and a test file of
//! `tests/mbdyn_files/` in MBDyn's style whose numbers are checked against a closed form
//! and against MBDyn 1.7.3's output on the same file (recorded here with the file's name;
//! MBDyn is never run by the tests).

use crate::common;
use common::mbdyn::{read_test_file as read, test_file as path};

use common::mbdyn::rewritten_test_file as rewritten;

use std::path::Path;

use common::fixtures::Noise;
use common::mbdyn::assert_jacobians;
use romdyn::analysis::run;
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::drive::Drive;
use romdyn::element::{RotationRemnant, Anchor, AxialRotation, CardanoHinge, Distance, GimbalRotation, ImposedVelocity, VelocityKind, DeformableJoint, DrivenElement, DrivenJoint, Element, InvariantDeformableHinge, Joint, LinearViscoelastic, SectionLaw, VectorDrive};
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};
use romdyn::kinematics::{Mat3, Vec3};

use romdyn::model::ConstraintForm;
use romdyn::model::ModelBuilder;


fn node(label: u32, n: &mut Noise) -> Anchor {
    Anchor::Node { label, offset: n.vec(), orientation: n.rotation() }
}

fn ground(n: &mut Noise) -> Anchor {
    Anchor::Ground { position: n.vec(), orientation: n.rotation() }
}

/// Rotation angle about global x of a frame that turned about x.
fn angle_about_x(r: &Mat3) -> f64 {
    r[(2, 1)].atan2(r[(1, 1)])
}

#[test]
fn axial_rotation_jacobian_matches_finite_differences() {
    assert_jacobians(|n| {
        let omega = Drive::Sine { t0: 0.0, omega: 2.0, amplitude: 1.5, cycles: None, v0: 0.2 };
        vec![
            Box::new(AxialRotation::new(1, node(2, n), node(3, n), omega.clone())),
            Box::new(AxialRotation::new(2, ground(n), node(2, n), omega.clone())),
            Box::new(AxialRotation::new(3, node(1, n), node(3, n), omega)),
        ]
    });
}

#[test]
fn axial_rotation_spins_a_rotor_up_as_the_closed_form_and_mbdyn() {
    // axial_rotation.mbd: Ω ramps at 2 rad/s² to 1 rad/s in 0.5 s, then holds: after 1 s the
    // rotor has turned 0.25 + 0.5 = 0.75 rad about x. MBDyn 1.7.3 (1727489e) on the same file:
    // node 2 Euler 123 angle 4.297183461665724e+01 deg at t = 1 s, ω_x = 1 rad/s.
    let m = read("axial_rotation.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, 1).kin;
    let mbdyn = 4.297183461665724e+01f64.to_radians();
    // ms integrates the orientation parameters, not the angle: 1e-9 rad of integration error
    // (MBDyn's own is 3e-10 rad); against MBDyn 1e-12 rad (the same discrete formulation).
    assert!((angle_about_x(&kin.r) - 0.75).abs() < 1e-9, "angle {}", angle_about_x(&kin.r));
    assert!((angle_about_x(&kin.r) - mbdyn).abs() < 1e-12, "angle {} against MBDyn {mbdyn}", angle_about_x(&kin.r));
    assert!((kin.omega - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-12, "ω = {}", kin.omega);
    // The motor moment after the ramp is 0 (MBDyn: 4.9e-13 N m).
    let motor = asm.dofs.element_first[1] + 5;
    assert!(report.final_state.y[motor].abs() < 1e-9, "motor moment {}", report.final_state.y[motor]);

    // During the ramp, J Ω̇ = 1 kg m² · 2 rad/s² = 2 N m (MBDyn at t = 0.25 s: 2.000000000000005
    // N m in its .jnt); romdyn's multiplier is the reaction's residual, −2 N m about x.
    let m = rewritten("axial_rotation.mbd", &[("final time: 1.;", "final time: .25;")]);
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    assert!((report.final_state.y[motor] + 2.0).abs() < 1e-9, "motor moment {}", report.final_state.y[motor]);
}

fn random_law6(n: &mut Noise) -> SectionLaw {
    let a = nalgebra::Matrix6::from_fn(|_, _| n.next());
    let mut law = SectionLaw::viscoelastic(100.0 * (a * a.transpose() + nalgebra::Matrix6::identity()), 3.0 * nalgebra::Matrix6::from_fn(|_, _| n.next()));
    law.prestrain = 0.1 * nalgebra::Vector6::from_fn(|_, _| n.next());
    law.prestress = nalgebra::Vector6::from_fn(|_, _| n.next());
    law
}

#[test]
fn deformable_joint_jacobians_match_finite_differences() {
    assert_jacobians(|n| {
        vec![
            Box::new(DeformableJoint::new(1, node(2, n), node(3, n), random_law6(n))),
            Box::new(DeformableJoint::new(2, ground(n), node(3, n), random_law6(n))),
            Box::new(DeformableJoint::new(3, node(1, n), node(2, n), random_law6(n))),
            Box::new(DeformableJoint::axial(4, node(2, n), node(3, n), 50.0, 2.0, 0.1, 0.3)),
            Box::new(DeformableJoint::axial(5, ground(n), node(2, n), 50.0, 2.0, -0.2, 0.0)),
            Box::new(DeformableJoint::hinge(6, node(2, n), node(3, n), &LinearViscoelastic { stiffness: 80.0 * n.matrix(), viscosity: 2.0 * n.matrix() }, n.vec(), n.vec())),
        ]
    });
}

#[test]
fn invariant_deformable_hinge_jacobian_matches_finite_differences() {
    assert_jacobians(|n| {
        let law = LinearViscoelastic { stiffness: 100.0 * n.matrix(), viscosity: 3.0 * n.matrix() };
        vec![
            Box::new(InvariantDeformableHinge { label: 1, a: node(2, n), b: node(3, n), law: law.clone(), variance: None }),
            Box::new(InvariantDeformableHinge { label: 2, a: ground(n), b: node(3, n), law: law.clone(), variance: None }),
            Box::new(InvariantDeformableHinge { label: 3, a: node(1, n), b: node(2, n), law, variance: None }),
        ]
    });
}

/// The rotation vector of `r` (nalgebra's, independent of romdyn's kinematics).
fn rotation_vector_of(r: &Mat3) -> Vec3 {
    nalgebra::Rotation3::from_matrix_unchecked(*r).scaled_axis()
}

/// Euler 1-2-3 angles [deg] of a node, as MBDyn's .mov writes them.
fn euler_deg(r: &Mat3) -> Vec3 {
    romdyn::kinematics::euler123(r).map(f64::to_degrees)
}

#[test]
fn deformable_joints_rest_and_swing_as_the_closed_forms_and_mbdyn() {
    // deformable_joints.mbd after 2001 steps of 1 ms (t = 2.001 s). MBDyn 1.7.3 (1727489e)
    // on the same file, .mov at the last step: node 2 x = (8.928571428571451e-03,
    // −9.710610932475841e-03, 4.999999999999986e-03) m, Euler 1-2-3 (2.216909650009216e-01,
    // −2.285892809177687e-01, 3.073847002567478e-01) deg; node 3 rz = −7.798576844872589 deg,
    // ω_z = −2.930783554201528 rad/s; node 4 (3.306825222132232e-01, −3.224136163404079e-01,
    // 1.178625309260404e+00) deg.
    let m = read("deformable_joints.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let st = &report.final_state;
    let kin = |label: u32| st.node_frame(&asm.dofs, m.model.node_index(label).unwrap()).kin;

    // Node 2: K [x; θ] = [f; m] (K from the file), solved here by LU; the transient has
    // decayed (overdamped, e^(−ζωt) < 1e-20): 1e-12 m and rad.
    let k = nalgebra::Matrix6::from_row_slice(&[
        1000., 0., 0., 0., 0., 200., 0., 2000., 0., -150., 0., 0., 0., 0., 3000., 0., 0., 0., 0., -150., 0., 400., 0., 0., 0., 0., 0., 0., 500., 0., 200., 0., 0., 0., 0., 600.,
    ]);
    let rest = k.lu().solve(&nalgebra::Vector6::new(10., -20., 15., 3., -2., 5.)).unwrap();
    let (x2, theta2) = (kin(2).x, rotation_vector_of(&kin(2).r));
    for i in 0..3 {
        assert!((x2[i] - rest[i]).abs() < 1e-12, "node 2 x{i} = {} against K⁻¹[f; m] {}", x2[i], rest[i]);
        assert!((theta2[i] - rest[3 + i]).abs() < 1e-12, "node 2 θ{i} = {} against K⁻¹[f; m] {}", theta2[i], rest[3 + i]);
    }
    let mbdyn_x2 = Vec3::new(8.928571428571451e-03, -9.710610932475841e-03, 4.999999999999986e-03);
    let mbdyn_e2 = Vec3::new(2.216909650009216e-01, -2.285892809177687e-01, 3.073847002567478e-01);
    assert!((x2 - mbdyn_x2).norm() < 1e-13 && (euler_deg(&kin(2).r) - mbdyn_e2).norm() < 1e-11, "node 2 against MBDyn");

    // Node 3: θ(t) = 0.2 cos(20 t); ms (ρ∞ = 0.6) at ω h = 0.02 lags by about
    // ω t (ω h)²/12 over 40 rad: 2.3e-4 rad measured, 5e-4 allowed. Against MBDyn 1e-8 rad
    // (4.6e-9 measured: the derivatives phases differ by m·a·dCoef in the momenta).
    let (theta3, w3) = (euler_deg(&kin(3).r)[2].to_radians(), kin(3).omega[2]);
    assert!((theta3 - 0.2 * (20.0 * st.t).cos()).abs() < 5e-4, "node 3 θ = {theta3} at t = {}", st.t);
    assert!((theta3 - (-7.798576844872589f64).to_radians()).abs() < 1e-8, "node 3 θ = {theta3} against MBDyn");
    assert!((w3 - -2.930783554201528).abs() < 1e-6, "node 3 ω = {w3} against MBDyn");

    // Node 4, invariant hinge: at rest exp(θ/2) K θ = m (the intermediate frame), which the
    // variant form K θ = m does not satisfy (it misses by 9.7e-3 N m here).
    let k4 = Mat3::new(400., 50., 0., 50., 300., 20., 0., 20., 200.);
    let theta4 = rotation_vector_of(&kin(4).r);
    let couple = Vec3::new(2., -1., 4.);
    let half = nalgebra::Rotation3::new(theta4 / 2.0).into_inner();
    assert!((half * k4 * theta4 - couple).norm() < 1e-10, "invariant hinge: {} against {couple}", half * k4 * theta4);
    assert!((k4 * theta4 - couple).norm() > 5e-3);
    let mbdyn_e4 = Vec3::new(3.306825222132232e-01, -3.224136163404079e-01, 1.178625309260404e+00);
    assert!((euler_deg(&kin(4).r) - mbdyn_e4).norm() < 1e-11, "node 4 {} against MBDyn {mbdyn_e4}", euler_deg(&kin(4).r));
}

#[test]
fn deformable_joint_with_offsets_and_frames_rests_where_mbdyn_does() {
    // deformable_joints.mbd with joint 2 between offset, turned frames (the lines below), and
    // MBDyn's derivatives settings it needs to start (it does not converge in 100 iterations
    // with the file's coefficient): MBDyn 1.7.3 (1727489e), node 2 at t = 2.001 s,
    // x = (3.292645290557419e-01, 2.151592223949560e-01, −1.256940211343785e-01) m, Euler
    // 1-2-3 (6.457694834069565, −1.785632720750061e+01, 5.801560504375785) deg. At rest:
    // 1e-12 m, 1e-10 deg.
    let m = rewritten(
        "deformable_joints.mbd",
        &[
            ("derivatives max iterations: 10;", "derivatives max iterations: 100; derivatives coefficient: auto;"),
            ("        1, position, null,\n        2, position, null,\n", "        1, position, .1, .2, -.1, orientation, euler123, .1, -.2, .3,\n        2, position, -.2, 0., .1, orientation, euler123, 0., .1, .2,\n"),
        ],
    );
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, m.model.node_index(2).unwrap()).kin;
    let x = Vec3::new(3.292645290557419e-01, 2.151592223949560e-01, -1.256940211343785e-01);
    let e = Vec3::new(6.457694834069565, -1.785632720750061e+01, 5.801560504375785);
    assert!((kin.x - x).norm() < 1e-12, "{} against MBDyn {x}", kin.x);
    assert!((euler_deg(&kin.r) - e).norm() < 1e-10, "{} against MBDyn {e}", euler_deg(&kin.r));
}

fn vector_drive(n: &mut Noise) -> VectorDrive {
    VectorDrive(vec![(n.vec(), Drive::Sine { t0: 0.0, omega: 2.0, amplitude: 0.7, cycles: None, v0: 0.1 }), (n.vec(), Drive::Time)])
}

#[test]
fn driven_joint_jacobians_match_finite_differences() {
    assert_jacobians(|n| {
        let mut out: Vec<Box<dyn Element>> = Vec::new();
        // Imposed position and rotation, all locked (drive displacement + drive hinge).
        let mut all = DrivenJoint::new(Joint::total(1, node(2, n), node(3, n), [true; 3], [true; 3]), "total joint");
        all.position = vector_drive(n);
        all.rotation = vector_drive(n);
        out.push(Box::new(all));
        // Position partly locked, velocity and angular velocity constraints, to ground.
        let mut rates = DrivenJoint::new(Joint::total(2, ground(n), node(2, n), [true, false, false], [false, true, false]), "total pin joint");
        rates.position = vector_drive(n);
        rates.velocity_locked = [false, true, true];
        rates.velocity = vector_drive(n);
        rates.angular_velocity_locked = [true, false, true];
        rates.angular_velocity = vector_drive(n);
        out.push(Box::new(rates));
        // Between the static node and a dynamic one, only velocity constraints.
        let mut v = DrivenJoint::new(Joint::total(3, node(1, n), node(3, n), [false; 3], [false; 3]), "total joint");
        v.velocity_locked = [true; 3];
        v.velocity = vector_drive(n);
        v.angular_velocity_locked = [true; 3];
        v.angular_velocity = vector_drive(n);
        out.push(Box::new(v));
        out
    });
}

#[test]
fn driven_joints_follow_their_drives_as_the_closed_forms_and_mbdyn() {
    // driven_joints.mbd at t = 1 s. MBDyn 1.7.3 (1727489e) on the same file, .mov:
    //   node 3: (−9.455211937633332e-02, 9.716469991507863e-02, 9.973874194612973e-01) m,
    //           (2.562046941862889e+01, 3.972146855160072e+01, 2.562046941862882e+01) deg;
    //   node 5: x = 5.000000000000092e-01 m, rz = 1.145915817029747e+02 deg, ω_z = 2 rad/s;
    //   nodes 2, 4, 6 at (1.2, 0, 0), (1, 1, 0.6), (0, −1.8, 0) m to 16 digits, node 6
    //   rz = 2.291831180523293e+01 deg.
    let m = read("driven_joints.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = |label: u32| report.final_state.node_frame(&asm.dofs, m.model.node_index(label).unwrap()).kin;
    assert!((report.final_state.t - 1.0).abs() < 1e-12);

    // Holonomic drives hold to Newton's tolerance (1e-10 on the constraint rows times dCoef).
    assert!((kin(2).x - Vec3::new(1.2, 0.0, 0.0)).norm() < 1e-12, "drive displacement pin: {}", kin(2).x);
    assert!((kin(4).x - Vec3::new(1.0, 1.0, 0.6)).norm() < 1e-12, "imposed displacement: {}", kin(4).x);
    assert!((kin(6).x - Vec3::new(0.0, -1.8, 0.0)).norm() < 1e-12, "total pin joint: {}", kin(6).x);
    assert!((rotation_vector_of(&kin(6).r) - Vec3::new(0.0, 0.0, 0.4)).norm() < 1e-12, "total pin joint rotation");
    assert!((euler_deg(&kin(6).r)[2] - 2.291831180523293e+01).abs() < 1e-10);

    // Drive hinge: 1 rad about the diagonal; the free node keeps its centre of mass (offset
    // c = (0.1, 0.2, 0.3) in the node frame) where it was: x = (0, 0, 1) + c − R c.
    let axis = Vec3::new(1.0, 1.0, 1.0).normalize();
    assert!((rotation_vector_of(&kin(3).r) - axis).norm() < 1e-12, "drive hinge: {}", rotation_vector_of(&kin(3).r));
    let c = Vec3::new(0.1, 0.2, 0.3);
    let cm = Vec3::new(0.0, 0.0, 1.0) + c - kin(3).r * c;
    // The centre of mass moves by the integrator's error only (ms, h = 1 ms): 1e-9 m.
    assert!((kin(3).x - cm).norm() < 1e-9, "drive hinge node {} against {cm}", kin(3).x);
    let mbdyn_x3 = Vec3::new(-9.455211937633332e-02, 9.716469991507863e-02, 9.973874194612973e-01);
    let mbdyn_e3 = Vec3::new(2.562046941862889e+01, 3.972146855160072e+01, 2.562046941862882e+01);
    assert!((kin(3).x - mbdyn_x3).norm() < 1e-12 && (euler_deg(&kin(3).r) - mbdyn_e3).norm() < 1e-10, "drive hinge against MBDyn");

    // Velocity constraints: x = 0.5 t exactly (a linear motion); 2 rad about z, within the
    // integration error of the orientation parameters at ω h = 2e-3 over 1000 steps
    // (4e-7 rad measured, as MBDyn's); against MBDyn 1e-11 deg.
    assert!((kin(5).x - Vec3::new(0.5, 0.0, 2.0)).norm() < 1e-12, "total joint velocity: {}", kin(5).x);
    assert!((kin(5).omega - Vec3::new(0.0, 0.0, 2.0)).norm() < 1e-12);
    let rz = euler_deg(&kin(5).r)[2];
    assert!((rz.to_radians() - 2.0).abs() < 1e-6, "total joint angular velocity: {rz} deg");
    assert!((rz - 1.145915817029747e+02).abs() < 1e-8, "{rz} deg against MBDyn");
}

#[test]
fn initial_velocities_are_checked_against_moving_and_velocity_constraints() {
    // A drive displacement pin ramping at 0.5 m/s from t = 0: the written velocity
    // (0.5, 0, 0) satisfies it (Φ_q q̇ + Φ_t = 0), a body at rest violates it by 0.5 m/s.
    let ramp = ("single, 1., 0., 0., cosine, 0., pi, .1, forever, 0.;", "single, 1., 0., 0., ramp, .5, 0., 1., 0.;");
    let at_rest = ("structural: 2, dynamic, 1., 0., 0., eye, null, null;", "structural: 2, dynamic, 1., 0., 0., eye, null, null;");
    let moving = ("structural: 2, dynamic, 1., 0., 0., eye, null, null;", "structural: 2, dynamic, 1., 0., 0., eye, .5, 0., 0., null;");
    let short = ("final time: 1.;", "final time: 1.e-3;");
    for (node, expected) in [(moving, None), (at_rest, Some(0.5))] {
        let m = rewritten("driven_joints.mbd", &[ramp, node, short]);
        let report = run(&m.model, &m.problem, &mut ()).unwrap();
        match (report.inconsistent_velocity.clone(), expected) {
            (None, None) => {}
            (Some((eq, rate)), Some(e)) => assert!((rate.abs() - e).abs() < 1e-6 && eq.contains("drive displacement pin 2"), "{eq}: {rate}"),
            (got, _) => panic!("expected {expected:?}, got {got:?}"),
        }
    }
    // The velocity constraint of total joint 5 (0.5 m/s along x) with node 5 written at rest:
    // the derivatives phase holds the written velocities (as MBDyn's), so it cannot hold, and
    // the run stops naming the constraint and its violation.
    let m = rewritten("driven_joints.mbd", &[("eye, .5, 0., 0., 0., 0., 2.;", "eye, null, 0., 0., 2.;"), short]);
    let message = run(&m.model, &m.problem, &mut ()).err().expect("the derivatives phase fails").to_string();
    assert!(message.contains("total joint 5 constraint v x (-5.000e-1)"), "{message}");
}

#[test]
fn cardano_hinge_jacobians_match_finite_differences() {
    assert_jacobians(|n| {
        vec![
            Box::new(CardanoHinge::new(1, node(2, n), node(3, n), true, "cardano hinge")),
            Box::new(CardanoHinge::new(2, ground(n), node(2, n), true, "cardano pin")),
            Box::new(CardanoHinge::new(3, node(1, n), node(3, n), false, "cardano rotation")),
            Box::new(Joint::revolute_rotation(4, node(2, n), node(3, n))),
        ]
    });
}

#[test]
fn cardano_joints_transmit_rotation_as_hooke_and_swing_as_mbdyn() {
    // cardano.mbd at t = 1 s. MBDyn 1.7.3 (1727489e) on the same file, .mov:
    //   node 3 Euler 1-2-3 (4.943239448296498e+01, 2.368119219419702e+01,
    //   −1.102397901969219e+01) deg; node 4 at (−8.194791944824115e-03,
    //   1.377184303355277e-02, −9.998715826167178e-01) m, (7.891199256471066e-01,
    //   4.695322477357720e-01, 3.2e-15) deg; node 5 the same 2 m along x.
    let m = read("cardano.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    assert!(report.inconsistent_velocity.is_none(), "{:?}", report.inconsistent_velocity);
    let asm = Assembler::new(&m.model);
    let kin = |label: u32| report.final_state.node_frame(&asm.dofs, m.model.node_index(label).unwrap()).kin;

    // Hooke's joint: tan φ₂ = tan φ₁ cos β, the output turning about its axis s (1e-10 rad:
    // the constraints hold to Newton's tolerance, whatever φ₁ the integrator reached).
    let b = std::f64::consts::PI / 6.0;
    let phi1 = rotation_vector_of(&kin(2).r);
    // The input's angle integrates ω = 1 rad/s through the orientation parameters: 4.9e-8
    // rad over 1000 steps, as MBDyn's (5.729578234769110e+01 deg); 1e-7 allowed.
    assert!(phi1.y.abs() < 1e-12 && phi1.z.abs() < 1e-12 && (phi1.x - 1.0).abs() < 1e-7, "input {phi1}");
    assert!((phi1.x.to_degrees() - 5.729578234769110e+01).abs() < 1e-10, "input {phi1} against MBDyn");
    let phi2 = (phi1.x.tan() * b.cos()).atan();
    let s = Vec3::new(b.cos(), b.sin(), 0.0);
    assert!((rotation_vector_of(&kin(3).r) - phi2 * s).norm() < 1e-10, "output {} against {}", rotation_vector_of(&kin(3).r), phi2 * s);
    let mbdyn_e3 = Vec3::new(4.943239448296498e+01, 2.368119219419702e+01, -1.102397901969219e+01);
    assert!((euler_deg(&kin(3).r) - mbdyn_e3).norm() < 1e-10, "node 3 {} against MBDyn {mbdyn_e3}", euler_deg(&kin(3).r));

    // The pendulums: as MBDyn to 1e-12 m and 1e-10 deg; the pin and the hinge to node 1
    // give the same motion (1e-12), no twist about z (Euler angle 3 below 1e-12 deg).
    let mbdyn_x4 = Vec3::new(-8.194791944824115e-03, 1.377184303355277e-02, -9.998715826167178e-01);
    let mbdyn_e4 = Vec3::new(7.891199256471066e-01, 4.695322477357720e-01, 3.220156314460234e-15);
    assert!((kin(4).x - mbdyn_x4).norm() < 1e-12, "node 4 {} against MBDyn {mbdyn_x4}", kin(4).x);
    assert!((euler_deg(&kin(4).r) - mbdyn_e4).norm() < 1e-10, "node 4 {} against MBDyn {mbdyn_e4}", euler_deg(&kin(4).r));
    assert!((kin(5).x - kin(4).x - Vec3::new(2.0, 0.0, 0.0)).norm() < 1e-12 && (kin(5).r - kin(4).r).norm() < 1e-12);
}

#[test]
fn a_velocity_constraint_linearizes_as_mbdyn_linearizes_it() {
    // spinning_pendulum.mbd, eigenanalysis at t = 0.5 s. MBDyn 1.7.3 (1727489e) on the same
    // file, sp_0.m: the only non-zero finite eigenvalues −4.7e-13 ± 3.1305270803j rad/s
    // (= sqrt(9.81/1.001), the frozen linearization's), the others zero. romdyn: the same
    // pair as its only dynamic mode, to 1e-9 relative.
    let m = read("spinning_pendulum.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let eig = &report.eigenanalyses[0];
    assert!((eig.time - 0.5).abs() < 1e-9);
    assert_eq!(eig.dynamic.len(), 2, "{:?}", eig.dynamic);
    for l in &eig.dynamic {
        assert!(l.re.abs() < 1e-9 && (l.im.abs() - 3.1305270803).abs() < 1e-9 * 3.13, "λ = {l}");
    }
    assert!((3.1305270803f64 - (9.81f64 / 1.001).sqrt()).abs() < 1e-9);
}

#[test]
fn a_prestressed_deformable_hinge_rests_at_its_shifted_strain_as_mbdyn() {
    // prestressed_hinge.mbd at t = 2.001 s: θ = θ_p − K⁻¹ M_p = (0.09, 0.01, −0.06) rad (the
    // transient has decayed, 1e-10 rad). MBDyn 1.7.3 (1727489e) on the same file, .mov:
    // Euler 1-2-3 (5.170809779775328, 4.172887875894098e-01, −3.458939942759398) deg.
    let m = read("prestressed_hinge.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let r = report.final_state.node_frame(&asm.dofs, 1).kin.r;
    let theta = rotation_vector_of(&r);
    assert!((theta - Vec3::new(0.09, 0.01, -0.06)).norm() < 1e-10, "θ = {theta}");
    let mbdyn = Vec3::new(5.170809779775328, 4.172887875894098e-01, -3.458939942759398);
    assert!((euler_deg(&r) - mbdyn).norm() < 1e-9, "{} against MBDyn {mbdyn}", euler_deg(&r));
    assert_eq!(m.model.elements[2].type_name(), "deformable hinge");
}

#[test]
fn revolute_rotation_and_spherical_hinge_swing_as_the_revolute_hinge_and_mbdyn() {
    // default_pendulum.mbd with its revolute hinge split into a spherical hinge and a
    // 'revolute rotation' (the lines below). MBDyn 1.7.3 (1727489e) on that file with output
    // precision 15: node 2 at (−9.861388655041501e-01, −1.659220839496490e-01, 0) m at t =
    // 1 s, as with the revolute hinge (−9.861388655041513e-01, −1.659220839496368e-01).
    let split = rewritten(
        "default_pendulum.mbd",
        &[
            ("    joints: 2;", "    joints: 3;"),
            ("    joint: 2, revolute hinge, 1, null, 2, reference, node, -1., 0., 0.;", "    joint: 2, spherical hinge, 1, null, 2, reference, node, -1., 0., 0.;\n    joint: 3, revolute rotation, 1, 2;"),
        ],
    );
    assert_eq!(split.model.elements[2].type_name(), "revolute rotation");
    let whole = read("default_pendulum.mbd");
    let x = |m: &MbdynModel| {
        let report = run(&m.model, &m.problem, &mut ()).unwrap();
        report.final_state.node_frame(&Assembler::new(&m.model).dofs, 1).kin.x
    };
    let (a, b) = (x(&split), x(&whole));
    assert!((a - b).norm() < 1e-10, "{a} against the revolute hinge {b}");
    let mbdyn = Vec3::new(-9.861388655041501e-01, -1.659220839496490e-01, 0.0);
    // The file has MBDyn's default tolerance (1e-6, one iteration per step): 2.0e-9 m
    // measured, 1e-8 allowed.
    assert!((a - mbdyn).norm() < 1e-8, "{a} against MBDyn {mbdyn}");
}

#[test]
fn imposed_velocity_jacobians_match_finite_differences() {
    assert_jacobians(|n| {
        let value = Drive::Sine { t0: 0.0, omega: 2.0, amplitude: 0.7, cycles: None, v0: 0.1 };
        vec![
            Box::new(ImposedVelocity { label: 1, node: 2, kind: VelocityKind::Linear, direction: n.vec().normalize(), value: value.clone() }),
            Box::new(ImposedVelocity { label: 2, node: 3, kind: VelocityKind::Angular, direction: n.vec().normalize(), value }),
        ]
    });
}

#[test]
fn linear_and_angular_velocity_joints_drive_free_bodies_as_the_closed_form_and_mbdyn() {
    // imposed_velocity.mbd at t = 1 s. MBDyn 1.7.3 (1727489e) on the same file, .mov:
    //   node 2 (7.071067811865589e-01, 7.071067811865589e-01, −4.905000009805131) m;
    //   node 3 Euler 1-2-3 (−1.085860953956683, 2.366511348351699, 1.146991813614214e+02)
    //   deg, ω = (1.741666832358590e-02, −3.786900929704295e-02, 2.002064585694221) rad/s.
    // MBDyn's free fall is off by g·dCoef in velocity (9.810000009810 m/s): its derivatives
    // phase keeps the momenta's Newton values, dCoef·F off m v (dCoef = 1e-6 h = 1e-9 s), as
    // romdyn's now does for MBDyn files; the first Crank–Nicolson step carries half of that
    // velocity into the position, so z = −g t²/2 − g dCoef (t − h/2).
    let m = read("imposed_velocity.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = |label: u32| report.final_state.node_frame(&asm.dofs, m.model.node_index(label).unwrap()).kin;
    // Node 2: 1 m along (1, 1, 0)/√2 (∫ 2t dt), free fall −g/2 (a parabola: exact) plus the
    // derivatives phase's −g dCoef (t − h/2) = −9.805e-9 m.
    let d = Vec3::new(1.0, 1.0, 0.0).normalize();
    let z = -4.905 - 9.81 * 1e-9 * (1.0 - 0.5e-3);
    assert!((kin(2).x - Vec3::new(d.x, d.y, z)).norm() < 1e-12, "node 2 {}", kin(2).x);
    assert!((kin(2).x - Vec3::new(7.071067811865589e-01, 7.071067811865589e-01, -4.905000009805131)).norm() < 1e-12, "node 2 against MBDyn");
    // Node 3: the spin about its own axis 3 held at 2 rad/s (Newton's tolerance); its
    // precession as MBDyn's to 1e-7 deg, 1e-9 rad/s.
    let (r, w) = (kin(3).r, kin(3).omega);
    assert!(((r * Vec3::z()).dot(&w) - 2.0).abs() < 1e-10, "spin {}", (r * Vec3::z()).dot(&w));
    let e = Vec3::new(-1.085860953956683, 2.366511348351699, 1.146991813614214e+02);
    let mbdyn_w = Vec3::new(1.741666832358590e-02, -3.786900929704295e-02, 2.002064585694221);
    assert!((euler_deg(&r) - e).norm() < 1e-7, "node 3 {} against MBDyn {e}", euler_deg(&r));
    assert!((w - mbdyn_w).norm() < 1e-9, "node 3 ω {w} against MBDyn {mbdyn_w}");
}

#[test]
fn driven_element_jacobians_match_finite_differences_on_and_off() {
    // Switched on (drive 1) the wrapped element's own Jacobian; switched off (drive 0) the
    // `−λ = 0` rows, in both constraint forms (the assembler scales the rows by 1/c in the
    // form of eq. 30), for holonomic and velocity constraints.
    for on in [1.0, 0.0] {
        assert_jacobians(|n| {
            let drive = Drive::Const(on);
            vec![
                Box::new(DrivenElement { drive: drive.clone(), inner: Box::new(Joint::spherical_hinge(1, node(2, n), node(3, n))), hints: Vec::new() }),
                Box::new(DrivenElement { drive: drive.clone(), inner: Box::new(Joint::prismatic(2, ground(n), node(2, n))), hints: Vec::new() }),
                Box::new(DrivenElement { drive, inner: Box::new(AxialRotation::new(3, node(1, n), node(3, n), Drive::Const(2.0))), hints: Vec::new() }),
            ]
        });
    }
}

#[test]
fn driven_elements_switch_as_in_mbdyn() {
    // driven_elements.mbd. Closed forms: node 2 turns at 1 rad/s until the revolute rotation
    // is switched off at t = 0.5 s, then the prismatic joint holds it at 0.5 rad, at rest.
    // After its hinge is switched off (t = 0.5005 s) the pendulum bob flies: between t = 0.75
    // s and 1 s its horizontal velocity holds and its vertical one falls by g · 0.25 s.
    let final_of = |m: &MbdynModel| {
        let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
        let asm = Assembler::new(&m.model);
        [1usize, 3].map(|i| report.final_state.node_frame(&asm.dofs, i).kin)
    };
    let [spun, bob] = final_of(&read("driven_elements.mbd"));
    let angle = spun.r[(1, 0)].atan2(spun.r[(0, 0)]);
    assert!((angle - 0.5).abs() < 1e-9 && spun.omega.norm() < 1e-9, "angle {angle}, ω {}", spun.omega);
    let [_, early] = final_of(&rewritten("driven_elements.mbd", &[("final time: 1.;", "final time: .75;")]));
    assert!((bob.xdot[0] - early.xdot[0]).abs() < 1e-9 && (bob.xdot[2] - early.xdot[2] + 9.81 * 0.25).abs() < 1e-9, "{} then {}", early.xdot, bob.xdot);
    // MBDyn 1.7.3 on driven_elements.mbd, .mov at t = 1 s: node 2 Euler 1-2-3 angle about z
    // 2.864788975654104e+01 deg; node 4 position (2.369508416588420, 0, −2.154024238998492)
    // m, velocity (8.120604118511876e-02, 0, −4.871807999150967) m/s. The same discrete
    // formulation: 1e-10 m, 1e-9 m/s (tolerance 1e-9).
    assert!((angle.to_degrees() - 2.864788975654104e+01).abs() < 1e-9, "angle {} deg", angle.to_degrees());
    let (x, v) = (Vec3::new(2.369508416588420, 0.0, -2.154024238998492), Vec3::new(8.120604118511876e-02, 0.0, -4.871807999150967));
    assert!((bob.x - x).norm() < 1e-10 && (bob.xdot - v).norm() < 1e-9, "bob at {} moving {}, MBDyn {x} {v}", bob.x, bob.xdot);
}

#[test]
fn distance_jacobian_matches_finite_differences() {
    // MBDyn's four-unknown distance (direction w = v − v₀ and tension α), with offsets, to
    // the ground and between nodes, a drive in time.
    assert_jacobians(|n| {
        let ramp = Drive::Ramp { slope: 0.1, t0: 0.0, t1: 9.0, v0: 0.5 };
        vec![
            Box::new(Distance { label: 1, a: node(2, n), b: node(3, n), length: ramp.clone(), direction: n.vec().normalize() }),
            Box::new(Distance { label: 2, a: ground(n), b: node(3, n), length: Drive::Const(0.7), direction: n.vec().normalize() }),
            Box::new(Distance { label: 3, a: node(1, n), b: node(2, n), length: ramp, direction: n.vec().normalize() }),
        ]
    });
}

#[test]
fn distance_joints_pass_the_derivatives_phase_with_rounded_lengths_as_mbdyn() {
    // distance_rounding.mbd: MBDyn's tests/stiff/Swing4 with one beam (derivatives
    // coefficient 1e-9: dCoef = 2e-13 s). With one multiplier and the row (|d| − L)/dCoef
    // romdyn stopped there ("distance 4 constraint f (5.551e-4)", the 1.1e-16 m rounding of
    // l + h − l); MBDyn 1.7.3 runs it. Closed form: both distances hold (to 1e-9 m, the
    // integrator's tolerance on the scaled rows). MBDyn 1.7.3 (1727489e) on the same file,
    // t = 0.05 s, nodes 1, 2, 3 (x, z) [m]; agreement to 3e-6 m (measured 2.1e-6: the
    // velocities differ by 4e-6 m/s after the first step, in this stiff beam's derivatives
    // phase at dCoef = 2e-13 s, where both programs keep Newton's momenta; not found).
    let m = read("distance_rounding.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let x = |i: usize| report.final_state.node_frame(&asm.dofs, i).kin.x;
    let (h, l) = (0.36, 0.72);
    assert!(((x(2) - x(0)).norm() - h).abs() < 1e-9, "distance 3: {}", (x(2) - x(0)).norm());
    assert!(((x(4) - x(1)).norm() - 2f64.sqrt() * h).abs() < 1e-9, "distance 4: {}", (x(4) - x(1)).norm());
    assert!((x(1) - Vec3::new(l + h, 0.0, 0.0)).norm() == 0.0);
    let mbdyn = [(2, 3.6053792463956345e-04, -3.5999981946163506e-01), (3, 3.6007784953723332e-01, -3.7232624471965925e-01), (4, 7.1978789093709417e-01, -3.5978776589047723e-01)];
    for (i, mx, mz) in mbdyn {
        let d = (x(i) - Vec3::new(mx, 0.0, mz)).norm();
        assert!(d < 3e-6, "node index {i}: {} against MBDyn ({mx}, 0, {mz}): {d:e} m", x(i));
    }
}

#[test]
fn gimbal_rotation_jacobian_matches_finite_differences() {
    assert_jacobians(|n| {
        vec![
            Box::new(GimbalRotation { label: 1, a: node(2, n), b: node(3, n), angles: [0.3, -0.7] }),
            Box::new(GimbalRotation { label: 2, a: ground(n), b: node(3, n), angles: [-0.2, 0.4] }),
            Box::new(GimbalRotation { label: 3, a: node(1, n), b: node(2, n), angles: [0.0, 0.0] }),
        ]
    });
}

#[test]
fn gimbal_angles_of_a_relative_orientation_in_its_set_are_exact() {
    // R(θ, φ) = E(θ) F(φ) E(θ) (gimbal.cc): the angles are recovered from R to rounding.
    let (e1, e2) = (Vec3::x_axis(), Vec3::y_axis());
    let rot = |axis, angle| *nalgebra::Rotation3::from_axis_angle(&axis, angle).matrix();
    let (theta, phi) = (-0.147, 0.188);
    let r = rot(e2, theta) * rot(e1, phi) * rot(e2, theta);
    let [t, p] = GimbalRotation::angles_of(&r);
    assert!((t - theta).abs() < 1e-14 && (p - phi).abs() < 1e-14, "{t} {p}");
}

#[test]
fn gimbal_rotation_transmits_rotation_homokinetically_as_mbdyn() {
    // gimbal_shafts.mbd: shaft A spun at W = 1 rad/s about z, shaft B on a hinge tilted by
    // 20° about x, joined by a gimbal rotation: B turns uniformly (homokinetic joint), W t =
    // 1 rad after 1 s; its Euler 1-2-3 angles are (20°, 0, W t). ms integrates the
    // orientation parameters: 5e-8 rad of integration error (MBDyn's: 4.9e-8 rad). MBDyn 1.7.3
    // (1727489e) on the same file at t = 1 s: node 3 Euler 123 (2.0000000000000796e+01,
    // 4.7953305731604711e-13, 5.7295782347692636e+01) deg, ω = (−2.88e-13,
    // −3.4202014332576131e-01, 9.3969262078591431e-01) rad/s.
    let m = read("gimbal_shafts.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, 2).kin;
    let e = euler_deg(&kin.r);
    assert!((e[0] - 20.0).abs() < 1e-9 && e[1].abs() < 1e-9, "{e}");
    assert!((e[2].to_radians() - 1.0).abs() < 1e-7, "turned {} rad", e[2].to_radians());
    assert!((e[2] - 5.7295782347692636e+01).abs() < 1e-8, "{} deg against MBDyn", e[2]);
    let w = Vec3::new(0.0, -20f64.to_radians().sin(), 20f64.to_radians().cos());
    assert!((kin.omega - w).norm() < 1e-9, "ω = {}", kin.omega);
    // With the initial assembly (MBDyn's fails here), romdyn starts from the written angles.
    let assembled = rewritten("gimbal_shafts.mbd", &[("    skip initial joint assembly;\n", "")]);
    let report = run(&assembled.model, &assembled.problem, &mut ()).unwrap();
    let kin = report.final_state.node_frame(&asm.dofs, 2).kin;
    assert!((euler_deg(&kin.r)[2] - 5.7295782347692636e+01).abs() < 1e-8);
}

#[test]
fn the_deprecated_pin_is_the_spherical_pin() {
    // joint.cc reads `pin` and `spherical pin` with one reader (`case PIN: case
    // SPHERICALPIN`): compat_spherical.mbd with `pin` gives the same run to the last bit.
    let (spherical, pin) = (read("compat_spherical.mbd"), rewritten("compat_spherical.mbd", &[("spherical pin,", "pin,")]));
    let (a, b) = (run(&spherical.model, &spherical.problem, &mut ()).unwrap(), run(&pin.model, &pin.problem, &mut ()).unwrap());
    assert_eq!(a.final_state.y, b.final_state.y);
    assert!(pin.model.elements.iter().any(|e| e.label() == 1 && e.type_name() == "spherical hinge"));
}

#[test]
fn the_revolute_hinge_chain_takes_mbdyns_newton_iterations() {
    // revolute_chain.mbd: the 10-link chain with revolute hinges, their position constraint
    // in the global frame as MBDyn's planej.cc (before, in node 1's frame: 1795 iterations,
    // MBDyn's count on the total-joint chain). MBDyn 1.7.3 (1727489e) on this file: 1508
    // Newton iterations over 1000 steps, 1 derivatives iteration, and the final x, y, ẋ, ẏ of
    // nodes 1–10 below (its .mov, output precision 16). romdyn: 1536 (its Jacobians are exact
    // where MBDyn's drop terms): to 3 %; positions and velocities to 1e-6 relative (issue 12's
    // acceptance; measured 5.0e-8 m).
    let want: [[f64; 4]; 10] = [
        [-8.6540736852381756e-02, -5.0106894386382918e-02, 2.4842890957304756e-01, -4.2906975219616317e-01],
        [-1.8627732208190581e-01, -4.2853373396244628e-02, 2.2819243360686539e-01, -7.0724157167768464e-01],
        [-2.8158476641319646e-01, -1.2579770124779212e-02, 2.2348601996430312e-01, -7.2205792171712579e-01],
        [-3.7335715614891762e-01, 2.7142119082499010e-02, 3.2553540762813210e-01, -4.8628815126275748e-01],
        [-4.6444625084215518e-01, 6.8406835584207792e-02, 4.0516491424690509e-01, -3.1051363308281299e-01],
        [-5.6380170669537322e-01, 7.9742328171615598e-02, 4.1317201804667286e-01, -2.4033041276177489e-01],
        [-6.5711015570010411e-01, 4.3776603594853164e-02, 3.9187310861308600e-01, -1.8507397507950454e-01],
        [-7.3946836036558505e-01, -1.2943111886439389e-02, 3.5438213298998922e-01, -1.3063653785928800e-01],
        [-8.1253435855101597e-01, -8.1217264456549060e-02, 3.3873405522569405e-01, -1.1389022075283081e-01],
        [-8.6897040015363702e-01, -1.6377011545654316e-01, 3.4143570107971172e-01, -1.1573715708420530e-01],
    ];
    let m = read("revolute_chain.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(report.steps, 1000);
    let iterations = report.newton_iterations as f64;
    assert!((iterations - 1508.0).abs() <= 0.03 * 1508.0, "romdyn {iterations} Newton iterations, MBDyn 1.7.3 1508");
    let asm = Assembler::new(&m.model);
    for (k, w) in want.iter().enumerate() {
        let kin = report.final_state.node_frame(&asm.dofs, k + 1).kin;
        let (dx, dv) = ((kin.x[0] - w[0]).hypot(kin.x[1] - w[1]) / w[0].hypot(w[1]), (kin.xdot[0] - w[2]).hypot(kin.xdot[1] - w[3]) / w[2].hypot(w[3]));
        assert!(dx < 1e-6 && dv < 1e-6, "node {}: position {dx:.1e}, velocity {dv:.1e} from MBDyn", k + 1);
    }
}

#[test]
fn revolute_rotation_constraints_keep_their_rank_past_half_a_turn() {
    // The hinge's rotation rows (MBDyn's planej.cc: e₃ₐ · e₂ᵦ, −e₃ₐ · e₁ᵦ) at a relative
    // rotation of π about the axis: closed form ∂/∂θ_b = (−1, 0, 0) and (0, −1, 0) (the skew
    // part's rows were zero there). Then rotor_half_turn.mbd: θ = t²/2 = 3.38 rad, ω = t = 2.6
    // rad/s at t = 2.6 s (ms: 1e-9 rad); MBDyn 1.7.3 (1727489e) on the same file: Euler 123 z
    // −1.6634026490697812e+02 deg, ω_z = 2.6000000001008177 rad/s.
    let half = *nalgebra::Rotation3::from_axis_angle(&Vec3::z_axis(), std::f64::consts::PI).matrix();
    let mut b = ModelBuilder::new();
    b.static_node(1, Vec3::zeros(), half);
    b.element(Joint::revolute_hinge(1, Anchor::Ground { position: Vec3::zeros(), orientation: Mat3::identity() }, Anchor::Node { label: 1, offset: Vec3::zeros(), orientation: Mat3::identity() }));
    let model = b.build().unwrap();
    let asm = Assembler::new(&model);
    let st = State::initial(&model, &asm.dofs);
    let j = asm.jacobian(&st, romdyn::dae::Coefficients::static_analysis());
    let first = asm.dofs.element_first[0];
    let entry = |row: usize, col: usize| (0..j.values.len()).filter(|&k| j.rows[k] == row && j.cols[k] == col).map(|k| j.values[k]).sum::<f64>();
    for (row, want) in [(first + 3, [-1.0, 0.0, 0.0]), (first + 4, [0.0, -1.0, 0.0])] {
        for (c, w) in want.iter().enumerate() {
            assert!((entry(row, 3 + c) - w).abs() < 1e-12, "row {row} col {c}: {}", entry(row, 3 + c));
        }
    }
    let m = read("rotor_half_turn.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, 1).kin;
    let turned = 2.6f64 * 2.6 / 2.0 - 2.0 * std::f64::consts::PI;
    let z = kin.r[(1, 0)].atan2(kin.r[(0, 0)]);
    assert!((z - turned).abs() < 1e-8, "turned {z} rad, closed form {turned}");
    assert!((z.to_degrees() - -1.6634026490697812e+02).abs() < 1e-9, "{} deg against MBDyn", z.to_degrees());
    assert!((kin.omega - Vec3::new(0.0, 0.0, 2.6)).norm() < 1e-9, "ω = {}", kin.omega);
}

#[test]
fn plane_displacement_is_refused_naming_mbdyns_own_refusal() {
    // MBDyn 1.7.3 on tests/joints/planed/planedisp: "PlaneDispJoint(2): unsupported; use an
    // InPlane and a RevoluteRotation" (joint.cc). romdyn refuses it at its file:line:col.
    let text = common::mbdyn::file("structural nodes: 2; joints: 2;", "structural: 1, static, null, eye, null, null;\nstructural: 2, static, null, eye, null, null;", "joint: 1, clamp, 1, node, node;\njoint: 2, plane displacement, 1, 2;");
    let err = parse_text(&text, Path::new("planedisp.mbd")).and_then(|d| build(&d)).err().expect("refused").to_string();
    assert!(err.contains("planedisp.mbd:") && err.contains("'plane displacement'") && err.contains("nor by MBDyn 1.7.3") && err.contains("'in plane' and a 'revolute rotation'"), "{err}");
}

/// Total joints whose position and rotation orientations differ (`total_joint_two_frames.mbd`,
/// after MBDyn's tests/eig/joints/totaljoint): one frame carries both kinds of constraint
/// when all three of one kind are constrained, the same constraint manifold.
#[test]
fn total_joints_with_two_frames_constrain_each_kind_in_its_own_frame() {
    let m = read("total_joint_two_frames.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let mut im: Vec<f64> = report.eigenanalyses[0].dynamic.iter().filter(|l| l.im > 0.0).map(|l| l.im).collect();
    im.sort_by(f64::total_cmp);
    // Closed forms in the file's header: sqrt(k/J) about x and y for node 2, sqrt(k/m)
    // along y and along (1, 0, −1)/√2 for node 1. MBDyn 1.7.3 (1727489e) on this file,
    // mb_0.m (alpha printed to 7 digits, eigenvalues rebuilt as scripts/compare_mbdyn.sh
    // does): 31.622779992, 44.721377080, 63.245549937, 70.710679912 rad/s.
    let exact = [1000f64.sqrt(), 2000f64.sqrt(), 4000f64.sqrt(), 5000f64.sqrt()];
    let mbdyn = [31.622779992, 44.721377080, 63.245549937, 70.710679912];
    assert_eq!(im.len(), 4, "{im:?}");
    for ((x, e), mb) in im.iter().zip(exact).zip(mbdyn) {
        // romdyn's eigenanalysis of the linearization at rest: rounding (1e-12 measured).
        assert!((x - e).abs() < 1e-9 * e, "{x} against the closed form {e}");
        // MBDyn's J(±c) pencil with parameter 1e-6 and 7 printed digits: 4e-7 measured; 1e-6.
        assert!((x - mb).abs() < 1e-6 * e, "{x} against MBDyn {mb}");
    }
    // The Jacobians of the two total joints against central differences, moved off rest.
    let asm = Assembler::new(&m.model);
    let mut st = State::initial(&m.model, &asm.dofs);
    let mut noise = Noise(5);
    st.y.iter_mut().chain(st.yp.iter_mut()).for_each(|v| *v += 1e-2 * noise.next());
    for c in check_jacobians(&asm, &st, 1e-3, m.model.constraint_form) {
        assert!(c.within(1e-7), "{c:?}");
    }
    // A partial constraint of each kind in different frames is still refused, naming the card.
    let t = std::fs::read_to_string(path("total_joint_two_frames.mbd")).unwrap();
    let partial = t.replacen("		orientation constraint, active, active, active,", "		orientation constraint, active, active, inactive,", 1);
    assert_ne!(partial, t);
    let e = parse_text(&partial, &path("total_joint_two_frames.mbd")).and_then(|d| build(&d)).err().expect("refused").to_string();
    assert!(e.contains("total_joint_two_frames.mbd:80:12") && e.contains("one constraint frame"), "{e}");
}

/// A total joint (two nodes) and a total pin joint with some rotations locked to imposed
/// values, in MBDyn's form with the remnant of the free components.
fn partial_rotation_joints(n: &mut Noise) -> Vec<Box<dyn Element>> {
    let mut two = DrivenJoint::new(Joint::total(1, node(2, n), node(3, n), [true, false, true], [false, true, true]), "total joint");
    two.rotation = VectorDrive(vector_drive(n).0.into_iter().map(|(v, d)| (Vec3::new(0.0, v.y, v.z), d)).collect());
    two.position = vector_drive(n);
    two.rotation_remnant = true;
    let mut pin = DrivenJoint::new(Joint::total(2, ground(n), node(2, n), [true; 3], [false, false, true]), "total pin joint");
    pin.rotation = VectorDrive(vector_drive(n).0.into_iter().map(|(v, d)| (Vec3::new(0.0, 0.0, v.z), d)).collect());
    pin.rotation_remnant = true;
    // With a velocity constraint beside the locked rotations.
    pin.angular_velocity_locked = [true, false, false];
    pin.angular_velocity = vector_drive(n);
    vec![Box::new(two), Box::new(pin)]
}

#[test]
fn partial_imposed_rotation_jacobians_match_finite_differences() {
    // Without a remnant (before the first convergence) …
    assert_jacobians(partial_rotation_joints);
    // … and with one latched on each joint (a constant of the state, as MBDyn's member).
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let model = common::mbdyn::model_with(form, partial_rotation_joints);
        let asm = Assembler::new(&model);
        let mut st = State::initial(&model, &asm.dofs);
        let mut n = Noise(17);
        st.t = 0.3;
        for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
            *x += 0.5 * n.next();
        }
        for (e, r) in [(0, Vec3::new(0.7, 0.0, 0.0)), (1, Vec3::new(-0.4, 0.9, 0.0))] {
            st.latched[e] = Some(std::sync::Arc::new(RotationRemnant(r)));
        }
        let checks = check_jacobians(&asm, &st, 0.37, form);
        assert!(!checks.is_empty());
        for w in checks {
            assert!(w.relative_error < 1e-6, "{form:?}: {} d({})/d({}): analytic {:e}, fd {:e}", w.element, w.equation, w.unknown, w.analytic, w.finite_difference);
        }
    }
}

#[test]
fn partial_rotation_locks_turn_as_the_closed_form_and_mbdyn() {
    // total_joint_partial_rotation.mbd at t = 1 s. MBDyn 1.7.3 (1727489e) on the same file,
    // .mov (Euler 1-2-3 angles [deg], angular velocity [rad/s]):
    //   node 2: rz = 5.729577951308232e+01, ω_z = 1.900206657701962e-10;
    //   node 3: (−8.595717718449890e+01, −2.873799590725513e+01, 3.063552560400624e+01),
    //           (3.385343733315137, 1.141747870550197, −6.595298244926470e-01);
    //   node 4: (−9.138510682728405e+01, 2.219105823728551e+01, −2.159911892784433e+01),
    //           (3.352423840183900, −8.181902096418520e-01, 4.904291908790889e-01);
    //   node 5: (−1.249581615029010e+02, 3.040478990732576e+01, 5.508886696940485e+01),
    //           (1.760707588114319, −1.255065836445735, −8.374622308903965e-03).
    let m = read("total_joint_partial_rotation.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = |label: u32| report.final_state.node_frame(&asm.dofs, m.model.node_index(label).unwrap()).kin;
    assert!((report.final_state.t - 1.0).abs() < 1e-12);

    // Node 2, driven about z with x and y free and nothing to turn it about them: closed form
    // R = R_z(0.5 (1 − cos πt)), 1 rad at t = 1 s (to Newton's tolerance on the scaled rows,
    // 1e-10 dCoef), at rest there (θ̇ = 0.5 π sin π = 0; the integrated ω to 2e-10 rad/s,
    // MBDyn's 1.9e-10).
    assert!((rotation_vector_of(&kin(2).r) - Vec3::new(0.0, 0.0, 1.0)).norm() < 1e-12, "rotor: {}", rotation_vector_of(&kin(2).r));
    assert!(kin(2).omega.norm() < 1e-9, "rotor: ω = {}", kin(2).omega);
    assert!(kin(2).x.norm() < 1e-12);

    // Nodes 3 and 4 swing about their free axis while turned, node 5 tumbles with one
    // rotation held at zero: the remnant decides the reaction's direction (with it frozen at
    // zero nodes 3 and 4 end 6 to 15 deg away; node 5 in the skew-part form romdyn used
    // before, the same zero set with the reaction normal to it, 0.85 deg away). Against MBDyn
    // to 1e-7 deg and 1e-7 rad/s (measured 3.4e-8 deg, 4.4e-9 rad/s: Newton's 1e-10
    // stopping differences over 1000 steps of a swing).
    let mbdyn = [
        (3, Vec3::new(-8.595717718449890e+01, -2.873799590725513e+01, 3.063552560400624e+01), Vec3::new(3.385343733315137e+00, 1.141747870550197e+00, -6.595298244926470e-01)),
        (4, Vec3::new(-9.138510682728405e+01, 2.219105823728551e+01, -2.159911892784433e+01), Vec3::new(3.352423840183900e+00, -8.181902096418520e-01, 4.904291908790889e-01)),
        (5, Vec3::new(-1.249581615029010e+02, 3.040478990732576e+01, 5.508886696940485e+01), Vec3::new(1.760707588114319e+00, -1.255065836445735e+00, -8.374622308903965e-03)),
    ];
    for (label, e, w) in mbdyn {
        let k = kin(label);
        assert!((euler_deg(&k.r) - e).norm() < 1e-7, "node {label}: {} deg against MBDyn {e}", euler_deg(&k.r));
        assert!((k.omega - w).norm() < 1e-7, "node {label}: ω {} against MBDyn {w}", k.omega);
    }
    // The joints' points stay where they are held.
    assert!((kin(3).x - Vec3::new(0.0, 0.0, 1.0)).norm() < 1e-12 && (kin(4).x - Vec3::new(2.0, 0.0, 0.0)).norm() < 1e-12);
    assert!((kin(5).x - Vec3::new(0.0, 0.0, 4.0)).norm() < 1e-12);
}
