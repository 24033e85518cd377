//! Shift-invert Krylov–Schur (issue 13 point 2): the 20 lowest modes of the hanging
//! N-link chain, right and left vectors, every pair checked by its true residual
//! (`lowest_20`), and right vectors only (`lowest_20_right_only`: no adjoint run, the work
//! scipy's `eigs` does, not certified).
//! Goals (issue 13): N = 100 (1712 equations) under 50 ms, N = 1000 (17012) under 1 s.
//! `cargo bench --bench sparse_eigen`.

#[allow(dead_code)]
#[path = "../tests/common/models.rs"]
mod models;

use romdyn::dae::{linearize_sparse, Assembler, State};
use romdyn::eigen::krylov::{sparse_modes, ModeTarget, SparseEigenSettings};
use romdyn::linear::SparseLinearDae;
use romdyn::model::ConstraintForm;
use romdyn::solve::{static_solution, NewtonSettings};

fn main() {
    divan::main();
}

/// The sparse linearization of the chain at rest.
fn chain_dae(n: u32) -> SparseLinearDae {
    // The hanging chain of the tests (ground clamped, links of 0.1 m and 0.1 kg), eq. 30.
    let model = models::hanging_chain(n, ConstraintForm::Scaled);
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

#[divan::bench(args = [100, 1000], sample_count = 5)]
fn lowest_20_right_only(bencher: divan::Bencher, n: u32) {
    let dae = chain_dae(n);
    let settings = SparseEigenSettings { left_vectors: false, ..Default::default() };
    bencher.bench_local(|| {
        let s = sparse_modes(&dae, ModeTarget::Lowest(20), &settings).unwrap();
        assert!(s.modal.modes.len() >= 40 && s.max_residual <= 1e-10);
        s
    });
}
