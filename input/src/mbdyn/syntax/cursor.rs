//! Reading a statement's arguments one at a time, with errors that say what was expected,
//! and the plain higher-order structures of the input manual ("General", §Higher-Order
//! Math Structures): `Vec3` and `Mat3x3` with `null`, `eye`, `diag`, `sym`, `skew`,
//! `matr` and the trailing `scale, FACTOR`.

use super::diagnostic::{MbdynError, Sources, Span};
use super::parser::{same_keyword, Statement, Value};
use crate::kinematics::{Mat3, Vec3};

pub struct Cursor<'a> {
    st: &'a Statement,
    pos: usize,
    sources: &'a Sources,
    /// What the part of the card being read publishes to `model::current` ([`Cursor::publish`]).
    current: Vec<(&'static str, f64)>,
}

/// Largest count romdyn reads for a list (points of a drive, eigenanalysis times, …).
const MAX_COUNT: f64 = 1.0e6;

impl<'a> Cursor<'a> {
    pub fn new(st: &'a Statement, sources: &'a Sources) -> Self {
        Cursor { st, pos: 0, sources, current: Vec::new() }
    }

    pub fn statement(&self) -> &'a Statement {
        self.st
    }

    /// Publishes `data` to `model::current("NAME")` in the arguments read until
    /// [`Cursor::withdraw`] (MBDyn's `PushCurrData` … `PopCurrData` around part of a card).
    pub fn publish(&mut self, data: &[(&'static str, f64)]) {
        self.current = data.to_vec();
    }
    /// Ends [`Cursor::publish`].
    pub fn withdraw(&mut self) {
        self.current.clear();
    }

    /// The input file `span` is in.
    pub fn source_path(&self, span: Span) -> Option<&'a std::path::Path> {
        self.sources.files.get(span.file).map(|(p, _)| p.as_path())
    }

    /// Where the next argument is (the ';' when none is left).
    pub fn here(&self) -> Span {
        self.st.args.get(self.pos).map_or(self.st.end, |a| a.span)
    }

    pub fn error(&self, message: impl Into<String>) -> MbdynError {
        self.sources.error(self.here(), message)
    }
    pub fn error_at(&self, span: Span, message: impl Into<String>) -> MbdynError {
        self.sources.error(span, message)
    }

    /// What the next argument is, for messages.
    pub fn found(&self) -> String {
        let Some(a) = self.st.args.get(self.pos) else { return "the end of the statement".into() };
        match &a.value {
            Value::Number(x) => format!("the number {x}"),
            Value::Word(w) => format!("'{w}'"),
            Value::Str(s) => format!("the string \"{s}\""),
            Value::Empty => "an empty field".into(),
            Value::Current(_) => format!("'{}'", a.text),
        }
    }

    /// Whether the next argument is a number (or an empty field).
    pub fn next_is_number(&self) -> bool {
        matches!(self.st.args.get(self.pos).map(|a| &a.value), Some(Value::Number(_) | Value::Empty | Value::Current(_)))
    }

    /// How many arguments are read.
    pub fn position(&self) -> usize {
        self.pos
    }

    /// The next argument's text as written, if there is one.
    pub fn peek_text(&self) -> Option<&'a str> {
        self.st.args.get(self.pos).map(|a| a.text.as_str())
    }

    /// Whether the next argument is a double-quoted string.
    pub fn next_is_string(&self) -> bool {
        matches!(self.st.args.get(self.pos).map(|a| &a.value), Some(Value::Str(_)))
    }

    /// The next argument read as a keyword, if it can be one.
    pub fn peek_keyword(&self) -> Option<&'a str> {
        self.st.args.get(self.pos).and_then(|a| a.keyword.as_deref())
    }

    /// Consumes the keyword `kw` if it is next.
    pub fn accept(&mut self, kw: &str) -> bool {
        if self.peek_keyword().is_some_and(|w| same_keyword(w, kw)) {
            self.pos += 1;
            true
        } else {
            false
        }
    }

    /// Consumes the next argument if it is one of `options`; returns that option.
    pub fn accept_any(&mut self, options: &[&'static str]) -> Option<&'static str> {
        let w = self.peek_keyword()?;
        let found = options.iter().copied().find(|o| same_keyword(o, w))?;
        self.pos += 1;
        Some(found)
    }

    /// One of `options`.
    pub fn keyword(&mut self, what: &str, options: &[&'static str]) -> Result<&'static str, MbdynError> {
        self.accept_any(options).ok_or_else(|| self.error(format!("expected {what} ({}), found {}", options.join(", "), self.found())))
    }

    /// A number; an empty field reads as `default`.
    pub fn real_or(&mut self, what: &str, default: f64) -> Result<f64, MbdynError> {
        let v = match self.st.args.get(self.pos).map(|a| &a.value) {
            Some(Value::Number(x)) if x.is_finite() => *x,
            Some(Value::Number(x)) => return Err(self.error(format!("expected {what} (a finite number), found {x}"))),
            Some(Value::Empty) => default,
            Some(Value::Current(d)) => match d.evaluate(self.sources, &self.current)? {
                x if x.is_finite() => x,
                x => return Err(self.error(format!("expected {what} (a finite number), found {x}"))),
            },
            Some(Value::Word(_)) if self.st.args.get(self.pos).is_some_and(|a| is_name(&a.text)) => {
                let name = self.st.args.get(self.pos).map_or("", |a| a.text.as_str());
                return Err(self.error(format!("expected {what} (a number), found '{name}', which is neither a number nor a defined variable")));
            }
            _ => return Err(self.error(format!("expected {what} (a number), found {}", self.found()))),
        };
        self.pos += 1;
        Ok(v)
    }

    /// A number; an empty field reads as zero.
    pub fn real(&mut self, what: &str) -> Result<f64, MbdynError> {
        self.real_or(what, 0.0)
    }

    /// A whole number.
    pub fn integer(&mut self, what: &str) -> Result<i64, MbdynError> {
        let span = self.here();
        let x = self.real(what)?;
        if x.fract() != 0.0 || !x.is_finite() || x.abs() > 9.0e15 {
            return Err(self.error_at(span, format!("expected {what} (a whole number), found {x}")));
        }
        Ok(x as i64)
    }

    /// A non-negative integer label.
    pub fn label(&mut self, what: &str) -> Result<u32, MbdynError> {
        let span = self.here();
        let x = self.real(what)?;
        if x < 0.0 || x.fract() != 0.0 || x > u32::MAX as f64 || !x.is_finite() {
            return Err(self.error_at(span, format!("expected {what} (a non-negative integer label), found {x}")));
        }
        Ok(x as u32)
    }

    /// A count for a list that follows.
    pub fn count(&mut self, what: &str) -> Result<usize, MbdynError> {
        let span = self.here();
        let x = self.real(what)?;
        if x < 0.0 || x.fract() != 0.0 || x > MAX_COUNT || !x.is_finite() {
            return Err(self.error_at(span, format!("expected {what} (a whole number from 0 to {MAX_COUNT}), found {x}")));
        }
        Ok(x as usize)
    }

    /// A double-quoted string.
    pub fn string(&mut self, what: &str) -> Result<String, MbdynError> {
        match self.st.args.get(self.pos).map(|a| &a.value) {
            Some(Value::Str(s)) => {
                self.pos += 1;
                Ok(s.clone())
            }
            _ => Err(self.error(format!("expected {what} (a string in double quotes), found {}", self.found()))),
        }
    }

    /// `yes`, `no`, or a number (non-zero is yes).
    pub fn flag(&mut self, what: &str) -> Result<bool, MbdynError> {
        if let Some(w) = self.accept_any(&["yes", "no", "true", "false"]) {
            return Ok(w == "yes" || w == "true");
        }
        Ok(self.real(&format!("{what} (yes or no)"))? != 0.0)
    }

    /// Skips every remaining argument (statements romdyn accepts and ignores).
    pub fn skip_rest(&mut self) {
        self.pos = self.st.args.len();
    }

    /// Errors unless every argument was read.
    pub fn finish(&self) -> Result<(), MbdynError> {
        if self.pos < self.st.args.len() {
            return Err(self.error(format!("unexpected extra argument {} in '{}'", self.found(), self.st.keyword)));
        }
        Ok(())
    }

    pub fn is_done(&self) -> bool {
        self.pos >= self.st.args.len()
    }

    /// Three numbers, or `null` / `default` (zero); a non-null vector may be followed by
    /// `scale, FACTOR`.
    pub fn vec3_values(&mut self, what: &str) -> Result<Vec3, MbdynError> {
        if self.accept("null") || self.accept("default") {
            return Ok(Vec3::zeros());
        }
        let v = Vec3::new(self.real(what)?, self.real(what)?, self.real(what)?);
        Ok(v * self.scale()?)
    }

    fn scale(&mut self) -> Result<f64, MbdynError> {
        if self.accept("scale") { self.real("scale factor") } else { Ok(1.0) }
    }

    /// A 3x3 matrix: `eye`, `null`, `diag, 3 values`, `sym, 6 values` (upper triangle by
    /// rows), `skew, 3 values`, or 9 values by rows (optionally after `matr`).
    pub fn mat3x3(&mut self, what: &str) -> Result<Mat3, MbdynError> {
        if self.accept("eye") {
            return Ok(Mat3::identity() * self.scale()?);
        }
        if self.accept("null") {
            return Ok(Mat3::zeros());
        }
        let m = if self.accept("diag") {
            Mat3::from_diagonal(&Vec3::new(self.real(what)?, self.real(what)?, self.real(what)?))
        } else if self.accept("sym") {
            let mut v = [0.0; 6];
            for x in &mut v {
                *x = self.real(what)?;
            }
            Mat3::new(v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5])
        } else if self.accept("skew") {
            crate::kinematics::skew(&Vec3::new(self.real(what)?, self.real(what)?, self.real(what)?))
        } else {
            self.accept("matr");
            let mut v = [0.0; 9];
            for x in &mut v {
                *x = self.real(what)?;
            }
            Mat3::from_row_slice(&v)
        };
        Ok(m * self.scale()?)
    }
}

impl Cursor<'_> {
    /// A 6x6 matrix (mbpar.cc `GetMat6x6`): `null`, `default` (zero), `eye`, `diag, 6
    /// values`, `sym, 21 values` (upper triangle by rows), or 36 values by rows (optionally
    /// after `matr`), then an optional `scale, FACTOR`. MBDyn's `anba` layout is refused by
    /// name.
    pub fn mat6x6(&mut self, what: &str) -> Result<nalgebra::Matrix6<f64>, MbdynError> {
        if self.accept("null") || self.accept("default") {
            return Ok(nalgebra::Matrix6::zeros());
        }
        let mut m = nalgebra::Matrix6::zeros();
        if self.accept("eye") {
            m = nalgebra::Matrix6::identity();
        } else if self.accept("diag") {
            for i in 0..6 {
                m[(i, i)] = self.real(what)?;
            }
        } else if self.accept("sym") {
            for i in 0..6 {
                for j in i..6 {
                    m[(i, j)] = self.real(what)?;
                    m[(j, i)] = m[(i, j)];
                }
            }
        } else if self.peek_keyword().is_some_and(|k| k.eq_ignore_ascii_case("anba")) {
            return Err(self.error("the 'anba' layout of a 6x6 matrix is not supported by romdyn (MBDyn 1.7.3 runs it) (write the 36 entries by rows, in MBDyn's axes)"));
        } else {
            self.accept("matr");
            for i in 0..6 {
                for j in 0..6 {
                    m[(i, j)] = self.real(what)?;
                }
            }
        }
        Ok(m * self.scale()?)
    }
}

/// Whether `text` is a single identifier.
fn is_name(text: &str) -> bool {
    text.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_') && text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}
