//! Forces and couples between two nodes (MBDyn's `absolute internal`, `follower internal`
//! and `total internal` forces and couples, strforce.cc and totalj.cc): equal and opposite
//! on the two nodes, node 1 receiving `+f`.

use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::{ForceFrame, VectorDrive};
use crate::kinematics::{skew, Mat3, Vec3};

/// `f(t)` applied at `p₁ = x₁ + R₁ a₁` on node 1 and `−f` at `p₂ = x₂ + R₂ a₂` on node 2;
/// `f = v(t)` (absolute) or `R₁ v(t)` (follower, in node 1's frame).
#[derive(Clone, Debug)]
pub struct InternalForce {
    pub label: Label,
    pub nodes: [Label; 2],
    pub frame: ForceFrame,
    pub arms: [Vec3; 2],
    pub value: VectorDrive,
}

/// `m(t)` on node 1 and `−m` on node 2; `m = v(t)` or `R₁ v(t)`.
#[derive(Clone, Debug)]
pub struct InternalCouple {
    pub label: Label,
    pub nodes: [Label; 2],
    pub frame: ForceFrame,
    pub value: VectorDrive,
}

/// MBDyn's `total internal` force (totalj.cc, `TotalForce`): force `F = R₁ R_f f(t)` and
/// couple `M = R₁ R_m m(t)` in node 1's frames, applied at node 2's point `p₂ = x₂ + R₂ a₂`:
/// node 1 receives `F` and `M + (p₂ − x₁) × F`, node 2 `−F` and `−(M + R₂ a₂ × F)`. (MBDyn
/// reads node 1's position and node 2's orientations and does not use them.)
#[derive(Clone, Debug)]
pub struct TotalInternalForce {
    pub label: Label,
    pub nodes: [Label; 2],
    pub force_orientation: Mat3,
    pub moment_orientation: Mat3,
    pub arm: Vec3,
    pub force: VectorDrive,
    pub moment: VectorDrive,
}

fn scaled(v: &VectorDrive, st: &dyn ElementState) -> Vec3 {
    v.value_in(st) * st.load_factor()
}

impl Element for InternalForce {
    fn reads_state(&self) -> bool {
        self.value.reads_state()
    }
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        match self.frame {
            ForceFrame::Absolute => "absolute internal force",
            ForceFrame::Follower => "follower internal force",
        }
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.to_vec()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (n1, n2) = (st.node(0), st.node(1));
        let v = scaled(&self.value, st);
        let f = if self.frame == ForceFrame::Follower { n1.r * v } else { v };
        let (b1, b2) = (n1.r * self.arms[0], n2.r * self.arms[1]);
        add_vec(out, Row::force(0), &(-f));
        add_vec(out, Row::moment(0), &(-b1.cross(&f)));
        add_vec(out, Row::force(1), &f);
        add_vec(out, Row::moment(1), &b2.cross(&f));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (n1, n2) = (st.node(0), st.node(1));
        let v = scaled(&self.value, st);
        let f = if self.frame == ForceFrame::Follower { n1.r * v } else { v };
        let (b1, b2) = (n1.r * self.arms[0], n2.r * self.arms[1]);
        let (fx, b1x, b2x) = (skew(&f), skew(&b1), skew(&b2));
        // Arms: δb = −[b×] δθ, so δ(−b₁ × f) = −[f×][b₁×] δθ₁ and δ(b₂ × f) = [f×][b₂×] δθ₂.
        add_block(out, Row::moment(0), Col::rotation(0), &(-fx * b1x));
        add_block(out, Row::moment(1), Col::rotation(1), &(fx * b2x));
        if self.frame == ForceFrame::Follower {
            // δf = −[f×] δθ₁.
            add_block(out, Row::force(0), Col::rotation(0), &fx);
            add_block(out, Row::moment(0), Col::rotation(0), &(b1x * fx));
            add_block(out, Row::force(1), Col::rotation(0), &(-fx));
            add_block(out, Row::moment(1), Col::rotation(0), &(-b2x * fx));
        }
    }
}

impl Element for InternalCouple {
    fn reads_state(&self) -> bool {
        self.value.reads_state()
    }
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        match self.frame {
            ForceFrame::Absolute => "absolute internal couple",
            ForceFrame::Follower => "follower internal couple",
        }
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.to_vec()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let v = scaled(&self.value, st);
        let m = if self.frame == ForceFrame::Follower { st.node(0).r * v } else { v };
        add_vec(out, Row::moment(0), &(-m));
        add_vec(out, Row::moment(1), &m);
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        if self.frame == ForceFrame::Follower {
            let m = st.node(0).r * scaled(&self.value, st);
            add_block(out, Row::moment(0), Col::rotation(0), &skew(&m));
            add_block(out, Row::moment(1), Col::rotation(0), &(-skew(&m)));
        }
    }
}

impl Element for TotalInternalForce {
    fn reads_state(&self) -> bool {
        self.force.reads_state() || self.moment.reads_state()
    }
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "total internal force"
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.to_vec()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (n1, n2) = (st.node(0), st.node(1));
        let f = n1.r * self.force_orientation * scaled(&self.force, st);
        let m = n1.r * self.moment_orientation * scaled(&self.moment, st);
        let b2 = n2.r * self.arm;
        let b1 = n2.x + b2 - n1.x;
        add_vec(out, Row::force(0), &(-f));
        add_vec(out, Row::moment(0), &(-(m + b1.cross(&f))));
        add_vec(out, Row::force(1), &f);
        add_vec(out, Row::moment(1), &(m + b2.cross(&f)));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (n1, n2) = (st.node(0), st.node(1));
        let f = n1.r * self.force_orientation * scaled(&self.force, st);
        let m = n1.r * self.moment_orientation * scaled(&self.moment, st);
        let b2 = n2.r * self.arm;
        let b1 = n2.x + b2 - n1.x;
        let (fx, mx, b1x, b2x) = (skew(&f), skew(&m), skew(&b1), skew(&b2));
        // δf = −[f×] δθ₁, δm = −[m×] δθ₁, δb₂ = −[b₂×] δθ₂, δb₁ = δx₂ − [b₂×] δθ₂ − δx₁.
        add_block(out, Row::force(0), Col::rotation(0), &fx);
        add_block(out, Row::moment(0), Col::rotation(0), &(mx + b1x * fx));
        add_block(out, Row::moment(0), Col::position(1), &fx);
        add_block(out, Row::moment(0), Col::position(0), &(-fx));
        add_block(out, Row::moment(0), Col::rotation(1), &(-fx * b2x));
        add_block(out, Row::force(1), Col::rotation(0), &(-fx));
        add_block(out, Row::moment(1), Col::rotation(0), &(-mx - b2x * fx));
        add_block(out, Row::moment(1), Col::rotation(1), &(fx * b2x));
    }
}
