//! The front ends' contract: the `romdyn` command line end to end (CASES C1, outputs and
//! errors), pencil files, the library calls the Python package makes (node histories, every
//! door into a study running the same checks), and the documentation's commands and shown
//! output against the CLI (`docs_commands`).

#[path = "../common/mod.rs"]
mod common;

mod cli;
mod docs_commands;
mod flag_spellings;
mod node_histories;
mod pencil_input;
mod report;
mod scalar_ports;
mod study_doors;
mod unit_test_reach;
