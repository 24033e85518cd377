//! MBDyn's `angular acceleration` joint (accj.cc, `AngularAccelerationJoint`; input manual,
//! "Elements", §Angular acceleration): one node's angular acceleration about a direction
//! `d` turning with it imposed, `d/dt ((R d) · ω) = α(t)`. As MBDyn, romdyn writes it with
//! two unknowns: the angular velocity `w` about `R d`, a differential state with its own
//! equation `ẇ − α(t) = 0`, and the moment `m`, the multiplier of the velocity-level
//! constraint `(R d) · ω − w = 0` (not divided by dCoef), whose reaction is the moment `R d
//! m` on the node. `w` starts at `(R d) · ω` of the initial state (MBDyn's `SetValue`): the
//! reader refuses a node whose initial angular velocity has a component about `R d`, since
//! romdyn starts an element's states at zero.

use super::contract::{add_block, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::drive::Drive;
use crate::kinematics::skew;
use crate::kinematics::Vec3;
use super::UnknownKind;

/// The state `w` and its equation `ẇ = α(t)`.
const RATE: usize = 0;
/// The moment `m` and the constraint `(R d) · ω = w`.
const MOMENT: usize = 1;

#[derive(Clone, Debug)]
pub struct AngularAcceleration {
    pub label: Label,
    pub node: Label,
    /// Unit direction in the node frame.
    pub direction: Vec3,
    /// Imposed angular acceleration [rad/s²].
    pub value: Drive,
    assembly: Absent,
}

impl AngularAcceleration {
    pub fn new(label: Label, node: Label, direction: Vec3, value: Drive) -> Self {
        AngularAcceleration { label, node, direction, value, assembly: Absent { label, node } }
    }
}

/// What the initial assembly sees of the joint: nothing (accj.cc, `iGetInitialNumDof` 0),
/// on its node.
#[derive(Clone, Debug)]
struct Absent {
    label: Label,
    node: Label,
}

impl Element for Absent {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "angular acceleration"
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn residual(&self, _st: &dyn ElementState, _out: &mut dyn ResidualSink) {}
    fn jacobian(&self, _st: &dyn ElementState, _out: &mut dyn JacobianSink) {}
}

impl Element for AngularAcceleration {
    fn reads_state(&self) -> bool {
        self.value.reads_state()
    }
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "angular acceleration"
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["w".into(), "m".into()]
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        match k {
            RATE => UnknownKind::State,
            MOMENT => UnknownKind::VelocityConstraint,
            _ => UnknownKind::Multiplier,
        }
    }
    fn assembly_form(&self) -> Option<&dyn Element> {
        Some(&self.assembly)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (n, e) = (st.node(0), st.node(0).r * self.direction);
        out.add(Row::Constraint(RATE), st.rate(RATE) - self.value.value_in(st));
        out.add(Row::Constraint(MOMENT), e.dot(&n.omega) - st.multiplier(RATE));
        let m = e * st.multiplier(MOMENT);
        for (i, row) in Row::moment(0).into_iter().enumerate() {
            out.add(row, m[i]);
        }
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (n, e) = (st.node(0), st.node(0).r * self.direction);
        out.add(Row::Constraint(RATE), Col::Rate(RATE), 1.0);
        out.add(Row::Constraint(MOMENT), Col::Multiplier(RATE), -1.0);
        // δ(R d) = δθ × R d: the constraint gains (R d × ω) · δθ, the moment −m [R d×] δθ.
        let d_theta = e.cross(&n.omega);
        for i in 0..3 {
            out.add(Row::Constraint(MOMENT), Col::AngularVelocity { slot: 0, comp: i }, e[i]);
            out.add(Row::Constraint(MOMENT), Col::Rotation { slot: 0, comp: i }, d_theta[i]);
            out.add(Row::Equilibrium { slot: 0, comp: 3 + i }, Col::Multiplier(MOMENT), e[i]);
        }
        add_block(out, Row::moment(0), Col::rotation(0), &(-st.multiplier(MOMENT) * skew(&e)));
    }
}
