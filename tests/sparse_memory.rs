//! The Study's sparse route keeps memory proportional to the non-zeros (issue 13 point 1):
//! on a 17012-equation chain, where one dense n x n matrix takes 2.3 GB, the whole workflow
//! (reference solution, sparse linearization, modes, modal table, warnings, ROM with static
//! correction, full-model frequency response) never allocates anything near n² entries;
//! and `romdyn run`'s eigenanalysis JSON is written without holding the document whole.
//! Measured by a counting allocator in this test binary (its only test, so nothing else runs
//! while it counts).
mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use common::models::hanging_chain;
use romdyn::analysis::{Eigenanalysis, Reference};
use romdyn::dae::{Assembler, State};
use romdyn::output::eigen_json::write_eigen_json;
use romdyn::model::ConstraintForm;
use romdyn::model::InitialValueProblem;
use romdyn::rom::ModeSelection;
use romdyn::study::{EigenSettings, Ports, Residualization, RomRequest, Solver, Study, StudySource};

struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static LARGEST: AtomicUsize = AtomicUsize::new(0);
/// Page-aligned allocations: faer's matrix product (private-gemm) keeps one packing buffer
/// per thread, `Vec<Page>` with 4096-byte alignment, sized from the processor's reported
/// L3 cache and never initialized as a whole (only what a product packs is touched). faer's
/// own matrices are 64-byte aligned, so no matrix lands here.
static PAGE_ALIGNED: AtomicUsize = AtomicUsize::new(0);
static PAGE_ALIGNED_LARGEST: AtomicUsize = AtomicUsize::new(0);
const PAGE: usize = 4096;

fn grew(layout: Layout, bytes: usize) {
    if layout.align() >= PAGE {
        PAGE_ALIGNED.fetch_add(1, Ordering::Relaxed);
        PAGE_ALIGNED_LARGEST.fetch_max(bytes, Ordering::Relaxed);
        return;
    }
    let live = LIVE.fetch_add(bytes, Ordering::Relaxed) + bytes;
    PEAK.fetch_max(live, Ordering::Relaxed);
    LARGEST.fetch_max(bytes, Ordering::Relaxed);
}

fn shrank(layout: Layout) {
    if layout.align() < PAGE {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

// SAFETY: every call forwards to `System` with the same arguments; the counters only
// observe sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        grew(layout, layout.size());
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        grew(layout, layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        shrank(layout);
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        shrank(layout);
        grew(layout, new_size);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// The process's resident set now and its high-water mark [bytes] (Linux: /proc/self/status).
fn resident() -> Option<(usize, usize)> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let kb = |key: &str| status.lines().find(|l| l.starts_with(key))?.split_whitespace().nth(1)?.parse::<usize>().ok().map(|k| k * 1024);
    Some((kb("VmRSS:")?, kb("VmHWM:")?))
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

#[test]
fn the_sparse_route_of_a_5112_equation_chain_never_allocates_a_dense_matrix() {
    let model = hanging_chain(1000, ConstraintForm::Scaled);
    let ports = Ports::Nodes { inputs: vec!["300:Fx".parse().unwrap()], outputs: vec!["300:x".parse().unwrap()] };
    let request = RomRequest::new(ModeSelection::Lowest(5)).residualize(Residualization::Dropped);
    let eigen = EigenSettings { solver: Solver::Sparse, ..EigenSettings::default() }.for_request(&request);
    let rss_before = resident();
    let before = LIVE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    LARGEST.store(0, Ordering::Relaxed);
    let study = Study::builder(StudySource::model(model, InitialValueProblem::default())).reference(Reference::Static { load_steps: 1 }).ports(ports).eigen(eigen).build().unwrap();
    let table = study.modal_report_of(None).unwrap().to_text();
    let rom = study.reduce(&request).unwrap();
    let h = study.full_frequency_response(&[0.1, 1.0, 3.0]).unwrap();
    let n = study.equations();
    assert_eq!(n, 17012);
    assert!(table.contains("sparse route") && rom.static_correction && h.len() == 3);
    let dense = n * n * std::mem::size_of::<f64>();
    let (peak, largest) = (PEAK.load(Ordering::Relaxed) - before, LARGEST.load(Ordering::Relaxed));
    let (buffers, buffer) = (PAGE_ALIGNED.load(Ordering::Relaxed), PAGE_ALIGNED_LARGEST.load(Ordering::Relaxed));
    eprintln!("n = {n}: peak {:.1} MB, largest allocation {:.1} MB, one dense matrix {:.0} MB; {buffers} page-aligned packing buffer(s), largest {:.1} MB (virtual, sized by the L3 cache)", peak as f64 / 1e6, largest as f64 / 1e6, dense as f64 / 1e6, buffer as f64 / 1e6);
    // One dense n x n matrix is 2.3 GB; the Krylov bases are n x (a few times the wanted
    // count) complex entries. A tenth of one dense matrix (231 MB) is a bound no n²
    // allocation fits under; the peak of everything allocated, a quarter. faer's packing
    // buffers are counted apart: their size follows the L3 cache the processor reports
    // (32 MiB and 64 MiB on earlier machines here, 2 x 480 MiB per thread on one whose
    // virtual processor reports a 480 MiB L3), most of it never touched.
    assert!(largest <= dense / 10, "largest allocation {largest} bytes");
    assert!(peak < dense / 4, "peak {peak} bytes");
    // What the process really holds, buffers included: the resident high-water mark grew by
    // less than a quarter of one dense matrix (measured: see the eprintln above).
    if let (Some((rss, _)), Some((_, hwm))) = (rss_before, resident()) {
        let grown = hwm.saturating_sub(rss);
        eprintln!("resident high-water mark grew by {:.1} MB", grown as f64 / 1e6);
        assert!(grown < dense / 4, "resident set grew by {grown} bytes");
    }

    // `romdyn run`'s eigenanalysis JSON (output/eigen_json.rs) is written as it is
    // serialized: the 10 lowest modes of the 12,024-equation string of masses (22 rows of
    // 3000 energy shares each) allocate far less than the file holds while it is written.
    // Built whole as a serde_json::Value, then printed to a string, the same document took
    // over ten times the file's size (1.4 GB for a 112 MB file at 96,024 equations).
    // Measured: 7.7 MB written, 0.57 MB allocated at the peak; bound: a quarter of the file.
    let m = common::mbdyn::read(&common::mbdyn::string_of_masses(1000, "use arpack, 10, 30, 0."));
    let state = State::initial(&m.model, &Assembler::new(&m.model).dofs);
    let analysis = Eigenanalysis::at(&m.model, &state, 0, m.problem.eigenanalysis.as_ref().unwrap()).unwrap();
    struct Counted(usize);
    impl std::io::Write for Counted {
        fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
            self.0 += b.len();
            Ok(b.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let mut file = Counted(0);
    let before = LIVE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    write_eigen_json(&mut file, "string.mbd", &analysis.file()).unwrap();
    let peak = PEAK.load(Ordering::Relaxed) - before;
    eprintln!("eigenanalysis JSON: {:.1} MB written, {:.2} MB allocated at the peak", file.0 as f64 / 1e6, peak as f64 / 1e6);
    assert!(file.0 > 5_000_000, "{} bytes", file.0);
    assert!(peak < file.0 / 4, "peak {peak} bytes while writing {} bytes", file.0);
}
