//! Octave/MATLAB scripts of the kind MBDyn writes (its eigenanalysis `.m` files): a
//! sequence of assignments `NAME = VALUE;` where VALUE is
//!
//! - a number (`1.5e-3`, `-Inf`, `NaN`, complex `re+i*im`),
//! - a matrix literal `[a b; c d]` (rows end at `;` or a newline, entries are separated by
//!   blanks or commas),
//! - `spconvert(NAME)` of a triplet matrix `[i j v; ...]` (sparse form; duplicates add up,
//!   the size is the largest index), or `zeros(R, C)`.
//!
//! `%` and `#` start comments. Anything else is an error naming file:line:column.

use std::path::{Path, PathBuf};

use super::chars::CharStream;
use super::text_file::{read_text_file, TextFileError};
use crate::limits::{check_dense, MAX_DENSE_ENTRIES};

/// A malformed script.
#[derive(Debug, thiserror::Error)]
pub enum OctaveError {
    #[error(transparent)]
    Read(#[from] TextFileError),
    #[error("{file}:{line}:{column}: {message}")]
    Syntax { file: PathBuf, line: usize, column: usize, message: String },
}

/// A numeric matrix (a scalar is 1 x 1), row-major, with optional imaginary parts.
#[derive(Clone, Debug, PartialEq)]
pub struct OctaveMatrix {
    pub rows: usize,
    pub cols: usize,
    pub re: Vec<f64>,
    /// Imaginary parts, when any entry is complex.
    pub im: Option<Vec<f64>>,
    /// Built by `spconvert` (its size is the largest index it holds).
    pub from_sparse: bool,
}

impl OctaveMatrix {
    fn real(rows: usize, cols: usize, re: Vec<f64>) -> Self {
        OctaveMatrix { rows, cols, re, im: None, from_sparse: false }
    }
    /// Entry `(i, j)`, 0-based (real part).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.re[i * self.cols + j]
    }
    /// The value of a 1 x 1 real matrix.
    pub fn scalar(&self) -> Option<f64> {
        (self.rows == 1 && self.cols == 1 && self.im.is_none()).then(|| self.re[0])
    }
}

/// Where a variable was assigned (1-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Position {
    pub line: usize,
    pub column: usize,
}

/// The variables a script defines, in assignment order (a later assignment replaces).
#[derive(Clone, Debug, Default)]
pub struct OctaveScript {
    pub file: PathBuf,
    pub variables: Vec<(String, OctaveMatrix, Position)>,
}

impl OctaveScript {
    pub fn get(&self, name: &str) -> Option<&OctaveMatrix> {
        self.variables.iter().find(|v| v.0 == name).map(|v| &v.1)
    }
    pub fn position(&self, name: &str) -> Option<Position> {
        self.variables.iter().find(|v| v.0 == name).map(|v| v.2)
    }
    fn set(&mut self, name: String, value: OctaveMatrix, at: Position) {
        self.variables.retain(|v| v.0 != name);
        self.variables.push((name, value, at));
    }
}

/// Reads a script file.
pub fn read_octave_script(file: &Path) -> Result<OctaveScript, OctaveError> {
    let text = read_text_file(file)?;
    parse_octave_script(&text, file)
}

struct Scanner<'a> {
    file: &'a Path,
    text: CharStream,
}

impl Scanner<'_> {
    fn peek(&self) -> Option<char> {
        self.text.peek()
    }
    fn peek_at(&self, k: usize) -> Option<char> {
        self.text.peek_at(k)
    }
    fn bump(&mut self) -> Option<char> {
        self.text.bump()
    }
    fn here(&self) -> Position {
        Position { line: self.text.line, column: self.text.column }
    }
    fn error_at(&self, at: Position, message: impl Into<String>) -> OctaveError {
        OctaveError::Syntax { file: self.file.to_path_buf(), line: at.line, column: at.column, message: message.into() }
    }
    fn error(&self, message: impl Into<String>) -> OctaveError {
        self.error_at(self.here(), message)
    }
    fn found(&self) -> String {
        match self.peek() {
            None => "the end of the file".into(),
            Some('\n') => "the end of the line".into(),
            Some(c) => format!("'{c}'"),
        }
    }
    /// Skips blanks and comments on the current line (not the newline).
    fn skip_blanks(&mut self) {
        while let Some(c) = self.peek() {
            match c {
                ' ' | '\t' | '\r' => {
                    self.bump();
                }
                '%' | '#' => {
                    while self.peek().is_some_and(|c| c != '\n') {
                        self.bump();
                    }
                }
                _ => break,
            }
        }
    }
    fn identifier(&mut self) -> Option<String> {
        let first = self.peek().filter(|c| c.is_ascii_alphabetic())?;
        let mut s = String::from(first);
        self.bump();
        while let Some(c) = self.peek().filter(|c| c.is_ascii_alphanumeric() || *c == '_') {
            s.push(c);
            self.bump();
        }
        Some(s)
    }
    fn require(&mut self, c: char, what: &str) -> Result<(), OctaveError> {
        self.skip_blanks();
        if self.peek() == Some(c) {
            self.bump();
            Ok(())
        } else {
            Err(self.error(format!("expected '{c}' {what}, found {}", self.found())))
        }
    }

    /// An unsigned real: digits, `.`, exponent; or `Inf`/`NaN`.
    fn unsigned(&mut self) -> Result<f64, OctaveError> {
        let at = self.here();
        if self.peek().is_some_and(|c| c.is_ascii_alphabetic()) {
            let word = self.identifier().unwrap_or_default();
            return match word.to_ascii_lowercase().as_str() {
                "inf" => Ok(f64::INFINITY),
                "nan" => Ok(f64::NAN),
                _ => Err(self.error_at(at, format!("expected a number, found '{word}'"))),
            };
        }
        let mut s = String::new();
        while let Some(c) = self.peek() {
            let exponent_sign = (c == '+' || c == '-') && s.ends_with(['e', 'E']);
            if c.is_ascii_digit() || c == '.' || c == 'e' || c == 'E' || exponent_sign {
                s.push(c);
                self.bump();
            } else {
                break;
            }
        }
        s.parse().map_err(|_| self.error_at(at, if s.is_empty() { format!("expected a number, found {}", self.found()) } else { format!("'{s}' is not a number") }))
    }

    /// A real or complex entry: `[+-]x` optionally followed, without blanks, by `[+-]i*y`.
    fn entry(&mut self) -> Result<(f64, f64), OctaveError> {
        let sign = |s: &mut Self| match s.peek() {
            Some('-') => {
                s.bump();
                -1.0
            }
            Some('+') => {
                s.bump();
                1.0
            }
            _ => 1.0,
        };
        let re = sign(self) * self.unsigned()?;
        if matches!(self.peek(), Some('+' | '-')) && self.peek_at(1) == Some('i') && self.peek_at(2) == Some('*') {
            let s = sign(self);
            self.bump();
            self.bump();
            return Ok((re, s * self.unsigned()?));
        }
        Ok((re, 0.0))
    }

    /// `[ ... ]`, the opening bracket already read.
    fn matrix(&mut self, open: Position) -> Result<OctaveMatrix, OctaveError> {
        let mut rows: Vec<(Position, Vec<(f64, f64)>)> = Vec::new();
        let mut row: Vec<(f64, f64)> = Vec::new();
        let mut row_start = self.here();
        let mut entries = 0usize;
        loop {
            self.skip_blanks();
            match self.peek() {
                None => return Err(self.error_at(open, "this '[' is never closed")),
                Some(']') => {
                    self.bump();
                    break;
                }
                Some(';') | Some('\n') => {
                    self.bump();
                    if !row.is_empty() {
                        rows.push((row_start, std::mem::take(&mut row)));
                    }
                    row_start = self.here();
                }
                Some(',') => {
                    self.bump();
                }
                Some(_) => {
                    if row.is_empty() {
                        row_start = self.here();
                    }
                    entries += 1;
                    if entries > MAX_DENSE_ENTRIES {
                        return Err(self.error_at(open, format!("this matrix has more than romdyn's budget of {MAX_DENSE_ENTRIES} entries for a dense matrix")));
                    }
                    row.push(self.entry()?);
                    if !matches!(self.peek(), None | Some(' ' | '\t' | '\r' | '\n' | ',' | ';' | ']' | '%' | '#')) {
                        return Err(self.error(format!("expected a blank, ',', ';' or ']' after a number, found {}", self.found())));
                    }
                }
            }
        }
        if !row.is_empty() {
            rows.push((row_start, row));
        }
        let cols = rows.first().map_or(0, |r| r.1.len());
        if let Some((at, r)) = rows.iter().find(|r| r.1.len() != cols) {
            return Err(self.error_at(*at, format!("this row has {} entries, the first row has {cols}", r.len())));
        }
        let entries: Vec<(f64, f64)> = rows.into_iter().flat_map(|r| r.1).collect();
        let complex = entries.iter().any(|e| e.1 != 0.0);
        let n = entries.len() / cols.max(1);
        Ok(OctaveMatrix {
            rows: if cols == 0 { 0 } else { n },
            cols,
            re: entries.iter().map(|e| e.0).collect(),
            im: complex.then(|| entries.iter().map(|e| e.1).collect()),
            from_sparse: false,
        })
    }

    /// A positive integer literal (a function argument).
    fn size(&mut self) -> Result<usize, OctaveError> {
        self.skip_blanks();
        let at = self.here();
        let x = self.unsigned()?;
        if x >= 0.0 && x.fract() == 0.0 && x < 1e9 { Ok(x as usize) } else { Err(self.error_at(at, format!("expected a size, found {x}"))) }
    }

    /// `name(args)`, the name already read.
    fn call(&mut self, script: &OctaveScript, name: &str, at: Position) -> Result<OctaveMatrix, OctaveError> {
        self.require('(', &format!("after '{name}'"))?;
        let value = match name {
            "zeros" => {
                let r = self.size()?;
                self.require(',', "between the sizes of zeros(R, C)")?;
                let c = self.size()?;
                check_dense(r, c, || format!("zeros({r}, {c})")).map_err(|e| self.error_at(at, e.to_string()))?;
                OctaveMatrix::real(r, c, vec![0.0; r * c])
            }
            "spconvert" => {
                self.skip_blanks();
                let arg_at = self.here();
                let arg = self.identifier().ok_or_else(|| self.error(format!("expected a variable name in spconvert(), found {}", self.found())))?;
                let t = script.get(&arg).ok_or_else(|| self.error_at(arg_at, format!("'{arg}' is not defined before this line")))?;
                spconvert(t).map_err(|m| self.error_at(arg_at, format!("spconvert({arg}): {m}")))?
            }
            _ => return Err(self.error_at(at, format!("function '{name}' is not supported (romdyn reads numbers, [matrices], spconvert and zeros)"))),
        };
        self.require(')', &format!("to close '{name}('"))?;
        Ok(value)
    }
}

/// The sparse matrix of triplets `[i j re (im)]` as a dense one.
fn spconvert(t: &OctaveMatrix) -> Result<OctaveMatrix, String> {
    if t.cols != 3 && t.cols != 4 {
        return Err(format!("expected 3 or 4 columns [i j value], found {}", t.cols));
    }
    let index = |x: f64| if x >= 1.0 && x.fract() == 0.0 && x < 1e9 { Ok(x as usize - 1) } else { Err(format!("{x} is not a valid row or column index")) };
    let mut triplets = Vec::with_capacity(t.rows);
    for k in 0..t.rows {
        triplets.push((index(t.get(k, 0))?, index(t.get(k, 1))?, t.get(k, 2), if t.cols == 4 { t.get(k, 3) } else { 0.0 }));
    }
    let rows = triplets.iter().map(|t| t.0 + 1).max().unwrap_or(0);
    let cols = triplets.iter().map(|t| t.1 + 1).max().unwrap_or(0);
    check_dense(rows, cols, || "the matrix (its size is the largest row and column index)".into()).map_err(|e| e.to_string())?;
    let mut re = vec![0.0; rows * cols];
    let mut im = if triplets.iter().any(|t| t.3 != 0.0) { vec![0.0; rows * cols] } else { Vec::new() };
    for (i, j, r, c) in triplets {
        re[i * cols + j] += r;
        if !im.is_empty() {
            im[i * cols + j] += c;
        }
    }
    let complex = im.iter().any(|x| *x != 0.0);
    Ok(OctaveMatrix { rows, cols, re, im: complex.then_some(im), from_sparse: true })
}

/// Parses a script (`file` names it in errors).
pub fn parse_octave_script(text: &str, file: &Path) -> Result<OctaveScript, OctaveError> {
    let mut s = Scanner { file, text: CharStream::new(text) };
    let mut script = OctaveScript { file: file.to_path_buf(), variables: Vec::new() };
    loop {
        s.skip_blanks();
        match s.peek() {
            None => break,
            Some('\n' | ';' | ',') => {
                s.bump();
                continue;
            }
            _ => {}
        }
        let at = s.here();
        let name = s.identifier().ok_or_else(|| s.error(format!("expected a variable name, found {}", s.found())))?;
        s.require('=', &format!("after '{name}'"))?;
        s.skip_blanks();
        let value_at = s.here();
        let value = match s.peek() {
            Some('[') => {
                s.bump();
                s.matrix(value_at)?
            }
            Some(c) if c.is_ascii_alphabetic() => {
                // A function call, or Inf/NaN (read again as a number).
                let save = s.text.mark();
                let word = s.identifier().unwrap_or_default();
                if matches!(word.to_ascii_lowercase().as_str(), "inf" | "nan") {
                    s.text.reset(save);
                    let (re, im) = s.entry()?;
                    OctaveMatrix { rows: 1, cols: 1, re: vec![re], im: (im != 0.0).then(|| vec![im]), from_sparse: false }
                } else {
                    s.call(&script, &word, value_at)?
                }
            }
            _ => {
                let (re, im) = s.entry()?;
                OctaveMatrix { rows: 1, cols: 1, re: vec![re], im: (im != 0.0).then(|| vec![im]), from_sparse: false }
            }
        };
        s.skip_blanks();
        if s.peek() == Some(';') {
            s.bump();
            s.skip_blanks();
        }
        if !matches!(s.peek(), None | Some('\n' | ',' | ';')) {
            return Err(s.error(format!("expected the end of the statement, found {}", s.found())));
        }
        script.set(name, value, at);
    }
    Ok(script)
}
