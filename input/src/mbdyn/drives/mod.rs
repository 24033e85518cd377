//! Drive callers and what they read: the plain ones, templates of every dimension, counters and random numbers, node and element reads, scalar functions, and the `drivers` block's file drivers.

pub(super) mod callers;
pub(super) mod counter;
pub(super) mod element_reads;
pub(super) mod file_drivers;
pub(super) mod scalar_functions;
pub(super) mod template_dim;
pub(super) mod templates;
