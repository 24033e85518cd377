//! Linearized spring–mass systems against closed forms (issue 3).

use romdyn::c64;
use romdyn::dae::{linearize, Assembler, State};
use romdyn::element::{Anchor, DeformableDisplacement, DeformableHinge, LinearViscoelastic, RigidBody};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::model::{Model, ModelBuilder};
use romdyn::solve::{static_solution, NewtonSettings};

fn ground() -> Anchor {
    Anchor::Ground { position: Vec3::zeros(), orientation: Mat3::identity() }
}
fn at_node() -> Anchor {
    Anchor::Node { label: 1, offset: Vec3::zeros(), orientation: Mat3::identity() }
}

fn modes(model: &Model) -> ModalAnalysis {
    let asm = Assembler::new(model);
    let mut st = State::initial(model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    let dae = linearize(model, &st, &[], &[], None).unwrap();
    ModalAnalysis::compute(&dae.jacobians, EigenRoute::Direct).unwrap()
}

/// λ = −c/(2m) ± j sqrt(k/m − (c/2m)²) (closed form).
fn damped(k: f64, c: f64, m: f64) -> c64 {
    c64::new(-c / (2.0 * m), (k / m - (c / (2.0 * m)).powi(2)).sqrt())
}

fn assert_has(modal: &ModalAnalysis, want: c64, ctx: &str) {
    let ok = modal.modes.iter().any(|m| m.kind == ModeKind::Dynamic && (m.lambda - want).norm() / want.norm() < 1e-9);
    let got: Vec<c64> = modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic).map(|m| m.lambda).collect();
    assert!(ok, "{ctx}: {want} not among {got:?}");
}

#[test]
fn mass_on_a_3d_spring_with_and_without_damper() {
    let (m, k) = (2.0, Vec3::new(100.0, 400.0, 900.0));
    for c in [Vec3::zeros(), Vec3::new(1.0, 2.0, 3.0)] {
        let mut b = ModelBuilder::new();
        b.dynamic_node(1, Vec3::zeros(), Mat3::identity(), Vec3::zeros(), Vec3::zeros())
            .element(RigidBody::new(1, 1, m, Vec3::zeros(), 0.1 * Mat3::identity()))
            .element(DeformableDisplacement {
                label: 2,
                a: ground(),
                b: at_node(),
                law: LinearViscoelastic { stiffness: Mat3::from_diagonal(&k), viscosity: Mat3::from_diagonal(&c) },
                rest: Vec3::zeros(),
            });
        let modal = modes(&b.build().unwrap());
        // Three translational pairs; the free rotations give zero eigenvalues.
        assert_eq!(modal.count(ModeKind::Dynamic), 6);
        assert_eq!(modal.count(ModeKind::Zero), 6);
        for i in 0..3 {
            assert_has(&modal, damped(k[i], c[i], m), &format!("direction {i}, c = {c:?}"));
        }
    }
}

#[test]
fn free_body_on_soft_springs_has_six_spring_modes() {
    // Translation: sqrt(k/m); rotation: sqrt(k_θ/J_i) with the body's principal inertias.
    let (m, inertia) = (3.0, Vec3::new(0.5, 1.0, 2.0));
    let (k, kt) = (1e-2, Vec3::new(1e-3, 2e-3, 3e-3));
    let mut b = ModelBuilder::new();
    b.dynamic_node(1, Vec3::new(1.0, 2.0, 3.0), Mat3::identity(), Vec3::zeros(), Vec3::zeros())
        .element(RigidBody::new(1, 1, m, Vec3::zeros(), Mat3::from_diagonal(&inertia)))
        .element(DeformableDisplacement {
            label: 2,
            a: Anchor::Ground { position: Vec3::new(1.0, 2.0, 3.0), orientation: Mat3::identity() },
            b: at_node(),
            law: LinearViscoelastic::isotropic(k, 0.0),
            rest: Vec3::zeros(),
        })
        .element(DeformableHinge { label: 3, a: ground(), b: at_node(), law: LinearViscoelastic::elastic(Mat3::from_diagonal(&kt)) });
    let modal = modes(&b.build().unwrap());
    assert_eq!(modal.count(ModeKind::Dynamic), 12);
    for want in [(k / m).sqrt(), (kt.x / inertia.x).sqrt(), (kt.y / inertia.y).sqrt(), (kt.z / inertia.z).sqrt()] {
        assert_has(&modal, c64::new(0.0, want), "free body");
    }
}
