//! Forces and couples applied to a node: absolute (fixed global direction) or follower
//! (direction fixed in the node frame), with a time drive.

use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, ResidualSink, Row};
use super::VectorDrive;
use super::drive::Drive;
use crate::kinematics::{skew, Vec3};
use super::contract::Label;

/// The frame a force or couple direction is given in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ForceFrame {
    Absolute,
    Follower,
}

/// `f(t) = Σ dir_k · drive_k(t)` applied at `offset` (node frame) [N].
#[derive(Clone, Debug)]
pub struct Force {
    pub label: Label,
    pub node: Label,
    pub frame: ForceFrame,
    pub value: VectorDrive,
    pub offset: Vec3,
}

/// `m(t) = Σ dir_k · drive_k(t)` [N m].
#[derive(Clone, Debug)]
pub struct Couple {
    pub label: Label,
    pub node: Label,
    pub frame: ForceFrame,
    pub value: VectorDrive,
}

impl Force {
    /// One direction times one drive.
    pub fn new(label: Label, node: Label, frame: ForceFrame, direction: Vec3, offset: Vec3, drive: Drive) -> Self {
        Force { label, node, frame, value: VectorDrive(vec![(direction, drive)]), offset }
    }
}

impl Couple {
    /// One direction times one drive.
    pub fn new(label: Label, node: Label, frame: ForceFrame, direction: Vec3, drive: Drive) -> Self {
        Couple { label, node, frame, value: VectorDrive(vec![(direction, drive)]) }
    }
}

impl Element for Force {
    fn reads_state(&self) -> bool {
        self.value.reads_state()
    }
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        match self.frame {
            ForceFrame::Absolute => "absolute force",
            ForceFrame::Follower => "follower force",
        }
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let n = st.node(0);
        let v = self.value.value_in(st) * st.load_factor();
        let f = if self.frame == ForceFrame::Follower { n.r * v } else { v };
        add_vec(out, Row::force(0), &(-f));
        add_vec(out, Row::moment(0), &(-(n.r * self.offset).cross(&f)));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let n = st.node(0);
        let v = self.value.value_in(st) * st.load_factor();
        let arm = n.r * self.offset;
        match self.frame {
            // −(R o) × f with δ(R o) = −[(R o)×] δθ.
            ForceFrame::Absolute => add_block(out, Row::moment(0), Col::rotation(0), &(-skew(&v) * skew(&arm))),
            // −R v and −R (o × v): δ(R w) = −[(R w)×] δθ.
            ForceFrame::Follower => {
                add_block(out, Row::force(0), Col::rotation(0), &skew(&(n.r * v)));
                add_block(out, Row::moment(0), Col::rotation(0), &skew(&(n.r * self.offset.cross(&v))));
            }
        }
    }
}

impl Element for Couple {
    fn reads_state(&self) -> bool {
        self.value.reads_state()
    }
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        match self.frame {
            ForceFrame::Absolute => "absolute couple",
            ForceFrame::Follower => "follower couple",
        }
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let v = self.value.value_in(st) * st.load_factor();
        let m = if self.frame == ForceFrame::Follower { st.node(0).r * v } else { v };
        add_vec(out, Row::moment(0), &(-m));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        if self.frame == ForceFrame::Follower {
            let v = self.value.value_in(st) * st.load_factor();
            add_block(out, Row::moment(0), Col::rotation(0), &skew(&(st.node(0).r * v)));
        }
    }
}
