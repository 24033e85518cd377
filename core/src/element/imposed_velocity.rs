//! MBDyn's `linear velocity` and `angular velocity` joints (drvj.cc): one node's velocity
//! along a fixed direction `d`, `d · ẋ = v(t)`, or its angular velocity about a direction
//! turning with it, `(R d) · ω = w(t)`; velocity-level constraints (not divided by dCoef)
//! with the reaction force `d λ` or moment `R d λ`.

use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::drive::Drive;
use crate::kinematics::{skew, Vec3};
use super::UnknownKind;

/// Which velocity is imposed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VelocityKind {
    /// `d` fixed in space, along the node's velocity.
    Linear,
    /// `d` in the node frame, along its angular velocity.
    Angular,
}

/// One node's velocity or angular velocity imposed along a unit direction.
#[derive(Clone, Debug)]
pub struct ImposedVelocity {
    pub label: Label,
    pub node: Label,
    pub kind: VelocityKind,
    /// Unit direction: global (linear) or in the node frame (angular).
    pub direction: Vec3,
    /// Imposed velocity [m/s] or angular velocity [rad/s].
    pub value: Drive,
}

impl ImposedVelocity {
    /// The direction in the global frame now.
    fn axis(&self, st: &dyn ElementState) -> Vec3 {
        match self.kind {
            VelocityKind::Linear => self.direction,
            VelocityKind::Angular => st.node(0).r * self.direction,
        }
    }
}

impl Element for ImposedVelocity {
    fn reads_state(&self) -> bool {
        self.value.reads_state()
    }
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        match self.kind {
            VelocityKind::Linear => "linear velocity",
            VelocityKind::Angular => "angular velocity",
        }
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn multipliers(&self) -> Vec<String> {
        vec![if self.kind == VelocityKind::Linear { "f" } else { "m" }.into()]
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::VelocityConstraint
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (n, e) = (st.node(0), self.axis(st));
        let (rate, rows) = match self.kind {
            VelocityKind::Linear => (n.xdot, Row::force(0)),
            VelocityKind::Angular => (n.omega, Row::moment(0)),
        };
        out.add(Row::Constraint(0), e.dot(&rate) - self.value.value_in(st));
        add_vec(out, rows, &(e * st.multiplier(0)));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (n, e) = (st.node(0), self.axis(st));
        let (rows, cols) = match self.kind {
            VelocityKind::Linear => (Row::force(0), Col::velocity(0)),
            VelocityKind::Angular => (Row::moment(0), Col::angular_velocity(0)),
        };
        for i in 0..3 {
            out.add(Row::Constraint(0), cols[i], e[i]);
            out.add(rows[i], Col::Multiplier(0), e[i]);
        }
        if self.kind == VelocityKind::Angular {
            // δ(R d) = δθ × R d: the row gains (R d × ω) · δθ, the moment −λ [R d×] δθ.
            let d_theta = e.cross(&n.omega);
            for i in 0..3 {
                out.add(Row::Constraint(0), Col::Rotation { slot: 0, comp: i }, d_theta[i]);
            }
            add_block(out, rows, Col::rotation(0), &(-st.multiplier(0) * skew(&e)));
        }
    }
}
