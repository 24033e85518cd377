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

#[cfg(test)]
mod tests {
    use super::syntax::keywords::{check_documented, KeywordTable};

    /// The book's lists of the keywords romdyn reads are the reader's keyword tables.
    #[test]
    fn the_book_lists_the_keywords_of_the_tables() {
        let chapters: [(&KeywordTable, &str, &str); 4] = [
            (&super::elements::block::ELEMENT_TYPES, "elements.md", include_str!("../../../docs/src/mbdyn/elements.md")),
            (&super::elements::genels::GENEL_TYPES, "elements.md", include_str!("../../../docs/src/mbdyn/elements.md")),
            (&super::elements::joints::JOINT_TYPES, "joints.md", include_str!("../../../docs/src/mbdyn/joints.md")),
            (&super::drives::callers::DRIVE_CALLERS, "drives.md", include_str!("../../../docs/src/mbdyn/drives.md")),
        ];
        for (table, name, chapter) in chapters {
            if let Err(e) = check_documented(table, chapter) {
                panic!("docs/src/mbdyn/{name}: {e}");
            }
        }
    }
}
