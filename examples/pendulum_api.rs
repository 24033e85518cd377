//! The Rust API on the paper's simple pendulum (§7.2; the book's "Rust API" chapter shows
//! this file): a model built in code, its static equilibrium, the linearization with one
//! input and one output, and its eigenanalysis: 29 equations, λ = ±3.1305 j rad/s (eq. 82).

use romdyn::dae::{linearize, Assembler, State};
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::element::{Anchor, Joint, RigidBody};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::model::ModelBuilder;
use romdyn::solve::{static_solution, NewtonSettings};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut b = ModelBuilder::new();
    b.static_node(1, Vec3::zeros(), Mat3::identity())
        .dynamic_node(2, Vec3::new(0.0, -1.0, 0.0), Mat3::identity(), Vec3::zeros(), Vec3::zeros())
        .element(Joint::clamp(1, 1, Vec3::zeros(), Mat3::identity()))
        .element(Joint::revolute_hinge(
            2,
            Anchor::Node { label: 1, offset: Vec3::zeros(), orientation: Mat3::identity() },
            Anchor::Node { label: 2, offset: Vec3::new(0.0, 1.0, 0.0), orientation: Mat3::identity() },
        ))
        .element(RigidBody::new(3, 2, 1.0, Vec3::zeros(), 0.001 * Mat3::identity()))
        .gravity(Vec3::new(0.0, -9.81, 0.0));
    let model = b.build()?;
    let asm = Assembler::new(&model);
    let mut state = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut state, 1, &NewtonSettings::default())?;
    let dae = linearize(&model, &state, &["2:Mz".parse()?], &["2:rz".parse()?], None)?;
    let modes = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Lambda)?;
    for m in modes.modes.iter().filter(|m| m.kind == ModeKind::Dynamic) {
        println!("λ = {:+.6} {:+.6} j rad/s", m.lambda.re, m.lambda.im);
    }
    Ok(())
}
