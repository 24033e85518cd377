//! Shift-invert Krylov–Schur (issue 13 point 2): the 20 lowest modes of the hanging
//! N-link chain, right and left vectors, every pair checked by its true residual.
//! Goals (issue 13): N = 100 (1712 equations) under 50 ms, N = 1000 (17012) under 1 s.
//! `cargo bench --bench sparse_eigen`.

use romdyn::dae::{linearize_sparse, Assembler, State};
use romdyn::element::{Anchor, Joint, RigidBody};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::linear::krylov::{sparse_modes, ModeTarget, SparseEigenSettings};
use romdyn::linear::SparseLinearDae;
use romdyn::model::{Model, ModelBuilder};
use romdyn::solve::{static_solution, NewtonSettings};

fn main() {
    divan::main();
}

/// Ground node 0 clamped; links 1..=n of 0.1 m and 0.1 kg hinged about z, hanging.
fn chain(n: u32) -> Model {
    let dir = Vec3::new(0.0, -0.1, 0.0);
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
    b.gravity(Vec3::new(0.0, -9.81, 0.0));
    b.build().unwrap()
}

/// The sparse linearization of the chain at rest.
pub fn chain_dae(n: u32) -> SparseLinearDae {
    let model = chain(n);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    linearize_sparse(&model, &st, &[], &[]).unwrap()
}

#[divan::bench(args = [100, 1000], sample_count = 5)]
fn lowest_20(bencher: divan::Bencher, n: u32) {
    let dae = chain_dae(n);
    bencher.bench_local(|| {
        let s = sparse_modes(&dae, ModeTarget::Lowest(20), &SparseEigenSettings::default()).unwrap();
        assert!(s.certified);
        s
    });
}
