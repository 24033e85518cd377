//! MBDyn's input language (the MBDyn input manual, `manual/input/*.tex`): lexer, the math
//! parser's typed expressions over `set:` variables, statements and blocks with
//! `include:`, reference frames, drive callers and constitutive laws, and the mapping of
//! the supported subset onto a [`Model`] and an [`InitialValueProblem`].
//!
//! Everything else is named in an error: romdyn never skips a statement silently.
//! Statements that only tune MBDyn's own numerics or output are accepted and ignored.
//!
//! [`Model`]: crate::model::Model
//! [`InitialValueProblem`]: crate::model::InitialValueProblem

mod beam_slider;
mod beams;
mod card_tables;
mod control;
mod counter_drives;
mod cursor;
mod diagnostic;
mod drives;
mod electric;
mod driven;
mod element_context;
mod element_reads;
mod elements;
mod expr;
mod file_drivers;
mod forces;
mod friction;
mod functions;
mod genels;
mod hints;
mod hydraulic;
mod hydraulic_args;
mod hydraulic_elements;
mod joints;
mod total_joint;
mod laws;
mod lexer;
mod modal;
mod model;
mod model_namespace;
mod nodes;
mod orientation;
mod parser;
mod plates;
mod problem;
mod rbk;
mod read_options;
mod references;
mod scalar_functions;
mod scalar_nodes;
mod template_dim;
mod templates;
mod total_equation;
mod screw;
mod value;
mod variable_body;
mod written_nodes;

pub use diagnostic::MbdynError;
pub use expr::{SetOverrides, Variable, Variables};
pub use model::{build, read_model, read_model_text, read_model_with, MbdynModel};
pub use parser::Document;
pub use read_options::{BeamUpdateChoice, BeamUpdateRule, ReadOptions};
pub use written_nodes::{parse_file, parse_file_with, parse_text, parse_text_with};
pub use value::TypedValue;
