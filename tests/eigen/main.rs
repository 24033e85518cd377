//! The eigensolvers: the deflated dense eigenanalysis against QZ on the whole pencil, its
//! scaling and degenerate pencils, the sparse shift-invert Krylov–Schur route and its exact
//! mode count against the dense one, and the sparse linear model, ROM, `Study` and
//! `--solver sparse` against their dense counterparts.
//! (The sparse route's memory bound is tested in a binary of its own, tests/sparse_memory.rs:
//! it counts this process's allocations with a global allocator.)

#[path = "../common/mod.rs"]
mod common;

mod beam_family;
mod defective_roots;
mod degenerate_pencils;
mod dense_eigen_scaling;
mod eigen_deflation;
mod half_size;
mod sparse_cli;
mod sparse_count;
mod sparse_dae;
mod sparse_eigen;
mod sparse_rom;
mod sparse_study;
mod vector_reference;
