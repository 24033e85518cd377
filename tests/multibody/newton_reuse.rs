//! Newton's iterations of a time step that keep the last factorization when the residual
//! fell fast ([`NewtonWorkspace::keep_jacobian_below`], issue 36 point 4): the same motion as
//! full Newton (every iteration assembling and factoring its Jacobian) on the same model, to
//! the Newton tolerance. The reference is full Newton itself (`keep_jacobian_below = 0`): both
//! solve the same discrete equations to the same residual tolerance, so their final
//! positions may differ only by what that tolerance leaves (the brief's bound: 1e-6
//! relative).

use crate::common;

use common::beams::{cantilever, BeamData};
use common::models::link_chain;
use romdyn::dae::{Assembler, State};
use romdyn::kinematics::Vec3;
use romdyn::model::{ConstraintForm, Model};
use romdyn::solve::{initial_derivatives, Integrator, Method, NewtonSettings, NewtonWorkspace, KEEP_JACOBIAN_BELOW};

/// Final state, iterations that factored and iterations that reused, after `steps` steps of
/// ms (ρ∞ = 0.6) from rest with `keep` as the workspace's reuse threshold.
fn run(model: &Model, h: f64, steps: usize, settings: NewtonSettings, keep: f64) -> (State, usize, usize, usize) {
    let asm = Assembler::new(model);
    let mut st = State::initial(model, &asm.dofs);
    initial_derivatives(&asm, &mut st, &settings).unwrap();
    let mut workspace = NewtonWorkspace::new();
    workspace.keep_jacobian_below = keep;
    let mut int = Integrator::with_workspace(&asm, st, Method::Ms { rho: 0.6 }, h, settings, workspace);
    let mut iterations = 0;
    for _ in 0..steps {
        iterations += int.step().unwrap().iterations;
    }
    let (factored, reused) = (int.workspace().factored, int.workspace().reused);
    (int.state, iterations, factored, reused)
}

/// Largest difference of the nodes' positions between two states, relative to the largest
/// coordinate.
fn position_difference(model: &Model, a: &State, b: &State) -> f64 {
    let asm = Assembler::new(model);
    let (mut diff, mut size) = (0.0f64, 0.0f64);
    for &f in &asm.dofs.node_first {
        for k in 0..3 {
            diff = diff.max((a.y[f + k] - b.y[f + k]).abs());
            size = size.max(a.y[f + k].abs());
        }
    }
    diff / size
}

fn compare(name: &str, model: &Model, h: f64, steps: usize, settings: NewtonSettings) {
    let (full, full_iterations, full_factored, full_reused) = run(model, h, steps, settings, 0.0);
    let (kept, iterations, factored, reused) = run(model, h, steps, settings, KEEP_JACOBIAN_BELOW);
    let diff = position_difference(model, &full, &kept);
    eprintln!("{name}: full Newton {full_iterations} iterations ({full_factored} factored); kept below {KEEP_JACOBIAN_BELOW}: {iterations} iterations, {factored} factored, {reused} reused; final positions {diff:.1e} apart (relative)");
    // Full Newton factors at every iteration that solves.
    assert_eq!((full_factored, full_reused), (full_iterations, 0));
    // The reuse happened, and saved factorizations overall.
    assert!(reused > 0 && factored + reused == iterations && factored < full_factored, "{name}: {factored} factored, {reused} reused of {iterations}; full {full_factored}");
    // Same motion to the tolerance's effect (issue 36: 1e-6 relative).
    assert!(diff <= 1e-6, "{name}: final positions {diff:.1e} apart");
}

#[test]
fn a_chain_released_under_gravity_moves_as_with_full_newton() {
    // 10 links horizontal, released from rest (the stepping benchmark's chain), h = 1 ms,
    // 300 steps, tolerance 1e-9 N.
    let model = link_chain(10, Vec3::new(0.1, 0.0, 0.0), ConstraintForm::Scaled);
    compare("chain N = 10", &model, 1e-3, 300, NewtonSettings::default());
}

#[test]
fn a_cantilever_under_a_suddenly_applied_tip_force_moves_as_with_full_newton() {
    // CASES C5's cantilever (10 beam3 elements, EA = GA = 1e8 N, EJ = GJ = 1e3 N m²,
    // ρA = 1 kg/m), 1000 N at the tip from t = 0 (large deflection), h = 1e-4 s, 100 steps,
    // tolerance 1e-6 N (rounding alone leaves ~1e-7 N at EA = 1e8 N).
    let d = BeamData { length: 1.0, ea: 1e8, ga: 1e8, gj: 1e3, ej: 1e3, rho_a: 1.0 };
    let model = cantilever(&d, 10, Vec3::new(0.0, -1e3, 0.0));
    compare("cantilever", &model, 1e-4, 100, NewtonSettings { tolerance: 1e-6, ..NewtonSettings::default() });
}
