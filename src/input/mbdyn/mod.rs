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

mod blocks;
mod drives;
mod elements;
mod model;
mod nodes;
mod read_options;
mod syntax;
mod written_nodes;


pub use syntax::diagnostic::MbdynError;
pub use syntax::expr::{SetOverrides, Variable, Variables};
pub use model::{build, read_model, read_model_text, read_model_with, MbdynModel};
pub use syntax::parser::Document;
pub use read_options::{BeamUpdateChoice, BeamUpdateRule, ReadOptions};
pub use written_nodes::{parse_file, parse_file_with, parse_text, parse_text_with};
pub use syntax::value::TypedValue;
