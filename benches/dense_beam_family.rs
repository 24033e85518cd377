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
//!
//! Both benchmarks check what they time (not timed themselves): the 20 lowest modes (each
//! copy of a double one) agree with the independent mass–stiffness problem of the same beam
//! (tests/common/beam_family.rs, `MassStiffness`, its lowest 20 refined to the stored
//! matrices' exact eigenvalues) to 1e-8 relative beyond the reference's own 1e-13, issue
//! 30's acceptance line; tests/eigen/beam_family.rs asserts the same at 8 to 64 elements,
//! this is where 128 elements (3090 equations) is checked.

#[allow(dead_code)]
#[path = "../tests/common/beam_family.rs"]
mod beam_family;

use std::cell::RefCell;
use std::path::Path;

use romdyn::dae::{linearize, linearize_sparse, Assembler, State};
use romdyn::eigen::krylov::{sparse_modes, ModeTarget, SparseEigenSettings};
use romdyn::eigen::{EigenRoute, ModalAnalysis, Mode, ModeKind};
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

/// Issue 30's acceptance line: relative agreement of the 20 lowest modes with the
/// mass–stiffness reference, beyond the reference's own error bound.
const AGREE: f64 = 1e-8;

/// The independent reference of the member: `MassStiffness` of its dense linearization at
/// rest (an LU inverse and Hessenberg QR of `M^(1/2) K⁻¹ M^(1/2)`, the lowest 20 refined).
fn reference(elements: usize, ea_over_ej: f64) -> beam_family::MassStiffness {
    let (m, st) = model(elements, ea_over_ej);
    let lin = linearize(&m, &st, &[], &[], None).unwrap();
    beam_family::MassStiffness::of(&lin, &Assembler::new(&m).dofs.node_first, elements)
}

/// Asserts that `modes`' lowest dynamic eigenvalues (upper half-plane, by |λ|) are the
/// reference's 20 lowest (and the second copy of a double 20th) to [`AGREE`]; prints the
/// largest relative difference.
fn check(modes: &[Mode], elements: usize, decades: i32, route: &str) {
    let reference = reference(elements, 10f64.powi(decades));
    let mut found: Vec<f64> = modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 0.0).map(|m| m.lambda.norm()).collect();
    found.sort_by(f64::total_cmp);
    let last = reference.omega[19];
    let expected = reference.omega.iter().filter(|&&w| w <= last * (1.0 + 1e-6)).count();
    assert!(found.len() >= expected, "{elements} elements, EA/EJ = 1e{decades}, {route}: {} modes, {expected} expected", found.len());
    // Source: the mass–stiffness problem, less its own error bound (1e-13 ω).
    let off = found.iter().zip(&reference.omega).take(expected).map(|(&got, &w)| ((got - w).abs() - reference.error(w)).max(0.0) / w).fold(0.0, f64::max);
    eprintln!("{elements} elements, EA/EJ = 1e{decades}, {route}: {expected} lowest modes within {off:.1e} of the mass–stiffness reference (asserted {AGREE:e})");
    assert!(off <= AGREE, "{elements} elements, EA/EJ = 1e{decades}, {route}: {off:.1e} off the reference");
}

#[divan::bench(args = [8, 16, 32, 64, 128], consts = [3, 5, 7], sample_count = 1, sample_size = 1)]
fn default_dense_eigenanalysis<const DECADES: i32>(bencher: divan::Bencher, elements: usize) {
    let dae = dae(elements, 10f64.powi(DECADES));
    let last = RefCell::new(None);
    bencher.bench_local(|| *last.borrow_mut() = Some(ModalAnalysis::of_dae(&dae, EigenRoute::Lambda, None).unwrap()));
    check(&last.into_inner().expect("timed once").modes, elements, DECADES, "dense");
}

#[divan::bench(args = [8, 16, 32, 64, 128], consts = [3, 5, 7], sample_count = 1, sample_size = 1)]
fn sparse_count_20<const DECADES: i32>(bencher: divan::Bencher, elements: usize) {
    let dae = sparse_dae(elements, 10f64.powi(DECADES));
    let last = RefCell::new(None);
    bencher.bench_local(|| {
        let found = sparse_modes(&dae, ModeTarget::Lowest(20), &SparseEigenSettings::default()).unwrap();
        assert!(found.certified, "{elements} elements, EA/EJ = 1e{DECADES}: {:?}", found.note);
        *last.borrow_mut() = Some(found);
    });
    check(&last.into_inner().expect("timed once").modal.modes, elements, DECADES, "sparse --count 20");
}
