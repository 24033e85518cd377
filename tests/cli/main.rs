//! The front ends' contract: the `romdyn` command line end to end (CASES C1, outputs and
//! errors), pencil files, and the library calls the Python package makes (node histories).

#[path = "../common/mod.rs"]
mod common;

mod cli;
mod node_histories;
mod pencil_input;
