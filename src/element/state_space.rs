//! MBDyn's state-space genels on scalar nodes (input manual §Genel Element, §Scalar filter;
//! genfilt.cc): controllers and filters, `ẋ = A x + b u`, `y = c·x + d u`.
//!
//! Residuals are romdyn's `F` (the negative of MBDyn's `AssRes`); Jacobians the plain
//! derivatives.

use super::drive::Drive;
use super::genel::ScalarDof;
use super::{Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row, ScalarNodeId, UnknownKind};

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
