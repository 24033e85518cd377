//! MBDyn's general elements on scalar nodes (input manual §Genel Element; genel_.cc,
//! genfilt.cc) and the abstract force (§Abstract force): controllers, filters and scalar
//! mechanical analogues written with abstract, electric or hydraulic nodes.
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
    fn read(&self, st: &dyn ElementState, slot: usize) -> f64 {
        if self.derivative { st.scalar_rate(slot) } else { st.scalar_value(slot) }
    }
    /// Its column, the node being the element's scalar slot `slot`.
    fn col(&self, slot: usize) -> Col {
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
    fn nodes(&self) -> Vec<Label> {
        Vec::new()
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
    fn nodes(&self) -> Vec<Label> {
        Vec::new()
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
/// zero (MBDyn starts it at the node's initial derivative).
pub struct ScalarMass {
    pub label: Label,
    pub node: ScalarNodeId,
    pub mass: Drive,
}

impl Element for ScalarMass {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "genel mass"
    }
    fn nodes(&self) -> Vec<Label> {
        Vec::new()
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

/// The input of a state-space genel: a scalar dof or a drive (MBDyn's `ScalarValue`).
#[derive(Clone)]
pub enum ScalarInput {
    Dof(ScalarDof),
    Drive(Drive),
}

/// `genel: L, state space SISO, …` and `genel: L, scalar filter, …` (GenelStateSpaceSISO,
/// genfilt.cc): own differential states `x` with `ẋ = A x + b u`, and the output node's
/// equation `y − c·x − d u = 0` (the output must be an algebraic value). MBDyn's Jacobian
/// leaves out the output row's `−d` on an input dof; romdyn writes it (the solution is the
/// same, Newton's convergence is quadratic).
pub struct StateSpaceSiso {
    pub label: Label,
    pub output: ScalarNodeId,
    pub input: ScalarInput,
    /// `A`, row by row (n × n).
    pub a: Vec<f64>,
    pub b: Vec<f64>,
    pub c: Vec<f64>,
    pub d: f64,
    /// MBDyn's keyword ("state space SISO" or "scalar filter").
    pub keyword: &'static str,
}

impl StateSpaceSiso {
    fn order(&self) -> usize {
        self.b.len()
    }
    fn input_value(&self, st: &dyn ElementState) -> f64 {
        match &self.input {
            ScalarInput::Dof(dof) => dof.read(st, 1),
            ScalarInput::Drive(d) => d.value_in(st),
        }
    }
}

impl Element for StateSpaceSiso {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        if self.keyword == "scalar filter" { "genel scalar filter" } else { "genel state space SISO" }
    }
    fn nodes(&self) -> Vec<Label> {
        Vec::new()
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        match &self.input {
            ScalarInput::Dof(dof) => vec![self.output, dof.node],
            ScalarInput::Drive(_) => vec![self.output],
        }
    }
    fn multipliers(&self) -> Vec<String> {
        (1..=self.order()).map(|i| format!("state {i}")).collect()
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::State
    }
    fn reads_state(&self) -> bool {
        matches!(&self.input, ScalarInput::Drive(d) if d.reads_state())
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let n = self.order();
        let u = self.input_value(st);
        let mut y = st.scalar_value(0) - self.d * u;
        for i in 0..n {
            let ax: f64 = (0..n).map(|j| self.a[i * n + j] * st.multiplier(j)).sum();
            out.add(Row::Constraint(i), st.rate(i) - ax - self.b[i] * u);
            y -= self.c[i] * st.multiplier(i);
        }
        out.add(Row::Scalar { slot: 0 }, y);
    }
    fn jacobian(&self, _st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let n = self.order();
        let input = match &self.input {
            ScalarInput::Dof(dof) => Some(dof.col(1)),
            ScalarInput::Drive(_) => None,
        };
        for i in 0..n {
            out.add(Row::Constraint(i), Col::Rate(i), 1.0);
            for j in 0..n {
                out.add(Row::Constraint(i), Col::Multiplier(j), -self.a[i * n + j]);
            }
            if let Some(col) = input {
                out.add(Row::Constraint(i), col, -self.b[i]);
            }
            out.add(Row::Scalar { slot: 0 }, Col::Multiplier(i), -self.c[i]);
        }
        out.add(Row::Scalar { slot: 0 }, Col::ScalarValue { slot: 0 }, 1.0);
        if let Some(col) = input {
            out.add(Row::Scalar { slot: 0 }, col, -self.d);
        }
    }
}

/// The controllable canonical realization MBDyn gives a `scalar filter` (genel.cc, case
/// SCALARFILTER) of `B(s)/A(s)`, `A` monic: `den = [a_1 … a_n]`, `num = [b_0 … b_n]`
/// (padded with leading zeros to `n + 1`, already multiplied by the gain). Returns `(A, b,
/// c, d)`; a proper filter (`b_0 ≠ 0`) becomes a strictly proper one plus the feedthrough
/// `d = b_0`.
pub fn controllable_form(den: &[f64], num: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>, f64) {
    let n = den.len();
    let d = num[0];
    let mut a = vec![0.0; n * n];
    for j in 0..n {
        a[j] = -den[j];
    }
    for i in 1..n {
        a[i * n + i - 1] = 1.0;
    }
    let mut b = vec![0.0; n];
    b[0] = 1.0;
    let c = (1..=n).map(|i| num[i] - den[i - 1] * d).collect();
    (a, b, c, d)
}

/// The observable canonical realization (`canonical form, observable`).
pub fn observable_form(den: &[f64], num: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>, f64) {
    let n = den.len();
    let d = num[0];
    let mut a = vec![0.0; n * n];
    for i in 0..n {
        a[i * n] = -den[i];
        if i + 1 < n {
            a[i * n + i + 1] = 1.0;
        }
    }
    let b = (1..=n).map(|i| num[i] - den[i - 1] * d).collect();
    let mut c = vec![0.0; n];
    c[0] = 1.0;
    (a, b, c, d)
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
    fn nodes(&self) -> Vec<Label> {
        Vec::new()
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
