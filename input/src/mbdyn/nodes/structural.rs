//! The `nodes` block (input manual, "Nodes", §Structural Node): `structural: LABEL,
//! {static | dynamic}, [position,] X, [orientation,] R, [velocity,] V, [angular velocity,]
//! W` (each optionally in a `reference`), or `at reference, LABEL`; then the optional
//! `assembly`, `scale`, `output` and `accelerations` settings (`assembly` sets the node's
//! initial-assembly penalties, `scale` is ignored, `output` selects the node's `.mov` rows,
//! `accelerations, yes` on a dynamic node appends its accelerations to them).
//! A node label may be followed by `name, "…"`. `dummy` nodes carry no unknowns: they are
//! counted, kept out of the model, and written to the motion file from their base node
//! (which may itself be a dummy node). `output: structural, LABEL | range, A, B, …;` turns
//! the output of those nodes on (dataman3.cc, `DataManager::ReadNodes`).

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Span};
use crate::mbdyn::syntax::parser::{known, Statement};
use crate::mbdyn::syntax::references::{Context, Frame, Frames};
use super::scalar::{scalar_node, ScalarEntry, SCALAR_TYPES};
use crate::model::{Label, NodeAssembly, NodeKind, NodeSource, OrientationOutput, StructuralNode};
use crate::mbdyn::syntax::diagnostic;

/// A node of the file: a structural node of the model, or a dummy node.
#[derive(Clone, Debug)]
pub struct NodeEntry {
    /// For a dummy node, its initial kinematics (with the base node's kind).
    pub node: StructuralNode,
    pub dummy: bool,
    pub span: Span,
    /// Where its motion-file rows come from.
    pub source: NodeSource,
    /// `output, yes | no` (`None`: the `default output` of control data).
    pub output: Option<bool>,
    /// `orientation description, …` (`None`: the `default orientation` of control data).
    pub orientation: Option<OrientationOutput>,
    /// `assembly, POSITION, VELOCITY, OMEGA_ROTATES`: its own initial-assembly penalties.
    pub assembly: Option<NodeAssembly>,
    /// `name, "…"` after the label.
    pub name: Option<String>,
    /// `accelerations, yes | no` (dynamic nodes only; `None`: the `default output` of
    /// control data).
    pub accelerations: Option<bool>,
    /// A `static displacement` or `dynamic displacement` node (no rotations).
    pub displacement: bool,
    /// A `modal` node (a dynamic node that a `modal` joint's floating frame follows).
    pub modal: bool,
}

/// The structural nodes, in file order, and where each label is in it (a search through
/// the list at every node made N nodes O(N²) to read: 1.6 min for 10^5); then the scalar
/// nodes (abstract, electric, hydraulic), in file order.
#[derive(Default)]
pub struct Nodes(pub Vec<NodeEntry>, std::collections::HashMap<Label, usize>, pub Vec<ScalarEntry>);

impl Nodes {
    pub fn find(&self, label: Label) -> Option<&NodeEntry> {
        self.1.get(&label).and_then(|&k| self.0.get(k))
    }
    /// The nodes that carry unknowns.
    pub fn structural(&self) -> impl Iterator<Item = &StructuralNode> {
        self.0.iter().filter(|n| !n.dummy).map(|n| &n.node)
    }
}

const NODE_TYPES: [&str; 6] = ["abstract", "electric", "hydraulic", "parameter", "thermal", "structural"];

/// Reads one statement of the `nodes` block.
pub fn node_statement(st: &Statement, c: &mut Cursor, frames: &Frames, nodes: &mut Nodes) -> Result<(), MbdynError> {
    if known(&st.keyword, &["output"]).is_some() {
        return output_card(c, nodes);
    }
    match known(&st.keyword, &NODE_TYPES) {
        Some("structural") => {}
        Some(kind) if SCALAR_TYPES.contains(&kind) => {
            let entry = scalar_node(kind, c, st.span, &nodes.2)?;
            nodes.2.push(entry);
            return c.finish();
        }
        Some(other) => return Err(c.error_at(st.span, diagnostic::mbdyn_runs_it(&format!("node type '{other}'")))),
        None => return Err(c.error_at(st.span, format!("unknown node type '{}' (MBDyn's are {})", st.keyword, NODE_TYPES.join(", ")))),
    }
    let label_span = c.here();
    let label = c.label("node label")?;
    if let Some(prev) = nodes.find(label) {
        return Err(c.error_at(label_span, format!("structural node {label} is defined twice (first at line {})", prev.span.line)));
    }
    let name = if c.accept("name") { Some(c.string("node name")?) } else { None };
    let kind_span = c.here();
    let kind = c.keyword("the node type", &["static", "dynamic", "dummy", "modal", "static displacement", "dynamic displacement"])?;
    let ctx = Context::global(frames, st.seq);
    let (node, dummy, source, orientation) = match kind {
        // A modal node is a dynamic node (strnode.cc, `ModalNode`: a `DynamicStructNode`
        // with velocities as unknowns where romdyn's has momenta; the same motion).
        "static" | "dynamic" | "modal" => {
            let (node, orientation) = structural(c, &ctx, label, if kind == "static" { NodeKind::Static } else { NodeKind::Dynamic })?;
            (node, false, NodeSource::Node(label), orientation)
        }
        "dummy" => {
            let (node, source, orientation) = dummy(c, &ctx, label, nodes)?;
            (node, true, source, orientation)
        }
        "static displacement" | "dynamic displacement" => {
            let node = displacement(c, &ctx, label, if kind == "static displacement" { NodeKind::Static } else { NodeKind::Dynamic })?;
            (node, false, NodeSource::Node(label), None)
        }
        _ => return Err(c.error_at(kind_span, format!("'{kind}' structural nodes are not supported by romdyn (supported: static, dynamic, modal, dummy, static displacement, dynamic displacement)"))),
    };
    let modal = kind == "modal";
    let (output, assembly, accelerations) = settings(c, kind)?;
    let displacement = kind.ends_with("displacement");
    // strnode.cc, `ReadStructNode`: after the settings, anything but ';' stops MBDyn too
    // (e.g. the initial-assembly stiffnesses written without the `assembly` keyword).
    c.finish().map_err(|mut e| {
        e.message.push_str(&format!(" (after the velocities a structural node takes only 'assembly, …', 'scale, …', 'output, …', 'accelerations, …'); MBDyn 1.7.3 does not read it either (its reader stops: \"ReadStructNode({label}): semicolon expected\")"));
        e
    })?;
    nodes.1.entry(label).or_insert(nodes.0.len());
    nodes.0.push(NodeEntry { node, dummy, span: st.span, source, output, orientation, assembly, name, accelerations, displacement, modal });
    Ok(())
}

/// `output: structural [, accelerations], {LABEL | range, FIRST, LAST} …;`: those nodes'
/// output on (labels that name no node are skipped, as MBDyn does with a warning).
fn output_card(c: &mut Cursor, nodes: &mut Nodes) -> Result<(), MbdynError> {
    let kind = c.keyword("a node type", &NODE_TYPES)?;
    if SCALAR_TYPES.contains(&kind) {
        return scalar_output_card(kind, c, nodes);
    }
    if kind != "structural" {
        // Nodes romdyn does not read have no rows to switch on.
        c.skip_rest();
        return Ok(());
    }
    c.accept("accelerations");
    while !c.is_done() {
        let (first, last) = if c.accept("range") {
            let span = c.here();
            let (a, b) = (c.label("first node label")?, c.label("last node label")?);
            if b < a {
                return Err(c.error_at(span, format!("output: range end {b} is before its start {a}")));
            }
            (a, b)
        } else {
            let l = c.label("node label (or range)")?;
            (l, l)
        };
        for n in nodes.0.iter_mut().filter(|n| (first..=last).contains(&n.node.label)) {
            n.output = Some(true);
        }
    }
    Ok(())
}

/// `output: abstract | electric | hydraulic, {LABEL | range, FIRST, LAST} …;`.
fn scalar_output_card(kind: &str, c: &mut Cursor, nodes: &mut Nodes) -> Result<(), MbdynError> {
    while !c.is_done() {
        let (first, last) = if c.accept("range") {
            (c.label("first node label")?, c.label("last node label")?)
        } else {
            let l = c.label("node label (or range)")?;
            (l, l)
        };
        for n in nodes.2.iter_mut().filter(|n| n.node.id.kind.keyword() == kind && (first..=last).contains(&n.node.id.label)) {
            n.output = Some(true);
        }
    }
    Ok(())
}

fn structural(c: &mut Cursor, ctx: &Context, label: Label, kind: NodeKind) -> Result<(StructuralNode, Option<OrientationOutput>), MbdynError> {
    if c.accept("at reference") {
        let span = c.here();
        let r = c.label("reference label")?;
        let f = ctx.frames.get(r, ctx.seq, span, c, None)?;
        let od = orientation_description(c)?;
        return Ok((StructuralNode { label, kind, position: f.x, orientation: f.r, velocity: f.v, angular_velocity: f.w }, od));
    }
    c.accept("position");
    let position = ctx.position(c, "node position [m]")?;
    c.accept("orientation");
    let orientation = ctx.orientation(c, "node orientation")?;
    let od = orientation_description(c)?;
    c.accept("velocity");
    let velocity = ctx.velocity(c, "node velocity [m/s]", &position)?;
    c.accept("angular velocity");
    let angular_velocity = ctx.angular_velocity(c, "node angular velocity [rad/s]")?;
    Ok((StructuralNode { label, kind, position, orientation, velocity, angular_velocity }, od))
}

/// `static displacement | dynamic displacement, [position,] X, [velocity,] V` (strnode.cc,
/// `ReadStructNode` with `bDisp`): a point without orientation (kept the identity).
fn displacement(c: &mut Cursor, ctx: &Context, label: Label, kind: NodeKind) -> Result<StructuralNode, MbdynError> {
    if c.accept("at reference") {
        return Err(c.error("'at reference' on a displacement node is not supported by romdyn (MBDyn 1.7.3 runs it) (write its position and velocity)"));
    }
    c.accept("position");
    let position = ctx.position(c, "node position [m]")?;
    c.accept("velocity");
    let velocity = ctx.velocity(c, "node velocity [m/s]", &position)?;
    Ok(StructuralNode { label, kind, position, orientation: crate::kinematics::Mat3::identity(), velocity, angular_velocity: crate::kinematics::Vec3::zeros() })
}

fn orientation_description(c: &mut Cursor) -> Result<Option<OrientationOutput>, MbdynError> {
    if c.accept("orientation description") {
        return orientation_kind(c).map(Some);
    }
    Ok(None)
}

/// `euler123 | euler313 | euler321 | orientation vector | orientation matrix` (input
/// manual, "Orientation description"; `euler` alone is 1-2-3).
pub fn orientation_kind(c: &mut Cursor) -> Result<OrientationOutput, MbdynError> {
    Ok(match c.keyword("an orientation description", &["euler123", "euler 123", "euler313", "euler 313", "euler321", "euler 321", "euler", "orientation vector", "orientation matrix"])? {
        "euler313" | "euler 313" => OrientationOutput::Euler313Degrees,
        "euler321" | "euler 321" => OrientationOutput::Euler321Degrees,
        "orientation vector" => OrientationOutput::RotationVector,
        "orientation matrix" => OrientationOutput::Matrix,
        _ => OrientationOutput::Euler123Degrees,
    })
}

/// `dummy, BASE, offset, OFFSET, ORIENTATION` (the base may be a dummy node) or `dummy,
/// BASE, relative frame, REF`: the node's initial kinematics and where its rows come from.
fn dummy(c: &mut Cursor, ctx: &Context, label: Label, nodes: &Nodes) -> Result<(StructuralNode, NodeSource, Option<OrientationOutput>), MbdynError> {
    let span = c.here();
    let base_label = c.label("base node label")?;
    let Some(base) = nodes.0.iter().position(|n| n.node.label == base_label) else {
        return Err(c.error_at(span, format!("structural node {base_label} is not defined (a dummy node must follow its base node)")));
    };
    if nodes.0[base].displacement {
        return Err(c.error_at(span, format!("structural node {base_label} is a displacement node (no orientation): a dummy node needs a base with rotations (MBDyn 1.7.3 reads the base as a 6-DoF StructNode)")));
    }
    let b = &nodes.0[base].node;
    let on_base = Context { node: Some(Frame::of_node(b)), ..*ctx };
    match c.keyword("the dummy node type", &["offset", "relative frame"])? {
        "offset" => {
            let offset = on_base.relative_position(c, "dummy node offset [m]")?;
            let orientation = on_base.relative_orientation(c, "dummy node orientation")?;
            let od = orientation_description(c)?;
            let arm = b.orientation * offset;
            let node = StructuralNode {
                label,
                position: b.position + arm,
                orientation: b.orientation * orientation,
                velocity: b.velocity + b.angular_velocity.cross(&arm),
                ..b.clone()
            };
            Ok((node, NodeSource::Offset { base, offset, orientation }, od))
        }
        _ => {
            let r = c.here();
            let reference_label = c.label("reference node label")?;
            let Some(reference) = nodes.0.iter().position(|n| n.node.label == reference_label) else {
                return Err(c.error_at(r, format!("structural node {reference_label} is not defined")));
            };
            if nodes.0[reference].displacement {
                return Err(c.error_at(r, format!("structural node {reference_label} is a displacement node (no orientation): a relative frame needs a node with rotations")));
            }
            if let Some(k) = c.accept_any(&["position", "orientation", "pivot node"]) {
                return Err(c.error(format!("'{k}' of a relative-frame dummy node is not supported by romdyn (supported: dummy, BASE, relative frame, REFERENCE)")));
            }
            // MBDyn 1.7.3 reads no `orientation description` here (only after an
            // `orientation`, which romdyn refuses) and writes the rows without orientation
            // columns; romdyn still takes one, and then writes the orientation.
            let od = Some(orientation_description(c)?.unwrap_or(OrientationOutput::Unwritten));
            let f = &nodes.0[reference].node;
            let (rt, d) = (f.orientation.transpose(), b.position - f.position);
            let node = StructuralNode {
                label,
                position: rt * d,
                orientation: rt * b.orientation,
                velocity: rt * (b.velocity - f.velocity - f.angular_velocity.cross(&d)),
                angular_velocity: rt * (b.angular_velocity - f.angular_velocity),
                ..b.clone()
            };
            Ok((node, NodeSource::RelativeFrame { base, reference }, od))
        }
    }
}

/// `assembly, …`, `scale, …`, `output, …`, `accelerations, …`: the node's output flag,
/// initial-assembly settings and accelerations flag, returned (`scale`, a residual scaling,
/// is ignored). MBDyn 1.7.3 reads `accelerations` on dynamic nodes only (strnode.cc,
/// `ReadStructNode`); on the others its reader stops at the keyword, and so does romdyn's.
fn settings(c: &mut Cursor, kind: &str) -> Result<(Option<bool>, Option<NodeAssembly>, Option<bool>), MbdynError> {
    let mut output = None;
    let mut assembly = None;
    let mut accelerations = None;
    loop {
        if c.accept("assembly") {
            let position_stiffness = c.real("position initial stiffness")?;
            let velocity_stiffness = c.real("velocity initial stiffness")?;
            // strnode.cc: a displacement node has no `omega rotates` flag.
            let omega_rotates = if kind.ends_with("displacement") { false } else { c.flag("omega rotates")? };
            assembly = Some(NodeAssembly { position_stiffness, velocity_stiffness, omega_rotates });
        } else if c.accept("scale") {
            if !c.accept("default") {
                c.real("residual scale factor")?;
            }
        } else if c.accept("output") {
            output = Some(c.flag("output flag")?);
        } else if let (span, true) = (c.here(), c.accept("accelerations")) {
            if !matches!(kind, "dynamic" | "dynamic displacement" | "modal") {
                return Err(c.error_at(span, format!("'accelerations' is read on dynamic structural nodes only, not on a {kind} node (MBDyn 1.7.3 stops there too: \"semicolon expected\"; its static nodes have no momenta to differentiate, a dummy node writes accelerations when its base node does)")));
            }
            if accelerations.is_some() {
                return Err(c.error_at(span, "'accelerations' is set twice for this node (MBDyn 1.7.3 refuses it too: \"accelerations\" already set)"));
            }
            accelerations = Some(c.flag("accelerations flag")?);
        } else {
            return Ok((output, assembly, accelerations));
        }
    }
}
