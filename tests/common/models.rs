//! Multibody models shared by the tests, built through the Rust API.

use romdyn::element::{Anchor, Joint, RigidBody};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::model::ConstraintForm;
use romdyn::model::{Model, ModelBuilder};

/// CASES C2/C3 data (paper Table 4).
pub const M: f64 = 1.0;
pub const J: f64 = 0.001;
pub const L: f64 = 1.0;
pub const G: f64 = 9.81;

/// The simple pendulum of paper §7.2: ground node 1 (static, clamped), pendulum node 2
/// (dynamic) carrying the body, revolute hinge about z at the ground node. The node hangs
/// at angle `theta` from the downward vertical (`upright` flips gravity's side: the
/// inverted pendulum of eq. 87 stands above the hinge).
pub fn pendulum(theta: f64, upright: bool, form: ConstraintForm) -> Model {
    let s = if upright { -1.0 } else { 1.0 };
    let pos = Vec3::new(L * theta.sin(), -s * L * theta.cos(), 0.0);
    let orientation = *nalgebra::Rotation3::from_axis_angle(&Vec3::z_axis(), theta).matrix();
    let mut b = ModelBuilder::new();
    b.static_node(1, Vec3::zeros(), Mat3::identity())
        .dynamic_node(2, pos, orientation, Vec3::zeros(), Vec3::zeros())
        .element(Joint::clamp(1, 1, Vec3::zeros(), Mat3::identity()))
        .element(Joint::revolute_hinge(
            2,
            Anchor::Node { label: 1, offset: Vec3::zeros(), orientation: Mat3::identity() },
            // The hinge point seen from node 2, in node 2's frame.
            Anchor::Node { label: 2, offset: Vec3::new(0.0, s * L, 0.0), orientation: Mat3::identity() },
        ))
        .element(RigidBody::new(3, 2, M, Vec3::zeros(), J * Mat3::identity()))
        .gravity(Vec3::new(0.0, -G, 0.0))
        .constraint_form(form);
    b.build().expect("valid pendulum")
}

/// N-link pendulum chain (issue 13 benchmark): ground node 0 clamped; links 1..=n of 0.1 m
/// and 0.1 kg (inertia 1e-4 kg m²), hinged about z, hanging. 17 n + 12 equations.
pub fn hanging_chain(n: u32, form: ConstraintForm) -> Model {
    link_chain(n, Vec3::new(0.0, -0.1, 0.0), form)
}

/// The same chain with link i's node at `i dir` (`dir` = (0.1, 0, 0): horizontal, released
/// from rest under gravity: the time-integration benchmark).
pub fn link_chain(n: u32, dir: Vec3, form: ConstraintForm) -> Model {
    let mut b = ModelBuilder::new();
    b.static_node(0, Vec3::zeros(), Mat3::identity()).element(Joint::clamp(0, 0, Vec3::zeros(), Mat3::identity()));
    for i in 1..=n {
        b.dynamic_node(i, dir * i as f64, Mat3::identity(), Vec3::zeros(), Vec3::zeros());
        b.element(RigidBody::new(i, i, 0.1, Vec3::zeros(), 1e-4 * Mat3::identity()));
        b.element(Joint::revolute_hinge(
            n + i,
            Anchor::Node { label: i - 1, offset: Vec3::zeros(), orientation: Mat3::identity() },
            Anchor::Node { label: i, offset: -dir, orientation: Mat3::identity() },
        ));
    }
    b.gravity(Vec3::new(0.0, -9.81, 0.0)).constraint_form(form);
    b.build().expect("valid chain")
}
