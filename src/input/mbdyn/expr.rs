//! Arithmetic expressions over `set:` variables: `+ - * / ^`, unary minus, parentheses,
//! functions (sin, cos, tan, asin, acos, atan, atan2, sqrt, exp, log, abs, sinh, cosh,
//! tanh, ceil, floor) and the constants `pi` and `e`.

use std::collections::HashMap;

use super::diagnostic::{MbdynError, Sources, Span};
use super::lexer::{Spanned, Token};

/// A `set:` variable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Variable {
    pub value: f64,
    pub integer: bool,
    pub constant: bool,
}

/// Variables defined so far, with the predefined constants.
#[derive(Clone, Debug)]
pub struct Variables(pub HashMap<String, Variable>);

impl Default for Variables {
    fn default() -> Self {
        let c = |value| Variable { value, integer: false, constant: true };
        Variables(HashMap::from([("pi".to_string(), c(std::f64::consts::PI)), ("e".to_string(), c(std::f64::consts::E))]))
    }
}

const FUNCTIONS: [&str; 16] = ["sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "exp", "log", "abs", "sinh", "cosh", "tanh", "ceil", "floor"];

/// Whether a word names a function or a variable (so the word starts an expression).
pub fn is_expression_word(w: &str, vars: &Variables) -> bool {
    FUNCTIONS.contains(&w) || vars.0.contains_key(w)
}

/// Recursive-descent evaluator over a token slice.
pub struct Evaluator<'a> {
    tokens: &'a [Spanned],
    pos: usize,
    vars: &'a Variables,
    sources: &'a Sources,
    end: Span,
}

impl<'a> Evaluator<'a> {
    pub fn new(tokens: &'a [Spanned], vars: &'a Variables, sources: &'a Sources, end: Span) -> Self {
        Evaluator { tokens, pos: 0, vars, sources, end }
    }

    fn span(&self) -> Span {
        self.tokens.get(self.pos).map_or(self.end, |t| t.span)
    }

    fn err(&self, span: Span, m: impl Into<String>) -> MbdynError {
        self.sources.error(span, m)
    }

    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.pos).map(|t| &t.token)
    }

    /// Evaluates the whole slice as one expression.
    pub fn evaluate(mut self) -> Result<f64, MbdynError> {
        let v = self.sum()?;
        if self.pos < self.tokens.len() {
            return Err(self.err(self.span(), "expected an operator or ',' after this expression"));
        }
        Ok(v)
    }

    fn sum(&mut self) -> Result<f64, MbdynError> {
        let mut v = self.product()?;
        while let Some(Token::Punct(op @ ('+' | '-'))) = self.peek().cloned() {
            self.pos += 1;
            let r = self.product()?;
            v = if op == '+' { v + r } else { v - r };
        }
        Ok(v)
    }

    fn product(&mut self) -> Result<f64, MbdynError> {
        let mut v = self.unary()?;
        while let Some(Token::Punct(op @ ('*' | '/'))) = self.peek().cloned() {
            let span = self.span();
            self.pos += 1;
            let r = self.unary()?;
            if op == '/' && r == 0.0 {
                return Err(self.err(span, "division by zero"));
            }
            v = if op == '*' { v * r } else { v / r };
        }
        Ok(v)
    }

    fn unary(&mut self) -> Result<f64, MbdynError> {
        match self.peek() {
            Some(Token::Punct('-')) => {
                self.pos += 1;
                Ok(-self.unary()?)
            }
            Some(Token::Punct('+')) => {
                self.pos += 1;
                self.unary()
            }
            _ => self.power(),
        }
    }

    fn power(&mut self) -> Result<f64, MbdynError> {
        let base = self.primary()?;
        if let Some(Token::Punct('^')) = self.peek() {
            self.pos += 1;
            let exp = self.unary()?;
            return Ok(base.powf(exp));
        }
        Ok(base)
    }

    fn primary(&mut self) -> Result<f64, MbdynError> {
        let span = self.span();
        let Some(tok) = self.tokens.get(self.pos) else {
            return Err(self.err(span, "expected a number, a variable or '('"));
        };
        self.pos += 1;
        match &tok.token {
            Token::Number(x) => Ok(*x),
            Token::Punct('(') => {
                let v = self.sum()?;
                match self.peek() {
                    Some(Token::Punct(')')) => {
                        self.pos += 1;
                        Ok(v)
                    }
                    _ => Err(self.err(span, "unbalanced parenthesis: expected ')' to close this '('")),
                }
            }
            Token::Word(w) if FUNCTIONS.contains(&w.as_str()) => self.call(w, span),
            Token::Word(w) => self.vars.0.get(w.as_str()).map(|v| v.value).ok_or_else(|| self.err(span, format!("undefined variable '{w}'"))),
            other => Err(self.err(span, format!("expected a number, a variable or '(', found {}", describe(other)))),
        }
    }

    fn call(&mut self, name: &str, span: Span) -> Result<f64, MbdynError> {
        if self.peek() != Some(&Token::Punct('(')) {
            return Err(self.err(span, format!("expected '(' after function '{name}'")));
        }
        self.pos += 1;
        let mut args = vec![self.sum()?];
        while self.peek() == Some(&Token::Punct(',')) {
            self.pos += 1;
            args.push(self.sum()?);
        }
        if self.peek() != Some(&Token::Punct(')')) {
            return Err(self.err(span, format!("unbalanced parenthesis in the call of '{name}': expected ')'")));
        }
        self.pos += 1;
        let want = if name == "atan2" { 2 } else { 1 };
        if args.len() != want {
            return Err(self.err(span, format!("'{name}' takes {want} argument(s), found {}", args.len())));
        }
        let x = args[0];
        let domain = |ok: bool, what: &str| if ok { Ok(()) } else { Err(self.err(span, format!("{name}({x}): argument out of domain ({what})"))) };
        let v = match name {
            "sin" => x.sin(),
            "cos" => x.cos(),
            "tan" => x.tan(),
            "asin" | "acos" => {
                domain(x.abs() <= 1.0, "|x| must not exceed 1")?;
                if name == "asin" { x.asin() } else { x.acos() }
            }
            "atan" => x.atan(),
            "atan2" => x.atan2(args[1]),
            "sqrt" => {
                domain(x >= 0.0, "x must not be negative")?;
                x.sqrt()
            }
            "exp" => x.exp(),
            "log" => {
                domain(x > 0.0, "x must be positive")?;
                x.ln()
            }
            "abs" => x.abs(),
            "sinh" => x.sinh(),
            "cosh" => x.cosh(),
            "tanh" => x.tanh(),
            "ceil" => x.ceil(),
            _ => x.floor(),
        };
        Ok(v)
    }
}

/// "',' ", "the word 'x'", … for messages.
pub fn describe(t: &Token) -> String {
    match t {
        Token::Number(x) => format!("the number {x}"),
        Token::Word(w) => format!("the word '{w}'"),
        Token::Str(s) => format!("the string \"{s}\""),
        Token::Punct(c) => format!("'{c}'"),
    }
}
