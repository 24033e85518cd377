//! The process's allocator: the system's, except that an allocation the system refuses ends
//! romdyn with a clear message and exit status 1 instead of Rust's abort (SIGABRT). Input
//! sizes are checked against `romdyn::limits` before anything is allocated; this catches
//! what those budgets cannot see (a machine with less memory than a budget allows, a
//! `ulimit -v`). Temporary output files of the interrupted command are removed by the next
//! run in the same folder (the book, docs/src/guide/run.md: "Output sets").

use std::alloc::{GlobalAlloc, Layout, System};
use std::io::Write;

pub struct ReportingAllocator;

#[global_allocator]
static ALLOCATOR: ReportingAllocator = ReportingAllocator;

/// Writes the message without allocating (the size digit by digit into a stack buffer).
fn out_of_memory(bytes: usize) -> ! {
    let mut digits = [0u8; 20];
    let mut err = std::io::stderr().lock();
    let _ = err.write_all(b"romdyn: error: out of memory: the system refused ");
    let _ = err.write_all(romdyn::output::scientific::decimal(bytes as u64, &mut digits));
    let _ = err.write_all(b" bytes (the model or pencil is too large for this machine's memory or the process's limit)\n");
    std::process::exit(1)
}

// SAFETY: every call forwards to `System` with the same arguments; a null result, which
// `System` returns on failure, ends the process instead of returning.
unsafe impl GlobalAlloc for ReportingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if p.is_null() {
            out_of_memory(layout.size());
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if p.is_null() {
            out_of_memory(layout.size());
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            out_of_memory(new_size);
        }
        p
    }
}
