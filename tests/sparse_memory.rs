//! The Study's sparse route keeps memory proportional to the non-zeros (issue 13 point 1):
//! on a 17012-equation chain, where one dense n x n matrix takes 2.3 GB, the whole workflow
//! (reference solution, sparse linearization, modes, modal table, warnings, ROM with static
//! correction, full-model frequency response) never allocates anything near n² entries.
//! Measured by a counting allocator in this test binary (its only test, so nothing else runs
//! while it counts).
mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use common::models::hanging_chain;
use romdyn::analysis::Reference;
use romdyn::linear::ConstraintForm;
use romdyn::model::InitialValueProblem;
use romdyn::rom::ModeSelection;
use romdyn::study::{EigenSettings, Ports, Residualization, RomRequest, Solver, Study};

struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static LARGEST: AtomicUsize = AtomicUsize::new(0);

fn grew(bytes: usize) {
    let live = LIVE.fetch_add(bytes, Ordering::Relaxed) + bytes;
    PEAK.fetch_max(live, Ordering::Relaxed);
    LARGEST.fetch_max(bytes, Ordering::Relaxed);
}

// SAFETY: every call forwards to `System` with the same arguments; the counters only
// observe sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        grew(layout.size());
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        grew(layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        grew(new_size);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

#[test]
fn the_sparse_route_of_a_5112_equation_chain_never_allocates_a_dense_matrix() {
    let model = hanging_chain(1000, ConstraintForm::Scaled);
    let ports = Ports::Nodes { inputs: vec!["300:Fx".parse().unwrap()], outputs: vec!["300:x".parse().unwrap()] };
    let request = RomRequest::new(ModeSelection::Lowest(5)).residualize(Residualization::Dropped);
    let eigen = EigenSettings { solver: Solver::Sparse, ..EigenSettings::default() }.for_request(&request);
    let before = LIVE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    LARGEST.store(0, Ordering::Relaxed);
    let (study, _) = Study::of_model(model, &InitialValueProblem::default(), Reference::Static { load_steps: 1 }, &ports, eigen, None).unwrap();
    let table = study.modal_report_of(None).unwrap().to_text();
    let rom = study.reduce(&request).unwrap();
    let h = study.full_frequency_response(&[0.1, 1.0, 3.0]).unwrap();
    let n = study.equations();
    assert_eq!(n, 17012);
    assert!(table.contains("sparse route") && rom.static_correction && h.len() == 3);
    let dense = n * n * std::mem::size_of::<f64>();
    let (peak, largest) = (PEAK.load(Ordering::Relaxed) - before, LARGEST.load(Ordering::Relaxed));
    eprintln!("n = {n}: peak {:.1} MB, largest allocation {:.1} MB, one dense matrix {:.0} MB", peak as f64 / 1e6, largest as f64 / 1e6, dense as f64 / 1e6);
    // One dense n x n matrix is 2.3 GB; the Krylov bases are n x (a few times the wanted
    // count) complex entries. faer's matrix product (private-gemm) keeps one packing buffer
    // per thread whose size follows the machine's caches (measured: 32 MiB on one machine
    // here, 64 MiB on another, the largest allocation at 5112 equations), and the right and
    // adjoint Krylov runs go on two threads. A tenth of one dense matrix (231 MB) is a bound
    // no n² allocation fits under and any such buffer does; the peak, buffers included
    // (at 5112 equations: 81.6 MB with 32 MiB buffers, 144.5 MB with 64 MiB), a quarter.
    assert!(largest <= dense / 10, "largest allocation {largest} bytes");
    assert!(peak < dense / 4, "peak {peak} bytes");
}
