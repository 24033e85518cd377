//! Expressions of MBDyn's math parser as MBDyn 1.7.3 evaluates them (libmbutil/mathp.cc,
//! checked by running it; its input manual's operator table says otherwise): unary `- + !`
//! bind to the operand that follows (`-2^2` = 4, `!1 > 2` = 0), then `^` (right
//! associative; integer powers by products, a negative integer exponent giving 0, a negative
//! base with an exponent ≤ 0 refused), `* / %`, `+ -`, comparisons, and `&&`, `||`, `~|`
//! (xor) at one level from left to right (`1 || 0 && 0` = 0); declarations `[ifndef] [const] TYPE NAME [= EXPR]`,
//! assignments `NAME = EXPR`, and statement lists `(S1; S2; …)` whose value is the last
//! one. Expressions are evaluated as they are read, so later `set:` statements do not
//! change earlier values.

mod current;
pub mod element_calls;
mod model_calls;

pub use current::{reads_current, Deferred};

use std::collections::{BTreeMap, HashMap};

use super::diagnostic::{MbdynError, Sources, Span};
use super::functions::{call, constants, is_function, FUNCTIONS, UNSUPPORTED_FUNCTIONS};
use super::lexer::{Spanned, Token};
pub use super::model_namespace::Reads;
use super::value::{Type, TypedValue};

/// A variable of the math parser.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    pub value: TypedValue,
    pub constant: bool,
    /// Where it was declared (`None` for the predefined constants).
    pub declared: Option<Span>,
}

/// The symbol table: predefined constants plus everything declared so far.
///
/// Two layers: a shared, read-only base (an `Arc`, see [`Variables::shared`]) and the
/// variables declared or assigned on top of it. A `string` drive evaluates on its own
/// copy (it sets `Time` and `Var`, and its statements may assign), and a copy of a
/// shared table costs O(1), not O(variables): a file of N drives and N `set:` cards reads
/// in O(N), not O(N²) (issue 32). `generation` counts the changes, so that "have the
/// variables changed since" costs O(1) too.
#[derive(Clone, Debug)]
pub struct Variables {
    base: std::sync::Arc<HashMap<String, Variable>>,
    own: HashMap<String, Variable>,
    generation: u64,
}

impl Default for Variables {
    fn default() -> Self {
        let own = constants().into_iter().map(|(n, value)| (n.to_string(), Variable { value, constant: true, declared: None })).collect();
        Variables { base: Default::default(), own, generation: 0 }
    }
}

impl Variables {
    pub fn get(&self, name: &str) -> Option<&Variable> {
        self.own.get(name).or_else(|| self.base.get(name))
    }
    /// Declares `name` (or replaces its value).
    pub fn insert(&mut self, name: String, var: Variable) {
        self.generation += 1;
        self.own.insert(name, var);
    }
    /// Assigns a value to a declared variable (nothing if `name` is not one).
    pub fn set_value(&mut self, name: &str, value: TypedValue) {
        if let Some(v) = self.own.get_mut(name) {
            v.value = value;
        } else if let Some(v) = self.base.get(name) {
            let var = Variable { value, ..v.clone() };
            self.own.insert(name.to_string(), var);
        } else {
            return;
        }
        self.generation += 1;
    }
    /// Counts the changes made to this table (to tell cheaply whether it changed).
    pub fn generation(&self) -> u64 {
        self.generation
    }
    /// Every variable, by name (those declared on top of the base hide the base's).
    pub fn iter(&self) -> impl Iterator<Item = (&String, &Variable)> {
        self.own.iter().chain(self.base.iter().filter(|(n, _)| !self.own.contains_key(*n)))
    }
    /// The same variables as a shared base: its clones cost O(1) (one O(variables) copy
    /// here, when the table has its own variables).
    pub fn shared(&self) -> Variables {
        if self.own.is_empty() {
            return Variables { base: self.base.clone(), own: HashMap::new(), generation: self.generation };
        }
        let all: HashMap<String, Variable> = self.iter().map(|(n, v)| (n.clone(), v.clone())).collect();
        Variables { base: std::sync::Arc::new(all), own: HashMap::new(), generation: self.generation }
    }
    /// Errors (about the whole `file`) unless every name is a variable the file declares with
    /// `set:` (a swept or overridden name).
    pub fn check_declared<'n>(&self, names: impl IntoIterator<Item = &'n String>, file: &std::path::Path) -> Result<(), MbdynError> {
        for name in names {
            if self.get(name).is_none_or(|v| v.declared.is_none()) {
                let mut declared: Vec<&str> = self.iter().filter(|(_, v)| v.declared.is_some()).map(|(n, _)| n.as_str()).collect();
                declared.sort_unstable();
                let list = if declared.is_empty() { "none".to_string() } else { declared.join(", ") };
                let message = format!("--set {name}: the file declares no variable '{name}' with 'set:' (its variables: {list})");
                return Err(MbdynError { file: file.to_path_buf(), line: 0, column: 0, message, source_line: String::new() });
            }
        }
        Ok(())
    }

    /// The numeric value of a variable (`None` if undefined or a string).
    pub fn real(&self, name: &str) -> Option<f64> {
        self.get(name).and_then(|v| v.value.real())
    }
}

/// Values that replace what the file's `set:` statements give some variables (a design
/// point of a sweep, `--set NAME=VALUE`): an overridden variable holds its override from its
/// declaration on, whatever the file assigns it (the override is cast to the variable's type;
/// an integer or bool variable needs an integer value).
pub type SetOverrides = BTreeMap<String, f64>;

/// Nesting of parentheses, unary operators and `!` romdyn follows (each level costs a few
/// stack frames; real files nest a handful).
const MAX_DEPTH: usize = 100;

/// Nesting levels of all the evaluators running on a thread (a string drive's
/// `model::drive` call evaluates another drive's expression inside this one's): their
/// stack adds up, so their levels count together (see [`Evaluator::enter`]). A level with
/// its drive call takes about 5 KB of stack: 64 chained string drives of 7 levels each
/// overflowed the 2 MiB stack of a sweep's worker thread before 400 levels, 320 ran.
const MAX_NESTED_DEPTH: usize = 2 * MAX_DEPTH;

thread_local! {
    static NESTED_DEPTH: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Recursive-descent evaluator over one expression's tokens.
pub struct Evaluator<'a> {
    tokens: &'a [Spanned],
    pos: usize,
    vars: &'a mut Variables,
    sources: &'a Sources,
    end: Span,
    depth: usize,
    overrides: Option<&'a SetOverrides>,
    /// The scalar functions `model::sf::NAME(x)` calls (string drives; `None` while the file is
    /// read, where `set:` runs before the `scalar function:` cards are read).
    functions: Option<&'a super::card_tables::FunctionsBefore>,
    /// What `model::` state functions read (`None`: they are refused).
    reads: Option<Reads<'a>>,
    /// The element state a string drive is evaluated in, passed on to `model::drive`.
    state: Option<&'a dyn crate::element::ElementState>,
    /// The `drive caller:` cards `model::drive(LABEL, x)` calls.
    drives: Option<&'a super::card_tables::DrivesBefore>,
    /// A check before any state exists: out-of-domain arguments of built-in functions give
    /// NaN instead of an error (the placeholder values of the reads cause them).
    lenient: bool,
    /// What `model::…_prev` functions read (the previous step's state, in a hint).
    previous: Option<Reads<'a>>,
    /// The data the element card being read publishes to `model::current("NAME")`
    /// (MBDyn's `DataManager::PushCurrData`: a distance's drive, a rod's law); empty
    /// elsewhere.
    current: &'a [(&'static str, f64)],
    /// The elements `model::element::TYPE(LABEL, "NAME")` reads (`None` outside the reading
    /// of the file: refused).
    elements: Option<&'a super::model_namespace::ElementsRead>,
    /// What `model::element::…` reads in a string drive (its check, or the run).
    run_elements: Option<element_calls::RunElements<'a>>,
}

impl<'a> Evaluator<'a> {
    pub fn new(tokens: &'a [Spanned], vars: &'a mut Variables, sources: &'a Sources, end: Span) -> Self {
        Evaluator { tokens, pos: 0, vars, sources, end, depth: 0, overrides: None, functions: None, reads: None, state: None, drives: None, lenient: false, previous: None, current: &[], elements: None, run_elements: None }
    }

    /// Makes the `model::` state functions read `reads`; `state` is the element state of a
    /// string drive's evaluation (`None` while the file is read). A check (`Reads::Labels`)
    /// is lenient with the domains of built-in functions.
    pub fn with_reads(mut self, reads: Reads<'a>, state: Option<&'a dyn crate::element::ElementState>) -> Self {
        self.lenient = matches!(reads, Reads::Labels(_));
        self.reads = Some(reads);
        self.state = state;
        self
    }

    /// Makes the `model::…_prev` functions read `previous` (a hint's drive, parsed when a
    /// driven element switches on: the previous step's state).
    pub fn with_previous(mut self, previous: Reads<'a>) -> Self {
        self.previous = Some(previous);
        self
    }

    /// Makes `model::current("NAME")` read `current` (what the element card being read
    /// publishes, see [`Deferred`]).
    pub fn with_current(mut self, current: &'a [(&'static str, f64)]) -> Self {
        self.current = current;
        self
    }

    /// Makes `model::element::TYPE(LABEL, "NAME")` read these elements (while the file is
    /// read).
    pub fn with_elements(mut self, elements: &'a super::model_namespace::ElementsRead) -> Self {
        self.elements = Some(elements);
        self
    }

    /// Makes `model::element::TYPE(LABEL, "NAME")` note or read the elements' private data
    /// of a string drive (see [`element_calls::RunElements`]).
    pub fn with_run_elements(mut self, run: element_calls::RunElements<'a>) -> Self {
        self.run_elements = Some(run);
        self
    }

    /// Makes `model::drive(LABEL, x)` call these drive callers.
    pub fn with_drives(mut self, drives: &'a super::card_tables::DrivesBefore) -> Self {
        self.drives = Some(drives);
        self
    }

    /// Makes `model::sf::NAME(x)` call these scalar functions (modelns.cc: the
    /// `scalar function:` cards, the only part of the `model` namespace without run-time
    /// state).
    pub fn with_functions(mut self, functions: &'a super::card_tables::FunctionsBefore) -> Self {
        self.functions = Some(functions);
        self
    }

    /// Declarations and assignments of these variables take the override's value (a `set:`
    /// statement of a design point).
    pub fn with_overrides(mut self, overrides: &'a SetOverrides) -> Self {
        self.overrides = Some(overrides);
        self
    }

    /// The value a declaration or an assignment of `name` stores: the override when there is
    /// one (checked against the variable's type), else `value`.
    fn overridden(&self, name: &str, ty: Type, span: Span, value: TypedValue) -> Result<TypedValue, MbdynError> {
        let Some(&x) = self.overrides.and_then(|o| o.get(name)) else { return Ok(value) };
        let exact = match ty {
            Type::Real => true,
            Type::Integer | Type::Bool => x.fract() == 0.0 && x.abs() < 9.0e15,
            Type::String => false,
        };
        if !exact {
            return Err(self.err(span, format!("--set {name}={x}: '{name}' is declared {} here, the value must be {}", ty.name(), if ty == Type::String { "given in the file (strings cannot be overridden)" } else { "a whole number" })));
        }
        TypedValue::Real(x).cast(ty).map_err(self.at(span))
    }

    /// Evaluates all the tokens as one statement list.
    pub fn evaluate(mut self) -> Result<TypedValue, MbdynError> {
        let v = self.statements()?;
        if let Some(t) = self.tokens.get(self.pos) {
            let what = if t.token == Token::Symbol(")") { "unbalanced parenthesis: this ')' closes nothing".to_string() } else { format!("expected an operator or the end of the value, found {}", describe(&t.token)) };
            return Err(self.sources.error(t.span, what));
        }
        Ok(v)
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
    fn peek_at(&self, k: usize) -> Option<&Token> {
        self.tokens.get(self.pos + k).map(|t| &t.token)
    }
    fn symbol(&self) -> Option<&'static str> {
        match self.peek() {
            Some(Token::Symbol(s)) => Some(s),
            _ => None,
        }
    }
    fn eat(&mut self, sym: &str) -> bool {
        if self.symbol() == Some(sym) {
            self.pos += 1;
            true
        } else {
            false
        }
    }
    /// One level deeper: at most [`MAX_DEPTH`] in this expression, and
    /// [`MAX_NESTED_DEPTH`] with those of the expressions that called it.
    fn enter(&mut self) -> Result<(), MbdynError> {
        self.depth += 1;
        let nested = NESTED_DEPTH.with(|d| {
            d.set(d.get() + 1);
            d.get()
        });
        if self.depth > MAX_DEPTH {
            return Err(self.err(self.span(), format!("expression nested more than {MAX_DEPTH} levels deep")));
        }
        if nested > MAX_NESTED_DEPTH {
            return Err(self.err(self.span(), format!("expressions nested more than {MAX_NESTED_DEPTH} levels deep, counting those of the string drives that call this one through model::drive")));
        }
        Ok(())
    }
    fn leave(&mut self) {
        self.depth -= 1;
        NESTED_DEPTH.with(|d| d.set(d.get().saturating_sub(1)));
    }
    fn at(&self, span: Span) -> impl Fn(String) -> MbdynError + '_ {
        move |m| self.sources.error(span, m)
    }

    fn statements(&mut self) -> Result<TypedValue, MbdynError> {
        self.enter()?;
        let mut v = self.statement()?;
        while self.eat(";") {
            v = self.statement()?;
        }
        self.leave();
        Ok(v)
    }

    fn word(&self, k: usize) -> Option<&str> {
        match self.peek_at(k) {
            Some(Token::Word(w)) => Some(w),
            _ => None,
        }
    }

    /// A declaration, an assignment, or an expression.
    fn statement(&mut self) -> Result<TypedValue, MbdynError> {
        let start = self.span();
        let mut k = 0;
        let ifndef = self.word(k) == Some("ifndef");
        k += usize::from(ifndef);
        let constant = self.word(k) == Some("const");
        k += usize::from(constant);
        let ty = self.word(k).and_then(Type::from_name);
        if let Some(ty) = ty.filter(|_| self.peek_at(k + 1) != Some(&Token::Symbol("("))) {
            self.pos += k + 1;
            return self.declaration(ty, constant, ifndef);
        }
        if ifndef || constant {
            return Err(self.err(start, format!("expected a type (bool, integer, real or string) after '{}'", if constant { "const" } else { "ifndef" })));
        }
        if let (Some(name), Some(Token::Symbol("="))) = (self.word(0).map(str::to_string), self.peek_at(1)) {
            self.pos += 2;
            let value = self.logical()?;
            return self.assign(&name, start, value);
        }
        self.logical()
    }

    fn declaration(&mut self, ty: Type, constant: bool, ifndef: bool) -> Result<TypedValue, MbdynError> {
        let span = self.span();
        let Some(name) = self.word(0).map(str::to_string) else {
            return Err(self.err(span, format!("expected a variable name after '{}'", ty.name())));
        };
        if is_function(&name) || Type::from_name(&name).is_some() || ["const", "ifndef"].contains(&name.as_str()) {
            return Err(self.err(span, format!("'{name}' is a keyword of the math parser and cannot name a variable")));
        }
        self.pos += 1;
        let value = if self.eat("=") {
            Some(self.logical()?)
        } else if constant {
            return Err(self.err(span, format!("constant '{name}' needs a value: 'const {} {name} = …'", ty.name())));
        } else {
            None
        };
        if let Some(old) = self.vars.get(&name) {
            if ifndef {
                return Ok(old.value.clone());
            }
            let line = old.declared.map_or("predefined".to_string(), |s| format!("declared at line {}", s.line));
            return Err(self.err(span, if old.constant {
                format!("'{name}' is a constant ({line}) and cannot be declared again")
            } else {
                format!("variable '{name}' is already declared ({line}): assign it with 'set: {name} = …;' or declare it with 'ifndef'")
            }));
        }
        let value = match value {
            Some(v) => v.cast(ty).map_err(self.at(span))?,
            None => ty.zero(),
        };
        let value = self.overridden(&name, ty, span, value)?;
        self.vars.insert(name, super::expr::Variable { value: value.clone(), constant, declared: Some(span) });
        Ok(value)
    }

    fn assign(&mut self, name: &str, span: Span, value: TypedValue) -> Result<TypedValue, MbdynError> {
        let ty = match self.vars.get(name) {
            None => return Err(self.err(span, format!("undefined variable '{name}': declare it first, e.g. 'set: real {name} = …;'"))),
            Some(var) if var.constant => return Err(self.sources.error(span, format!("'{name}' is a constant and cannot be assigned"))),
            Some(var) => var.value.type_of(),
        };
        let value = value.cast(ty).map_err(|m| self.sources.error(span, m))?;
        let value = self.overridden(name, ty, span, value)?;
        self.vars.set_value(name, value.clone());
        Ok(value)
    }

    /// `&&`, `||` and `~|`, one level, left to right (mathp.cc `logical_int`).
    fn logical(&mut self) -> Result<TypedValue, MbdynError> {
        let mut v = self.relational()?;
        while let Some(op @ ("~|" | "||" | "&&")) = self.symbol() {
            let span = self.span();
            self.pos += 1;
            let r = self.relational()?;
            let (a, b) = (v.truth().map_err(self.at(span))?, r.truth().map_err(self.at(span))?);
            v = TypedValue::Bool(match op {
                "~|" => a != b,
                "||" => a || b,
                _ => a && b,
            });
        }
        Ok(v)
    }

    fn relational(&mut self) -> Result<TypedValue, MbdynError> {
        let mut v = self.sum()?;
        while let Some(op @ (">" | ">=" | "==" | "<=" | "<" | "!=")) = self.symbol() {
            let span = self.span();
            self.pos += 1;
            let r = self.sum()?;
            v = v.compare(op, &r).map_err(self.at(span))?;
        }
        Ok(v)
    }

    fn sum(&mut self) -> Result<TypedValue, MbdynError> {
        let mut v = self.product()?;
        while let Some(op @ ("+" | "-")) = self.symbol() {
            let span = self.span();
            self.pos += 1;
            let r = self.product()?;
            v = v.arithmetic(op, &r).map_err(self.at(span))?;
        }
        Ok(v)
    }

    fn product(&mut self) -> Result<TypedValue, MbdynError> {
        let mut v = self.power()?;
        while let Some(op @ ("*" | "/" | "%")) = self.symbol() {
            let span = self.span();
            self.pos += 1;
            let r = self.power()?;
            v = v.arithmetic(op, &r).map_err(self.at(span))?;
        }
        Ok(v)
    }

    /// `UNARY [^ POWER]`: right associative, its base the unary operand (`-2^2` = 4).
    fn power(&mut self) -> Result<TypedValue, MbdynError> {
        let base = self.unary()?;
        if self.symbol() == Some("^") {
            let span = self.span();
            self.pos += 1;
            self.enter()?;
            let exponent = self.power()?;
            self.leave();
            return base.power(&exponent).map_err(self.at(span));
        }
        Ok(base)
    }

    /// `- + !` applied to the operand that follows (mathp.cc `unary`: `-expr()`), before any
    /// `^`. romdyn also takes a chain of them (`--x`), which MBDyn refuses.
    fn unary(&mut self) -> Result<TypedValue, MbdynError> {
        let span = self.span();
        if let Some(op @ ("-" | "+" | "!")) = self.symbol() {
            self.pos += 1;
            self.enter()?;
            let v = self.unary()?;
            self.leave();
            return match op {
                "-" => v.negate().map_err(self.at(span)),
                "!" => Ok(TypedValue::Bool(!v.truth().map_err(self.at(span))?)),
                _ => Ok(v),
            };
        }
        self.primary()
    }

    fn primary(&mut self) -> Result<TypedValue, MbdynError> {
        let span = self.span();
        let Some(tok) = self.tokens.get(self.pos) else {
            return Err(self.err(span, "expected a value (a number, a variable, a function call or '(')"));
        };
        self.pos += 1;
        match &tok.token {
            Token::Integer(i) => Ok(TypedValue::Int(*i)),
            Token::Real(x) => Ok(TypedValue::Real(*x)),
            Token::Str(s) => Ok(TypedValue::Str(s.clone())),
            Token::Symbol("(") => {
                let v = self.statements()?;
                if !self.eat(")") {
                    return Err(self.err(span, "unbalanced parenthesis: expected ')' to close this '('"));
                }
                Ok(v)
            }
            Token::Symbol("[") => Err(self.err(span, "plugin variables ('[node, …]', '[element, …]', '[dof, …]') read run-time values and are not supported by romdyn (MBDyn 1.7.3 runs them)")),
            Token::Word(w) => {
                let mut name = w.clone();
                if self.eat("::") {
                    match (name.as_str(), self.word(0).map(str::to_string)) {
                        ("default", Some(f)) => {
                            self.pos += 1;
                            name = f;
                        }
                        ("model", Some(sf)) if sf == "sf" && self.tokens.get(self.pos + 1).is_some_and(|t| t.token == Token::Symbol("::")) => {
                            // modelns.cc: `model::sf::NAME(x [, order])`, a scalar function
                            // card's value (order 0) or derivative (order 1); no run-time state.
                            self.pos += 2;
                            let Some(f) = self.word(0).map(str::to_string) else {
                                return Err(self.err(span, "model::sf:: expects a scalar function's name"));
                            };
                            self.pos += 1;
                            return self.scalar_function(&f, span);
                        }
                        ("model", Some(f)) => {
                            self.pos += 1;
                            return self.model_function(&f, span);
                        }
                        ("model", None) => return Err(self.err(span, "model:: expects a function name")),
                        (ns, _) => return Err(self.err(span, format!("unknown namespace '{ns}' (romdyn knows 'default' and 'model')"))),
                    }
                }
                if self.symbol() == Some("(") {
                    return self.call(&name, span);
                }
                match self.vars.get(&name) {
                    Some(v) => Ok(v.value.clone()),
                    None => Err(self.err(span, format!("undefined variable '{name}'"))),
                }
            }
            other => Err(self.err(span, format!("expected a value (a number, a variable, a function call or '('), found {}", describe(other)))),
        }
    }

    /// The arguments of a call whose '(' is next, as values.
    fn arguments(&mut self, what: &str, span: Span) -> Result<Vec<TypedValue>, MbdynError> {
        if !self.eat("(") {
            return Err(self.err(span, format!("{what}: expected '(' and the arguments")));
        }
        let mut args = Vec::new();
        if self.eat(")") {
            return Ok(args);
        }
        loop {
            args.push(self.statements()?);
            if self.eat(",") {
                continue;
            }
            if self.eat(")") {
                return Ok(args);
            }
            return Err(self.err(span, format!("unbalanced parenthesis in the call of '{what}': expected ',' or ')'")));
        }
    }

    fn call(&mut self, name: &str, span: Span) -> Result<TypedValue, MbdynError> {
        self.pos += 1;
        let mut args = Vec::new();
        if !self.eat(")") {
            loop {
                args.push(self.statements()?);
                if self.eat(",") {
                    continue;
                }
                if self.eat(")") {
                    break;
                }
                return Err(self.err(span, format!("unbalanced parenthesis in the call of '{name}': expected ',' or ')'")));
            }
        }
        // `bool_eval(x)`, `integer_eval`, `real_eval`, `string_eval` (mathp.cc of MBDyn's
        // development version, `mp_eval`; not in 1.7.3): the cast of x, computed when the
        // expression is read. Here every expression is evaluated as it is read, so it is
        // the cast; a string drive's text is staticized when its card is read
        // ([`staticize_evals`]).
        if let Some(ty) = eval_type(name).or_else(|| Type::from_name(name)) {
            if args.len() != 1 {
                return Err(self.err(span, format!("the cast '{name}(…)' takes 1 argument, found {}", args.len())));
            }
            return args[0].cast(ty).map_err(self.at(span));
        }
        if UNSUPPORTED_FUNCTIONS.contains(&name) {
            return Err(self.err(span, format!("function '{name}' is not supported by romdyn (MBDyn 1.7.3 runs it)")));
        }
        let Some(&(_, want)) = FUNCTIONS.iter().find(|(f, _)| *f == name) else {
            return Err(self.err(span, format!("unknown function '{name}'")));
        };
        if args.len() != want {
            return Err(self.err(span, format!("'{name}' takes {want} argument(s), found {}", args.len())));
        }
        let reals = args.iter().map(|a| a.real().ok_or_else(|| self.err(span, format!("'{name}' takes numbers, found a string")))).collect::<Result<Vec<f64>, _>>()?;
        match call(name, &reals) {
            Err(_) if self.lenient => Ok(TypedValue::Real(f64::NAN)),
            result => result.map_err(self.at(span)),
        }
    }
}

/// An evaluator that stops (an error) leaves its levels behind: they are given back here.
impl Drop for Evaluator<'_> {
    fn drop(&mut self) {
        let depth = self.depth;
        NESTED_DEPTH.with(|d| d.set(d.get().saturating_sub(depth)));
    }
}

/// "the number 3", "the word 'x'", … for messages.
pub fn describe(t: &Token) -> String {
    match t {
        Token::Integer(x) => format!("the number {x}"),
        Token::Real(x) => format!("the number {x}"),
        Token::Word(w) => format!("the word '{w}'"),
        Token::Str(s) => format!("the string \"{s}\""),
        Token::Symbol(c) => format!("'{c}'"),
    }
}

/// The type of a `TYPE_eval` function (mathp.cc, development version: `bool_eval`,
/// `integer_eval`, `real_eval`, `string_eval`).
pub fn eval_type(name: &str) -> Option<Type> {
    name.strip_suffix("_eval").and_then(Type::from_name)
}

/// A string drive's text with each `TYPE_eval(EXPR)` replaced by its value now (mathp.cc,
/// development version: `MathParser::readfunc` evaluates an `_eval` call while it parses the
/// expression and keeps the value, so later `set:` statements do not change it, while the
/// rest of the expression reads the variables when the drive is called). `None` when the
/// text has no `_eval` call, or one that cannot be evaluated here (it is then evaluated
/// with the rest, and its error, if any, reported there).
pub fn staticize_evals(text: &str, vars: &mut Variables, reads: Option<Reads<'_>>, drives: Option<&super::card_tables::DrivesBefore>) -> Option<String> {
    if !text.contains("_eval") {
        return None;
    }
    let mut sources = Sources::default();
    sources.files.push(("string drive".into(), text.to_string()));
    let tokens = super::lexer::tokenize(text, 0, &sources).ok()?;
    let mut out: Vec<String> = Vec::new();
    let mut k = 0;
    let mut changed = false;
    while k < tokens.len() {
        let is_eval = matches!(&tokens[k].token, Token::Word(w) if eval_type(w).is_some()) && tokens.get(k + 1).is_some_and(|t| t.token == Token::Symbol("("));
        if is_eval {
            let mut depth = 0usize;
            let close = (k + 1..tokens.len()).find(|&j| {
                match tokens[j].token {
                    Token::Symbol("(") => depth += 1,
                    Token::Symbol(")") => depth -= 1,
                    _ => {}
                }
                depth == 0
            })?;
            let mut e = Evaluator::new(&tokens[k..=close], vars, &sources, Span::default());
            if let Some(r) = reads {
                e = e.with_reads(r, None);
            }
            if let Some(d) = drives {
                e = e.with_drives(d);
            }
            let literal = match e.evaluate().ok()? {
                TypedValue::Real(x) if x.is_finite() => format!("({x:?})"),
                TypedValue::Int(i) => format!("({i})"),
                TypedValue::Bool(b) => (if b { "TRUE" } else { "FALSE" }).to_string(),
                TypedValue::Str(s) if !s.contains('"') => format!("\"{s}\""),
                _ => return None,
            };
            out.push(literal);
            changed = true;
            k = close + 1;
        } else {
            out.push(tokens[k].token.text());
            k += 1;
        }
    }
    changed.then(|| out.join(" "))
}
