//! Counts of nodes, elements and equations, by kind.

use std::collections::BTreeMap;
use std::fmt;

use super::{Model, NodeKind};

/// What a model contains.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Summary {
    pub static_nodes: usize,
    pub dynamic_nodes: usize,
    /// Element count by type name (gravity counted as one element when present).
    pub elements: BTreeMap<&'static str, usize>,
    pub node_equations: usize,
    pub constraint_equations: usize,
}

impl Summary {
    pub fn of(model: &Model) -> Self {
        let count = |k| model.nodes.iter().filter(|n| n.kind == k).count();
        let mut elements = BTreeMap::new();
        for e in &model.elements {
            *elements.entry(e.type_name()).or_insert(0) += 1;
        }
        if model.has_gravity {
            elements.insert("gravity", 1);
        }
        Summary {
            static_nodes: count(NodeKind::Static),
            dynamic_nodes: count(NodeKind::Dynamic),
            elements,
            node_equations: model.nodes.iter().map(|n| n.kind.unknowns()).sum(),
            constraint_equations: model.elements.iter().map(|e| e.multipliers().len()).sum(),
        }
    }

    /// Total number of equations (= unknowns).
    pub fn equations(&self) -> usize {
        self.node_equations + self.constraint_equations
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "structural nodes: {} ({} static, {} dynamic)", self.static_nodes + self.dynamic_nodes, self.static_nodes, self.dynamic_nodes)?;
        for (k, n) in &self.elements {
            writeln!(f, "{k}: {n}")?;
        }
        write!(f, "equations: {} ({} node, {} constraint)", self.equations(), self.node_equations, self.constraint_equations)
    }
}
