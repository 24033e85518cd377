//! Linearization of a multibody model at a solution: `F_/ẏ`, `F_/y` (directly, or as
//! `J(±c)`, eqs. 13–16), with inputs (nodal forces and moments) and outputs (nodal
//! displacements and rotations) named by node and component.

use std::str::FromStr;

use super::ports::{Direction, Excitation, InputPort, Measurement, OutputPort, Point, PortError, PortMap};
use super::{Assembler, Coefficients, State};
use crate::kinematics::Vec3;
use crate::linear::{Jacobians, LinearDae, SparseLinearDae, SparseMatrix};
use crate::model::ConstraintForm;
use crate::model::{Label, Model, ScalarNodeId, ScalarNodeKind};

const FORCES: [&str; 9] = ["Fx", "Fy", "Fz", "Mx", "My", "Mz", "abstract", "electric", "hydraulic"];
const MOTIONS: [&str; 12] = ["x", "y", "z", "rx", "ry", "rz", "abstract", "electric", "hydraulic", "abstract_rate", "electric_rate", "hydraulic_rate"];
const SCALAR_KINDS: [ScalarNodeKind; 3] = [ScalarNodeKind::Abstract, ScalarNodeKind::Electric, ScalarNodeKind::Hydraulic];

/// A force or moment component at a node, global frame (`NODE:Fx|Fy|Fz|Mx|My|Mz`) [N, N m],
/// or an input on a scalar node's equation (`NODE:abstract|electric|hydraulic`, components
/// 6 to 8, [`Excitation::Scalar`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NodeInput {
    pub node: Label,
    pub component: usize,
}

/// A displacement or rotation component of a node (`NODE:x|y|z|rx|ry|rz`) [m, rad], or a
/// scalar node's value (`NODE:abstract|electric|hydraulic`, components 6 to 8) or derivative
/// (`NODE:abstract_rate|electric_rate|hydraulic_rate`, 9 to 11), or a modal joint's
/// coordinate of mode K (`JOINT:qK`, `node` the joint's label, component
/// [`NodeOutput::MODAL_FIRST`]` + 2 (K − 1)`) or its rate (`JOINT:qK_rate`, one more).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NodeOutput {
    pub node: Label,
    pub component: usize,
}

fn parse_port(s: &str, names: &[&str]) -> Result<(Label, usize), PortError> {
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
        if let Some((joint, comp)) = s.split_once(':') {
            let comp = comp.trim();
            let (digits, rate) = comp.strip_suffix("_rate").map_or((comp, false), |d| (d, true));
            let mode = digits.strip_prefix(['q', 'Q']).and_then(|d| d.parse::<usize>().ok()).filter(|m| *m >= 1);
            if let (Some(mode), Ok(joint)) = (mode, joint.trim().parse::<Label>()) {
                return Ok(NodeOutput::modal(joint, mode, rate));
            }
        }
        parse_port(s, &MOTIONS).map(|(node, component)| NodeOutput { node, component }).map_err(|_| PortError::Syntax(s.to_string(), format!("{}|qK|qK_rate (K a mode of modal joint NODE)", MOTIONS.join("|"))))
    }
}

fn unit(k: usize) -> Vec3 {
    Vec3::from_fn(|i, _| if i == k { 1.0 } else { 0.0 })
}

impl NodeInput {
    pub fn name(&self) -> String {
        self.port().label()
    }
    /// The same input as a port: a force at the node's origin or a moment, global axes.
    pub fn port(&self) -> InputPort {
        if self.component >= 6 {
            let node = ScalarNodeId { kind: SCALAR_KINDS[self.component - 6], label: self.node };
            return InputPort { name: format!("{node}"), excitation: Excitation::Scalar { node } };
        }
        let direction = Direction::global(unit(self.component % 3));
        let excitation = if self.component < 3 {
            Excitation::Force { point: Point::node(self.node), direction }
        } else {
            Excitation::Moment { node: self.node, direction }
        };
        InputPort { name: format!("node {} {}", self.node, FORCES[self.component]), excitation }
    }
}

impl NodeOutput {
    /// The first component of a modal coordinate ([`NodeOutput`]).
    pub const MODAL_FIRST: usize = MOTIONS.len();

    /// Modal joint `joint`'s coordinate of mode `mode` (its number in the FEM file, from 1),
    /// or its rate.
    pub fn modal(joint: Label, mode: usize, rate: bool) -> Self {
        NodeOutput { node: joint, component: Self::MODAL_FIRST + 2 * (mode.max(1) - 1) + usize::from(rate) }
    }

    pub fn name(&self) -> String {
        self.port().label()
    }
    /// The same output as a port: displacement of the node's origin or rotation, global axes.
    pub fn port(&self) -> OutputPort {
        if self.component >= Self::MODAL_FIRST {
            let (joint, mode) = (self.node, (self.component - Self::MODAL_FIRST) / 2 + 1);
            return match (self.component - Self::MODAL_FIRST) % 2 {
                0 => OutputPort { name: format!("modal {joint} q{mode}"), measurement: Measurement::ModalCoordinate { joint, mode } },
                _ => OutputPort { name: format!("modal {joint} q{mode} rate"), measurement: Measurement::ModalRate { joint, mode } },
            };
        }
        if self.component >= 6 {
            let node = ScalarNodeId { kind: SCALAR_KINDS[(self.component - 6) % 3], label: self.node };
            return match self.component {
                6..=8 => OutputPort { name: format!("{node}"), measurement: Measurement::ScalarValue { node } },
                _ => OutputPort { name: format!("{node} rate"), measurement: Measurement::ScalarRate { node } },
            };
        }
        let direction = Direction::global(unit(self.component % 3));
        let measurement = if self.component < 3 {
            Measurement::Displacement { point: Point::node(self.node), direction }
        } else {
            Measurement::Rotation { node: self.node, direction }
        };
        OutputPort { name: format!("node {} {}", self.node, MOTIONS[self.component]), measurement }
    }
}

/// Errors when an element's drive reads the model's state: its Jacobian, as MBDyn's, holds
/// the drive's value fixed, so `F_/y` and `F_/ẏ` would miss the drive's derivatives (a
/// drag force's damping, say) and the modes would look right while being wrong.
fn linearizable(model: &Model) -> Result<(), PortError> {
    match model.elements.iter().find(|e| e.reads_state()) {
        Some(e) => Err(PortError::Invalid(
            format!("{} {}", e.type_name(), e.label()),
            "a drive of this element reads the model's state (model:: functions in a string drive, node, dof or element drive callers); its derivatives are in no Jacobian (as in MBDyn), so romdyn does not linearize this model".into(),
        )),
        None => Ok(()),
    }
}

/// The constraint form of the linearization: the model's, but eq. 29 for a model whose
/// constraint rows read their multipliers (a joint regularization, `Φ − C λ`): in the form of
/// eq. 30 that row's `λ` entry goes as `1/c` in `J(c)`, which no pencil `λ F_/ẏ + F_/y`
/// holds, while eq. 29 holds it exactly (`−C` in `F_/y`: the joint a spring of stiffness
/// `1/C`).
pub(super) fn linearization_form(model: &Model) -> ConstraintForm {
    if model.elements.iter().any(|e| e.constraint_rows_read_multipliers()) {
        ConstraintForm::Plain
    } else {
        model.constraint_form
    }
}

/// Linearizes `model` at `state` (in [`State::linearization_base`]: rotations measured by `g`
/// from the moving reference, angular velocities carried in `W_ref`).
/// With `dcoef = Some(c)` the Jacobians are assembled as `J(±c)` (eqs. 13–14), otherwise
/// `F_/ẏ` and `F_/y` directly; both routes agree to rounding.
pub fn linearize(model: &Model, state: &State, inputs: &[NodeInput], outputs: &[NodeOutput], dcoef: Option<f64>) -> Result<LinearDae, PortError> {
    let inputs: Vec<InputPort> = inputs.iter().map(NodeInput::port).collect();
    let outputs: Vec<OutputPort> = outputs.iter().map(NodeOutput::port).collect();
    linearize_ports(model, state, &inputs, &outputs, dcoef)
}

/// [`linearize`] with inputs and outputs at points of nodes along any direction, rates
/// included (`B̃`, `C̃`, `C̃_v` by [`PortMap`]).
pub fn linearize_ports(model: &Model, state: &State, inputs: &[InputPort], outputs: &[OutputPort], dcoef: Option<f64>) -> Result<LinearDae, PortError> {
    linearizable(model)?;
    let asm = Assembler::new(model);
    let mut st = state.clone();
    st.linearization_base(&asm.dofs);
    let form = linearization_form(model);
    let coef = |a, b| Coefficients { a, b, form, dcoef: dcoef.unwrap_or(1.0) };
    let jacobians = match dcoef {
        None => Jacobians::Derivatives { fyd: asm.jacobian(&st, coef(1.0, 0.0)).to_dense(), fy: asm.jacobian(&st, coef(0.0, 1.0)).to_dense() },
        Some(c) => Jacobians::Coefficient { j: asm.jacobian(&st, coef(1.0, c)).to_dense(), jstar: asm.jacobian(&st, coef(1.0, -c)).to_dense(), dcoef: c },
    };
    let n = asm.dofs.len;
    let ports = PortMap::new(model, &st);
    // A force u enters the equilibrium residual as −u, and −ΔF = B̃ u (eq. 38).
    let b = ports.input_matrix(inputs)?;
    let (c, c_rate) = ports.output_matrices(outputs)?;
    Ok(LinearDae {
        jacobians,
        b,
        c,
        unknown_names: (0..n).map(|i| asm.dofs.unknown_name(model, i)).collect(),
        input_names: inputs.iter().map(InputPort::label).collect(),
        output_names: outputs.iter().map(OutputPort::label).collect(),
        constraint_form: Some(form),
        multipliers: (0..n).filter(|&i| asm.dofs.is_multiplier(i)).collect(),
        c_rate,
    })
}

/// [`linearize_ports`] keeping `F_/ẏ` and `F_/y` sparse as assembled ([`SparseLinearDae`]:
/// memory proportional to the non-zeros, not to n²).
pub fn linearize_sparse(model: &Model, state: &State, inputs: &[InputPort], outputs: &[OutputPort]) -> Result<SparseLinearDae, PortError> {
    linearizable(model)?;
    let asm = Assembler::new(model);
    let mut st = state.clone();
    st.linearization_base(&asm.dofs);
    let form = linearization_form(model);
    let n = asm.dofs.len;
    let sparse = |a: f64, b: f64| sparse_jacobian(&asm, &st, Coefficients { a, b, form, dcoef: 1.0 });
    let (fyd, fy) = (sparse(1.0, 0.0), sparse(0.0, 1.0));
    let ports = PortMap::new(model, &st);
    let b = ports.input_matrix(inputs)?;
    let (c, c_rate) = ports.output_matrices(outputs)?;
    Ok(SparseLinearDae {
        fyd,
        fy,
        b,
        c,
        c_rate,
        unknown_names: (0..n).map(|i| asm.dofs.unknown_name(model, i)).collect(),
        input_names: inputs.iter().map(InputPort::label).collect(),
        output_names: outputs.iter().map(OutputPort::label).collect(),
        constraint_form: Some(form),
        multipliers: (0..n).filter(|&i| asm.dofs.is_multiplier(i)).collect(),
    })
}

/// `a F_/ẏ + b F_/y` in the constraint form of `c` as assembled, sparse.
fn sparse_jacobian(asm: &Assembler, st: &State, c: Coefficients) -> SparseMatrix {
    let n = asm.dofs.len;
    let t = asm.jacobian(st, c);
    SparseMatrix::from_triplet_parts(n, n, &t.rows, &t.cols, &t.values).unwrap_or_else(|| unreachable!("the assembler writes inside its {n} x {n} pattern"))
}

/// `J(+c)` and `J(−c)` (eqs. 13–14; MBDyn's `Aplus`, `Aminus`) at `state`, kept sparse as
/// assembled: the matrices [`linearize`] with `Some(c)` gives dense, entry for entry, with
/// memory proportional to the non-zeros.
pub fn sparse_jacobian_pair(model: &Model, state: &State, c: f64) -> Result<(SparseMatrix, SparseMatrix), PortError> {
    linearizable(model)?;
    let asm = Assembler::new(model);
    let mut st = state.clone();
    st.linearization_base(&asm.dofs);
    let form = linearization_form(model);
    let j = |b: f64| sparse_jacobian(&asm, &st, Coefficients { a: 1.0, b, form, dcoef: c });
    Ok((j(c), j(-c)))
}
