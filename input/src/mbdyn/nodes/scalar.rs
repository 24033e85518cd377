//! Scalar nodes in the `nodes` block (input manual §Nodes: Electric Node, Abstract Node,
//! Hydraulic Node; dataman3.cc, `ReadScalarAlgebraicNode`, `ReadScalarDifferentialNode`):
//!
//! ```text
//! abstract: LABEL [, name, "…"], [algebraic | differential] [, [value,] X [, derivative, XP]]
//!     [, scale, …] [, output, FLAG];
//! electric: LABEL, [[value,] X [, derivative, XP]] …;      (differential)
//! hydraulic: LABEL, [[value,] P] …;                          (algebraic, a pressure)
//! ```
//!
//! and the scalar degrees of freedom (`ScalarDof`, dataman3.cc `ReadScalarDof`) that genels
//! and abstract forces read: `LABEL, TYPE [, algebraic | differential | order, N]`, the
//! order being read (and required) on a differential node only.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Span};
use crate::element::ScalarDof;
use crate::model::{ScalarNode, ScalarNodeId, ScalarNodeKind};
use crate::mbdyn::syntax::parser;

/// A scalar node of the file.
#[derive(Clone, Debug)]
pub struct ScalarEntry {
    pub node: ScalarNode,
    pub span: Span,
    /// `output, yes | no` (`None`: control data's `default output`).
    pub output: Option<bool>,
}

/// The node types that are scalar nodes with an unknown.
pub const SCALAR_TYPES: [&str; 3] = ["abstract", "electric", "hydraulic"];

fn kind_of(keyword: &str) -> ScalarNodeKind {
    match keyword {
        "electric" => ScalarNodeKind::Electric,
        "hydraulic" => ScalarNodeKind::Hydraulic,
        _ => ScalarNodeKind::Abstract,
    }
}

/// The scalar nodes a nodes block declares, each with whether it is differential (a scan
/// before the drive callers are read, which the nodes follow in MBDyn's files).
pub fn scan(nodes: &[parser::Statement]) -> std::collections::HashMap<ScalarNodeId, bool> {
    let mut out = std::collections::HashMap::new();
    for st in nodes {
        let Some(keyword) = parser::known(&st.keyword, &SCALAR_TYPES) else { continue };
        if let Some(parser::Arg { value: parser::Value::Number(x), .. }) = st.args.first()
            && *x >= 0.0
            && x.fract() == 0.0
            && *x <= u32::MAX as f64
        {
            let kind = kind_of(keyword);
            let algebraic = kind == ScalarNodeKind::Hydraulic || (kind == ScalarNodeKind::Abstract && st.args.iter().take(4).any(|a| a.keyword.as_deref().is_some_and(|k| parser::same_keyword(k, "algebraic"))));
            out.insert(ScalarNodeId { kind, label: *x as u32 }, !algebraic);
        }
    }
    out
}

/// Reads one `abstract`, `electric` or `hydraulic` node card (its keyword is `keyword`).
pub fn scalar_node(keyword: &'static str, c: &mut Cursor, span: Span, defined: &[ScalarEntry]) -> Result<ScalarEntry, MbdynError> {
    let kind = kind_of(keyword);
    let label_span = c.here();
    let label = c.label(&format!("{keyword} node label"))?;
    let id = ScalarNodeId { kind, label };
    if let Some(prev) = defined.iter().find(|e| e.node.id == id) {
        return Err(c.error_at(label_span, format!("{id} is defined twice (first at line {})", prev.span.line)));
    }
    // dataman3.cc reads a hydraulic node with `ReadScalarAlgebraicNode(…, Node::ABSTRACT, …)`,
    // which looks the label up among the abstract nodes defined above it.
    if let Some(prev) = defined.iter().find(|e| kind == ScalarNodeKind::Hydraulic && e.node.id == ScalarNodeId { kind: ScalarNodeKind::Abstract, label }) {
        return Err(c.error_at(label_span, format!("hydraulic node {label} has the label of abstract node {label} (line {}): MBDyn 1.7.3 refuses it (\"Abstract({label}) already defined\": its reader checks a hydraulic node's label among the abstract nodes)", prev.span.line)));
    }
    // `name, "…"` is read and kept by MBDyn for messages only.
    if c.accept("name") {
        c.string("node name")?;
    }
    let differential = match kind {
        ScalarNodeKind::Abstract => !matches!(c.accept_any(&["algebraic", "differential"]), Some("algebraic")),
        ScalarNodeKind::Electric => true,
        ScalarNodeKind::Hydraulic => false,
    };
    let (mut value, mut derivative) = (0.0, 0.0);
    // MBDyn reads a value whenever an argument follows (`value` optional; dataman3.cc
    // `ReadScalarAlgebraicNode`: `if (HP.IsArg())`), so `output` or `scale` right after the
    // node type stop it too; then, on a differential node, `derivative, XP`.
    if !c.is_done() {
        c.accept("value");
        value = c.real(&format!("initial value of {id} (MBDyn 1.7.3 reads a value whenever an argument follows the node type)"))?;
        if differential && c.accept("derivative") {
            derivative = c.real(&format!("initial derivative of {id}"))?;
        }
    }
    if c.accept("derivative") {
        let what = if differential { "a derivative is read after a value ('value, X, derivative, XP')" } else { "an algebraic node has no derivative" };
        return Err(c.error(format!("{id}: {what} (MBDyn 1.7.3 reads 'derivative' only after 'value' on a differential node)")));
    }
    let mut output = None;
    loop {
        if c.accept("scale") {
            if !c.accept("default") {
                c.real("residual scale factor")?;
            }
        } else if c.accept("output") {
            output = Some(c.flag("output flag")?);
        } else {
            break;
        }
    }
    Ok(ScalarEntry { node: ScalarNode { id, differential, value, derivative, output: true }, span, output })
}

/// A scalar degree of freedom `LABEL, TYPE [, algebraic | differential]` of a scalar node in
/// `nodes`; `order` whether an order is read on a differential node (MBDyn's `bOrder`; an
/// abstract force reads none: it writes to the node's equation whatever the order).
/// Degrees of freedom of structural nodes and parameter nodes are refused by name.
pub fn scalar_dof(c: &mut Cursor, nodes: &[ScalarEntry], what: &str, order: bool) -> Result<(ScalarDof, bool), MbdynError> {
    let span = c.here();
    let label = c.label(&format!("{what}: node label"))?;
    let type_span = c.here();
    let keyword = c.keyword(&format!("{what}: the node type"), &["abstract", "electric", "hydraulic", "structural", "parameter", "thermal"])?;
    if !SCALAR_TYPES.contains(&keyword) {
        return Err(c.error_at(type_span, format!("{what}: a degree of freedom of a {keyword} node is not supported by romdyn (MBDyn 1.7.3 runs it) (genels and abstract forces connect to abstract, electric and hydraulic nodes)")));
    }
    let id = ScalarNodeId { kind: kind_of(keyword), label };
    let Some(node) = nodes.iter().find(|e| e.node.id == id) else {
        return Err(c.error_at(span, format!("{what}: {id} is not defined")));
    };
    let differential = node.node.differential;
    let mut derivative = false;
    if order && differential {
        let order_span = c.here();
        derivative = match c.keyword(&format!("{what}: the order of differential {id} ('algebraic' for its value, 'differential' for its derivative)"), &["algebraic", "differential", "order"])? {
            "differential" => true,
            "order" => match c.integer("order (0 or 1)")? {
                0 => false,
                1 => true,
                n => return Err(c.error_at(order_span, format!("{what}: order {n} of {id}: a scalar node has orders 0 (value) and 1 (derivative)"))),
            },
            _ => false,
        };
    }
    if order && !differential && let Some(k) = c.peek_keyword().filter(|k| ["algebraic", "differential", "order"].iter().any(|o| parser::same_keyword(k, o))) {
        return Err(c.error(format!("{what}: {id} is algebraic, and MBDyn 1.7.3 reads no order ('{k}') after an algebraic node's type (dataman3.cc, ReadScalarDof): remove it")));
    }
    Ok((ScalarDof { node: id, derivative }, differential))
}

/// A node label of `kind` defined in the nodes block (MBDyn's `ReadNode` of one kind: a
/// label alone).
pub fn scalar_node_of(c: &mut Cursor, nodes: &[ScalarEntry], kind: ScalarNodeKind, what: &str) -> Result<ScalarNodeId, MbdynError> {
    let span = c.here();
    let id = ScalarNodeId { kind, label: c.label(&format!("{what}: {} node label", kind.keyword()))? };
    if nodes.iter().any(|e| e.node.id == id) {
        Ok(id)
    } else {
        Err(c.error_at(span, format!("{what}: {id} is not defined")))
    }
}
