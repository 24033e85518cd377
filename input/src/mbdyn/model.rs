//! From a parsed document to a [`Model`] and the analysis it asks for: the cards
//! (`reference`, `drive caller`, `constitutive law`) in file order, then the `data`,
//! `initial value`, `control data`, `nodes` and `elements` blocks, with the counts of
//! control data checked against the model as MBDyn does.

use std::collections::HashMap;
use std::path::Path;

use super::blocks::control::{control_data, Counts, COUNTED};
use super::syntax::cursor::Cursor;
use super::syntax::diagnostic::{MbdynError, Span};
use super::drives::callers::{drive_caller_card, Drives};
use super::elements::context::{ElementContext, Parsed};
use super::elements::block::{counted_kind, element, label_space};
use super::elements::laws::{constitutive_law_card, Laws};
use super::nodes::structural::{node_statement, Nodes};
use super::read_options::{BeamUpdateRule, ReadOptions};
use super::syntax::parser::{known, same_keyword, Block, Document, CARDS};
use super::written_nodes::{parse_file_with, parse_text_with};
use super::blocks::problem::{data, initial_value};
use super::syntax::references::{reference, Frames};
use crate::model::{InitialValueProblem, Model, ModelBuilder, MotionOutput, NodeKind, NodeSource, WrittenNode};

/// A model file: the model and the initial-value problem it asks for.
pub struct MbdynModel {
    pub model: Model,
    pub problem: InitialValueProblem,
    /// Why beams that [`BeamUpdateRule::IncrementalWherePossible`] could not give MBDyn's
    /// incremental update keep the path-independent one (empty if none): a study makes each
    /// a warning.
    pub beam_notes: Vec<String>,
}

/// Reads an MBDyn input file into a model.
pub fn read_model(path: &Path) -> Result<MbdynModel, MbdynError> {
    read_model_with(path, ReadOptions::default())
}

/// Reads an MBDyn input file into a model with `options` ([`ReadOptions`]: `set:`
/// variables overridden, the beams' update; a bare `&SetOverrides` is accepted).
pub fn read_model_with<'o>(path: &Path, options: impl Into<ReadOptions<'o>>) -> Result<MbdynModel, MbdynError> {
    let options = options.into();
    checked(parse_file_with(path, options.overrides)?, options.beam_update)
}

/// [`read_model_with`] on the text of a file named `name` (includes resolve relative to its
/// folder): a sweep's work unit is the file's text, not a path another machine may lack.
pub fn read_model_text<'o>(text: &str, name: &Path, options: impl Into<ReadOptions<'o>>) -> Result<MbdynModel, MbdynError> {
    let options = options.into();
    checked(parse_text_with(text, name, options.overrides)?, options.beam_update)
}

fn checked(doc: Document, beam_update: BeamUpdateRule) -> Result<MbdynModel, MbdynError> {
    let m = build_with(&doc, beam_update)?;
    // An empty, blank or comments-only file would "run" and write empty outputs.
    if m.model.nodes.is_empty() && m.model.elements.is_empty() {
        let at = Span { file: 0, line: 1, column: 1 };
        return Err(doc.sources.error(at, "the file defines no nodes and no elements: there is no model to solve (expected 'begin: nodes;' and 'begin: elements;' blocks)"));
    }
    Ok(m)
}

const BLOCKS: [&str; 7] = ["data", "initial value", "control data", "nodes", "drivers", "elements", "inverse dynamics"];

fn block<'d>(doc: &'d Document, name: &str) -> Option<&'d Block> {
    doc.blocks.iter().find(|b| same_keyword(&b.name, name))
}

/// The entities cards define: frames, drive callers, constitutive laws.
#[derive(Default)]
struct Cards {
    frames: Frames,
    drives: Drives,
    laws: Laws,
    fluids: super::elements::context::Fluids,
}

fn cards(doc: &Document) -> Result<Cards, MbdynError> {
    let mut out = Cards::default();
    out.drives.variables = doc.variables.shared();
    // The structural nodes `model::` functions of string drives may read (drive callers are
    // read before the nodes): `structural: LABEL, KIND, …` with KIND not `dummy`.
    for st in block(doc, "nodes").map_or(&[][..], |b| &b.statements).iter().filter(|st| same_keyword(&st.keyword, "structural")) {
        let dummy = st.args.get(1).and_then(|a| a.keyword.as_deref()).is_some_and(|k| same_keyword(k, "dummy"));
        if let Some(super::syntax::parser::Arg { value: super::syntax::parser::Value::Number(x), .. }) = st.args.first()
            && !dummy
            && *x >= 0.0
            && x.fract() == 0.0
            && *x <= u32::MAX as f64
        {
            out.drives.structural_nodes.insert(*x as u32);
        }
    }
    out.drives.scalar_nodes = super::nodes::scalar::scan(block(doc, "nodes").map_or(&[][..], |b| &b.statements));
    out.drives.private.scan_parameter_nodes(block(doc, "nodes").map_or(&[][..], |b| &b.statements));
    for st in doc.cards.iter().filter(|st| known(&st.keyword, &["reference"]).is_some()) {
        if let Some(super::syntax::parser::Arg { value: super::syntax::parser::Value::Number(x), .. }) = st.args.first()
            && *x >= 0.0
            && x.fract() == 0.0
            && *x <= u32::MAX as f64
        {
            out.frames.announce(*x as u32, st.span);
        }
    }
    for st in block(doc, "drivers").map_or(&[][..], |b| &b.statements) {
        let mut c = Cursor::new(st, &doc.sources);
        if !same_keyword(&st.keyword, "file") {
            return Err(c.error_at(st.span, format!("'{}' in the drivers block is not supported by romdyn (supported: file)", st.keyword)));
        }
        super::drives::file_drivers::file_driver(st, &mut c, &mut out.drives.file_drivers)?;
    }
    for st in &doc.cards {
        let mut c = Cursor::new(st, &doc.sources);
        match known(&st.keyword, &CARDS) {
            Some("reference") => reference(st, &mut c, &mut out.frames)?,
            Some("drive caller") => {
                drive_caller_card(st, &mut c, &mut out.drives)?;
            }
            Some("template drive caller") => super::drives::templates::template_drive_caller_card(st, &mut c, &mut out.drives)?,
            Some("constitutive law") => constitutive_law_card(st, &mut c, &mut out.laws, &out.drives)?,
            Some("scalar function") => super::drives::scalar_functions::scalar_function_card(&mut c, &mut out.drives.functions, st.seq)?,
            Some("hydraulic fluid") => super::elements::hydraulic::fluid_card(&mut c, st.seq, &mut out.fluids)?,
            Some("setenv" | "print symbol table") => {}
            // mbdyn.cc, `ModuleLoad_int`: only an MBDyn built with libltdl loads modules (the
            // 1.7.3 built here stops: "dynamic modules not supported; libltdl support needed").
            Some("module load") => return Err(c.error_at(st.span, "the 'module load' card is not supported by romdyn (an MBDyn 1.7.3 built with run-time modules runs it, with the module it names)")),
            Some(other) => return Err(c.error_at(st.span, super::syntax::diagnostic::mbdyn_runs_it(&format!("the '{other}' card")))),
            None => return Err(c.error_at(st.span, format!("unknown card '{}'", st.keyword))),
        }
    }
    Ok(out)
}

/// `output meter: DRIVE` in control data (dataman3.cc, case OUTPUTMETER): the drive that
/// decides which steps are written; with `output frequency` MBDyn stops ("Output
/// meter/frequency already defined"), and so does romdyn.
fn output_meter(cd: Option<&Block>, src: &super::syntax::diagnostic::Sources, drives: &Drives) -> Result<Option<crate::element::drive::Drive>, MbdynError> {
    let mut meter = None;
    let mut seen: Option<Span> = None;
    for st in cd.map_or(&[][..], |b| &b.statements) {
        let Some(k) = known(&st.keyword, &["output meter", "output frequency"]) else { continue };
        if let Some(first) = seen {
            return Err(src.error(st.span, format!("'{k}': the output meter or frequency is already given (line {}), as MBDyn says", first.line)));
        }
        seen = Some(st.span);
        if k == "output meter" {
            let mut c = Cursor::new(st, src);
            meter = Some(super::drives::callers::drive(&mut c, drives, st.seq)?);
            c.finish()?;
        }
    }
    Ok(meter)
}

/// Builds the model from a parsed document.
pub fn build(doc: &Document) -> Result<MbdynModel, MbdynError> {
    build_with(doc, BeamUpdateRule::default())
}

/// [`build`] with the beams' update given by `beam_update`.
fn build_with(doc: &Document, beam_update: BeamUpdateRule) -> Result<MbdynModel, MbdynError> {
    let src = &doc.sources;
    let first = doc.blocks.first().map_or(Span::default(), |b| b.span);
    let mut seen: HashMap<&str, Span> = HashMap::new();
    for b in &doc.blocks {
        let Some(name) = known(&b.name, &BLOCKS) else {
            return Err(src.error(b.span, format!("block '{}' is not supported by romdyn", b.name)));
        };
        if name == "inverse dynamics" {
            return Err(src.error(b.span, super::syntax::diagnostic::mbdyn_runs_it("block 'inverse dynamics'")));
        }
        if let Some(prev) = seen.insert(name, b.span) {
            return Err(src.error(b.span, format!("block '{name}' appears twice (first at line {})", prev.line)));
        }
    }
    block_order(doc)?;
    // The data block is optional: MBDyn's problem defaults to the initial value problem.
    if let Some(data_block) = block(doc, "data") {
        data(data_block, src)?;
    }
    let cards = cards(doc)?;
    let mut problem = initial_value(block(doc, "initial value"), src, &cards.drives)?;
    let (counts, control_output, assembly) = control_data(block(doc, "control data"), src)?;
    // `model: static` (dataman3.cc): bodies are static bodies, on static nodes.
    let static_model = block(doc, "control data").is_some_and(|b| b.statements.iter().any(|st| same_keyword(&st.keyword, "model")));
    // `rigid body kinematics:` (the last one, as control data re-reads a repeated statement).
    let mut frame_motion = None;
    for st in block(doc, "control data").map_or(&[][..], |b| &b.statements).iter().filter(|st| same_keyword(&st.keyword, "rigid body kinematics")) {
        let mut c = Cursor::new(st, src);
        frame_motion = Some(std::sync::Arc::new(super::blocks::rbk::rigid_body_kinematics(&mut c, &cards.drives, &cards.frames, st.seq)?));
        c.finish()?;
    }
    let mut nodes = Nodes::default();
    let mut parameter_nodes = HashMap::new();
    for st in block(doc, "nodes").map_or(&[][..], |b| &b.statements) {
        let mut c = Cursor::new(st, src);
        if known(&st.keyword, &["parameter"]).is_some() {
            super::drives::element_reads::parameter_node(&mut c, &mut parameter_nodes)?;
        } else {
            node_statement(st, &mut c, &cards.frames, &mut nodes)?;
        }
    }
    // strnode.cc, `ReadStructNode`: in a static model MBDyn turns every dynamic node (and
    // dynamic displacement node) into a static one, after reading it as written (its
    // `accelerations` flag included): its bodies then only weigh (`StaticBody`, `StaticMass`).
    if static_model {
        for n in nodes.0.iter_mut().filter(|n| !n.dummy && n.node.kind == NodeKind::Dynamic) {
            n.node.kind = NodeKind::Static;
        }
    }
    // strnode.cc: a dynamic node computes its accelerations when it is output and asks for
    // them (or `default output: accelerations`); an offset dummy node when its base does, a
    // relative-frame one when both its nodes do.
    let mut written: Vec<WrittenNode> = Vec::with_capacity(nodes.0.len());
    for n in &nodes.0 {
        let output = n.output.unwrap_or(control_output.structural_nodes);
        let accelerations = match &n.source {
            NodeSource::Node(_) => n.node.kind == NodeKind::Dynamic && output && n.accelerations.unwrap_or(control_output.accelerations),
            NodeSource::Offset { base, .. } => written[*base].accelerations,
            NodeSource::RelativeFrame { base, reference } => written[*base].accelerations && written[*reference].accelerations,
        };
        written.push(WrittenNode { label: n.node.label, source: n.source.clone(), written: output, orientation: n.orientation.unwrap_or(control_output.orientation), accelerations });
    }
    problem.output = Some(MotionOutput {
        nodes: written,
        every: control_output.every,
        meter: output_meter(block(doc, "control data"), src, &cards.drives)?,
        precision: control_output.precision,
    });
    problem.assembly = assembly;
    problem.assembly.nodes = nodes.0.iter().filter(|n| !n.dummy).filter_map(|n| n.assembly.map(|a| (n.node.label, a))).collect();
    let mut b = ModelBuilder::new();
    for n in nodes.structural() {
        b.node(n.clone());
    }
    for n in &nodes.2 {
        let default = control_output.scalar_nodes[n.node.id.kind as usize];
        b.scalar_node(crate::model::ScalarNode { output: n.output.unwrap_or(default), ..n.node.clone() });
    }
    if let Some(f) = &frame_motion {
        b.frame_motion(f.clone());
    }
    for n in nodes.0.iter().filter(|n| n.displacement) {
        b.displacement_node(n.node.label);
    }
    for n in &nodes.0 {
        if let Some(name) = &n.name {
            b.node_name(n.node.label, name.clone());
        }
    }
    let mut found: HashMap<&'static str, (usize, Span)> = HashMap::new();
    found.insert("structural nodes", (nodes.0.len(), block(doc, "nodes").map_or(first, |b| b.span)));
    for (kind, counter) in [(crate::model::ScalarNodeKind::Abstract, "abstract nodes"), (crate::model::ScalarNodeKind::Electric, "electric nodes"), (crate::model::ScalarNodeKind::Hydraulic, "hydraulic nodes")] {
        if let Some(first_of_kind) = nodes.2.iter().find(|n| n.node.id.kind == kind) {
            found.insert(counter, (nodes.2.iter().filter(|n| n.node.id.kind == kind).count(), first_of_kind.span));
        }
    }
    found.insert("parameter nodes", (parameter_nodes.len(), block(doc, "nodes").map_or(first, |b| b.span)));
    if let Some(b) = block(doc, "drivers") {
        found.insert("file drivers", (cards.drives.file_drivers.len(), b.span));
    }
    let mut labels: HashMap<(&'static str, u32), Span> = HashMap::new();
    let mut gravity: Option<Span> = None;
    let mut central = None;
    let mut bodies = Vec::new();
    // Variable-mass bodies weigh in a uniform field only.
    let mut variable_bodies = Vec::new();
    let mut beams = super::elements::context::BeamNodes::new();
    let beam_notes = std::cell::RefCell::new(Vec::new());
    // Elements are kept until the block ends: a `bind` reads the ones above it.
    let mut built: Vec<(&'static str, Span, usize, Box<dyn crate::element::Element>)> = Vec::new();
    let mut output_only = std::collections::HashSet::new();
    let mut pending = super::elements::total_equation::Pending::default();
    let mut uses: HashMap<usize, Vec<String>> = HashMap::new();
    for st in block(doc, "elements").map_or(&[][..], |b| &b.statements) {
        let mut c = Cursor::new(st, src);
        if super::drives::element_reads::is_bind(&st.keyword) {
            let defined = built.iter().map(|(space, _, _, e)| (*space, e.label())).chain(output_only.iter().copied()).collect();
            super::drives::element_reads::bind(&mut c, &cards.drives.private, &defined)?;
            continue;
        }
        if known(&st.keyword, &["inertia"]).is_some()
            && let Some(super::syntax::parser::Arg { value: super::syntax::parser::Value::Number(x), .. }) = st.args.first()
            && *x >= 0.0
            && x.fract() == 0.0
            && *x <= u32::MAX as f64
        {
            output_only.insert(("inertia", *x as u32));
        }
        let ctx = ElementContext { nodes: &nodes, frames: &cards.frames, drives: &cards.drives, laws: &cards.laws, fluids: &cards.fluids, beams: &beams, seq: st.seq, static_model, beam_update, beam_notes: &beam_notes, hydraulic_output: control_output.hydraulic_elements };
        let label_span = c.here();
        cards.drives.functions.take_used();
        let parsed = element(st, &mut c, &ctx)?;
        let used = cards.drives.functions.take_used();
        if !used.is_empty() {
            uses.insert(st.seq, cards.drives.functions.described(&used, |at| place(src, at)));
        }
        let parsed = match &st.driven {
            Some(head) => super::elements::driven::wrap(head, parsed, src, &ctx)?,
            None => parsed,
        };
        let parsed = match parsed {
            Parsed::Body(mut body) => {
                // body.cc (ReadBody): in a static model a body sits on a static node (every
                // dynamic one has turned static above) and only weighs (`StaticBody`), as
                // romdyn's body on a static node.
                bodies.push((body.label, body.node, body.mass, body.offset));
                body.frame = frame_motion.clone();
                Parsed::Element(Box::new(body))
            }
            Parsed::Element(e) if e.type_name() == "variable body" => {
                if frame_motion.is_some() {
                    return Err(src.error(st.span, "a variable-mass body in a model with 'rigid body kinematics' is not supported by romdyn (MBDyn 1.7.3 runs it)"));
                }
                variable_bodies.push(st.span);
                Parsed::Element(e)
            }
            p => p,
        };
        c.finish()?;
        if let Some(kind) = counted_kind(&st.keyword) {
            found.entry(kind).or_insert((0, st.span)).0 += 1;
        }
        match parsed {
            Parsed::Gravity(g) => {
                if let Some(prev) = gravity.replace(st.span) {
                    return Err(src.error(st.span, format!("gravity is defined twice (first at line {})", prev.line)));
                }
                b.gravity(g);
            }
            Parsed::CentralGravity { origin, gm } => {
                if let Some(prev) = gravity.replace(st.span) {
                    return Err(src.error(st.span, format!("gravity is defined twice (first at line {})", prev.line)));
                }
                central = Some(Field::Central { origin, gm });
            }
            Parsed::DrivenGravity { direction, drive } => {
                if let Some(prev) = gravity.replace(st.span) {
                    return Err(src.error(st.span, format!("gravity is defined twice (first at line {})", prev.line)));
                }
                central = Some(Field::Driven { direction, drive });
            }
            Parsed::Body(_) => unreachable!("bodies are turned into elements above"),
            Parsed::Element(e) => {
                let on = e.nodes();
                // strforce.cc, `ReadStructuralForce`, reads the two nodes of an absolute or
                // follower internal force or couple without comparing them: on one node the
                // pair acts on it twice (a couple cancels, a force leaves the moment of its
                // two arms), as in MBDyn's tests/forces/force/force-old.
                let one_node_allowed = matches!(e.type_name(), "absolute internal force" | "follower internal force" | "absolute internal couple" | "follower internal couple");
                if let Some(n) = on.iter().enumerate().find(|(k, n)| on[..*k].contains(n)).map(|(_, n)| n).filter(|_| !one_node_allowed) {
                    return Err(src.error(label_span, format!("{} {} connects node {n} to itself", e.type_name(), e.label())));
                }
                let space = label_space(&st.keyword);
                if let Some(prev) = labels.insert((space, e.label()), st.span) {
                    return Err(src.error(label_span, format!("{space} {} is defined twice (first at line {})", e.label(), prev.line)));
                }
                if let ("beam", &[n1, n2, n3]) = (space, &on[..]) {
                    beams.insert(e.label(), [n1, n2, n3]);
                }
                built.push((space, st.span, st.seq, e));
            }
            Parsed::TotalEquation(j) => {
                if let Some(prev) = labels.insert(("joint", crate::element::Element::label(&j)), st.span) {
                    return Err(src.error(label_span, format!("joint {} is defined twice (first at line {})", crate::element::Element::label(&j), prev.line)));
                }
                pending.equation(j, st.span, st.seq);
            }
            Parsed::TotalReaction { reaction, equation, span } => {
                if let Some(prev) = labels.insert(("joint", reaction.label), st.span) {
                    return Err(src.error(label_span, format!("joint {} is defined twice (first at line {})", reaction.label, prev.line)));
                }
                pending.reaction(src, reaction, equation, span)?;
            }
            Parsed::Regularization { joint, c, span } => pending.regularization(joint, c, span),
            Parsed::Ignored => {}
        }
    }
    pending.finish(src, &mut built)?;
    let defined = built.iter().map(|(space, at, seq, e)| ((*space, e.label()), (e.as_ref(), *at, *seq))).collect();
    let memories = cards.drives.private.resolve(src, &defined)?;
    for (_, at, seq, e) in built {
        b.element_from(e, place(src, at));
        b.element_uses(uses.remove(&seq).unwrap_or_default());
    }
    // A central or time-varying field acts on every body at its node (gravity.cc, body.cc).
    if let (Some(_), Some(at)) = (&central, variable_bodies.first()) {
        return Err(src.error(*at, "a variable-mass body in a central or time-varying gravity field is not supported by romdyn (MBDyn 1.7.3 runs it) (only in a uniform one)"));
    }
    if let Some(field) = central {
        for (label, node, mass, offset) in bodies {
            b.boxed_element(match &field {
                Field::Central { origin, gm } => Box::new(crate::element::CentralGravity { label, node, mass, offset, origin: *origin, gm: *gm }),
                Field::Driven { direction, drive } => Box::new(crate::element::DrivenGravity { label, node, mass, offset, direction: *direction, drive: drive.clone() }),
            });
        }
    }
    check_counts(doc, &counts, &found)?;
    b.step_drives(cards.drives.take_stepped());
    b.step_drives(memories);
    let model = b.build().map_err(|e| src.error(first, e.to_string()))?;
    Ok(MbdynModel { model, problem, beam_notes: beam_notes.into_inner() })
}

/// A gravity field romdyn applies body by body (a constant uniform field is the model's).
enum Field {
    Central { origin: crate::kinematics::Vec3, gm: f64 },
    Driven { direction: crate::kinematics::Vec3, drive: crate::element::drive::Drive },
}

/// MBDyn's data manager reads `control data`, then `nodes`, `drivers` and `elements` in
/// this order (mbdyn/base/dataman.cc: "<begin: nodes;> expected"); romdyn refuses the
/// same files.
fn block_order(doc: &Document) -> Result<(), MbdynError> {
    const ORDER: [&str; 4] = ["control data", "nodes", "drivers", "elements"];
    let mut last: Option<(usize, &Block)> = None;
    for b in &doc.blocks {
        let Some(rank) = ORDER.iter().position(|o| same_keyword(o, &b.name)) else { continue };
        if let Some((prev, pb)) = last.filter(|(prev, _)| *prev > rank) {
            return Err(doc.sources.error(b.span, format!("block '{}' must come before '{}' (line {}): MBDyn reads control data, nodes, drivers and elements in this order", ORDER[rank], ORDER[prev], pb.span.line)));
        }
        last = Some((rank, b));
    }
    Ok(())
}

/// Errors unless every kind found in the model is declared in control data with its
/// number, and every declared number is matched.
fn check_counts(doc: &Document, counts: &Counts, found: &HashMap<&'static str, (usize, Span)>) -> Result<(), MbdynError> {
    let src = &doc.sources;
    for kind in COUNTED {
        let have = found.get(kind).map_or(0, |x| x.0);
        match (counts.get(kind), found.get(kind)) {
            (Some((declared, span)), _) if *declared != have => {
                return Err(src.error(*span, format!("control data declares {declared} {kind}, the model has {have}")));
            }
            (None, Some((n, span))) if *n > 0 && kind != "automatic structural elements" => {
                return Err(src.error(*span, format!("the model has {n} {kind}, but control data does not declare '{kind}'")));
            }
            _ => {}
        }
    }
    Ok(())
}

/// `file:line:col` of `at`, as run-time messages name a card.
fn place(src: &super::syntax::diagnostic::Sources, at: Span) -> String {
    let origin = src.error(at, "");
    format!("{}:{}:{}", origin.file.display(), origin.line, origin.column)
}
