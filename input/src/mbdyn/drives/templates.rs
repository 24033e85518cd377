//! `template drive caller:` cards of every dimension, and the template drive callers of
//! dimension 1, 6, 3x3 and 6x6 (input manual, "General", §Template Drive; MBDyn's
//! tpldrive_impl.cc and mbpar.cc, `GetTplDriveCaller`, `GetVec6`, `GetMat3x3`,
//! `GetMat6x6`). The 3-vector ones, read with frames, are in [`super::callers`].
//!
//! A template drive caller is a sum of `value · drive` terms:
//! - `null` (`zero`, deprecated): no term (the zero value);
//! - `single, VALUE, DRIVE` (the keyword may be left out): one term; in dimension 1 there is
//!   no value, the term is the drive itself (tpldrive.cc, `GetT` of a real reads nothing);
//! - `component, …`: one drive, or `inactive`, per entry (in dimension 1 it is `single`);
//!   a matrix may be written `sym` (the upper triangle by rows, mirrored) or `diag` (the
//!   diagonal, zero elsewhere);
//! - `array, N, VALUE, DRIVE, …`: N single terms (N = 1 is `single`, N = 0 an error);
//! - `reference, LABEL`: a `template drive caller:` card of the same dimension read before.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use super::callers::{drive, other_dims_of, Drives};
pub use super::template_dim::{TemplateDim, Term};
use crate::mbdyn::syntax::parser::Statement;
use crate::kinematics::Mat3;

/// Reads a `template drive caller: LABEL, [name, "NAME",] DIM, TPL_DRIVE_CALLER;` card
/// (input manual §Template Drive Caller; mbpar.cc): DIM is `1`, `3`, `6` (numbers or
/// strings) or `"3x3"`, `"6x6"` (strings), anything else is refused as MBDyn 1.7.3 refuses
/// it. The 3-vector ones' vectors are given as numbers (the frame of the element that uses
/// the card by `reference, LABEL`, as MBDyn's card keeps them); the other dimensions are
/// read by [`template`].
pub fn template_drive_caller_card(st: &Statement, c: &mut Cursor, drives: &mut Drives) -> Result<(), MbdynError> {
    let span = c.here();
    let label = c.label("template drive caller label")?;
    if c.accept("name") {
        c.string("template drive caller name")?;
    }
    let dim_span = c.here();
    let what = "the dimension (1, 3, 6, \"3x3\" or \"6x6\")";
    let (dim, numeric) = if c.next_is_number() { (c.integer(what)?.to_string(), true) } else { (c.string(what)?, false) };
    let other = TemplateDim::from_name(&dim).filter(|d| !numeric || !matches!(d, TemplateDim::Mat3x3 | TemplateDim::Mat6x6));
    if dim != "3" && other.is_none() {
        return Err(c.error_at(dim_span, format!("template drive caller {label}: unsupported dimension {dim} (MBDyn 1.7.3 reads 1, 3, 6, \"3x3\", \"6x6\")")));
    }
    if let Some(d) = other {
        if let Some((_, _, at)) = drives.other_templates.get(&(d, label)) {
            return Err(c.error_at(span, format!("template drive caller {label} of dimension {} is defined twice (first at line {})", d.name(), at.line)));
        }
        let terms = template(c, drives, st.seq, d)?;
        c.finish()?;
        drives.other_templates.insert((d, label), (terms, st.seq, st.span));
        return Ok(());
    }
    if let Some((_, _, at)) = drives.templates.get(&label) {
        return Err(c.error_at(span, format!("template drive caller {label} is defined twice (first at line {})", at.line)));
    }
    let terms = super::callers::template_terms(c, drives, st.seq, &Mat3::identity(), &|c: &mut Cursor| c.vec3_values("template drive caller vector"), 0)?;
    c.finish()?;
    drives.templates.insert(label, (terms, st.seq, st.span));
    Ok(())
}

impl Drives {
    /// A copy of the `template drive caller:` card `label` of dimension `dim`, for a
    /// statement at `seq` (MBDyn's `pCopy`), or why there is none.
    pub fn template_card(&self, dim: TemplateDim, label: u32, seq: usize) -> Result<Vec<Term>, String> {
        match self.other_templates.get(&(dim, label)) {
            Some((terms, s, _)) if *s < seq => Ok(terms.iter().map(|(v, d)| (v.clone(), super::counter::copied(d, &self.steps, seq))).collect()),
            Some((_, _, at)) => Err(format!("template drive caller {label} (dimension {}) is used before its definition (line {})", dim.name(), at.line)),
            None => Err(format!("template drive caller {label} of dimension {} is not defined{}", dim.name(), other_dims_of(self, label, Some(dim)))),
        }
    }
}

/// Reads a template drive caller of dimension `dim`: its terms. An `array` holds single
/// terms only (tpldrive_impl.cc, `ArrayTDCR`) and `reference` copies a card read before, so
/// nothing nests.
pub fn template(c: &mut Cursor, drives: &Drives, seq: usize, dim: TemplateDim) -> Result<Vec<Term>, MbdynError> {
    let (rows, cols) = dim.shape();
    let n = rows * cols;
    if c.accept("null") || c.accept("zero") {
        return Ok(Vec::new());
    }
    if c.accept("reference") {
        let span = c.here();
        let label = c.label(&format!("template drive caller label (a dimension {} 'template drive caller:' card)", dim.name()))?;
        return drives.template_card(dim, label, seq).map_err(|m| c.error_at(span, m));
    }
    if dim != TemplateDim::Scalar && c.accept("component") {
        let unit = |k: usize| {
            let mut v = vec![0.0; n];
            v[k] = 1.0;
            v
        };
        let mut terms = Vec::new();
        let entry = |c: &mut Cursor, ks: &[usize], terms: &mut Vec<Term>| -> Result<(), MbdynError> {
            if !c.accept("inactive") {
                let d = drive(c, drives, seq)?;
                for &k in ks {
                    terms.push((unit(k), d.clone()));
                }
            }
            Ok(())
        };
        if cols > 1 && c.accept("sym") {
            for i in 0..rows {
                for j in i..cols {
                    let ks = if i == j { vec![i * cols + j] } else { vec![i * cols + j, j * cols + i] };
                    entry(c, &ks, &mut terms)?;
                }
            }
        } else if cols > 1 && c.accept("diag") {
            for i in 0..rows {
                entry(c, &[i * cols + i], &mut terms)?;
            }
        } else {
            if c.peek_keyword().is_some_and(|k| k.eq_ignore_ascii_case("sym") || k.eq_ignore_ascii_case("diag")) {
                return Err(c.error("'sym' and 'diag' apply to matrix template drive callers, not to vectors"));
            }
            for k in 0..n {
                entry(c, &[k], &mut terms)?;
            }
        }
        return Ok(terms);
    }
    let count = if c.accept("array") {
        let span = c.here();
        let k = c.count("number of template drive callers")?;
        if k == 0 {
            return Err(c.error_at(span, "an array template drive caller needs at least one drive (MBDyn 1.7.3 refuses zero)"));
        }
        k
    } else {
        // `single`, or `component` of a scalar (tpldrive_impl.cc registers `SingleTDCR`).
        let _ = c.accept("single") || c.accept("component");
        1
    };
    let mut terms = Vec::with_capacity(count);
    for _ in 0..count {
        let value = value(c, dim)?;
        terms.push((value, drive(c, drives, seq)?));
    }
    Ok(terms)
}

/// The value of a `single` term (mbpar.cc `GetVec6`, `GetMat3x3`, `GetMat6x6`); nothing
/// is read in dimension 1.
fn value(c: &mut Cursor, dim: TemplateDim) -> Result<Vec<f64>, MbdynError> {
    let what = format!("dimension {} template drive caller value", dim.name());
    match dim {
        TemplateDim::Scalar => Ok(vec![1.0]),
        TemplateDim::Mat3x3 => Ok(c.mat3x3(&what)?.transpose().iter().copied().collect()),
        TemplateDim::Vec6 => {
            if c.accept("null") || c.accept("default") {
                return Ok(vec![0.0; 6]);
            }
            let mut v = (0..6).map(|_| c.real(&what)).collect::<Result<Vec<_>, _>>()?;
            scale(c, &mut v)?;
            Ok(v)
        }
        TemplateDim::Mat6x6 => Ok(c.mat6x6(&what)?.transpose().iter().copied().collect()),
    }
}

fn scale(c: &mut Cursor, v: &mut [f64]) -> Result<(), MbdynError> {
    if c.accept("scale") {
        let s = c.real("scale factor")?;
        v.iter_mut().for_each(|x| *x *= s);
    }
    Ok(())
}

