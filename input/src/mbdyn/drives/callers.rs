//! Drive callers (input manual, "General", §Drives and Drive Callers) mapped onto
//! romdyn's [`Drive`]: a plain number, `const`, `null`, `unit`, `time`, `direct`, `ramp`,
//! `step`, `sine`, `cosine`, `piecewise linear`, `linear`, `parabolic`, `cubic`,
//! `exponential`, `tanh`, `double ramp`, `double step`, `array`, `mult`, `drive` (one drive
//! of another's value), `frequency sweep`,
//! `periodic`, `fourier series`, `sample and hold`, `discrete filter`, `meter`, `closest
//! next` and `random` (with a memory of the steps, [`StepDrive`]; see `counter_drives`), `string` (an expression of `Time` for the math parser, evaluated with the
//! file's variables as they stand at the end of the input, as MBDyn evaluates it during the
//! run), and `reference, LABEL` to a `drive caller:` card;
//! and the 3-vector template drive callers (§Template Drive): `null`, `single`,
//! `component`, `array` (the other dimensions in [`super::templates`]).

use std::collections::{HashMap, HashSet};

use std::sync::{Arc, Mutex};

use crate::mbdyn::syntax::card_tables::{DriveCard, DriveTable};
pub use crate::mbdyn::syntax::card_tables::DrivesBefore;
use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Sources, Span};
use crate::mbdyn::syntax::expr::element_calls::RunElements;
use crate::mbdyn::syntax::expr::{Evaluator, Variable, Variables};
use crate::mbdyn::syntax::lexer::{tokenize, Token};
use crate::mbdyn::syntax::model_namespace::{node_private_data, Live, Reads};
use crate::mbdyn::syntax::parser::Statement;
use super::template_dim::{TemplateDim, Term};
use crate::mbdyn::syntax::value::TypedValue;
use crate::element::ElementState;
use crate::element::drive::{note_evaluation_failure, Drive, EvaluationCost, StepDrive, StepKind, TimeFunction};
use crate::kinematics::{Mat3, Vec3};
use crate::mbdyn::nodes::scalar;
use crate::mbdyn::syntax::card_tables;
use crate::mbdyn::syntax::lexer;
use crate::mbdyn::syntax::keywords::{read, Keyword, KeywordTable, Support};

/// Every drive caller of MBDyn 1.7.3 (drive_.cc and the readers it registers), with whether
/// romdyn evaluates it.
pub(in crate::mbdyn) const DRIVE_CALLERS: KeywordTable = KeywordTable {
    what: "drive caller",
    keywords: &[
        read("postponed"), read("meter"), read("closest next"), read("random"), read("fourier series"), read("sample and hold"),
        read("discrete filter"), read("drive"), read("file"), read("node"), read("dof"), read("element"), read("const"), read("null"),
        read("unit"), read("one"), read("time"), read("direct"), read("ramp"), read("step"), read("sine"), read("cosine"),
        read("piecewise linear"), read("linear"), read("parabolic"), read("cubic"), read("exponential"), read("tanh"),
        read("double ramp"), read("double step"), read("array"), read("mult"), read("frequency sweep"), read("periodic"),
        read("string"), read("reference"), read("zero"), read("constant"), read("scalar function"),
        // `ginac` needs GiNaC (MBDyn 1.7.3 built without it refuses it too).
        Keyword { name: "ginac", support: Support::MbdynRunsWhen("an MBDyn 1.7.3 built with GiNaC runs it, one built without refuses it too") },
    ],
};

/// Nesting of drive callers inside drive callers romdyn follows.
const MAX_DEPTH: usize = 16;

/// The `drive caller:` cards read so far, and the variables `string` drives evaluate with.
#[derive(Default)]
pub struct Drives {
    table: DriveTable,
    pub variables: Variables,
    /// The `scalar function:` cards (which `scalar function` drives and laws use).
    pub functions: super::scalar_functions::ScalarFunctions,
    /// Labels of the structural nodes the file declares (not the dummy ones): the nodes the
    /// `model::` functions of a string drive may read.
    pub structural_nodes: HashSet<u32>,
    /// The scalar nodes the file declares (abstract, electric, hydraulic), each with
    /// whether it is differential: the nodes `dof` and `node` drive callers may read.
    pub scalar_nodes: std::collections::HashMap<crate::model::ScalarNodeId, bool>,
    /// The `drivers` block's file drivers (which `file` drive callers read).
    pub file_drivers: super::file_drivers::FileDrivers,
    /// Parameter nodes, `bind`s and the reads of `dof` and `element` drive callers.
    pub private: super::element_reads::PrivateReads,
    /// The drives with a memory of the steps, which the model advances at every step.
    pub steps: super::counter::StepDrives,
    /// The 3-vector `template drive caller:` cards: their terms, statement, place.
    pub(in crate::mbdyn) templates: HashMap<u32, TemplateCard>,
    /// The `template drive caller:` cards of dimension 1, 6, 3x3, 6x6, by dimension and
    /// label (MBDyn keeps one table per dimension: a label may name one card of each).
    pub(in crate::mbdyn) other_templates: HashMap<(TemplateDim, u32), (Vec<Term>, usize, Span)>,
}

/// A 3-vector template drive caller card: its terms, statement and place.
type TemplateCard = (Vec<(Vec3, Drive)>, usize, Span);

impl Drives {
    /// Forgets the `drive caller:` cards (to read them again with other variables).
    pub fn clear_cards(&mut self) {
        // A new table: the string drives read so far keep the old one.
        self.table = DriveTable::default();
        self.templates.clear();
        self.other_templates.clear();
    }
    /// The drives with memory read so far (emptied).
    pub fn take_stepped(&self) -> Vec<StepDrive> {
        self.steps.take()
    }
    /// What a hint's drive, parsed during the run, reads (input manual, §Driven Element):
    /// the `drive caller:` cards, the variables and the structural nodes' labels as now; no
    /// scalar functions, file drivers or element reads (refused in a hint).
    pub fn for_hints(&self) -> Drives {
        Drives { table: self.table.clone(), variables: self.variables.clone(), structural_nodes: self.structural_nodes.clone(), scalar_nodes: self.scalar_nodes.clone(), private: super::element_reads::PrivateReads::for_hints(), ..Drives::default() }
    }
    /// The drive caller cards of statements before `seq`, shared.
    pub fn defined_before(&self, seq: usize) -> DrivesBefore {
        self.table.before(seq)
    }
}

/// `FILE:LINE:COLUMN` of `span`, for messages of the run.
fn place(c: &Cursor, span: Span) -> String {
    let file = c.source_path(span).map_or_else(|| "input".to_string(), |p| p.display().to_string());
    format!("{file}:{}:{}", span.line, span.column)
}

/// Reads a `drive caller: LABEL, [name, "…",] DRIVE;` card; returns its label.
pub fn drive_caller_card(st: &Statement, c: &mut Cursor, drives: &mut Drives) -> Result<u32, MbdynError> {
    let span = c.here();
    let label = c.label("drive caller label")?;
    if let Some(card) = drives.table.get(label) {
        return Err(c.error_at(span, format!("drive caller {label} is defined twice (first at line {})", card.span.line)));
    }
    if c.accept("name") {
        c.string("drive caller name")?;
    }
    c.accept("deferred");
    let before = drives.functions.take_used();
    let d = drive(c, drives, st.seq)?;
    let used = drives.functions.take_used();
    if !used.is_empty() {
        drives.functions.set_operands(&card_tables::drive_key(label), used);
    }
    before.iter().for_each(|n| drives.functions.note_used(n));
    drives.functions.set_drive_card(label, st.span);
    // `output, {yes | no | value, FLAG | derivative, FLAG …}` (drive_.cc,
    // `DriveCallerRead::ReadOutput`) asks for MBDyn's .drv file, which romdyn does not write.
    if c.accept("output") {
        let mut keyed = false;
        for kw in ["value", "derivative"] {
            if c.accept(kw) {
                keyed = true;
                c.flag(&format!("drive caller output {kw}"))?;
            }
        }
        if !keyed {
            c.flag("drive caller output")?;
        }
    }
    c.finish()?;
    drives.table.insert(label, DriveCard { drive: Arc::new(d), seq: st.seq, span: st.span });
    Ok(label)
}

/// One drive caller; `seq` is the reading statement's position (for `reference, LABEL`).
pub fn drive(c: &mut Cursor, drives: &Drives, seq: usize) -> Result<Drive, MbdynError> {
    nested_drive(c, drives, seq, 0)
}

/// A drive caller inside `depth` others, refused where it is written when one call of it
/// would cost more than romdyn's budget ([`EvaluationCost`]; `reference`, `array` and
/// `model::drive` could otherwise nest without bound or double at every card).
fn nested_drive(c: &mut Cursor, drives: &Drives, seq: usize, depth: usize) -> Result<Drive, MbdynError> {
    let span = c.here();
    let d = unchecked_drive(c, drives, seq, depth)?;
    match d.cost().over_budget("this drive caller") {
        Some(why) => Err(c.error_at(span, why)),
        None => Ok(d),
    }
}

fn unchecked_drive(c: &mut Cursor, drives: &Drives, seq: usize, depth: usize) -> Result<Drive, MbdynError> {
    if depth > MAX_DEPTH {
        return Err(c.error(format!("drive callers nested more than {MAX_DEPTH} deep")));
    }
    let inner = |c: &mut Cursor| nested_drive(c, drives, seq, depth + 1);
    if c.accept("const") || c.accept("constant") {
        return Ok(Drive::Const(c.real("constant value of the drive")?));
    }
    let span = c.here();
    let Some(kind) = c.accept_any(&DRIVE_CALLERS.read()) else {
        if c.next_is_number() {
            return Ok(Drive::Const(c.real("constant value of the drive")?));
        }
        if let Some(w) = c.peek_keyword().filter(|w| DRIVE_CALLERS.find(w).is_some()) {
            return Err(c.error(DRIVE_CALLERS.refusal(w)));
        }
        return Err(c.error(format!("expected a drive caller (a number, {}), found {}", DRIVE_CALLERS.read().join(", "), c.found())));
    };
    Ok(match kind {
        "null" | "zero" => Drive::Const(0.0),
        "unit" | "one" => Drive::Const(1.0),
        // `direct` passes its argument through; called with none it gives the time.
        "time" | "direct" => Drive::Time,
        "linear" => Drive::Polynomial(vec![c.real("constant coefficient")?, c.real("slope")?]),
        "parabolic" => Drive::Polynomial(vec![c.real("constant coefficient")?, c.real("linear coefficient")?, c.real("parabolic coefficient")?]),
        "cubic" => Drive::Polynomial(vec![c.real("constant coefficient")?, c.real("linear coefficient")?, c.real("parabolic coefficient")?, c.real("cubic coefficient")?]),
        "exponential" => {
            let amplitude = c.real("amplitude")?;
            let span = c.here();
            let tau = c.real("time constant [s]")?;
            if tau == 0.0 {
                return Err(c.error_at(span, "exponential: the time constant must not be zero"));
            }
            Drive::Exponential { amplitude, tau, t0: c.real("initial time [s]")?, v0: c.real("initial value")? }
        }
        "tanh" => Drive::Tanh { t0: c.real("initial time [s]")?, amplitude: c.real("amplitude")?, slope: c.real("slope")?, v0: c.real("initial value")? },
        "double ramp" => {
            let (a_slope, a_t0, a_t1) = (c.real("ascending slope")?, c.real("ascending initial time [s]")?, c.real("ascending final time [s]")?);
            let (d_slope, d_t0) = (c.real("descending slope")?, c.real("descending initial time [s]")?);
            let d_t1 = if c.accept("forever") { f64::INFINITY } else { c.real("descending final time [s] (or forever)")? };
            if !(a_t0 <= a_t1 && a_t1 <= d_t0 && d_t0 <= d_t1) {
                return Err(c.error(format!("double ramp: the times must not decrease, found {a_t0}, {a_t1}, {d_t0}, {d_t1}")));
            }
            Drive::DoubleRamp { a_slope, a_t0, a_t1, d_slope, d_t0, d_t1, v0: c.real("initial value")? }
        }
        "double step" => Drive::DoubleStep { t0: c.real("initial time [s]")?, t1: c.real("final time [s]")?, value: c.real("step value")?, v0: c.real("initial value")? },
        "array" => {
            let span = c.here();
            let n = c.count("number of drive callers")?;
            if n == 0 {
                return Err(c.error_at(span, "array: at least one drive caller is needed"));
            }
            let mut terms = Vec::with_capacity(n.min(64));
            let mut cost = 0u64;
            for _ in 0..n {
                let at = c.here();
                let term = inner(c)?;
                // Checked as the terms come: their copies are not all made before the check.
                cost = cost.saturating_add(term.cost().terms);
                if let Some(why) = (EvaluationCost { depth: 1, terms: cost.saturating_add(1) }).over_budget("this array drive caller") {
                    return Err(c.error_at(at, why));
                }
                terms.push(term);
            }
            if terms.len() == 1 { terms.remove(0) } else { Drive::Sum(terms) }
        }
        "sample and hold" => {
            // drive_.cc, `SHDCR::Read`: FUNCTION, TRIGGER [, initial value, V0].
            let function = inner(c)?;
            let trigger = inner(c)?;
            let initial = if c.accept("initial value") { c.real("initial value of the sample and hold")? } else { 0.0 };
            drives.steps.register(StepKind::SampleAndHold { function, trigger, initial })
        }
        "discrete filter" => {
            // drive_.cc, `DiscreteFilterDCR::Read`: n_a, a_1…, b_0, n_b, b_1…, INPUT.
            let a = coefficients(c, "a")?;
            let b0 = c.real("discrete filter direct coefficient b_0")?;
            let b = coefficients(c, "b")?;
            drives.steps.register(StepKind::DiscreteFilter { a, b0, b, input: inner(c)? })
        }
        "file" => super::file_drivers::file_drive(c, &drives.file_drivers, seq)?,
        "node" => node_drive(c, drives, &inner)?,
        "dof" => super::element_reads::dof_drive(c, &drives.structural_nodes, &drives.scalar_nodes, &inner)?,
        "element" => super::element_reads::element_drive(c, &drives.private, seq, &inner)?,
        "scalar function" => {
            let name = c.peek_text().unwrap_or_default().to_string();
            let first = c.position();
            let f = super::scalar_functions::scalar_function(c, &drives.functions, seq)?;
            let origin = format!("scalar function drive caller {name} at {}", place(c, span));
            let cost = EvaluationCost::around([f.cost()]);
            // The text decides equality (two forces with equal drives add up): a card's name
            // is unique, a definition written inline is told apart by its place.
            let text = if c.position() > first + 1 { format!("scalar function, {name}, defined at {}", place(c, span)) } else { format!("scalar function, {name}") };
            Drive::Expression(TimeFunction::new(text, move |t| {
                let v = f.value(t);
                if !v.is_finite() {
                    note_evaluation_failure(t, || format!("{origin}: its value at {t} is {v}"));
                }
                v
            }).with_cost(cost))
        }
        "mult" => {
            let a = inner(c)?;
            Drive::Product(Box::new(a), Box::new(inner(c)?))
        }
        // `drive, F, G` (drive_.cc, `DriveDCR::Read`): F of G's value.
        "drive" => {
            let f = inner(c)?;
            Drive::Compose(Box::new(f), Box::new(inner(c)?))
        }
        "meter" => super::counter::meter(c, &drives.steps)?,
        "closest next" => super::counter::closest_next(c, &drives.steps, &inner)?,
        "random" => super::counter::random(c, &drives.steps, seq)?,
        "fourier series" => super::counter::fourier_series(c)?,
        // `postponed, LABEL` (drive_.cc, `PostponedDriveCaller::Check`): a copy of the
        // drive caller card LABEL, which may come later in the file. MBDyn resolves it when
        // first called; romdyn reads the cards before the problem and element blocks, so
        // there it resolves any card; inside a card it needs a card read before.
        "postponed" => {
            let label = c.label("drive caller label")?;
            match drives.table.get(label) {
                // A random drive copied at its first call draws after all those read.
                Some(card) => {
                    drives.functions.note_used(&card_tables::drive_key(label));
                    super::counter::copied(&card.drive, &drives.steps, usize::MAX)
                }
                None => {
                    return Err(c.error_at(span, format!("postponed drive caller {label}: no drive caller card {label} is read before this one (romdyn resolves a postponed drive caller inside a drive caller card when it reads the card)")));
                }
            }
        }
        "frequency sweep" => {
            let t0 = c.real("initial time [s]")?;
            let omega = Box::new(inner(c)?);
            let amplitude = Box::new(inner(c)?);
            let v0 = c.real("initial value")?;
            let t1 = if c.accept("forever") { f64::INFINITY } else { c.real("final time [s] (or forever)")? };
            Drive::FrequencySweep { t0, omega, amplitude, v0, t1, v1: c.real("final value")? }
        }
        "periodic" => {
            let t0 = c.real("initial time [s]")?;
            let span = c.here();
            let period = c.real("period [s]")?;
            if period <= 0.0 {
                return Err(c.error_at(span, format!("periodic: the period must be positive, found {period}")));
            }
            Drive::Periodic { t0, period, f: Box::new(inner(c)?) }
        }
        "string" => {
            let span = c.here();
            let text = c.string("the expression (a string in double quotes)")?;
            let origin = format!("string drive \"{text}\" at {}", place(c, span));
            Drive::Expression(string_drive(&text, drives, seq, span, origin).map_err(|m| c.error_at(span, format!("string drive \"{text}\": {m}")))?)
        }
        "ramp" => {
            let slope = c.real("ramp slope")?;
            let t0 = c.real("ramp initial time [s]")?;
            let t1_span = c.here();
            let t1 = if c.accept("forever") { f64::INFINITY } else { c.real("ramp final time [s] (or forever)")? };
            if t1 < t0 {
                return Err(c.error_at(t1_span, format!("ramp: final time {t1} is before the initial time {t0}")));
            }
            Drive::Ramp { slope, t0, t1, v0: c.real("ramp initial value")? }
        }
        "step" => Drive::Step { t0: c.real("step time [s]")?, value: c.real("step value")?, v0: c.real("initial value")? },
        "sine" | "cosine" => {
            let (t0, omega, amplitude) = (c.real("initial time [s]")?, c.real("angular frequency [rad/s]")?, c.real("amplitude")?);
            let cycles = cycles(c, kind == "sine")?;
            let v0 = c.real("initial value")?;
            if kind == "sine" { Drive::Sine { t0, omega, amplitude, cycles, v0 } } else { Drive::Cosine { t0, omega, amplitude, cycles, v0 } }
        }
        "piecewise linear" => {
            let n_span = c.here();
            let n = c.count("number of points")?;
            if n == 0 {
                return Err(c.error_at(n_span, "piecewise linear: at least one point is needed"));
            }
            let mut points: Vec<(f64, f64)> = Vec::new();
            for _ in 0..n {
                let t_span = c.here();
                let t = c.real("point (time [s])")?;
                if points.last().is_some_and(|(prev, _)| t <= *prev) {
                    return Err(c.error_at(t_span, format!("piecewise linear: the points must increase, {t} does not follow {}", points.last().map_or(0.0, |p| p.0))));
                }
                points.push((t, c.real("value")?));
            }
            Drive::PiecewiseLinear(points)
        }
        _ => {
            let label = c.label("drive caller label")?;
            match drives.table.get(label) {
                Some(card) if card.seq < seq => {
                    drives.functions.note_used(&card_tables::drive_key(label));
                    super::counter::copied(&card.drive, &drives.steps, seq)
                }
                Some(card) => return Err(c.error_at(span, format!("drive caller {label} is used before its definition (line {})", card.span.line))),
                None => return Err(c.error_at(span, format!("drive caller {label} is not defined"))),
            }
        }
    })
}

/// `n, c_1, …, c_n` of a discrete filter (`n` ≥ 0).
fn coefficients(c: &mut Cursor, name: &str) -> Result<Vec<f64>, MbdynError> {
    let n = c.count(&format!("discrete filter: number of coefficients {name}"))?;
    let mut v = Vec::with_capacity(n.min(64));
    for i in 1..=n {
        v.push(c.real(&format!("discrete filter coefficient {name}_{i}"))?);
    }
    Ok(v)
}

/// The expression of a `string` drive as a function of time: the math parser on its tokens
/// with `Var` the argument MBDyn passes and `Time` the state's time (the argument where the
/// drive is evaluated without a state, see [`TimeFunction::of_argument`]); checked at
/// t = 0 so that errors show when the file is read. A value that cannot be computed later
/// (out of a function's domain) is NaN, which the Newton iteration reports.
/// `model::sf::NAME(x)` calls the scalar functions defined before the drive,
/// `model::drive(LABEL, x)` the drive caller cards defined before it; the `model::`
/// functions of the nodes' state read the state the drive is evaluated in (see
/// [`TimeFunction`]); the check at t = 0 only checks their node labels against the
/// structural nodes the file declares (each read is 0 there, and out-of-domain arguments
/// of built-in functions are not errors). `model::element::TYPE(LABEL, "NAME")` reads the
/// element's private datum at that state too: the check notes the reads, which are filled
/// after the elements block (see [`super::element_reads`]).
///
/// A value that is not finite where the check computes it (`10.^400.`, `1e309`) is an
/// error there; one that fails or is not finite during the run is noted with `origin`
/// (the drive and its `FILE:LINE:COLUMN`), which the Newton iteration's failure names
/// ([`note_evaluation_failure`]). The drive's cost counts the drives and functions its
/// `model::drive` and `model::sf` calls reach ([`call_costs`]).
fn string_drive(text: &str, drives: &Drives, seq: usize, span: Span, origin: String) -> Result<TimeFunction, String> {
    let mut sources = Sources::default();
    sources.files.push(("string drive".into(), text.to_string()));
    let tokens = tokenize(text, 0, &sources).map_err(|e| e.message)?;
    if tokens.is_empty() {
        return Err("the expression is empty".into());
    }
    let functions = drives.functions.before(seq);
    let table = drives.defined_before(seq);
    let cost = EvaluationCost::around(call_costs(&tokens, &functions, &drives.table, seq));
    if let Some(why) = cost.over_budget("the drive") {
        return Err(why);
    }
    let is_word = |t: &Token, w: &str| matches!(t, Token::Word(x) if x == w);
    let reads_state = tokens.windows(3).any(|w| is_word(&w[0].token, "model") && w[1].token == Token::Symbol("::") && !is_word(&w[2].token, "sf"));
    let evaluate = move |vars: &mut Variables, tokens: &[lexer::Spanned], sources: &Sources, var: f64, reads: Option<Reads>, state: Option<&dyn ElementState>, elements: Option<RunElements>| -> Result<f64, String> {
        // MBDyn's `StringDriveCaller::dGet(dVar)` sets `Var`; `Time` is the simulation's
        // time, which is the argument unless a drive passes another value (a dof, element
        // or node drive caller's datum, `model::drive(L, x)`, a periodic drive's phase).
        let time = state.map_or(var, |s| s.time());
        for (name, value) in [("Time", time), ("Var", var)] {
            vars.insert(name.into(), Variable { value: TypedValue::Real(value), constant: false, declared: None });
        }
        let mut e = Evaluator::new(tokens, vars, sources, Span::default()).with_functions(&functions).with_drives(&table);
        if let Some(reads) = reads {
            e = e.with_reads(reads, state);
        }
        if let Some(elements) = elements {
            e = e.with_run_elements(elements);
        }
        let v = e.evaluate().map_err(|e| e.message)?;
        v.real().ok_or_else(|| "the expression gives a string, not a number".to_string())
    };
    let mut vars = drives.variables.clone();
    let noted = std::cell::RefCell::new(Vec::new());
    let first = evaluate(&mut vars, &tokens, &sources, 0.0, reads_state.then_some(Reads::Labels(&drives.structural_nodes)), None, Some(RunElements::Note(&noted)))?;
    // With the state's reads at their placeholder 0, a value may be out of range only there.
    if !first.is_finite() && !reads_state {
        return Err(format!("the value at Time = 0 is {first}, not a finite number"));
    }
    let noted = noted.into_inner();
    drives.private.string_reads(text, span, &noted)?;
    let state = Mutex::new(vars);
    let run = move |t: f64, st: Option<&dyn ElementState>| {
        let mut vars = state.lock().unwrap_or_else(|e| e.into_inner());
        let value = match (reads_state, st) {
            (false, st) => evaluate(&mut vars, &tokens, &sources, t, None, st, None),
            // No state to read: NaN by design (see [`TimeFunction::reading_state`]).
            (true, None) => return f64::NAN,
            (true, Some(st)) => evaluate(&mut vars, &tokens, &sources, t, Some(Reads::Nodes(&Live(st))), Some(st), Some(RunElements::Read(&noted, st))),
        };
        let time = st.map_or(t, |s| s.time());
        match value {
            Ok(v) if v.is_finite() => v,
            Ok(v) => {
                note_evaluation_failure(time, || format!("{origin}: the value at Time = {time} is {v}"));
                v
            }
            Err(why) => {
                note_evaluation_failure(time, || format!("{origin}: {why} at Time = {time}"));
                f64::NAN
            }
        }
    };
    let f = if reads_state { TimeFunction::reading_state(text, run) } else { TimeFunction::of_argument(text, run) };
    Ok(f.with_cost(cost))
}

/// The costs of what a string drive's `model::drive(LABEL, …)` and `model::sf::NAME(…)`
/// calls reach, one per call: the card `LABEL` where it is written as a number, every card
/// before the drive where it is computed.
fn call_costs(tokens: &[lexer::Spanned], functions: &super::scalar_functions::FunctionsBefore, table: &DriveTable, seq: usize) -> Vec<EvaluationCost> {
    let word = |k: usize, w: &str| tokens.get(k).is_some_and(|t| matches!(&t.token, Token::Word(x) if x == w));
    let symbol = |k: usize, s: &'static str| tokens.get(k).is_some_and(|t| t.token == Token::Symbol(s));
    let mut costs = Vec::new();
    for k in 0..tokens.len() {
        if !(word(k, "model") && symbol(k + 1, "::")) {
            continue;
        }
        if word(k + 2, "drive") && symbol(k + 3, "(") {
            let literal = match tokens.get(k + 4).map(|t| &t.token) {
                Some(Token::Integer(l)) if symbol(k + 5, ",") || symbol(k + 5, ")") => u32::try_from(*l).ok(),
                Some(Token::Real(x)) if (symbol(k + 5, ",") || symbol(k + 5, ")")) && x.fract() == 0.0 && (0.0..=u32::MAX as f64).contains(x) => Some(*x as u32),
                _ => None,
            };
            match literal {
                Some(l) => costs.extend(table.get(l).filter(|d| d.seq < seq).map(|d| d.drive.cost())),
                // Any card before may be called: the deepest and the dearest.
                None => costs.push(table.costs_before(seq).into_iter().fold(EvaluationCost::LEAF, |a, b| EvaluationCost { depth: a.depth.max(b.depth), terms: a.terms.max(b.terms) })),
            }
        } else if word(k + 2, "sf") && symbol(k + 3, "::") {
            if let Some(Token::Word(name)) = tokens.get(k + 4).map(|t| &t.token) {
                costs.extend(functions.get(name).map(|(_, c)| c));
            }
        }
    }
    costs
}

/// `node, LABEL, structural, string, "NAME[i]", DRIVE` (drive_.cc, `NodeDCR::Read`;
/// privdrive.h, `PrivDriveCaller::dGet`): DRIVE of the node's private data (the names of
/// [`node_private_data`]), read from the state the drive is evaluated in, as a `model::`
/// function in a string drive (see [`TimeFunction`]).
fn node_drive(c: &mut Cursor, drives: &Drives, inner: &dyn Fn(&mut Cursor) -> Result<Drive, MbdynError>) -> Result<Drive, MbdynError> {
    let label = c.label("node label")?;
    let at = c.here();
    if let Some(kind) = c.accept_any(&scalar::SCALAR_TYPES) {
        return super::element_reads::scalar_node_drive(c, label, kind, at, &drives.scalar_nodes, inner);
    }
    if c.keyword("the node type (romdyn reads structural, abstract, electric and hydraulic nodes)", &["structural"]).is_err() {
        return Err(c.error_at(at, format!("node drive caller: romdyn reads structural, abstract, electric and hydraulic nodes, found {}", c.found())));
    }
    if c.accept("index") {
        return Err(c.error("node drive caller: 'index' (deprecated in MBDyn) is not supported by romdyn (MBDyn 1.7.3 runs it): write 'string, \"NAME[i]\"'"));
    }
    c.keyword("'string' and the private data name", &["string"])?;
    let name_at = c.here();
    let data = c.string("the private data name, e.g. \"X[3]\"")?;
    node_private_data(label as f64, &data, Reads::Labels(&drives.structural_nodes)).map_err(|m| c.error_at(name_at, format!("node drive caller: {m}")))?;
    let f = inner(c)?;
    let text = format!("node, {label}, structural, string, \"{data}\", {f:?}");
    let cost = EvaluationCost::around([f.cost()]);
    Ok(Drive::Expression(TimeFunction::reading_state(text, move |_, st| {
        let Some(st) = st else { return f64::NAN };
        node_private_data(label as f64, &data, Reads::Nodes(&Live(st))).map_or(f64::NAN, |x| f.value_at(x, Some(st)))
    }).with_cost(cost)))
}

/// Cycles of `sine`/`cosine` as full periods before the phase freezes. Sine: `N > 0` ends
/// after `N − 1/2` periods, `N < 0` after `|N| − 3/4` (`one` = 1, `half` = −1); cosine:
/// `N > 0` after `N`, `N < 0` after `|N| − 1/2` (`one` = 1, `half` = −1).
fn cycles(c: &mut Cursor, sine: bool) -> Result<Option<f64>, MbdynError> {
    let n = match c.accept_any(&["forever", "one", "half"]) {
        Some("forever") => return Ok(None),
        Some("one") => 1.0,
        Some(_) => -1.0,
        None => {
            let span = c.here();
            let n = c.integer("number of cycles (or forever, one, half)")? as f64;
            if n == 0.0 {
                return Err(c.error_at(span, "number of cycles must not be zero (write 'forever' for no end)"));
            }
            n
        }
    };
    Ok(Some(match (sine, n > 0.0) {
        (true, true) => n - 0.5,
        (true, false) => -n - 0.75,
        (false, true) => n,
        (false, false) => -n - 0.5,
    }))
}

/// A 3-vector template drive caller: a sum of `direction · drive` terms. `direction`
/// reads the vector of `single` (with its optional `reference`); `basis` maps the
/// components of `component` to the same frame.
pub fn template_vec3(c: &mut Cursor, drives: &Drives, seq: usize, basis: &Mat3, direction: &dyn Fn(&mut Cursor) -> Result<Vec3, MbdynError>) -> Result<Vec<(Vec3, Drive)>, MbdynError> {
    template_terms(c, drives, seq, basis, direction, 0)
}

/// Nesting of `array` template drive callers romdyn follows.
const MAX_ARRAY_DEPTH: usize = 8;

pub(in crate::mbdyn) fn template_terms(c: &mut Cursor, drives: &Drives, seq: usize, basis: &Mat3, direction: &dyn Fn(&mut Cursor) -> Result<Vec3, MbdynError>, depth: usize) -> Result<Vec<(Vec3, Drive)>, MbdynError> {
    // `zero` is the deprecated name of `null` (tpldrive_impl.cc, ZeroTDCR).
    if c.accept("null") || c.accept("zero") {
        return Ok(vec![(Vec3::zeros(), Drive::Const(0.0))]);
    }
    if c.accept("component") {
        if c.accept_any(&["sym", "diag"]).is_some() {
            return Err(c.error("'sym' and 'diag' apply to matrix template drive callers, not to vectors"));
        }
        let mut terms = Vec::new();
        for k in 0..3 {
            if !c.accept("inactive") {
                terms.push((basis.column(k).into_owned(), drive(c, drives, seq)?));
            }
        }
        return Ok(terms);
    }
    if c.accept("array") {
        if depth >= MAX_ARRAY_DEPTH {
            return Err(c.error(format!("template drive callers nested in 'array' more than {MAX_ARRAY_DEPTH} deep")));
        }
        let n = c.count("number of template drive callers")?;
        let mut terms = Vec::new();
        for _ in 0..n {
            terms.extend(template_terms(c, drives, seq, basis, direction, depth + 1)?);
        }
        return Ok(terms);
    }
    if c.accept("reference") {
        // A `template drive caller:` card, copied (MBDyn's `pCopy`), its vectors in the
        // element's frame.
        let span = c.here();
        let label = c.label("template drive caller label (a 'template drive caller:' card; to give the vector in another frame write 'single, reference, FRAME, x, y, z, DRIVE')")?;
        return match drives.templates.get(&label) {
            Some((terms, s, _)) if *s < seq => Ok(terms.iter().map(|(v, d)| (basis * v, super::counter::copied(d, &drives.steps, seq))).collect()),
            Some((_, _, at)) => Err(c.error_at(span, format!("template drive caller {label} is used before its definition (line {})", at.line))),
            None => Err(c.error_at(span, format!("template drive caller {label} is not defined{}", other_dims_of(drives, label, None)))),
        };
    }
    c.accept("single");
    let dir = direction(c)?;
    Ok(vec![(dir, drive(c, drives, seq)?)])
}

/// The single `direction · drive` romdyn's forces, couples and gravity take: terms with a
/// zero direction or a zero drive drop out, constant terms add up, terms with one and the
/// same drive add up.
pub fn single_term(terms: Vec<(Vec3, Drive)>) -> Option<(Vec3, Drive)> {
    let terms: Vec<_> = terms.into_iter().filter(|(d, dr)| *d != Vec3::zeros() && *dr != Drive::Const(0.0)).collect();
    let Some((_, first)) = terms.first() else { return Some((Vec3::zeros(), Drive::Const(0.0))) };
    if terms.iter().all(|(_, d)| matches!(d, Drive::Const(_))) {
        let sum = terms.iter().map(|(v, d)| v * if let Drive::Const(x) = d { *x } else { 0.0 }).sum();
        return Some((sum, Drive::Const(1.0)));
    }
    if terms.iter().all(|(_, d)| d == first) {
        return Some((terms.iter().map(|(v, _)| *v).sum(), first.clone()));
    }
    None
}

/// ", (there is one of dimension …)" when `label` names cards of other dimensions than
/// `except` (those of dimension 3 too when `except` is one of the others).
pub fn other_dims_of(drives: &Drives, label: u32, except: Option<TemplateDim>) -> String {
    let mut dims: Vec<&str> = drives.other_templates.keys().filter(|(d, l)| *l == label && Some(*d) != except).map(|(d, _)| d.name()).collect();
    if except.is_some() && drives.templates.contains_key(&label) {
        dims.push("3");
    }
    dims.sort();
    if dims.is_empty() { String::new() } else { format!(" (there is one of dimension {})", dims.join(", ")) }
}
