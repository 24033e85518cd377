//! MBDyn's general elements on scalar nodes (input manual §Genel Element; genel_.cc) and
//! the abstract force (§Abstract force): scalar mechanical analogues (clamp, distance,
//! springs, mass) written with abstract, electric or hydraulic nodes; the state-space
//! genels are in [`super::state_space`].
//!
//! Residuals are romdyn's `F` (the negative of MBDyn's `AssRes`); Jacobians are the plain
//! derivatives, which the assembler turns into `J(c)`. A node's equation
//! ([`Row::Scalar`]) collects what every element connected to it writes, as MBDyn's scalar
//! nodes' rows do.

use super::drive::Drive;
use super::{Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row, ScalarNodeId, UnknownKind};

/// A degree of freedom of a scalar node as MBDyn's `ScalarDof` reads it: its value
/// (`algebraic`, order 0) or its derivative (`differential`, order 1, a differential node's).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ScalarDof {
    pub node: ScalarNodeId,
    pub derivative: bool,
}

impl ScalarDof {
    /// Its value at a state, the node being the element's scalar slot `slot`.
    pub(super) fn read(&self, st: &dyn ElementState, slot: usize) -> f64 {
        if self.derivative { st.scalar_rate(slot) } else { st.scalar_value(slot) }
    }
    /// Its column, the node being the element's scalar slot `slot`.
    pub(super) fn col(&self, slot: usize) -> Col {
        if self.derivative { Col::ScalarRate { slot } } else { Col::ScalarValue { slot } }
    }
}

/// `genel: L, clamp, DOF, DRIVE` (GenelClamp): the dof equals the drive, `x − d(t) = 0`, held
/// by a reaction `λ` added to the node's equation. On a value the constraint is holonomic (a
/// multiplier, divided by dCoef in the form of eq. 30, as MBDyn does on a differential
/// node); on a derivative it is a velocity-level constraint.
pub struct ScalarClamp {
    pub label: Label,
    pub dof: ScalarDof,
    pub drive: Drive,
}

impl Element for ScalarClamp {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "genel clamp"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        vec![self.dof.node]
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["reaction".into()]
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        if self.dof.derivative { UnknownKind::VelocityConstraint } else { UnknownKind::Multiplier }
    }
    fn reads_state(&self) -> bool {
        self.drive.reads_state()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        out.add(Row::Scalar { slot: 0 }, st.multiplier(0));
        out.add(Row::Constraint(0), self.dof.read(st, 0) - self.drive.value_in(st));
    }
    fn jacobian(&self, _st: &dyn ElementState, out: &mut dyn JacobianSink) {
        out.add(Row::Scalar { slot: 0 }, Col::Multiplier(0), 1.0);
        out.add(Row::Constraint(0), self.dof.col(0), 1.0);
    }
}

/// `genel: L, distance, DOF1, DOF2, DRIVE` (GenelDistance): `x₂ − x₁ − d(t) = 0`, its
/// reaction `λ` subtracted from node 1's equation and added to node 2's (MBDyn's residual
/// `+λ`, `−λ`). Holonomic (a multiplier) on two values, a velocity-level constraint when
/// either dof is a derivative, as MBDyn divides by dCoef on two values only.
pub struct ScalarDistance {
    pub label: Label,
    pub dofs: [ScalarDof; 2],
    pub drive: Drive,
}

impl Element for ScalarDistance {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "genel distance"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.dofs.iter().map(|d| d.node).collect()
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["reaction".into()]
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        if self.dofs.iter().any(|d| d.derivative) { UnknownKind::VelocityConstraint } else { UnknownKind::Multiplier }
    }
    fn reads_state(&self) -> bool {
        self.drive.reads_state()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let lambda = st.multiplier(0);
        out.add(Row::Scalar { slot: 0 }, -lambda);
        out.add(Row::Scalar { slot: 1 }, lambda);
        out.add(Row::Constraint(0), self.dofs[1].read(st, 1) - self.dofs[0].read(st, 0) - self.drive.value_in(st));
    }
    fn jacobian(&self, _st: &dyn ElementState, out: &mut dyn JacobianSink) {
        out.add(Row::Scalar { slot: 0 }, Col::Multiplier(0), -1.0);
        out.add(Row::Scalar { slot: 1 }, Col::Multiplier(0), 1.0);
        out.add(Row::Constraint(0), self.dofs[1].col(1), 1.0);
        out.add(Row::Constraint(0), self.dofs[0].col(0), -1.0);
    }
}

/// `genel: L, spring, DOF1, DOF2, LAW` (GenelSpring, an elastic law): `f = f(x₂ − x₁)`
/// (each a value or a derivative) subtracted from node 1's equation and added to node 2's.
pub struct ScalarSpringPair {
    pub label: Label,
    pub dofs: [ScalarDof; 2],
    pub law: ScalarLaw,
}

impl Element for ScalarSpringPair {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "genel spring"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.dofs.iter().map(|d| d.node).collect()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let f = self.law.force(self.dofs[1].read(st, 1) - self.dofs[0].read(st, 0), 0.0);
        out.add(Row::Scalar { slot: 0 }, -f);
        out.add(Row::Scalar { slot: 1 }, f);
    }
    fn jacobian(&self, _st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let k = self.law.stiffness;
        for (slot, sign) in [(0, -1.0), (1, 1.0)] {
            out.add(Row::Scalar { slot }, self.dofs[1].col(1), sign * k);
            out.add(Row::Scalar { slot }, self.dofs[0].col(0), -sign * k);
        }
    }
}

/// A linear (visco)elastic scalar law `f = k (ε − ε_p) + c ε̇ + f_p` (a 1-D `linear elastic`,
/// `linear viscous` or `linear viscoelastic` constitutive law).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScalarLaw {
    pub stiffness: f64,
    pub viscosity: f64,
    pub prestrain: f64,
    pub prestress: f64,
}

impl ScalarLaw {
    fn force(&self, strain: f64, rate: f64) -> f64 {
        self.stiffness * (strain - self.prestrain) + self.viscosity * rate + self.prestress
    }
}

/// `genel: L, spring support, NODE, TYPE, algebraic, LAW [, position, X0]`
/// (GenelSpringSupport, GenelSpringDamperSupport) and `genel: L, cross spring support, ROW,
/// COL, LAW` (GenelCrossSpringSupport): the law's force of the `col` node's value `x` (minus
/// `x0`) and derivative `ẋ`, added to the `row` node's equation, `F_row += f(x − x0, ẋ)`.
/// A spring support is the case `row = col`. MBDyn 1.7.3 passes a zero rate to an elastic
/// law; a cross spring support with a viscous law reads the column node's derivative
/// (GenelCrossSpringDamperSupport), as romdyn does for both.
pub struct ScalarSpring {
    pub label: Label,
    pub row: ScalarNodeId,
    pub col: ScalarNodeId,
    pub law: ScalarLaw,
    pub x0: f64,
}

impl ScalarSpring {
    /// The scalar slot of the column node (0 for a support, 1 for a cross support).
    fn col_slot(&self) -> usize {
        usize::from(self.row != self.col)
    }
}

impl Element for ScalarSpring {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        if self.row == self.col { "genel spring support" } else { "genel cross spring support" }
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        if self.row == self.col { vec![self.row] } else { vec![self.row, self.col] }
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let k = self.col_slot();
        out.add(Row::Scalar { slot: 0 }, self.law.force(st.scalar_value(k) - self.x0, st.scalar_rate(k)));
    }
    fn jacobian(&self, _st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let slot = self.col_slot();
        out.add(Row::Scalar { slot: 0 }, Col::ScalarValue { slot }, self.law.stiffness);
        if self.law.viscosity != 0.0 {
            out.add(Row::Scalar { slot: 0 }, Col::ScalarRate { slot }, self.law.viscosity);
        }
    }
}

/// `genel: L, mass, NODE, TYPE, algebraic, MASS` (GenelMass): an own differential unknown
/// `u`, `u − ẋ = 0`, and `m u̇` added to the node's equation (`m ẍ + … = f`). `u` starts at
/// the node's initial derivative, as MBDyn's `GenelMass::SetValue` starts it (at zero the
/// derivatives phase made ẋ = u = 0: the node lost its initial velocity).
pub struct ScalarMass {
    pub label: Label,
    pub node: ScalarNodeId,
    pub mass: Drive,
    /// The node's initial derivative `ẋ(t₀)`.
    pub initial_rate: f64,
}

impl Element for ScalarMass {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "genel mass"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        vec![self.node]
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["derivative".into()]
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::State
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        vec![(0, self.initial_rate, 0.0)]
    }
    fn reads_state(&self) -> bool {
        self.mass.reads_state()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        out.add(Row::Scalar { slot: 0 }, self.mass.value_in(st) * st.rate(0));
        out.add(Row::Constraint(0), st.multiplier(0) - st.scalar_rate(0));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        out.add(Row::Scalar { slot: 0 }, Col::Rate(0), self.mass.value_in(st));
        out.add(Row::Constraint(0), Col::Multiplier(0), 1.0);
        out.add(Row::Constraint(0), Col::ScalarRate { slot: 0 }, -1.0);
    }
}

/// `force: L, abstract, NODE, TYPE, DRIVE` (input manual §Abstract force): `f(t)` added to
/// the node's equation (residual `… − f`), times the load factor as every applied load.
pub struct AbstractForce {
    pub label: Label,
    pub node: ScalarNodeId,
    pub value: Drive,
}

impl Element for AbstractForce {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "abstract force"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        vec![self.node]
    }
    fn reads_state(&self) -> bool {
        self.value.reads_state()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        out.add(Row::Scalar { slot: 0 }, -self.value.value_in(st) * st.load_factor());
    }
    fn jacobian(&self, _st: &dyn ElementState, _out: &mut dyn JacobianSink) {}
}
