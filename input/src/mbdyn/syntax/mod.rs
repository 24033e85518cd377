//! MBDyn's input syntax: tokens, statements and blocks, the cursor that reads a statement's arguments, errors with file:line:col, the math parser's values and expressions (with the tables of the cards they look into), reference frames and orientations.

pub(super) mod card_tables;
pub(super) mod cursor;
pub(super) mod diagnostic;
pub(super) mod expr;
pub(super) mod functions;
pub(super) mod keywords;
pub(super) mod lexer;
pub(super) mod model_namespace;
pub(super) mod orientation;
pub(super) mod parser;
pub(super) mod references;
pub(super) mod value;
