//! Errors in MBDyn input files, with the file, line and column, the offending line and a
//! caret under the column.

use std::fmt;
use std::path::PathBuf;

/// A refusal of a card MBDyn 1.7.3 runs (issue 38 point 4: a refusal says whether MBDyn
/// runs the card, so a user learns the file is valid MBDyn and the limit is romdyn's):
/// "`what` is not supported by romdyn (MBDyn 1.7.3 runs it)".
pub fn mbdyn_runs_it(what: &str) -> String {
    format!("{what} is not supported by romdyn (MBDyn 1.7.3 runs it)")
}

/// A refusal of a name that neither romdyn nor MBDyn 1.7.3 knows: "unknown `what`
/// 'name': MBDyn 1.7.3 has none either".
pub fn unknown_to_both(what: &str, name: &str) -> String {
    format!("unknown {what} '{name}': MBDyn 1.7.3 has none either")
}

/// A position in a source file (1-based line and column, in characters).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Span {
    pub file: usize,
    pub line: usize,
    pub column: usize,
}

/// An error in an MBDyn input file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MbdynError {
    pub file: PathBuf,
    pub line: usize,
    pub column: usize,
    pub message: String,
    /// The text of the offending line (empty when unknown).
    pub source_line: String,
}

impl fmt::Display for MbdynError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            return write!(f, "{}: error: {}", self.file.display(), self.message);
        }
        write!(f, "{}:{}:{}: error: {}", self.file.display(), self.line, self.column, self.message)?;
        if !self.source_line.is_empty() {
            let width = self.line.to_string().len();
            // Tabs are kept under tabs so the caret lines up however they are displayed.
            let pad: String = self.source_line.chars().take(self.column.saturating_sub(1)).map(|c| if c == '\t' { '\t' } else { ' ' }).collect();
            write!(f, "\n{:width$} |\n{} | {}\n{:width$} | {pad}^", "", self.line, self.source_line, "")?;
        }
        Ok(())
    }
}

impl std::error::Error for MbdynError {}

/// The files read so far (main file and includes), to turn spans into messages.
#[derive(Default, Debug)]
pub struct Sources {
    pub files: Vec<(PathBuf, String)>,
    /// Where each line starts, by file, made at a file's first error: an error costs
    /// O(log lines), not O(file) (the reader makes and drops errors as it goes, and a
    /// file of N cards with one each read in O(N²)).
    line_starts: std::sync::Mutex<std::collections::HashMap<usize, std::sync::Arc<Vec<usize>>>>,
}

impl Sources {
    pub fn error(&self, span: Span, message: impl Into<String>) -> MbdynError {
        let Some((file, text)) = self.files.get(span.file) else {
            return MbdynError { file: PathBuf::new(), line: span.line, column: span.column, message: message.into(), source_line: String::new() };
        };
        let starts = {
            let mut index = self.line_starts.lock().unwrap_or_else(|e| e.into_inner());
            let starts = index.entry(span.file).or_insert_with(|| std::sync::Arc::new(std::iter::once(0).chain(text.match_indices('\n').map(|(k, _)| k + 1)).collect()));
            starts.clone()
        };
        let source_line = match starts.get(span.line.saturating_sub(1)) {
            Some(&a) => text[a..].lines().next().unwrap_or("").to_string(),
            _ => String::new(),
        };
        MbdynError { file: file.clone(), line: span.line, column: span.column, message: message.into(), source_line }
    }
}
