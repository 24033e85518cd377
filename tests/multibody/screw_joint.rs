//! MBDyn's `screw` joint (issue 12, point 3): its analytic Jacobian against central finite
//! differences of its residual (both constraint forms, with the angle past several turns),
//! and two screws under gravity against the closed form and MBDyn 1.7.3.

use crate::common;

use std::path::Path;

use common::fixtures::Noise;
use romdyn::analysis::run;
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::{Anchor, Element, Screw};
use romdyn::input::mbdyn::read_model;
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::model::ConstraintForm;
use romdyn::model::ModelBuilder;

#[test]
fn screw_jacobians_match_finite_differences() {
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let mut n = Noise(4242);
        let mut b = ModelBuilder::new();
        b.static_node(1, n.vec(), n.rotation()).dynamic_node(2, n.vec(), n.rotation(), n.vec(), n.vec()).dynamic_node(3, n.vec(), n.rotation(), n.vec(), n.vec());
        let node = |label: u32, n: &mut Noise| Anchor::Node { label, offset: n.vec(), orientation: n.rotation() };
        let screws: Vec<Box<dyn Element>> = vec![
            Box::new(Screw { label: 1, a: node(2, &mut n), b: node(3, &mut n), pitch: 0.3, theta0: 0.4, d0: 0.2 }),
            Box::new(Screw { label: 2, a: Anchor::Ground { position: n.vec(), orientation: n.rotation() }, b: node(2, &mut n), pitch: -0.7, theta0: -1.0, d0: 0.0 }),
            Box::new(Screw { label: 3, a: node(1, &mut n), b: node(3, &mut n), pitch: 0.1, theta0: 2.0, d0: 0.1 }),
        ];
        for s in screws {
            b.boxed_element(s);
        }
        b.constraint_form(form);
        let model = b.build().unwrap();
        let asm = Assembler::new(&model);
        let mut st = State::initial(&model, &asm.dofs);
        let mut n = Noise(99);
        st.t = 0.3;
        for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
            *x += 0.5 * n.next();
        }
        // The angles several turns on (the residual is periodic in them), the forces a few N.
        for (e, turns) in [(0, 3.0), (1, -2.0), (2, 7.0)] {
            let first = asm.dofs.element_first[e];
            st.y[first] += turns * std::f64::consts::TAU;
            st.y[first + 1] = 3.0 * n.next();
        }
        for w in check_jacobians(&asm, &st, 0.37, form) {
            assert!(w.relative_error < 1e-6, "{form:?}: {} d({})/d({}): analytic {:e}, fd {:e} (error {:e})", w.element, w.equation, w.unknown, w.analytic, w.finite_difference, w.relative_error);
        }
    }
}

#[test]
fn screws_turn_and_fall_as_the_closed_form_and_mbdyn() {
    // screw.mbd at t = 1 s: z'' = −a, a = g/(1 + J (2π/P)²/m). MBDyn 1.7.3 (1727489e, the same
    // file), .mov: node 2 z 2.078858019775223e-01 m, ż −8.422879205815642e-02 m/s, Euler z
    // 1.496777774238160e+02 deg; node 3 z −2.921147606799040e-01 m, ż −5.842302536231735e-01
    // m/s, Euler z 1.496773723104691e+02 deg, ω_z −7.341634302624394e+00 rad/s.
    let m = read_model(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/screw.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    assert!(report.inconsistent_velocity.is_none(), "{:?}", report.inconsistent_velocity);
    let asm = Assembler::new(&m.model);
    let st = &report.final_state;
    let kin = |label: u32| st.node_frame(&asm.dofs, m.model.node_index(label).unwrap()).kin;
    let (p, tau) = (0.5, std::f64::consts::TAU);
    let a = 9.81 / (1.0 + 0.1 * (tau / p).powi(2));
    // The screw ties z to the angle, which ms integrates through the orientation parameters,
    // not exactly (a local error of about (ω h)³): node 2 ends 2e-7 m and node 3 6e-7 m from
    // the closed form, node 3's ż 2.4e-6 m/s (4e-6 relative), as MBDyn's do (the two 6e-10
    // m, 5e-10 m/s apart): 5e-6 m, 1e-5 m/s.
    for (label, v0, mbdyn) in [(2, 0.5, 2.078858019775223e-01), (3, 0.0, -2.921147606799040e-01)] {
        let z = v0 - a / 2.0;
        assert!((kin(label).x - Vec3::new(if label == 3 { 1.0 } else { 0.0 }, 0.0, z)).norm() < 5e-6, "node {label} at {}, closed form z = {z}", kin(label).x);
        assert!((kin(label).xdot.z - (v0 - a)).abs() < 1e-5, "node {label} ż = {}", kin(label).xdot.z);
        // MBDyn: 6e-10 m apart.
        assert!((kin(label).x.z - mbdyn).abs() < 2e-9, "node {label} z {} against MBDyn {mbdyn}", kin(label).x.z);
        // The screw's angle, counted through the turns, holds the screw's relation to the
        // node's z (Newton's tolerance), and the node's frame is turned by it.
        let screw = (0..m.model.elements.len()).find(|&e| m.model.elements[e].type_name() == "screw" && m.model.elements[e].label() == if label == 2 { 3 } else { 5 }).unwrap();
        let theta = st.y[asm.dofs.element_first[screw]];
        assert!((theta - tau * kin(label).x.z / p).abs() < 1e-8, "node {label} angle {theta}, z {}", kin(label).x.z);
        let (s, c) = theta.sin_cos();
        assert!((kin(label).r - Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)).norm() < 1e-8, "node {label} frame {}", kin(label).r);
    }
    let theta3 = tau * kin(3).x.z / p;
    assert!(theta3 < -std::f64::consts::PI, "node 3 turned {theta3} rad: past −π");
    let euler = |label: u32| romdyn::kinematics::euler123(&kin(label).r).z.to_degrees();
    assert!((euler(2) - 1.496777774238160e+02).abs() < 1e-6 && (euler(3) - 1.496773723104691e+02).abs() < 1e-6, "Euler z {} {} against MBDyn", euler(2), euler(3));
}
