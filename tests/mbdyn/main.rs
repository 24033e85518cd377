//! Compatibility with MBDyn's input language and runs: the reader (syntax, `set:`,
//! `include:`, `model::` namespace, errors at file:line:column), drive callers, events,
//! node kinds, the initial assembly and derivatives phase, `romdyn run` and the files MBDyn
//! writes (`.mov`, `.out`, `.m` read back by Octave), the FEM file of the modal element,
//! each against MBDyn's manual or sources, closed forms or MBDyn 1.7.3's numbers on the
//! files of `tests/mbdyn_files/`.

#[path = "../common/mod.rs"]
mod common;

mod cms_round_trip;
mod collection_classes;
mod counter_drives;
mod derivatives_phase;
mod displacement_nodes;
mod eigen_digits;
mod examples_run;
mod fem_file;
mod initial_assembly;
mod mbdyn_compat;
mod modal_joint;
mod mbdyn_displacement_forces;
mod mbdyn_element_drives;
mod mbdyn_errors;
mod mbdyn_events;
mod mbdyn_file_drivers;
mod mbdyn_input;
mod mbdyn_model_current;
mod mbdyn_reader;
mod mbdyn_rod_prestrain;
mod mbdyn_runs;
mod mbdyn_state_drives;
mod mbdyn_string_element_reads;
mod mbdyn_syntax;
mod refusals;
mod node_accelerations;
mod octave;
mod octave_script;
mod rigid_body_kinematics;
mod run_command;
mod scalar_output;
mod step_drive_times;
mod step_drives;
mod time_variant_laws;
mod use_arpack;
mod variable_mass_body;
mod varying_radius;
