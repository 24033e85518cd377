//! Cantilever of N 3-node beam elements (issue 5 benchmark): time per Newton iteration
//! (assembly of F and J(c) + sparse LU with the symbolic factorization reused) and per time
//! step (ms, ρ∞ = 0.6, h = 1e-4 s, released from a small static tip deflection), for
//! N = 1000 and 10000 (2N + 1 dynamic nodes, about 15 N unknowns).
//! `cargo bench --bench beam_cantilever`.

#[allow(dead_code)]
#[path = "../tests/common/beams.rs"]
mod beams;

use romdyn::dae::{Assembler, Coefficients, SparseLu, State, Triplets};
use romdyn::kinematics::Vec3;
use romdyn::model::Model;
use romdyn::solve::{initial_derivatives, static_solution, Integrator, Method, NewtonSettings};

fn main() {
    divan::main();
}

/// Table 3's section (EA = GA = 1e6 N, EJ = GJ = 1e3 N m², ρA = 1 kg/m) on L = 1 m.
const SECTION: beams::BeamData = beams::TABLE3;

fn cantilever(elements: usize, tip: f64) -> Model {
    beams::cantilever(&SECTION, elements, Vec3::new(0.0, -tip, 0.0))
}

/// Residual tolerance 1e-4 N: with 2N segments of stiffness EA/h = 2e9..2e10 N/m, rounding
/// alone leaves residuals of about 1e-5 N.
fn settings() -> NewtonSettings {
    NewtonSettings { tolerance: 1e-4, ..NewtonSettings::default() }
}

#[divan::bench(args = [1000, 10000], sample_count = 3, sample_size = 1)]
fn newton_iteration(bencher: divan::Bencher, elements: usize) {
    let model = cantilever(elements, 0.0);
    let asm = Assembler::new(&model);
    let st = State::initial(&model, &asm.dofs);
    let (mut lu, mut j) = (SparseLu::new(), Triplets::new(0));
    let coef = Coefficients::newton(5e-5, model.constraint_form);
    bencher.bench_local(|| {
        let mut f = asm.residual(&st, model.constraint_form, 5e-5);
        asm.jacobian_into(&st, coef, &mut j);
        lu.solve(&j, &mut f).unwrap();
        f
    });
}

#[divan::bench(args = [1000, 10000], sample_count = 3, sample_size = 1)]
fn time_step(bencher: divan::Bencher, elements: usize) {
    let loaded = cantilever(elements, 1.0);
    let asm_loaded = Assembler::new(&loaded);
    let mut st = State::initial(&loaded, &asm_loaded.dofs);
    static_solution(&asm_loaded, &mut st, 1, &settings()).unwrap();
    let free = cantilever(elements, 0.0);
    let asm = Assembler::new(&free);
    initial_derivatives(&asm, &mut st, &settings()).unwrap();
    let mut int = Integrator::new(&asm, st, Method::Ms { rho: 0.6 }, 1e-4, settings());
    bencher.bench_local(|| int.step().unwrap());
}

/// The parts of a Newton iteration: assembly of F …
#[divan::bench(args = [1000, 10000], sample_count = 3, sample_size = 1)]
fn assemble_residual(bencher: divan::Bencher, elements: usize) {
    let model = cantilever(elements, 0.0);
    let asm = Assembler::new(&model);
    let st = State::initial(&model, &asm.dofs);
    bencher.bench_local(|| asm.residual(&st, model.constraint_form, 5e-5));
}
/// … and of J(c) (the rest is the sparse LU).
#[divan::bench(args = [1000, 10000], sample_count = 3, sample_size = 1)]
fn assemble_jacobian(bencher: divan::Bencher, elements: usize) {
    let model = cantilever(elements, 0.0);
    let asm = Assembler::new(&model);
    let st = State::initial(&model, &asm.dofs);
    let coef = Coefficients::newton(5e-5, model.constraint_form);
    bencher.bench_local(|| asm.jacobian(&st, coef));
}
