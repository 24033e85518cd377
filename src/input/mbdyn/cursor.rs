//! Reading a statement's arguments one at a time, with errors that say what was expected.

use super::diagnostic::{MbdynError, Sources, Span};
use super::parser::{Statement, Value};
use crate::kinematics::{Mat3, Vec3};

pub struct Cursor<'a> {
    st: &'a Statement,
    pos: usize,
    sources: &'a Sources,
}

impl<'a> Cursor<'a> {
    pub fn new(st: &'a Statement, sources: &'a Sources) -> Self {
        Cursor { st, pos: 0, sources }
    }

    fn here(&self) -> Span {
        self.st.args.get(self.pos).map_or(self.st.end, |a| a.span)
    }

    pub fn error(&self, message: impl Into<String>) -> MbdynError {
        self.sources.error(self.here(), message)
    }

    fn found(&self) -> String {
        match self.st.args.get(self.pos).map(|a| &a.value) {
            None => "the end of the statement".into(),
            Some(Value::Number(x)) => format!("the number {x}"),
            Some(Value::Word(w)) => format!("'{w}'"),
            Some(Value::Str(s)) => format!("\"{s}\""),
        }
    }

    /// A number.
    pub fn real(&mut self, what: &str) -> Result<f64, MbdynError> {
        match self.st.args.get(self.pos).map(|a| &a.value) {
            Some(Value::Number(x)) => {
                self.pos += 1;
                Ok(*x)
            }
            _ => Err(self.error(format!("expected {what} (a number), found {}", self.found()))),
        }
    }

    /// A non-negative integer label.
    pub fn label(&mut self, what: &str) -> Result<u32, MbdynError> {
        let span = self.here();
        let x = self.real(what)?;
        if x < 0.0 || x.fract() != 0.0 || x > u32::MAX as f64 {
            return Err(self.sources.error(span, format!("expected {what} (a non-negative integer label), found {x}")));
        }
        Ok(x as u32)
    }

    /// The next argument if it is a word.
    pub fn peek_word(&self) -> Option<&str> {
        match self.st.args.get(self.pos).map(|a| &a.value) {
            Some(Value::Word(w)) => Some(w),
            _ => None,
        }
    }

    /// Consumes the word `w` if it is next.
    pub fn accept(&mut self, w: &str) -> bool {
        if self.peek_word() == Some(w) {
            self.pos += 1;
            true
        } else {
            false
        }
    }

    /// One of the given words.
    pub fn word(&mut self, what: &str, options: &[&str]) -> Result<String, MbdynError> {
        match self.peek_word() {
            Some(w) if options.is_empty() || options.contains(&w) => {
                let w = w.to_string();
                self.pos += 1;
                Ok(w)
            }
            _ => Err(self.error(format!("expected {what} ({}), found {}", options.join(", "), self.found()))),
        }
    }

    /// `null`, or three numbers (optionally after `reference, global`).
    pub fn vec3(&mut self, what: &str) -> Result<Vec3, MbdynError> {
        if self.accept("null") || self.accept("default") {
            return Ok(Vec3::zeros());
        }
        self.global_reference(what)?;
        Ok(Vec3::new(self.real(what)?, self.real(what)?, self.real(what)?))
    }

    fn global_reference(&mut self, what: &str) -> Result<(), MbdynError> {
        if self.accept("reference") {
            match self.peek_word() {
                Some("global") => self.pos += 1,
                _ => return Err(self.error(format!("{what}: only 'reference, global' is supported by romdyn so far, found {}", self.found()))),
            }
        }
        Ok(())
    }

    /// `eye`, `null`, `euler123, a, b, c` (`euler`: the same, radians), `matr, 9 numbers`
    /// (row by row), or the two-vector form `I, v_I, J, v_J`.
    pub fn orientation(&mut self, what: &str) -> Result<Mat3, MbdynError> {
        if self.accept("eye") || self.accept("null") {
            return Ok(Mat3::identity());
        }
        self.global_reference(what)?;
        if self.accept("euler123") || self.accept("euler") {
            let (a, b, c) = (self.real("angle about x [rad]")?, self.real("angle about y [rad]")?, self.real("angle about z [rad]")?);
            let r = |axis: Vec3, angle: f64| *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle).matrix();
            return Ok(r(Vec3::x(), a) * r(Vec3::y(), b) * r(Vec3::z(), c));
        }
        if self.accept("matr") {
            let mut m = Mat3::zeros();
            for i in 0..3 {
                for j in 0..3 {
                    m[(i, j)] = self.real("an orientation matrix entry")?;
                }
            }
            return Ok(m);
        }
        self.two_vectors(what)
    }

    fn two_vectors(&mut self, what: &str) -> Result<Mat3, MbdynError> {
        let span = self.here();
        let axis = |c: &mut Self| -> Result<usize, MbdynError> {
            let k = c.real(&format!("{what}: 'eye', 'euler123', 'matr' or an axis index 1, 2 or 3"))?;
            if ![1.0, 2.0, 3.0].contains(&k) {
                return Err(c.error(format!("{what}: axis index must be 1, 2 or 3, found {k}")));
            }
            Ok(k as usize - 1)
        };
        let i = axis(self)?;
        let vi = Vec3::new(self.real("vector component")?, self.real("vector component")?, self.real("vector component")?);
        let j = axis(self)?;
        let vj = Vec3::new(self.real("vector component")?, self.real("vector component")?, self.real("vector component")?);
        let ei = vi.try_normalize(1e-12);
        let ej = ei.and_then(|ei| (vj - ei * ei.dot(&vj)).try_normalize(1e-12));
        let (Some(ei), Some(ej)) = (ei, ej) else {
            return Err(self.sources.error(span, format!("{what}: the two vectors are null or parallel")));
        };
        if i == j {
            return Err(self.sources.error(span, format!("{what}: the two axis indices must differ")));
        }
        let k = 3 - i - j;
        let sign = if (j + 3 - i) % 3 == 1 { 1.0 } else { -1.0 };
        let ek = sign * ei.cross(&ej);
        let mut m = Mat3::zeros();
        m.set_column(i, &ei);
        m.set_column(j, &ej);
        m.set_column(k, &ek);
        Ok(m)
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
}
