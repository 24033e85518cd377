//! Every element's analytic Jacobian against central finite differences of its residual, at
//! a random state (random orientation parameters, velocities, momenta, multipliers), in both
//! constraint forms. Tolerance: 1e-6 relative to the element's largest entry (issue 3).

use crate::common;

use common::fixtures::{Noise, WrongSpring};
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::drive::{ScalarFunction, Drive};
use romdyn::element::{Anchor, Beam2, Beam3, DeformableJoint, BeamNode, SectionLaw, SectionOrientation, Couple, DeformableDisplacement, DeformableHinge, Force, ForceFrame, Joint, LinearViscoelastic, RigidBody, Rod};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::model::ConstraintForm;
use romdyn::model::{Model, ModelBuilder};

fn node(label: u32, n: &mut Noise) -> Anchor {
    Anchor::Node { label, offset: n.vec(), orientation: n.rotation() }
}

/// Nodes 1 (static), 2 and 3 (dynamic) and one element of every type, each between
/// arbitrary offsets and frames.
fn every_element(form: ConstraintForm) -> Model {
    let mut n = Noise(12345);
    let mut b = ModelBuilder::new();
    b.static_node(1, n.vec(), n.rotation()).dynamic_node(2, n.vec(), n.rotation(), n.vec(), n.vec()).dynamic_node(3, n.vec(), n.rotation(), n.vec(), n.vec());
    let inertia = { let a = n.matrix(); a * a.transpose() + Mat3::identity() };
    b.element(RigidBody::new(1, 2, 2.5, n.vec(), inertia));
    b.element(RigidBody::new(2, 1, 1.5, n.vec(), Mat3::identity()));
    b.element(Joint::clamp(3, 1, n.vec(), n.rotation()));
    b.element(Joint::revolute_hinge(4, node(2, &mut n), node(3, &mut n)));
    b.element(Joint::spherical_hinge(5, node(1, &mut n), node(3, &mut n)));
    b.element(Joint::total(6, node(2, &mut n), node(3, &mut n), [true, false, true], [false, true, true]));
    b.element(Joint::total(7, Anchor::Ground { position: n.vec(), orientation: n.rotation() }, node(2, &mut n), [false, true, false], [true, false, false]));
    b.element(Joint::in_line(32, node(2, &mut n), node(3, &mut n)));
    b.element(Joint::in_plane(33, Anchor::Ground { position: n.vec(), orientation: n.rotation() }, node(3, &mut n)));
    b.element(Joint::prismatic(34, node(1, &mut n), node(2, &mut n)));
    b.element(romdyn::element::Distance { label: 35, a: node(2, &mut n), b: node(3, &mut n), length: Drive::Ramp { slope: 0.1, t0: 0.0, t1: 9.0, v0: 0.5 }, direction: Vec3::new(0.6, 0.0, 0.8) });
    b.element(romdyn::element::Distance { label: 36, a: Anchor::Ground { position: n.vec(), orientation: n.rotation() }, b: node(1, &mut n), length: Drive::Const(0.7), direction: Vec3::new(0.0, -1.0, 0.0) });
    let law = LinearViscoelastic { stiffness: n.matrix() * 100.0, viscosity: n.matrix() * 3.0 };
    b.element(DeformableDisplacement { label: 8, a: node(2, &mut n), b: node(3, &mut n), law: law.clone(), rest: n.vec() });
    b.element(DeformableDisplacement { label: 9, a: Anchor::Ground { position: n.vec(), orientation: n.rotation() }, b: node(3, &mut n), law: law.clone(), rest: Vec3::zeros() });
    b.element(DeformableHinge { label: 10, a: node(2, &mut n), b: node(3, &mut n), law: law.clone() });
    b.element(DeformableHinge { label: 11, a: Anchor::Ground { position: n.vec(), orientation: n.rotation() }, b: node(2, &mut n), law });
    b.element(Rod { label: 12, a: node(1, &mut n), b: node(3, &mut n), axial_stiffness: 1e3, length: 0.7, viscous: None, elastic: None });
    let drive = Drive::Sine { t0: 0.0, omega: 3.0, amplitude: 2.0, cycles: None, v0: 0.5 };
    for (label, frame) in [(13, ForceFrame::Absolute), (14, ForceFrame::Follower)] {
        b.element(Force::new(label, 3, frame, n.vec(), n.vec(), drive.clone()));
        b.element(Couple::new(label + 10, 2, frame, n.vec(), drive.clone()));
    }
    let random_law = |n: &mut Noise, viscous: bool| {
        let a = nalgebra::Matrix6::from_fn(|_, _| n.next());
        let v = nalgebra::Matrix6::from_fn(|_, _| n.next());
        let mut law = SectionLaw::viscoelastic(1e3 * (a * a.transpose() + nalgebra::Matrix6::identity()), if viscous { 10.0 * v } else { nalgebra::Matrix6::zeros() });
        law.prestrain = 1e-2 * nalgebra::Vector6::from_fn(|_, _| n.next());
        law.prestress = nalgebra::Vector6::from_fn(|_, _| n.next());
        law
    };
    let beam_nodes = |n: &mut Noise, b: &ModelBuilder| [0, 1, 2].map(|i| { let m = &b.nodes()[i]; BeamNode::new(m.label, m.position, m.orientation, 0.3 * n.vec()) }.with_orientation(n.rotation()));
    let (bn, laws) = (beam_nodes(&mut n, &b), [random_law(&mut n, false), random_law(&mut n, false)]);
    let elastic = Beam3::new(30, bn, [SectionOrientation::FromNodes, SectionOrientation::FromNodes], laws).unwrap();
    let (bn, laws) = (beam_nodes(&mut n, &b), [random_law(&mut n, true), random_law(&mut n, true)]);
    let viscous = Beam3::new(31, bn, [SectionOrientation::Given(n.rotation()), SectionOrientation::Given(n.rotation())], laws).unwrap();
    b.element(elastic).element(viscous);
    // A deformable axial joint with nlsf terms f′(θ₃ − θ_p) = θ³ − θ and f″(ω₃) = exp(2 ω₃).
    let (elastic, viscous) = (ScalarFunction::Sub(std::sync::Arc::new(ScalarFunction::Pow(3.0)), std::sync::Arc::new(ScalarFunction::Multilinear { points: vec![(-1.0, -1.0), (1.0, 1.0)], extrapolate: true })), ScalarFunction::Exp { multiplier: 1.0, base: std::f64::consts::E, coefficient: 2.0 });
    b.element(DeformableJoint::axial(42, node(2, &mut n), node(3, &mut n), 30.0, 2.0, 0.1, 0.5).with_axial_functions(Some(elastic), Some(viscous)));
    // beam2 on nodes 1 and 3 (both state perturbations turn them by about 0.5 rad apart).
    let two = |n: &mut Noise, b: &ModelBuilder, i: usize| { let m = &b.nodes()[i]; BeamNode::new(m.label, m.position, m.orientation, 0.3 * n.vec()).with_orientation(n.rotation()) };
    let (n1, n3) = (two(&mut n, &b, 0), two(&mut n, &b, 2));
    b.element(Beam2::new(40, [n1, n3], SectionOrientation::FromNodes, random_law(&mut n, false)).unwrap());
    let (n2, n3) = (two(&mut n, &b, 1), two(&mut n, &b, 2));
    b.element(Beam2::new(41, [n2, n3], SectionOrientation::Given(n.rotation()), random_law(&mut n, false)).unwrap());
    b.gravity(Vec3::new(0.3, -9.81, 0.2)).constraint_form(form);
    b.build().unwrap()
}

#[test]
fn every_element_jacobian_matches_finite_differences() {
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let model = every_element(form);
        let asm = Assembler::new(&model);
        let mut st = State::initial(&model, &asm.dofs);
        let mut n = Noise(777);
        st.t = 0.4;
        for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
            *x += 0.5 * n.next();
        }
        let worst = check_jacobians(&asm, &st, 0.37, form);
        assert_eq!(worst.len(), model.elements.len());
        for w in &worst { eprintln!("{form:?}: {} worst relative error {:e}", w.element, w.relative_error); }
        for w in &worst {
            assert!(w.relative_error < 1e-6, "{form:?}: {} d({})/d({}): analytic {:e}, fd {:e} (error {:e})", w.element, w.equation, w.unknown, w.analytic, w.finite_difference, w.relative_error);
        }
    }
}

#[test]
fn a_wrong_jacobian_is_reported_with_its_element_equation_and_unknown() {
    let mut b = ModelBuilder::new();
    b.dynamic_node(2, Vec3::new(0.1, 0.2, 0.3), Mat3::identity(), Vec3::zeros(), Vec3::zeros()).element(WrongSpring);
    let model = b.build().unwrap();
    let asm = Assembler::new(&model);
    let st = State::initial(&model, &asm.dofs);
    let w = &check_jacobians(&asm, &st, 0.5, ConstraintForm::Scaled)[0];
    // J(c) entry is c·20 = 10 analytic against c·10 = 5 by differences.
    assert_eq!((w.element.as_str(), w.equation.as_str(), w.unknown.as_str()), ("wrong spring 99", "node 2 force y equilibrium", "node 2 y"));
    assert!((w.analytic - 10.0).abs() < 1e-12 && (w.finite_difference - 5.0).abs() < 1e-6, "{w:?}");
}
