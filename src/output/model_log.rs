//! The model log in MBDyn's `.log` layout (manual, appendix "Log File Format"): a keyword
//! in the first column ended by a colon, then data; a row starting with a blank continues
//! the previous entry. romdyn writes the entries it can fill exactly:
//!
//! ```text
//! structural node: LABEL x y z euler123 a1 a2 a3      (m; deg)
//! struct node dofs: IDX ...           (0-based first unknown of each node)
//! struct node momentum dofs: IDX ...  (dynamic nodes: first momentum unknown)
//! struct node labels: LABEL ...
//! ```
//!
//! plus romdyn's own `model summary:` (counts and equations, one continuation row each) and
//! one `element:` row per element (type, label, nodes, constraint equations).

use std::io::Write;

use crate::dae::DofMap;
use crate::kinematics::euler123;
use crate::model::{Model, NodeKind, Summary};

/// Writes the `.log` of `model` (its initial configuration) for the input `input` to `w`.
pub fn write_model_log(w: &mut dyn Write, input: &str, model: &Model) -> std::io::Result<()> {
    let dofs = DofMap::new(model);
    let summary = Summary::of(model);
    {
        writeln!(w, "# romdyn {} model log of {input} (MBDyn .log layout; SI units, Euler angles in deg)", env!("CARGO_PKG_VERSION"))?;
        writeln!(w, "input file: {input}")?;
        writeln!(w, "model summary:")?;
        for line in summary.to_string().lines() {
            writeln!(w, " {line}")?;
        }
        for n in &model.nodes {
            let a = euler123(&n.orientation).map(f64::to_degrees);
            writeln!(w, "structural node: {} {:e} {:e} {:e} euler123 {:e} {:e} {:e}", n.label, n.position.x, n.position.y, n.position.z, a.x, a.y, a.z)?;
        }
        for (e, el) in model.elements.iter().enumerate() {
            let nodes: Vec<String> = el.nodes().iter().map(|l| l.to_string()).collect();
            writeln!(w, "element: {} {}; nodes {}; {} constraint equations", el.label(), el.type_name(), nodes.join(" "), dofs.element_len[e])?;
        }
        let list = |v: Vec<String>| v.join(" ");
        writeln!(w, "struct node dofs: {}", list(dofs.node_first.iter().map(|i| i.to_string()).collect()))?;
        let momentum = (0..model.nodes.len()).filter(|&i| dofs.node_kind[i] == NodeKind::Dynamic).map(|i| (dofs.node_first[i] + 6).to_string()).collect();
        writeln!(w, "struct node momentum dofs: {}", list(momentum))?;
        writeln!(w, "struct node labels: {}", list(model.nodes.iter().map(|n| n.label.to_string()).collect()))?;
        writeln!(w, "output frequency: 1")
    }
}
