//! MBDyn's input language: lexer, expressions over `set:` variables, statements and blocks
//! with `include:`, and the mapping of the supported subset to a [`Model`].
//!
//! [`Model`]: crate::model::Model

mod cursor;
mod diagnostic;
mod elements;
mod expr;
mod lexer;
mod model;
mod parser;

pub use diagnostic::MbdynError;
pub use model::{build, read_model, MbdynModel};
pub use parser::{parse_file, parse_text, Document};
