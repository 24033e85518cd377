//! Reliability: the reproducers of the reliability probes (exit status, message, and what a
//! folder holds afterwards), the reader's limits on deep and long inputs, bounded fuzzing of
//! every reader, and output sets that are complete or absent, also when a run is stopped by
//! SIGTERM or SIGKILL (those tests signal the child `romdyn` process, never this one).

#[path = "../common/mod.rs"]
mod common;

mod mbdyn_fuzz;
mod output_sets;
mod reader_fuzz;
mod reader_limits;
mod reliability;
mod reliability_outputs;
mod run_kill;
