//! Multibody models shared by the tests, built through the Rust API.

use romdyn::element::{Anchor, Joint, RigidBody};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::linear::ConstraintForm;
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
