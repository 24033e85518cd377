//! Numbering of unknowns and equations; names for reports.

use crate::model::{Model, NodeKind};
use crate::element::UnknownKind;

/// Where each node's and element's unknowns (and equations) start.
#[derive(Clone, Debug)]
pub struct DofMap {
    pub node_first: Vec<usize>,
    pub node_kind: Vec<NodeKind>,
    /// Whether each node is displacement-only ([`Model::displacement_nodes`]).
    pub node_displacement: Vec<bool>,
    pub element_first: Vec<usize>,
    pub element_len: Vec<usize>,
    /// Node index of each slot of each element.
    pub element_nodes: Vec<Vec<usize>>,
    /// The unknown (= equation) of each scalar node ([`Model::scalar_nodes`]): they follow
    /// the structural nodes' unknowns, one each.
    pub scalar_first: usize,
    /// Whether each scalar node is differential.
    pub scalar_differential: Vec<bool>,
    /// Scalar node index of each scalar slot of each element ([`Element::scalar_nodes`]).
    ///
    /// [`Element::scalar_nodes`]: crate::element::Element::scalar_nodes
    pub element_scalars: Vec<Vec<usize>>,
    /// Number of unknowns (= equations).
    pub len: usize,
    /// Whether each unknown is a Lagrange multiplier of a holonomic constraint (the
    /// unknowns of velocity-level constraints and elements' coordinates are not: they
    /// follow the node unknowns' coefficients in both constraint forms).
    multiplier: Vec<bool>,
    /// Whether each unknown is an element's coordinate ([`UnknownKind::Coordinate`]).
    ///
    /// [`UnknownKind::Coordinate`]: crate::element::UnknownKind::Coordinate
    coordinate: Vec<bool>,
    /// Whether each unknown is an element's differential state ([`UnknownKind::State`]).
    ///
    /// [`UnknownKind::State`]: crate::element::UnknownKind::State
    state: Vec<bool>,
}

/// What one unknown (and the equation with the same index) belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Owner {
    Node { index: usize, offset: usize },
    /// Scalar node `index` of [`Model::scalar_nodes`].
    Scalar { index: usize },
    Element { index: usize, offset: usize },
}

impl DofMap {
    /// Numbers the model; node labels of elements must exist (checked by the builder).
    pub fn new(model: &Model) -> Self {
        let mut first = 0;
        let mut node_first = Vec::with_capacity(model.nodes.len());
        for n in &model.nodes {
            node_first.push(first);
            first += n.kind.unknowns();
        }
        let scalar_first = first;
        first += model.scalar_nodes.len();
        let mut element_first = Vec::with_capacity(model.elements.len());
        let mut element_len = Vec::with_capacity(model.elements.len());
        let mut element_nodes = Vec::with_capacity(model.elements.len());
        for e in &model.elements {
            element_first.push(first);
            let k = e.multipliers().len();
            element_len.push(k);
            first += k;
            element_nodes.push(e.nodes().iter().map(|l| model.node_index(*l).unwrap_or(usize::MAX)).collect());
        }
        let element_scalars = model.elements.iter().map(|e| e.scalar_nodes().iter().map(|id| model.scalar_index(*id).unwrap_or(usize::MAX)).collect()).collect();
        let (mut multiplier, mut coordinate, mut state) = (vec![false; first], vec![false; first], vec![false; first]);
        for ((&f, &k), e) in element_first.iter().zip(&element_len).zip(&model.elements) {
            for j in 0..k {
                let kind = e.unknown_kind(j);
                coordinate[f + j] = kind == UnknownKind::Coordinate;
                state[f + j] = kind == UnknownKind::State;
                multiplier[f + j] = kind == UnknownKind::Multiplier;
            }
        }
        DofMap { node_first, node_kind: model.nodes.iter().map(|n| n.kind).collect(), node_displacement: model.nodes.iter().map(|n| model.displacement_nodes.contains(&n.label)).collect(), element_first, element_len, element_nodes, scalar_first, scalar_differential: model.scalar_nodes.iter().map(|n| n.differential).collect(), element_scalars, len: first, multiplier, coordinate, state }
    }

    /// First equilibrium row of a node (after the momentum definitions of a dynamic node).
    pub fn equilibrium_row(&self, node: usize) -> usize {
        self.node_first[node] + if self.node_kind[node] == NodeKind::Dynamic { 6 } else { 0 }
    }

    /// `(equation, unknown)` of every dynamic node's momentum definitions and momenta
    /// (`node_first + k`, `node_first + 6 + k`, k = 0..6): the definitions read `p − Σ …` and
    /// no element reads a momentum, so Newton's linear solver can eliminate them
    /// ([`SparseLu::eliminating`](super::SparseLu::eliminating)).
    pub fn momentum_pairs(&self) -> Vec<(usize, usize)> {
        let dynamic = self.node_first.iter().zip(&self.node_kind).filter(|(_, k)| **k == NodeKind::Dynamic);
        dynamic.flat_map(|(&f, _)| (0..6).map(move |k| (f + k, f + 6 + k))).collect()
    }

    /// Owner of unknown/equation `i`.
    pub fn owner(&self, i: usize) -> Owner {
        if (self.scalar_first..self.scalar_first + self.scalar_differential.len()).contains(&i) {
            return Owner::Scalar { index: i - self.scalar_first };
        }
        // The last element (node) whose first unknown is at or before i: `element_first` and
        // `node_first` are non-decreasing, so a binary search finds what a scan from the end
        // did (an element without unknowns shares its first index with the next one; the
        // last of them is the one that can own i). The scan took 0.6 s to name the 96,024
        // unknowns of a 8000-mass string.
        let last_at_or_before = |firsts: &[usize]| firsts.partition_point(|&f| f <= i).checked_sub(1);
        match last_at_or_before(&self.element_first) {
            Some(e) if i < self.element_first[e] + self.element_len[e] => Owner::Element { index: e, offset: i - self.element_first[e] },
            _ => {
                let n = last_at_or_before(&self.node_first).unwrap_or(0);
                Owner::Node { index: n, offset: i - self.node_first[n] }
            }
        }
    }

    /// Whether unknown `i` is the Lagrange multiplier of a holonomic constraint (equation `i`
    /// is then divided by dCoef in the form of eq. 30).
    pub fn is_multiplier(&self, i: usize) -> bool {
        self.multiplier[i]
    }

    /// Whether unknown `i` is an element's coordinate (a beam slider's abscissa): it moves
    /// with the configuration, like a node's position.
    pub fn is_coordinate(&self, i: usize) -> bool {
        self.coordinate[i]
    }

    /// Whether unknown `i` is an element's differential state (a friction model's `z`).
    pub fn is_state(&self, i: usize) -> bool {
        self.state[i]
    }

    /// "node 2 x", "node 2 gz", "node 2 beta_y", "revolute hinge 3 m x".
    pub fn unknown_name(&self, model: &Model, i: usize) -> String {
        const NAMES: [&str; 12] = ["x", "y", "z", "gx", "gy", "gz", "beta_x", "beta_y", "beta_z", "gamma_x", "gamma_y", "gamma_z"];
        match self.owner(i) {
            Owner::Node { index, offset } => format!("node {} {}", model.nodes[index].label, NAMES[offset]),
            Owner::Scalar { index } => format!("{} value", model.scalar_nodes[index].id),
            Owner::Element { index, offset } => {
                let e = &model.elements[index];
                format!("{} {} {}", e.type_name(), e.label(), e.multipliers().get(offset).cloned().unwrap_or_default())
            }
        }
    }

    /// "node 2 force x equilibrium", "node 2 linear momentum y definition", "clamp 1 constraint f z".
    pub fn equation_name(&self, model: &Model, i: usize) -> String {
        const EQ: [&str; 6] = ["force x", "force y", "force z", "moment x", "moment y", "moment z"];
        const DEF: [&str; 6] = ["linear momentum x", "linear momentum y", "linear momentum z", "angular momentum x", "angular momentum y", "angular momentum z"];
        match self.owner(i) {
            Owner::Node { index, offset } => {
                let label = model.nodes[index].label;
                match (self.node_kind[index], offset) {
                    (NodeKind::Dynamic, o) if o < 6 => format!("node {label} {} definition", DEF[o]),
                    (NodeKind::Dynamic, o) => format!("node {label} {} equilibrium", EQ[o - 6]),
                    (NodeKind::Static, o) => format!("node {label} {} equilibrium", EQ[o]),
                }
            }
            Owner::Scalar { index } => format!("{} equation", model.scalar_nodes[index].id),
            Owner::Element { index, offset } => {
                let e = &model.elements[index];
                format!("{} {} constraint {}", e.type_name(), e.label(), e.multipliers().get(offset).cloned().unwrap_or_default())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The binary search of `owner` against the scan from the end it replaced, on every
    /// unknown of a numbering with elements that own no unknowns (bodies) before, between
    /// and after those that do, and a scalar node.
    #[test]
    fn owner_by_binary_search_is_the_scan_from_the_end() {
        let node_first = vec![0, 12, 18, 30];
        let element_len = vec![0, 3, 0, 0, 1, 0, 6, 0];
        let scalar_first = 42;
        let mut element_first = Vec::new();
        let mut first = scalar_first + 1;
        for &k in &element_len {
            element_first.push(first);
            first += k;
        }
        let len = first;
        let dofs = DofMap {
            node_first: node_first.clone(),
            node_kind: vec![NodeKind::Dynamic, NodeKind::Static, NodeKind::Dynamic, NodeKind::Dynamic],
            node_displacement: vec![false; 4],
            element_first: element_first.clone(),
            element_len: element_len.clone(),
            element_nodes: vec![Vec::new(); element_len.len()],
            scalar_first,
            scalar_differential: vec![true],
            element_scalars: vec![Vec::new(); element_len.len()],
            len,
            multiplier: vec![false; len],
            coordinate: vec![false; len],
            state: vec![false; len],
        };
        let scan = |i: usize| {
            if i == scalar_first {
                return Owner::Scalar { index: 0 };
            }
            match element_first.iter().rposition(|&f| f <= i) {
                Some(e) if i < element_first[e] + element_len[e] => Owner::Element { index: e, offset: i - element_first[e] },
                _ => {
                    let n = node_first.iter().rposition(|&f| f <= i).unwrap_or(0);
                    Owner::Node { index: n, offset: i - node_first[n] }
                }
            }
        };
        for i in 0..len {
            assert_eq!(dofs.owner(i), scan(i), "unknown {i}");
        }
        assert_eq!(dofs.owner(43), Owner::Element { index: 1, offset: 0 });
        assert_eq!(dofs.owner(47), Owner::Element { index: 6, offset: 0 });
    }
}
