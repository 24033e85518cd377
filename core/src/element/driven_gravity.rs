//! MBDyn's uniform gravity field with a time-varying value (gravity.cc, `UniformGravity`
//! with a template drive; input manual, §Gravity Element) acting on one rigid body:
//! `g(t) = d D(t)`, the body's weight `m g(t)` and the moment `S × g(t)` of its static
//! moment `S = m R o` about the node, as the body adds a constant field (METHOD §5).

use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::drive::Drive;
use crate::kinematics::{skew, Vec3};

#[derive(Clone, Debug)]
pub struct DrivenGravity {
    /// The body's label.
    pub label: Label,
    pub node: Label,
    /// The body's mass [kg] and centre-of-mass offset in the node frame [m].
    pub mass: f64,
    pub offset: Vec3,
    /// The field's direction (global frame) and its drive: `g(t) = direction · drive(t)` [m/s²].
    pub direction: Vec3,
    pub drive: Drive,
}

impl DrivenGravity {
    fn field(&self, st: &dyn ElementState) -> Vec3 {
        self.direction * (self.drive.value_in(st) * st.load_factor())
    }
}

impl Element for DrivenGravity {
    fn reads_state(&self) -> bool {
        self.drive.reads_state()
    }
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "driven uniform gravity on body"
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let n = st.node(0);
        let g = self.field(st);
        let s = self.mass * (n.r * self.offset);
        add_vec(out, Row::force(0), &(-self.mass * g));
        add_vec(out, Row::moment(0), &(-s.cross(&g)));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let n = st.node(0);
        let g = self.field(st);
        let s = self.mass * (n.r * self.offset);
        // δS = δθ × S = −[S×] δθ, so δ(−S × g) = g × δS = −[g×][S×] δθ.
        add_block(out, Row::moment(0), Col::rotation(0), &(-skew(&g) * skew(&s)));
    }
}
