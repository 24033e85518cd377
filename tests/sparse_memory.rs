//! The Study's sparse route keeps memory proportional to the non-zeros (issue 13 point 1):
//! on a 5112-equation chain, where one dense n x n matrix takes 209 MB, the whole workflow
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
    let model = hanging_chain(300, ConstraintForm::Scaled);
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
    assert_eq!(n, 5112);
    assert!(table.contains("sparse route") && rom.static_correction && h.len() == 3);
    let dense = n * n * std::mem::size_of::<f64>();
    let (peak, largest) = (PEAK.load(Ordering::Relaxed) - before, LARGEST.load(Ordering::Relaxed));
    eprintln!("n = {n}: peak {:.1} MB, largest allocation {:.1} MB, one dense matrix {:.0} MB", peak as f64 / 1e6, largest as f64 / 1e6, dense as f64 / 1e6);
    // One dense n x n matrix is 209 MB; the Krylov bases are n x (a few times the wanted
    // count) complex entries. faer's matrix product (private-gemm) keeps one packing buffer of
    // 32 MiB per thread, whatever the size (measured: the largest allocation, 33554432 bytes,
    // from gemm's thread-local storage), and the right and adjoint Krylov runs go on two
    // threads (measured peak 81.6 MB, 46 MB before they did). Apart from those two buffers,
    // a tenth of one dense matrix is a bound no n² allocation fits under.
    // Since the real basis has its own Gram–Schmidt kernels (2026-12-02), the first faer
    // product in each run's thread is the dense eigensolver's (Hessenberg reduction of the
    // Rayleigh quotient), whose gemm takes a 64 MiB thread-local buffer (measured: the
    // largest allocation, 67108864 bytes, from faer's evd/hessenberg.rs through
    // triangular.rs; virtual, its touched part is small): the bound is two such buffers.
    const GEMM_BUFFER: usize = 1 << 26;
    assert!(largest <= GEMM_BUFFER.max(dense / 10), "largest allocation {largest} bytes");
    assert!(peak < 2 * GEMM_BUFFER + dense / 10, "peak {peak} bytes");
}
