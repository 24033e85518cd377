//! The `nodes` block (input manual, "Nodes", §Structural Node): `structural: LABEL,
//! {static | dynamic}, [position,] X, [orientation,] R, [velocity,] V, [angular velocity,]
//! W` (each optionally in a `reference`), or `at reference, LABEL`; then the optional
//! `assembly`, `scale`, `output` and `accelerations` settings, which only tune MBDyn's
//! initial assembly and output and are ignored. `dummy` nodes carry no unknowns (they only
//! produce output in MBDyn): they are counted and kept out of the model.

use super::cursor::Cursor;
use super::diagnostic::{MbdynError, Span};
use super::parser::{known, Statement};
use super::references::{Context, Frame, Frames};
use crate::model::{Label, NodeKind, StructuralNode};

/// A node of the file: a structural node of the model, or a dummy node.
#[derive(Clone, Debug)]
pub struct NodeEntry {
    pub node: StructuralNode,
    pub dummy: bool,
    pub span: Span,
}

/// The structural nodes, in file order.
#[derive(Default)]
pub struct Nodes(pub Vec<NodeEntry>);

impl Nodes {
    pub fn find(&self, label: Label) -> Option<&NodeEntry> {
        self.0.iter().find(|n| n.node.label == label)
    }
    /// The nodes that carry unknowns.
    pub fn structural(&self) -> impl Iterator<Item = &StructuralNode> {
        self.0.iter().filter(|n| !n.dummy).map(|n| &n.node)
    }
}

const NODE_TYPES: [&str; 6] = ["abstract", "electric", "hydraulic", "parameter", "thermal", "structural"];

/// Reads one statement of the `nodes` block.
pub fn node_statement(st: &Statement, c: &mut Cursor, frames: &Frames, nodes: &mut Nodes) -> Result<(), MbdynError> {
    match known(&st.keyword, &NODE_TYPES) {
        Some("structural") => {}
        Some(other) => return Err(c.error_at(st.span, format!("node type '{other}' is not supported by romdyn"))),
        None => return Err(c.error_at(st.span, format!("unknown node type '{}' (MBDyn's are {})", st.keyword, NODE_TYPES.join(", ")))),
    }
    let label_span = c.here();
    let label = c.label("node label")?;
    if let Some(prev) = nodes.find(label) {
        return Err(c.error_at(label_span, format!("structural node {label} is defined twice (first at line {})", prev.span.line)));
    }
    let kind_span = c.here();
    let kind = c.keyword("the node type", &["static", "dynamic", "dummy", "modal", "static displacement", "dynamic displacement"])?;
    let ctx = Context::global(frames, st.seq);
    let entry = match kind {
        "static" | "dynamic" => NodeEntry { node: structural(c, &ctx, label, if kind == "static" { NodeKind::Static } else { NodeKind::Dynamic })?, dummy: false, span: st.span },
        "dummy" => NodeEntry { node: dummy(c, &ctx, label, nodes)?, dummy: true, span: st.span },
        _ => return Err(c.error_at(kind_span, format!("'{kind}' structural nodes are not supported by romdyn (supported: static, dynamic, dummy)"))),
    };
    settings(c)?;
    c.finish()?;
    nodes.0.push(entry);
    Ok(())
}

fn structural(c: &mut Cursor, ctx: &Context, label: Label, kind: NodeKind) -> Result<StructuralNode, MbdynError> {
    if c.accept("at reference") {
        let span = c.here();
        let r = c.label("reference label")?;
        let f = ctx.frames.get(r, ctx.seq, span, c, None)?;
        orientation_description(c)?;
        return Ok(StructuralNode { label, kind, position: f.x, orientation: f.r, velocity: f.v, angular_velocity: f.w });
    }
    c.accept("position");
    let position = ctx.position(c, "node position [m]")?;
    c.accept("orientation");
    let orientation = ctx.orientation(c, "node orientation")?;
    orientation_description(c)?;
    c.accept("velocity");
    let velocity = ctx.velocity(c, "node velocity [m/s]", &position)?;
    c.accept("angular velocity");
    let angular_velocity = ctx.angular_velocity(c, "node angular velocity [rad/s]")?;
    Ok(StructuralNode { label, kind, position, orientation, velocity, angular_velocity })
}

fn orientation_description(c: &mut Cursor) -> Result<(), MbdynError> {
    if c.accept("orientation description") {
        c.keyword("an orientation description", &["euler123", "euler313", "euler321", "orientation vector", "orientation matrix"])?;
    }
    Ok(())
}

/// `dummy, BASE, offset, OFFSET, ORIENTATION` or `dummy, BASE, relative frame, …`: read
/// for the count and the labels; it contributes nothing to the model.
fn dummy(c: &mut Cursor, ctx: &Context, label: Label, nodes: &Nodes) -> Result<StructuralNode, MbdynError> {
    let span = c.here();
    let base = c.label("base node label")?;
    let Some(b) = nodes.find(base).filter(|b| !b.dummy) else {
        return Err(c.error_at(span, format!("structural node {base} is not defined (a dummy node must follow its base node)")));
    };
    let on_base = Context { node: Some(Frame::of_node(&b.node)), ..*ctx };
    match c.keyword("the dummy node type", &["offset", "relative frame"])? {
        "offset" => {
            on_base.relative_position(c, "dummy node offset [m]")?;
            on_base.relative_orientation(c, "dummy node orientation")?;
            orientation_description(c)?;
        }
        _ => {
            let r = c.here();
            let reference = c.label("reference node label")?;
            if nodes.find(reference).is_none() {
                return Err(c.error_at(r, format!("structural node {reference} is not defined")));
            }
            c.skip_rest();
        }
    }
    Ok(StructuralNode { label, ..b.node.clone() })
}

/// `assembly, …`, `scale, …`, `output, …`, `accelerations, …`: MBDyn's initial assembly
/// and output settings, ignored by romdyn.
fn settings(c: &mut Cursor) -> Result<(), MbdynError> {
    loop {
        if c.accept("assembly") {
            c.real("position initial stiffness")?;
            c.real("velocity initial stiffness")?;
            c.flag("omega rotates")?;
        } else if c.accept("scale") {
            if !c.accept("default") {
                c.real("residual scale factor")?;
            }
        } else if c.accept("output") || c.accept("accelerations") {
            c.flag("output flag")?;
        } else {
            return Ok(());
        }
    }
}
