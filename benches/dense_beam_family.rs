//! Issue 30, finding 3: the default dense eigenanalysis (`romdyn eig --solver dense`: the
//! deflation, QZ on the dynamic part in the Λ form with dCoef from the spectrum, labels and
//! both vector sets) of the beam family, a cantilever of N `beam3` elements with a tip mass
//! (12 (2N + 1) + 6 equations), N = 8 … 128, EA/EJ = 1e3 … 1e7 (EJ = 1e3 N m²). It must
//! finish on every member; times are compared with scipy's `eig` (both vector sets) on the
//! same pencil in the report of issue 30. `cargo bench --bench dense_beam_family`.

#[allow(dead_code)]
#[path = "../tests/common/beam_family.rs"]
mod beam_family;

use std::path::Path;

use romdyn::dae::{linearize, Assembler, State};
use romdyn::input::mbdyn::{build, parse_text};
use romdyn::eigen::{EigenRoute, ModalAnalysis};
use romdyn::linear::LinearDae;

fn main() {
    divan::main();
}

fn dae(elements: usize, ea_over_ej: f64) -> LinearDae {
    let ej = 1e3;
    let text = beam_family::cantilever(elements, ea_over_ej * ej, ej);
    let m = parse_text(&text, Path::new("beam.mbd")).and_then(|d| build(&d)).unwrap();
    let asm = Assembler::new(&m.model);
    let st = State::initial(&m.model, &asm.dofs);
    linearize(&m.model, &st, &[], &[], None).unwrap()
}

#[divan::bench(args = [8, 16, 32, 64, 128], consts = [3, 5, 7], sample_count = 1, sample_size = 1)]
fn default_dense_eigenanalysis<const DECADES: i32>(bencher: divan::Bencher, elements: usize) {
    let dae = dae(elements, 10f64.powi(DECADES));
    bencher.bench_local(|| ModalAnalysis::of_dae(&dae, EigenRoute::Lambda, None).unwrap());
}
