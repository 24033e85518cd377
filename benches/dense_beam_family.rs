//! Issue 30, finding 3: the eigenanalysis of the beam family, a cantilever of N `beam3`
//! elements with a tip mass (12 (2N + 1) + 6 equations), N = 8 … 128, EA/EJ = 1e3 … 1e7
//! (EJ = 1e3 N m²), on both routes. It must finish on every member:
//! - `default_dense_eigenanalysis`: `romdyn eig --solver dense` (the deflation, QZ on the
//!   dynamic part in the Λ form with dCoef from the spectrum, labels and both vector sets);
//! - `sparse_count_20`: `romdyn eig --solver sparse --count 20` (shift-invert Krylov–Schur,
//!   right and left vectors, the argument-principle count that certifies the 20 lowest).
//!
//! Times are compared with scipy's `eig` (both vector sets) on the same pencil in
//! docs/src/performance/ (scripts/bench_dense_eigen.py). `cargo bench --bench dense_beam_family`.

#[allow(dead_code)]
#[path = "../tests/common/beam_family.rs"]
mod beam_family;

use std::path::Path;

use romdyn::dae::{linearize, linearize_sparse, Assembler, State};
use romdyn::eigen::krylov::{sparse_modes, ModeTarget, SparseEigenSettings};
use romdyn::eigen::{EigenRoute, ModalAnalysis};
use romdyn::input::mbdyn::{build, parse_text};
use romdyn::linear::{LinearDae, SparseLinearDae};
use romdyn::model::Model;

fn main() {
    divan::main();
}

/// The model of `elements` elements, EA/EJ = `ea_over_ej`, and its state at rest.
fn model(elements: usize, ea_over_ej: f64) -> (Model, State) {
    let ej = 1e3;
    let text = beam_family::cantilever(elements, ea_over_ej * ej, ej);
    let m = parse_text(&text, Path::new("beam.mbd")).and_then(|d| build(&d)).unwrap();
    let asm = Assembler::new(&m.model);
    let st = State::initial(&m.model, &asm.dofs);
    (m.model, st)
}

fn dae(elements: usize, ea_over_ej: f64) -> LinearDae {
    let (m, st) = model(elements, ea_over_ej);
    linearize(&m, &st, &[], &[], None).unwrap()
}

fn sparse_dae(elements: usize, ea_over_ej: f64) -> SparseLinearDae {
    let (m, st) = model(elements, ea_over_ej);
    linearize_sparse(&m, &st, &[], &[]).unwrap()
}

#[divan::bench(args = [8, 16, 32, 64, 128], consts = [3, 5, 7], sample_count = 1, sample_size = 1)]
fn default_dense_eigenanalysis<const DECADES: i32>(bencher: divan::Bencher, elements: usize) {
    let dae = dae(elements, 10f64.powi(DECADES));
    bencher.bench_local(|| ModalAnalysis::of_dae(&dae, EigenRoute::Lambda, None).unwrap());
}

#[divan::bench(args = [8, 16, 32, 64, 128], consts = [3, 5, 7], sample_count = 1, sample_size = 1)]
fn sparse_count_20<const DECADES: i32>(bencher: divan::Bencher, elements: usize) {
    let dae = sparse_dae(elements, 10f64.powi(DECADES));
    bencher.bench_local(|| {
        let found = sparse_modes(&dae, ModeTarget::Lowest(20), &SparseEigenSettings::default()).unwrap();
        assert!(found.certified, "{elements} elements, EA/EJ = 1e{DECADES}: {:?}", found.note);
        found
    });
}
