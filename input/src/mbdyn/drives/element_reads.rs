//! Drive callers that read a node's degree of freedom or an element's private data during
//! the run (input manual: "General", §Dof drive, §Element drive; "Nodes", §Parameter Node;
//! "Elements", §Bind): `dof, NODE, structural, INDEX, {algebraic | differential}, DRIVE`,
//! `element, LABEL, TYPE, string, "NAME", DRIVE`, and the `parameter: LABEL, element;`
//! nodes with their `bind: ELEMENT, TYPE, PARAMETER, string, "NAME";` (output only: MBDyn
//! 1.7.3 refuses the `dof` drive caller on a parameter node).
//!
//! Drive caller cards are read before the elements block (see `model.rs`), so an `element`
//! read is a cell filled once the elements are read, from the element defined above the
//! drive caller, as MBDyn requires. The drive evaluates `DRIVE` at the value read from the
//! state it is evaluated in, as MBDyn's `DofDriveCaller`/`ElementDriveCaller` (`dGet(value)`:
//! `Var` is the value, `Time` stays the time), with no Jacobian of the read (see
//! [`TimeFunction`]).
//!
//! `model::element::TYPE(LABEL, "NAME")` inside a `string` drive ([`crate::mbdyn::syntax::expr::element_calls`]) is such a
//! cell too, filled from an element anywhere in the elements block: MBDyn's modelns.cc
//! (`model_elem`) looks the element up when the expression is evaluated, during the run,
//! and stops there ("model::element: unable to find …") if it does not exist.

use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Sources, Span};
use crate::mbdyn::syntax::parser::{known, same_keyword, Statement};
use crate::element::drive::{Drive, StepDrive, TimeFunction};
use crate::element::{Element, ElementState};
use crate::model::Label;

use crate::mbdyn::syntax::expr::element_calls::{Cell, StringRead};
use crate::mbdyn::nodes::scalar;
use crate::mbdyn::syntax::parser;

/// What an `element` drive caller reads, waiting for the elements block.
struct Request {
    /// The element's label space and label.
    element: (&'static str, Label),
    name: String,
    span: Span,
    /// The reading statement's position in the input, where the element must be defined
    /// above it (an `element` drive caller); `None` where it may be anywhere (a string drive).
    above: Option<usize>,
    /// Who reads, for messages.
    who: String,
    cell: Cell,
}

/// The parameter nodes, their bindings and the reads of `element` drive callers.
#[derive(Default)]
pub struct PrivateReads {
    /// `parameter: LABEL, element;` nodes (from a scan of the nodes block, which is read
    /// after the drive caller cards).
    parameters: HashSet<Label>,
    /// Where each parameter node was bound.
    bound: RefCell<HashMap<Label, Span>>,
    requests: RefCell<Vec<Request>>,
    /// The reads of a hint's drive (parsed during the run).
    in_hint: bool,
}

/// Element types a `bind` or an `element` drive caller names, as label spaces
/// (`elements::label_space`).
const ELEMENT_TYPES: [&str; 7] = ["joint", "body", "force", "couple", "beam", "inertia", "electric"];

fn space_of(kind: &'static str) -> &'static str {
    match kind {
        "couple" => "force",
        k => k,
    }
}

impl PrivateReads {
    /// Announces the parameter nodes of the nodes block (`parameter: LABEL, element, …`).
    pub fn scan_parameter_nodes(&mut self, nodes: &[Statement]) {
        for st in nodes.iter().filter(|st| same_keyword(&st.keyword, "parameter")) {
            let element = st.args.get(1).and_then(|a| a.keyword.as_deref()).is_some_and(|k| same_keyword(k, "element"));
            if let Some(parser::Arg { value: parser::Value::Number(x), .. }) = st.args.first()
                && element
                && *x >= 0.0
                && x.fract() == 0.0
                && *x <= u32::MAX as f64
            {
                self.parameters.insert(*x as u32);
            }
        }
    }

    /// After the elements block: fills every read from the element it names, which must
    /// be defined above the drive caller (MBDyn's `ElementDCR::Read` finds it while reading:
    /// "unable to find Joint(…)"), and have the datum; a string drive's reads fill from an
    /// element anywhere in the elements block. Returns the memories of the data that keep
    /// one (rotations counted across turns), for the run to advance at every step.
    pub fn resolve(&self, src: &Sources, elements: &HashMap<(&'static str, Label), (&dyn Element, Span, usize)>) -> Result<Vec<StepDrive>, MbdynError> {
        let mut memories = Vec::new();
        for r in self.requests.borrow().iter() {
            let ((space, label), who) = (r.element, &r.who);
            let message = match elements.get(&(space, label)) {
                None if r.above.is_some() => format!("{who}: there is no {space} {label}"),
                None => {
                    let mbdyn = space[..1].to_uppercase() + &space[1..];
                    format!("{who}: there is no {space} {label} in the elements block (MBDyn stops at the drive's first evaluation: \"model::element: unable to find {mbdyn}({label})\")")
                }
                Some((_, at, seq)) if r.above.is_some_and(|s| *seq >= s) => format!("{who}: {space} {label} is not defined above it (line {}); MBDyn reads the element first", at.line),
                Some((e, ..)) => match e.outputs().and_then(|o| o.private_data(&r.name)) {
                    Some(d) => {
                        memories.extend(d.memory().cloned());
                        let _ = r.cell.set(d);
                        continue;
                    }
                    None => format!("{who}: romdyn does not compute the private data \"{}\" of {} {label} ({COMPUTED})", r.name, e.type_name()),
                },
            };
            return Err(src.error(r.span, message));
        }
        Ok(memories)
    }

    fn request(&self, element: (&'static str, Label), name: String, span: Span, seq: usize, cell: Cell) {
        self.requests.borrow_mut().push(Request { element, name, span, above: Some(seq), who: "element drive caller".into(), cell });
    }

    /// Notes the `model::element::…` reads of the string drive `text` written at `span`, to
    /// be filled by [`Self::resolve`]. A hint's drive, parsed during the run, cannot have
    /// them (no elements block follows).
    pub fn string_reads(&self, text: &str, span: Span, reads: &[StringRead]) -> Result<(), String> {
        if self.in_hint && !reads.is_empty() {
            return Err("model::element::… in a hint's drive is not supported by romdyn (MBDyn 1.7.3 runs it) (it reads elements' private data in drives of the input file)".into());
        }
        for r in reads {
            let (space, label) = r.element;
            let who = format!("string drive \"{text}\": model::element::{space}({label}, \"{}\")", r.name);
            self.requests.borrow_mut().push(Request { element: r.element, name: r.name.clone(), span, above: None, who, cell: r.cell.clone() });
        }
        Ok(())
    }

    /// The reads of a hint's drives (see [`Self::string_reads`]).
    pub fn for_hints() -> Self {
        PrivateReads { in_hint: true, ..Self::default() }
    }
}

/// The private data romdyn computes, for messages.
const COMPUTED: &str = "it computes a body's \"E\", \"V\", \"m\", a rod's \"L\", \"LPrime\", \"rz\", \"wz\" of revolute hinges, revolute rotations and axial rotations, and \"px\" … \"pz\", \"rx\" … \"rz\", \"wx\" … \"wz\" of total joints and total pin joints, and a motor's \"i\", \"iP\", \"omega\", \"M\", \"U\", \"Pmech\", \"Pel\", \"R\"";

/// `parameter: LABEL, element;` in the nodes block; the other kinds (`value`, `sample and
/// hold`, `beam strain gage`) are refused by name.
pub fn parameter_node(c: &mut Cursor, seen: &mut HashMap<Label, Span>) -> Result<(), MbdynError> {
    let at = c.here();
    let label = c.label("parameter node label")?;
    if let Some(prev) = seen.insert(label, at) {
        return Err(c.error_at(at, format!("parameter node {label} is defined twice (first at line {})", prev.line)));
    }
    if c.accept("name") {
        c.string("node name")?;
    }
    let kind_at = c.here();
    if !c.accept("element") {
        let what = c.accept_any(&["value", "sample and hold", "beam strain gage"]).map_or_else(|| "without 'element'".to_string(), |k| format!("'{k}'"));
        return Err(c.error_at(kind_at, format!("parameter nodes {what} are not supported by romdyn (MBDyn 1.7.3 runs them) (supported: 'parameter: LABEL, element;', bound to an element's private data)")));
    }
    if c.accept("output") {
        c.flag("output flag")?;
    }
    c.finish()
}

/// `bind: ELEMENT, TYPE, PARAMETER, {string | name}, "NAME";` (dataman4.cc: the element
/// must be defined above, the parameter node exist and be bound once). It only makes the
/// parameter node write the datum to MBDyn's `.prm` output, which romdyn does not write:
/// MBDyn 1.7.3 refuses the `dof` drive caller on a parameter node (below), the one way a
/// drive could read it.
pub fn bind(c: &mut Cursor, reads: &PrivateReads, defined: &HashSet<(&'static str, Label)>) -> Result<(), MbdynError> {
    let el_at = c.here();
    let label = c.label("element label")?;
    let kind = c.keyword("the element type", &ELEMENT_TYPES)?;
    if !defined.contains(&(space_of(kind), label)) {
        return Err(c.error_at(el_at, format!("bind: there is no {kind} {label} above this statement")));
    }
    let p_at = c.here();
    let p = c.label("parameter node label")?;
    if !reads.parameters.contains(&p) {
        return Err(c.error_at(p_at, format!("bind: there is no parameter node {p} ('parameter: {p}, element;' in the nodes block)")));
    }
    if c.accept("string") || c.accept("name") {
        c.string("the private data name")?;
    } else {
        c.accept("index");
        c.label("the private data index")?;
    }
    c.finish()?;
    if let Some(at) = reads.bound.borrow_mut().insert(p, p_at) {
        return Err(c.error_at(p_at, format!("bind: parameter node {p} is already bound (line {})", at.line)));
    }
    Ok(())
}

/// `dof, NODE, TYPE, …, DRIVE` after the keyword.
pub fn dof_drive(c: &mut Cursor, structural: &HashSet<Label>, scalars: &std::collections::HashMap<crate::model::ScalarNodeId, bool>, inner: &dyn Fn(&mut Cursor) -> Result<Drive, MbdynError>) -> Result<Drive, MbdynError> {
    let at = c.here();
    let label = c.label("node label")?;
    let kind_at = c.here();
    if let Some(kind) = c.accept_any(&scalar::SCALAR_TYPES) {
        return scalar_node_drive(c, label, kind, at, scalars, inner);
    }
    match c.accept_any(&["parameter", "structural"]) {
        Some("parameter") => Err(c.error_at(
            kind_at,
            format!("dof drive caller on parameter node {label}: MBDyn 1.7.3 refuses it (\"Parameter({label}) must have dofs\", dataman3.cc ReadScalarDof: a parameter node owns no degree of freedom); read the element's private data with 'element, LABEL, TYPE, string, \"NAME\", DRIVE'"),
        )),
        Some(_) => {
            if !structural.contains(&label) {
                return Err(c.error_at(at, format!("dof drive caller: the file declares no structural node {label} (dummy nodes have no degrees of freedom)")));
            }
            let i_at = c.here();
            let i = c.integer("the degree of freedom (1 to 6)")?;
            if !(1..=6).contains(&i) {
                return Err(c.error_at(i_at, format!("dof drive caller: a structural node has degrees of freedom 1 to 6, found {i}")));
            }
            if i > 3 {
                return Err(c.error_at(i_at, "dof drive caller: romdyn reads a structural node's positions (1 to 3); degrees of freedom 4 to 6 are MBDyn's incremental orientation parameters (use 'node, N, structural, string, \"Phi[i]\"' for the rotation vector)"));
            }
            let order = c.keyword("'algebraic' (position) or 'differential' (velocity)", &["algebraic", "differential"])?;
            let (k, differential) = ((i - 1) as usize, order == "differential");
            let f = inner(c)?;
            let text = format!("dof, {label}, structural, {i}, {order}, {f:?}");
            let cost = crate::element::drive::EvaluationCost::around([f.cost()]);
            Ok(Drive::Expression(TimeFunction::reading_state(text, move |_, st| {
                let Some(n) = st.and_then(|s| s.structural_node(label)) else { return f64::NAN };
                let x = if differential { n.xdot[k] } else { n.x[k] };
                f.value_at(x, st)
            }).with_cost(cost)))
        }
        None => {
            let what = c.peek_keyword().map_or_else(|| c.found(), |w| format!("'{w}'"));
            Err(c.error_at(kind_at, format!("dof drive caller: romdyn reads structural, abstract, electric and hydraulic nodes, found {what} (thermal nodes are not supported)")))
        }
    }
}

/// The rest of `dof, LABEL, TYPE, [algebraic | differential,] DRIVE` and of `node, LABEL,
/// TYPE, string, "x" | "xP", DRIVE` on a scalar node (`kind` its TYPE, read): DRIVE of the
/// node's value or derivative (drive_.cc `DofDriveCaller`, node.cc `iGetPrivDataIdx`), read
/// from the state the drive is evaluated in. The order is read (and required) on a
/// differential node only, as MBDyn's `ReadScalarDof` does.
pub fn scalar_node_drive(c: &mut Cursor, label: Label, kind: &str, at: Span, scalars: &std::collections::HashMap<crate::model::ScalarNodeId, bool>, inner: &dyn Fn(&mut Cursor) -> Result<Drive, MbdynError>) -> Result<Drive, MbdynError> {
    let keyword = scalar::SCALAR_TYPES.iter().copied().find(|k| *k == kind).unwrap_or("abstract");
    let id = crate::model::ScalarNodeId { kind: match keyword { "electric" => crate::model::ScalarNodeKind::Electric, "hydraulic" => crate::model::ScalarNodeKind::Hydraulic, _ => crate::model::ScalarNodeKind::Abstract }, label };
    let Some(&differential) = scalars.get(&id) else {
        return Err(c.error_at(at, format!("drive caller: the file declares no {id}")));
    };
    let derivative = if c.accept("string") {
        let name_at = c.here();
        match c.string("the private data name (\"x\" or \"xP\")")?.as_str() {
            "x" => false,
            "xP" if differential => true,
            other => return Err(c.error_at(name_at, format!("node drive caller: {id} has the private data \"x\"{} , not \"{other}\"", if differential { " and \"xP\"" } else { "" }))),
        }
    } else if differential {
        c.keyword(&format!("'algebraic' (value) or 'differential' (derivative) of differential {id}"), &["algebraic", "differential"])? == "differential"
    } else {
        false
    };
    let f = inner(c)?;
    let text = format!("dof, {label}, {keyword}, {}, {f:?}", if derivative { "differential" } else { "algebraic" });
    let cost = crate::element::drive::EvaluationCost::around([f.cost()]);
    Ok(Drive::Expression(TimeFunction::reading_state(text, move |_, st| {
        let Some((x, xp)) = st.and_then(|s| s.scalar_node(id)) else { return f64::NAN };
        f.value_at(if derivative { xp } else { x }, st)
    }).with_cost(cost)))
}

/// `element, LABEL, TYPE, string, "NAME", DRIVE` after the keyword.
pub fn element_drive(c: &mut Cursor, reads: &PrivateReads, seq: usize, inner: &dyn Fn(&mut Cursor) -> Result<Drive, MbdynError>) -> Result<Drive, MbdynError> {
    let at = c.here();
    let label = c.label("element label")?;
    let kind = c.keyword("the element type", &ELEMENT_TYPES)?;
    let name_at = c.here();
    if !(c.accept("string") || c.accept("name")) {
        return Err(c.error_at(name_at, "element drive caller: romdyn reads the private data by name ('string, \"NAME\"'), not by index or implied"));
    }
    let name = c.string("the private data name")?;
    let f = inner(c)?;
    let cell: Cell = Arc::default();
    reads.request((space_of(kind), label), name.clone(), at, seq, cell.clone());
    Ok(reading(format!("element, {label}, {kind}, string, \"{name}\", {f:?}"), cell, f))
}

/// `f` of the datum in `cell`, read from the state the drive is evaluated in.
fn reading(text: String, cell: Cell, f: Drive) -> Drive {
    let cost = crate::element::drive::EvaluationCost::around([f.cost()]);
    Drive::Expression(TimeFunction::reading_state(text, move |_, st: Option<&dyn ElementState>| {
        let (Some(st), Some(datum)) = (st, cell.get()) else { return f64::NAN };
        datum.value(st).map_or(f64::NAN, |x| f.value_at(x, Some(st)))
    }).with_cost(cost))
}

/// Whether `keyword` is the `bind` statement.
pub fn is_bind(keyword: &str) -> bool {
    known(keyword, &["bind"]).is_some()
}
