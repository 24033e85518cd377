//! A driven element's hints (input manual, §Driven Element, "hint"; hint_impl.cc,
//! `ParseHint`; the joints' `ParseHint` and `SetValue`): `hint, "drive{DRIVE}"`,
//! `"drive3{TEMPLATE_DRIVE}"`, `"position-drive3{…}"`, `"orientation-drive3{…}"`. MBDyn
//! parses the text between the braces when the element switches on, so its expressions
//! (`model::xposition(1)`, `model::distance_prev(2, 1)`, …) take the model's values at that
//! instant; romdyn does the same with the state it latches at ([`crate::element::Element::latch`]).
//! The text is parsed once more while the file is read, with each `model::` read 0, so that
//! a mistake is reported at the hint's string.

use std::sync::{Arc, Mutex};

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Sources, Span};
use crate::mbdyn::drives::callers::{template_vec3, Drives};
use crate::mbdyn::syntax::expr::{Evaluator, Variables};
use crate::mbdyn::syntax::lexer::{tokenize, Spanned, Token};
use crate::mbdyn::syntax::model_namespace::{Live, Reads};
use crate::mbdyn::syntax::parser::{Arg, Statement, Value};
use crate::mbdyn::syntax::value::TypedValue;
use crate::element::{ElementState, Hint, HintValue, VectorDrive};
use crate::kinematics::Mat3;
use crate::mbdyn::drives::callers;

/// The hints romdyn builds, by the prefix of their text.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Drive,
    Drive3,
    PositionDrive3,
    OrientationDrive3,
}

const KINDS: [(&str, Kind); 4] = [("drive{", Kind::Drive), ("drive3{", Kind::Drive3), ("position-drive3{", Kind::PositionDrive3), ("orientation-drive3{", Kind::OrientationDrive3)];

/// The hint `text` written at `at`: checked now, built at each switch-on. With it, its
/// drive as the check built it (each `model::` read 0), to check that it applies.
pub fn hint(text: &str, at: Span, src: &Sources, drives: &Drives, seq: usize) -> Result<(Hint, HintValue), MbdynError> {
    let lower = text.trim().to_lowercase();
    let found = KINDS.iter().find(|(p, _)| lower.starts_with(p)).filter(|_| lower.ends_with('}'));
    let Some(&(prefix, kind)) = found else {
        return Err(src.error(at, format!("driven: hint \"{text}\" is not supported by romdyn (MBDyn 1.7.3 runs it) (supported: \"drive{{…}}\" on a distance joint, \"drive3{{…}}\" on a drive hinge, \"position-drive3{{…}}\" and \"orientation-drive3{{…}}\" on a total joint or total pin joint)")));
    };
    let trimmed = text.trim();
    let body = trimmed[prefix.len()..trimmed.len() - 1].to_string();
    let program = Program { kind, body, drives: Mutex::new(drives.for_hints()), seq };
    let labels = drives.structural_nodes.clone();
    let probe = program.build(Reads::Labels(&labels), Some(Reads::Labels(&labels))).map_err(|m| src.error(at, format!("driven: hint \"{text}\": {m}")))?;
    let build: Hint = Arc::new(move |now: &dyn ElementState, before: &dyn ElementState| program.build(Reads::Nodes(&Live(now)), Some(Reads::Nodes(&Live(before)))));
    Ok((build, probe))
}

/// A hint's text and what it reads.
struct Program {
    kind: Kind,
    body: String,
    /// Behind a lock: the run's threads share the element, and the reader's drive context
    /// holds cells for element reads (which a hint does not use).
    drives: Mutex<Drives>,
    seq: usize,
}

impl Program {
    /// The hint's drive with the `model::` functions reading `now` (`_prev`: `before`).
    fn build(&self, now: Reads, before: Option<Reads>) -> Result<HintValue, String> {
        let drives = self.drives.lock().unwrap_or_else(|e| e.into_inner());
        let drives = &*drives;
        let mut sources = Sources::default();
        sources.files.push(("hint".into(), self.body.clone()));
        let tokens = tokenize(&self.body, 0, &sources).map_err(|e| e.message)?;
        let mut vars = drives.variables.clone();
        let args = arguments(&tokens, &mut vars, &sources, now, before)?;
        let end = tokens.last().map_or(Span::default(), |t| t.span);
        let st = Statement { keyword: "hint".into(), span: Span::default(), args, end, seq: self.seq, driven: None };
        let mut c = Cursor::new(&st, &sources);
        let value = match self.kind {
            Kind::Drive => HintValue::Drive(callers::drive(&mut c, drives, self.seq).map_err(|e| e.message)?),
            kind => {
                let v = VectorDrive(template_vec3(&mut c, drives, self.seq, &Mat3::identity(), &|c: &mut Cursor| c.vec3_values("hint vector")).map_err(|e| e.message)?);
                match kind {
                    Kind::Drive3 => HintValue::Drive3(v),
                    Kind::PositionDrive3 => HintValue::PositionDrive3(v),
                    _ => HintValue::OrientationDrive3(v),
                }
            }
        };
        c.finish().map_err(|e| e.message)?;
        Ok(value)
    }
}

/// The hint's arguments: split at top-level commas, each a phrase of names (a keyword) or
/// an expression evaluated now (as MBDyn's parser reads a hint's text when it applies it).
fn arguments(tokens: &[Spanned], vars: &mut Variables, sources: &Sources, now: Reads, before: Option<Reads>) -> Result<Vec<Arg>, String> {
    let mut pieces: Vec<&[Spanned]> = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (k, t) in tokens.iter().enumerate() {
        match t.token {
            Token::Symbol("(" | "[") => depth += 1,
            Token::Symbol(")" | "]") => depth -= 1,
            Token::Symbol(",") if depth <= 0 => {
                pieces.push(&tokens[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    pieces.push(&tokens[start..]);
    let mut args = Vec::with_capacity(pieces.len());
    for p in pieces {
        let text = p.iter().map(|t| t.token.text()).collect::<Vec<_>>().join(" ");
        let Some(first) = p.first() else {
            return Err("an empty argument".into());
        };
        let span = first.span;
        let lower = text.to_lowercase();
        let is_variable = matches!(&first.token, Token::Word(w) if vars.get(w).is_some());
        let phrase = matches!(first.token, Token::Word(_)) && p.iter().all(|t| matches!(t.token, Token::Word(_) | Token::Integer(_))) && !(p.len() == 1 && is_variable);
        if phrase {
            args.push(Arg { value: Value::Word(lower.clone()), span, keyword: Some(lower), text });
            continue;
        }
        let mut e = Evaluator::new(p, vars, sources, span).with_reads(now, None);
        if let Some(b) = before {
            e = e.with_previous(b);
        }
        let value = match e.evaluate().map_err(|e| e.message)? {
            TypedValue::Str(s) => Value::Str(s),
            v => Value::Number(v.real().unwrap_or(0.0)),
        };
        let keyword = (p.len() == 1 && matches!(first.token, Token::Word(_))).then(|| lower.clone());
        args.push(Arg { value, span, keyword, text });
    }
    Ok(args)
}
