//! N-link pendulum chain (issue 3 benchmark): time per step and per Newton iteration for
//! N = 10, 100, 1000 dynamic nodes; eigenanalysis + ROM for N = 10 and 100.
//! `cargo bench --bench pendulum_chain`.

use romdyn::dae::{linearize, Assembler, Coefficients, LuPath, SparseLu, State};
use romdyn::kinematics::Vec3;
use romdyn::eigen::{EigenRoute, ModalAnalysis};
use romdyn::model::ConstraintForm;
use romdyn::model::Model;
use romdyn::rom::{select_modes, DescriptorRom, ModeSelection};
use romdyn::solve::{initial_derivatives, static_solution, Integrator, Method, NewtonSettings};

#[allow(dead_code)]
#[path = "../tests/common/models.rs"]
mod models;

fn main() {
    divan::main();
}

/// The chain of tests/common/models.rs: links of 0.1 m and 0.1 kg hinged about z, in a
/// horizontal line (released) or hanging (for the eigenanalysis).
fn chain(n: u32, hanging: bool) -> Model {
    let dir = if hanging { Vec3::new(0.0, -0.1, 0.0) } else { Vec3::new(0.1, 0.0, 0.0) };
    models::link_chain(n, dir, ConstraintForm::Scaled)
}

#[divan::bench(args = [10, 100, 1000], sample_count = 5)]
fn time_step(bencher: divan::Bencher, n: u32) {
    let model = chain(n, false);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    initial_derivatives(&asm, &mut st, &NewtonSettings::default()).unwrap();
    let mut int = Integrator::new(&asm, st, Method::Ms { rho: 0.6 }, 1e-3, NewtonSettings::default());
    bencher.bench_local(|| int.step().unwrap());
}

/// One Newton iteration = assembly of F and J(c) + sparse LU (symbolic factorization reused).
#[divan::bench(args = [10, 100, 1000], sample_count = 5)]
fn newton_iteration(bencher: divan::Bencher, n: u32) {
    let model = chain(n, false);
    let asm = Assembler::new(&model);
    let st = State::initial(&model, &asm.dofs);
    let mut lu = SparseLu::new();
    let coef = Coefficients::newton(5e-4, model.constraint_form);
    bencher.bench_local(|| {
        let mut f = asm.residual(&st, model.constraint_form, 5e-4);
        let j = asm.jacobian(&st, coef);
        lu.solve(&j, &mut f).unwrap();
        f
    });
}

/// The linear solve alone (values scattered, factored, solved; the pattern's ordering and
/// symbolic part reused): the banded path Newton takes on chains, and faer's sparse LU.
#[divan::bench(args = [10, 100, 1000], sample_count = 5)]
fn lu_banded(bencher: divan::Bencher, n: u32) {
    lu_solve(bencher, n, LuPath::Auto);
}
#[divan::bench(args = [10, 100, 1000], sample_count = 5)]
fn lu_general_sparse(bencher: divan::Bencher, n: u32) {
    lu_solve(bencher, n, LuPath::General);
}

fn lu_solve(bencher: divan::Bencher, n: u32, path: LuPath) {
    let model = chain(n, false);
    let asm = Assembler::new(&model);
    let st = State::initial(&model, &asm.dofs);
    let j = asm.jacobian(&st, Coefficients::newton(5e-4, model.constraint_form));
    let f = asm.residual(&st, model.constraint_form, 5e-4);
    let mut lu = SparseLu::with_path(path);
    bencher.bench_local(|| {
        let mut x = f.clone();
        lu.solve(&j, &mut x).unwrap();
        x
    });
}

#[divan::bench(args = [10, 100], sample_count = 1, sample_size = 1)]
fn eigen_and_rom(bencher: divan::Bencher, n: u32) {
    let model = chain(n, true);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    let output = format!("{n}:x").parse().unwrap();
    let input = format!("{n}:Fx").parse().unwrap();
    bencher.bench_local(|| {
        let dae = linearize(&model, &st, &[input], &[output], None).unwrap();
        let modal = ModalAnalysis::of_dae(&dae, EigenRoute::Direct, None).unwrap();
        let sel = select_modes(&modal, &ModeSelection::Lowest(3)).unwrap();
        DescriptorRom::project(&dae, &modal, &sel, true).unwrap().to_ordinary().unwrap()
    });
}

/// Dense eigenanalysis (Λ route, as `romdyn eig`) with the constraint structure deflated
/// first: N = 100 is the 1712-equation chain.
#[divan::bench(args = [20, 100], sample_count = 1, sample_size = 1)]
fn eigen_deflated(bencher: divan::Bencher, n: u32) {
    let model = chain(n, true);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    let dae = linearize(&model, &st, &[], &[], Some(1e-3)).unwrap();
    bencher.bench_local(|| ModalAnalysis::of_dae(&dae, EigenRoute::Lambda, None).unwrap());
}

/// The same on the whole pencil (QZ on all 17 N + 12 unknowns), for the ratio.
#[divan::bench(args = [20, 40], sample_count = 1, sample_size = 1)]
fn eigen_whole(bencher: divan::Bencher, n: u32) {
    let model = chain(n, true);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    let dae = linearize(&model, &st, &[], &[], Some(1e-3)).unwrap();
    bencher.bench_local(|| ModalAnalysis::compute(&dae.jacobians, EigenRoute::Lambda).unwrap());
}
