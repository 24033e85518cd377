//! The paper's application tools (§8) as a user runs them: ports at points of bodies,
//! dummy-spring removal, imposed motion and transmissibility (`application`), design-point
//! sweeps, Bode and line plots, and linearizing at a later time of a run.

#[path = "../common/mod.rs"]
mod common;

mod application;
mod mode_tracking;
mod bode_plot;
mod control;
mod loop_cut;
mod fem_node_outputs;
mod modal_ports;
mod modal_labels;
mod reference_solution;
mod reference_warnings;
mod sweep;
mod validate;
