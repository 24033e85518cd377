//! `scalar function: "NAME", [TYPE,] ARGS;` cards (input manual, §Scalar functions;
//! ScalarFunctionsImpl.cc, the `…SFR::Read` readers): `const` (the default), `exp`, `log`,
//! `pow`, `linear`, `cubic spline`, `multilinear`, `chebychev`, `sum`, `sub`, `mul`, `div`.

use std::sync::Arc;

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Span};
use crate::element::drive::{EvaluationCost, ScalarFunction};

pub use crate::mbdyn::syntax::card_tables::{FunctionsBefore, ScalarFunctions};
use crate::mbdyn::syntax::parser;

impl ScalarFunctions {
    /// The function `name` as defined before statement `seq`.
    pub fn get(&self, c: &Cursor, span: Span, name: &str, seq: usize) -> Result<Arc<ScalarFunction>, MbdynError> {
        match self.card(name) {
            Some((f, s, _, _)) if s < seq => {
                self.note_used(name);
                Ok(f)
            }
            Some((_, _, at, _)) => Err(c.error_at(span, format!("scalar function \"{name}\" is used before its definition (line {})", at.line))),
            None => Err(c.error_at(span, format!("scalar function \"{name}\" is not defined"))),
        }
    }
}

/// Errors at `span` when `f` costs more than romdyn's budget (see [`EvaluationCost`]).
fn within_budget(c: &Cursor, span: Span, name: &str, f: &ScalarFunction, functions: &ScalarFunctions) -> Result<EvaluationCost, MbdynError> {
    let cost = f.cost_with(&|g| functions.known_cost(g));
    if cost.over_budget("").is_none() {
        return Ok(cost);
    }
    Err(c.error_at(span, cost.over_budget(&format!("scalar function \"{name}\"")).unwrap_or_default()))
}

const TYPES: [&str; 12] = ["const", "exp", "log", "pow", "linear", "multilinear", "chebychev", "sum", "sub", "mul", "div", "cubic spline"];

/// Reads a `scalar function:` card at statement `seq`.
pub fn scalar_function_card(c: &mut Cursor, functions: &mut ScalarFunctions, seq: usize) -> Result<(), MbdynError> {
    let span = c.here();
    let name = c.string("the scalar function's name")?;
    if let Some((_, _, at, _)) = functions.card(&name) {
        return Err(c.error_at(span, format!("scalar function \"{name}\" is defined twice (first at line {})", at.line)));
    }
    let before = functions.take_used();
    let f = definition(c, functions, seq)?;
    c.finish()?;
    let cost = within_budget(c, span, &name, &f, functions)?;
    // Its operands are named from its function when a message needs them.
    functions.take_used();
    before.iter().for_each(|n| functions.note_used(n));
    functions.define(name, (Arc::new(f), seq, c.statement().span, cost));
    Ok(())
}

/// `"NAME"` of a defined function, or an inline `"NAME", TYPE, ARGS` definition (the
/// `scalar function` drive caller and constitutive laws).
/// The function is a shallow copy: its operands stay shared.
pub fn scalar_function(c: &mut Cursor, functions: &ScalarFunctions, seq: usize) -> Result<ScalarFunction, MbdynError> {
    let span = c.here();
    let name = c.string("the scalar function's name")?;
    if c.peek_keyword().is_some_and(|w| TYPES.iter().any(|t| parser::same_keyword(t, w))) {
        let f = definition(c, functions, seq)?;
        within_budget(c, span, &name, &f, functions)?;
        return Ok(f);
    }
    functions.get(c, span, &name, seq).map(|f| (*f).clone())
}

fn definition(c: &mut Cursor, functions: &ScalarFunctions, seq: usize) -> Result<ScalarFunction, MbdynError> {
    let span = c.here();
    let kind = c.accept_any(&TYPES).unwrap_or("const");
    let optional = |c: &mut Cursor, kw: &str, default: f64| -> Result<f64, MbdynError> { if c.accept(kw) { c.real(kw) } else { Ok(default) } };
    let positive = |c: &mut Cursor, x: f64, what: &str| if x > 0.0 { Ok(x) } else { Err(c.error_at(span, format!("{kind} scalar function: the {what} must be positive, found {x}"))) };
    let points = |c: &mut Cursor, min: usize| -> Result<Vec<(f64, f64)>, MbdynError> {
        let mut p = Vec::new();
        while p.len() < min || (!c.is_done() && !c.accept("end")) {
            p.push((c.real("x of a point")?, c.real("y of a point")?));
        }
        if let Some(w) = p.windows(2).find(|w| !(w[0].0 < w[1].0)) {
            return Err(c.error_at(span, format!("{kind} scalar function: the x values must increase, found {} then {}", w[0].0, w[1].0)));
        }
        Ok(p)
    };
    Ok(match kind {
        "const" => ScalarFunction::Const(c.real("the constant value")?),
        "exp" | "log" => {
            let base = optional(c, "base", std::f64::consts::E)?;
            let base = positive(c, base, "base")?;
            let coefficient = optional(c, "coefficient", 1.0)?;
            let multiplier = c.real("the multiplier")?;
            if kind == "exp" { ScalarFunction::Exp { multiplier, base, coefficient } } else { ScalarFunction::Log { multiplier, base, coefficient } }
        }
        "pow" => ScalarFunction::Pow(c.real("the exponent")?),
        "linear" => {
            // The line through two points with different x, in either order.
            let mut p = [(c.real("x of the first point")?, c.real("y of the first point")?), (c.real("x of the second point")?, c.real("y of the second point")?)];
            if !(p[0].0 != p[1].0 && (p[1].0 - p[0].0).is_finite()) {
                return Err(c.error_at(span, format!("linear scalar function: the two points need different x, found {} and {}", p[0].0, p[1].0)));
            }
            p.sort_by(|a, b| a.0.total_cmp(&b.0));
            ScalarFunction::Multilinear { points: p.to_vec(), extrapolate: true }
        }
        "multilinear" => {
            let extrapolate = !c.accept("do not extrapolate");
            ScalarFunction::Multilinear { points: points(c, 2)?, extrapolate }
        }
        "chebychev" => {
            let (a, b) = (c.real("the lower bound")?, c.real("the upper bound")?);
            if !(a < b) {
                return Err(c.error_at(span, format!("chebychev scalar function: the lower bound {a} must be below the upper bound {b}")));
            }
            let extrapolate = !c.accept("do not extrapolate");
            let mut coefficients = vec![c.real("coefficient 0")?];
            while !c.is_done() && !c.accept("end") {
                coefficients.push(c.real("a coefficient")?);
            }
            ScalarFunction::Chebychev { a, b, coefficients, extrapolate }
        }
        "cubic spline" => {
            let extrapolate = !c.accept("do not extrapolate");
            ScalarFunction::cubic_spline(points(c, 3)?, extrapolate)
        }
        _ => {
            let operand = |c: &mut Cursor| -> Result<Arc<ScalarFunction>, MbdynError> {
                let at = c.here();
                let name = c.string("the name of a scalar function")?;
                functions.get(c, at, &name, seq + 1)
            };
            let (f, g) = (operand(c)?, operand(c)?);
            match kind {
                "sum" => ScalarFunction::Sum(f, g),
                "sub" => ScalarFunction::Sub(f, g),
                "mul" => ScalarFunction::Mul(f, g),
                _ => ScalarFunction::Div(f, g),
            }
        }
    })
}
