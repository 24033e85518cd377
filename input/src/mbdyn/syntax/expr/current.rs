//! `model::current("NAME")` (modelns.cc, `model_curr`; input manual, "Elements", §Distance
//! and §Rod, "Current"): the data an element card publishes while part of it is read. MBDyn
//! pushes them (`DataManager::PushCurrData`) around that part only (joint.cc): a distance
//! joint publishes `"L"`, the distance between its two points as written, while it reads
//! its drive; a rod publishes `"L0"`, its length as input (or from nodes), and `"L"`, the
//! distance between its points, while it reads its constitutive law. Anywhere else MBDyn
//! stops ("model::current(NAME) not defined").
//!
//! romdyn evaluates a statement's arguments when it reads the statement, before the card's
//! reader knows its points: an argument of an element card that calls `model::current` is
//! kept as a [`Deferred`] expression, with the variables as they stand there, and evaluated
//! when the card's reader reads it as a number, with what that part of the card publishes
//! ([`crate::mbdyn::syntax::cursor::Cursor::publish`]).

use crate::mbdyn::syntax::diagnostic::{MbdynError, Sources, Span};
use crate::mbdyn::syntax::lexer::{Spanned, Token};
use super::{Evaluator, Variables};

/// An argument that calls `model::current`, evaluated when its card reads it.
#[derive(Clone, Debug)]
pub struct Deferred {
    tokens: Vec<Spanned>,
    end: Span,
    /// The variables where the argument is written (later `set:` do not change it).
    variables: Variables,
}

/// Two deferred arguments are equal when they are the same text at the same place.
impl PartialEq for Deferred {
    fn eq(&self, other: &Self) -> bool {
        self.tokens == other.tokens && self.end == other.end
    }
}

/// Whether the tokens of an argument call `model::current`.
pub fn reads_current(tokens: &[Spanned]) -> bool {
    tokens.windows(3).any(|w| matches!((&w[0].token, &w[1].token, &w[2].token), (Token::Word(m), Token::Symbol("::"), Token::Word(c)) if m == "model" && c == "current"))
}

impl Deferred {
    pub fn new(tokens: &[Spanned], end: Span, variables: &Variables) -> Self {
        Deferred { tokens: tokens.to_vec(), end, variables: variables.clone() }
    }

    /// Its value with `current` published (empty: nothing is, and `model::current` stops
    /// with MBDyn's message). An assignment inside it is refused: romdyn could not give the
    /// assigned value to the statements read after it, as MBDyn does.
    pub fn evaluate(&self, sources: &Sources, current: &[(&'static str, f64)]) -> Result<f64, MbdynError> {
        let mut vars = self.variables.clone();
        let at = self.tokens.first().map_or(self.end, |t| t.span);
        let v = Evaluator::new(&self.tokens, &mut vars, sources, self.end).with_current(current).evaluate()?;
        if vars.generation() != self.variables.generation() {
            return Err(sources.error(at, "an argument that reads model::current cannot declare or assign variables in romdyn (write the assignment in a 'set:' statement)"));
        }
        v.real().ok_or_else(|| sources.error(at, "expected a number, found a string"))
    }
}
