//! MBDyn's central gravity field (gravity.cc, `CentralGravity`; input manual, §Gravity
//! Element) acting on one rigid body: `g(x) = G M (x₀ − x)/|x₀ − x|³` evaluated at the
//! body's node, as MBDyn's bodies evaluate it (body.cc, `bGetGravity(pNode->GetXCurr())`);
//! the body's weight `m g` and the moment `S × g` of its static moment `S = m R o`.

use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use crate::kinematics::{skew, Mat3, Vec3};

#[derive(Clone, Debug)]
pub struct CentralGravity {
    /// The body's label.
    pub label: Label,
    pub node: Label,
    /// The body's mass [kg] and centre-of-mass offset in the node frame [m].
    pub mass: f64,
    pub offset: Vec3,
    /// Centre of the field [m].
    pub origin: Vec3,
    /// `G M` [m³/s²].
    pub gm: f64,
}

impl CentralGravity {
    /// `g(x)` and `∂g/∂x = G M (3 d dᵀ/|d|² − I)/|d|³` with `d = x₀ − x`.
    fn field(&self, x: &Vec3) -> (Vec3, Mat3) {
        let d = self.origin - x;
        let r = d.norm();
        let k = self.gm / (r * r * r);
        (k * d, k * (3.0 * d * d.transpose() / (r * r) - Mat3::identity()))
    }
}

impl Element for CentralGravity {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "central gravity on body"
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let n = st.node(0);
        let (g, _) = self.field(&n.x);
        let g = g * st.load_factor();
        let s = self.mass * (n.r * self.offset);
        add_vec(out, Row::force(0), &(-self.mass * g));
        add_vec(out, Row::moment(0), &(-s.cross(&g)));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let n = st.node(0);
        let (g, dg) = self.field(&n.x);
        let (g, dg) = (g * st.load_factor(), dg * st.load_factor());
        let s = self.mass * (n.r * self.offset);
        add_block(out, Row::force(0), Col::position(0), &(-self.mass * dg));
        // δ(−S × g) = −[g×][S×] δθ − [S×] ∂g/∂x δx.
        add_block(out, Row::moment(0), Col::rotation(0), &(-skew(&g) * skew(&s)));
        add_block(out, Row::moment(0), Col::position(0), &(-skew(&s) * dg));
    }
}
