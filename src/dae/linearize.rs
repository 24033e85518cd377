//! Linearization of a multibody model at a solution: `F_/ẏ`, `F_/y` (directly, or as
//! `J(±c)`, eqs. 13–16), with inputs (nodal forces and moments) and outputs (nodal
//! displacements and rotations) named by node and component.

use std::str::FromStr;

use super::{Assembler, Coefficients, State};
use crate::linear::{Jacobians, LinearDae, SparseLinearDae, SparseMatrix};
use crate::model::{Label, Model};

const FORCES: [&str; 6] = ["Fx", "Fy", "Fz", "Mx", "My", "Mz"];
const MOTIONS: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];

/// A force or moment component at a node, global frame (`NODE:Fx|Fy|Fz|Mx|My|Mz`) [N, N m].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NodeInput {
    pub node: Label,
    pub component: usize,
}

/// A displacement or rotation component of a node (`NODE:x|y|z|rx|ry|rz`) [m, rad].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NodeOutput {
    pub node: Label,
    pub component: usize,
}

/// A malformed or dangling input/output name.
#[derive(Debug, thiserror::Error)]
pub enum PortError {
    #[error("'{0}': expected NODE:COMPONENT with COMPONENT one of {1}")]
    Syntax(String, String),
    #[error("'{0}': structural node {1} is not defined")]
    UnknownNode(String, Label),
}

fn parse_port(s: &str, names: &[&str; 6]) -> Result<(Label, usize), PortError> {
    let bad = || PortError::Syntax(s.to_string(), names.join("|"));
    let (node, comp) = s.split_once(':').ok_or_else(bad)?;
    let node: Label = node.trim().parse().map_err(|_| bad())?;
    let comp = names.iter().position(|n| n.eq_ignore_ascii_case(comp.trim())).ok_or_else(bad)?;
    Ok((node, comp))
}

impl FromStr for NodeInput {
    type Err = PortError;
    fn from_str(s: &str) -> Result<Self, PortError> {
        parse_port(s, &FORCES).map(|(node, component)| NodeInput { node, component })
    }
}

impl FromStr for NodeOutput {
    type Err = PortError;
    fn from_str(s: &str) -> Result<Self, PortError> {
        parse_port(s, &MOTIONS).map(|(node, component)| NodeOutput { node, component })
    }
}

impl NodeInput {
    pub fn name(&self) -> String {
        format!("node {} {} [{}]", self.node, FORCES[self.component], if self.component < 3 { "N" } else { "N m" })
    }
}

impl NodeOutput {
    pub fn name(&self) -> String {
        format!("node {} {} [{}]", self.node, MOTIONS[self.component], if self.component < 3 { "m" } else { "rad" })
    }
}

/// `B̃` (a force enters its node's equilibrium rows) and `C̃` (a motion is read at its node's
/// first unknowns) for the given ports (eqs. 38–39).
fn port_matrices(model: &Model, asm: &Assembler, inputs: &[NodeInput], outputs: &[NodeOutput]) -> Result<(faer::Mat<f64>, faer::Mat<f64>), PortError> {
    let n = asm.dofs.len;
    let node = |label: Label, text: String| model.node_index(label).ok_or(PortError::UnknownNode(text, label));
    let mut b = faer::Mat::<f64>::zeros(n, inputs.len());
    for (k, p) in inputs.iter().enumerate() {
        let i = node(p.node, p.name())?;
        // A force u enters the equilibrium residual as −u, and −ΔF = B̃ u (eq. 38).
        b[(asm.dofs.equilibrium_row(i) + p.component, k)] = 1.0;
    }
    let mut c = faer::Mat::<f64>::zeros(outputs.len(), n);
    for (k, p) in outputs.iter().enumerate() {
        let i = node(p.node, p.name())?;
        // At g = 0 a rotation increment is δθ = δg.
        c[(k, asm.dofs.node_first[i] + p.component)] = 1.0;
    }
    Ok((b, c))
}

/// Linearizes `model` at `state` keeping `F_/ẏ` and `F_/y` sparse as assembled
/// ([`SparseLinearDae`]: memory proportional to the non-zeros).
pub fn linearize_sparse(model: &Model, state: &State, inputs: &[NodeInput], outputs: &[NodeOutput]) -> Result<SparseLinearDae, PortError> {
    let asm = Assembler::new(model);
    let mut st = state.clone();
    st.rebase(&asm.dofs);
    let form = model.constraint_form;
    let n = asm.dofs.len;
    let sparse = |a: f64, b: f64| {
        let t = asm.jacobian(&st, Coefficients { a, b, form, dcoef: 1.0 });
        let entries = (0..t.values.len()).map(|k| (t.rows[k], t.cols[k], t.values[k]));
        SparseMatrix::from_triplets(n, n, entries).unwrap_or_else(|| unreachable!("the assembler writes inside its {n} x {n} pattern"))
    };
    let (fyd, fy) = (sparse(1.0, 0.0), sparse(0.0, 1.0));
    let (b, c) = port_matrices(model, &asm, inputs, outputs)?;
    Ok(SparseLinearDae {
        fyd,
        fy,
        b,
        c,
        unknown_names: (0..n).map(|i| asm.dofs.unknown_name(model, i)).collect(),
        input_names: inputs.iter().map(NodeInput::name).collect(),
        output_names: outputs.iter().map(NodeOutput::name).collect(),
        constraint_form: Some(form),
        multipliers: (0..n).filter(|&i| asm.dofs.is_multiplier(i)).collect(),
    })
}

/// Linearizes `model` at `state` (re-based first so that rotations are measured by `g`).
/// With `dcoef = Some(c)` the Jacobians are assembled as `J(±c)` (eqs. 13–14), otherwise
/// `F_/ẏ` and `F_/y` directly; both routes agree to rounding.
pub fn linearize(model: &Model, state: &State, inputs: &[NodeInput], outputs: &[NodeOutput], dcoef: Option<f64>) -> Result<LinearDae, PortError> {
    let asm = Assembler::new(model);
    let mut st = state.clone();
    st.rebase(&asm.dofs);
    let form = model.constraint_form;
    let coef = |a, b| Coefficients { a, b, form, dcoef: dcoef.unwrap_or(1.0) };
    let jacobians = match dcoef {
        None => Jacobians::Derivatives { fyd: asm.jacobian(&st, coef(1.0, 0.0)).to_dense(), fy: asm.jacobian(&st, coef(0.0, 1.0)).to_dense() },
        Some(c) => Jacobians::Coefficient { j: asm.jacobian(&st, coef(1.0, c)).to_dense(), jstar: asm.jacobian(&st, coef(1.0, -c)).to_dense(), dcoef: c },
    };
    let n = asm.dofs.len;
    let (b, c) = port_matrices(model, &asm, inputs, outputs)?;
    Ok(LinearDae {
        jacobians,
        b,
        c,
        unknown_names: (0..n).map(|i| asm.dofs.unknown_name(model, i)).collect(),
        input_names: inputs.iter().map(NodeInput::name).collect(),
        output_names: outputs.iter().map(NodeOutput::name).collect(),
        constraint_form: Some(form),
        multipliers: (0..n).filter(|&i| asm.dofs.is_multiplier(i)).collect(),
    })
}
