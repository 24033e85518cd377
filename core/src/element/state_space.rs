//! MBDyn's state-space genels on scalar nodes (input manual §Genel Element, §Scalar filter;
//! genfilt.cc): controllers and filters, `ẋ = A x + B u`, `y = C x + D u`.
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

/// `genel: L, state space SISO, …`, `genel: L, state space MIMO, …` and `genel: L, scalar
/// filter, …` (GenelStateSpaceSISO, GenelStateSpaceMIMO, genfilt.cc): own differential
/// states `x` with `E ẋ = A x + B u` (`E = I` unless `matrix E` is given, a descriptor
/// form), and each output node's equation `y_i − (C x)_i − (D u)_i = 0` (the outputs are
/// algebraic values). MBDyn 1.7.3's SISO Jacobian writes the
/// input column with the wrong sign and leaves out the output row's `−d`; romdyn writes
/// the derivatives of the residual (the runs agree, MBDyn's eigenanalysis of a loop closed
/// through the genel does not: tests/multibody/scalar_nodes.rs).
pub struct StateSpace {
    pub label: Label,
    pub outputs: Vec<ScalarNodeId>,
    pub inputs: Vec<ScalarInput>,
    /// `E` (n × n, `None`: the identity), `A` (n × n), `B` (n × m), `C` (p × n), `D` (p × m),
    /// each row by row.
    pub e: Option<Vec<f64>>,
    pub a: Vec<f64>,
    pub b: Vec<f64>,
    pub c: Vec<f64>,
    pub d: Vec<f64>,
    /// MBDyn's keyword ("state space SISO", "state space MIMO" or "scalar filter").
    pub keyword: &'static str,
}

impl StateSpace {
    fn order(&self) -> usize {
        self.a.len().isqrt()
    }
    /// Each input's value and, for a dof, its column (its node's scalar slot follows the
    /// outputs' and the dof inputs' before it).
    fn inputs_at(&self, st: &dyn ElementState) -> Vec<(f64, Option<Col>)> {
        let mut slot = self.outputs.len();
        self.inputs
            .iter()
            .map(|input| match input {
                ScalarInput::Dof(dof) => {
                    slot += 1;
                    (dof.read(st, slot - 1), Some(dof.col(slot - 1)))
                }
                ScalarInput::Drive(d) => (d.value_in(st), None),
            })
            .collect()
    }
}

impl Element for StateSpace {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        match self.keyword {
            "scalar filter" => "genel scalar filter",
            "state space MIMO" => "genel state space MIMO",
            _ => "genel state space SISO",
        }
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        let dofs = self.inputs.iter().filter_map(|i| match i {
            ScalarInput::Dof(dof) => Some(dof.node),
            ScalarInput::Drive(_) => None,
        });
        self.outputs.iter().copied().chain(dofs).collect()
    }
    fn multipliers(&self) -> Vec<String> {
        (1..=self.order()).map(|i| format!("state {i}")).collect()
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::State
    }
    fn reads_state(&self) -> bool {
        self.inputs.iter().any(|i| matches!(i, ScalarInput::Drive(d) if d.reads_state()))
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (n, m) = (self.order(), self.inputs.len());
        let u: Vec<f64> = self.inputs_at(st).into_iter().map(|(v, _)| v).collect();
        for i in 0..n {
            let ax: f64 = (0..n).map(|j| self.a[i * n + j] * st.multiplier(j)).sum();
            let bu: f64 = (0..m).map(|j| self.b[i * m + j] * u[j]).sum();
            let ex: f64 = match &self.e {
                Some(e) => (0..n).map(|j| e[i * n + j] * st.rate(j)).sum(),
                None => st.rate(i),
            };
            out.add(Row::Constraint(i), ex - ax - bu);
        }
        for (k, _) in self.outputs.iter().enumerate() {
            let cx: f64 = (0..n).map(|j| self.c[k * n + j] * st.multiplier(j)).sum();
            let du: f64 = (0..m).map(|j| self.d[k * m + j] * u[j]).sum();
            out.add(Row::Scalar { slot: k }, st.scalar_value(k) - cx - du);
        }
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (n, m) = (self.order(), self.inputs.len());
        let inputs = self.inputs_at(st);
        for i in 0..n {
            for j in 0..n {
                let e = self.e.as_ref().map_or(f64::from(u8::from(i == j)), |e| e[i * n + j]);
                if e != 0.0 {
                    out.add(Row::Constraint(i), Col::Rate(j), e);
                }
                out.add(Row::Constraint(i), Col::Multiplier(j), -self.a[i * n + j]);
            }
            for (j, (_, col)) in inputs.iter().enumerate() {
                if let Some(col) = col {
                    out.add(Row::Constraint(i), *col, -self.b[i * m + j]);
                }
            }
        }
        for k in 0..self.outputs.len() {
            let row = Row::Scalar { slot: k };
            out.add(row, Col::ScalarValue { slot: k }, 1.0);
            for j in 0..n {
                out.add(row, Col::Multiplier(j), -self.c[k * n + j]);
            }
            for (j, (_, col)) in inputs.iter().enumerate() {
                if let Some(col) = col {
                    out.add(row, *col, -self.d[k * m + j]);
                }
            }
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
