//! MBDyn's `axial rotation` (planej.cc, `AxialRotationJoint`): a revolute hinge whose
//! relative angular velocity about the hinge axis is imposed, `ψ = e₃ₐ · (ω_b − ω_a) − Ω(t)
//! = 0`, a velocity-level constraint (not divided by dCoef) whose multiplier is the motor
//! moment `μ`, applied as `e₃ₐ μ` on B and `−e₃ₐ μ` on A.

use super::contract::{add_block, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::anchor::Pair;
use super::{Anchor, Joint};
use super::drive::Drive;
use crate::kinematics::{skew, Vec3};
use super::UnknownKind;
use crate::element::Outputs;

/// A revolute hinge (5 holonomic constraints) driven at relative angular velocity `Ω(t)`
/// about axis 3 of frame A (1 velocity constraint).
#[derive(Clone, Debug)]
pub struct AxialRotation {
    hinge: Joint,
    /// Imposed relative angular velocity Ω(t) [rad/s].
    pub omega: Drive,
}

impl AxialRotation {
    pub fn new(label: Label, a: Anchor, b: Anchor, omega: Drive) -> Self {
        AxialRotation { hinge: Joint::revolute_hinge(label, a, b), omega }
    }
}

/// Index of the velocity constraint (after the hinge's five).
const RATE: usize = 5;

impl Element for AxialRotation {
    fn reads_state(&self) -> bool {
        self.omega.reads_state()
    }
    fn label(&self) -> Label {
        self.hinge.label
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn type_name(&self) -> &'static str {
        "axial rotation"
    }
    fn nodes(&self) -> Vec<Label> {
        self.hinge.nodes()
    }
    fn multipliers(&self) -> Vec<String> {
        let mut m = self.hinge.multipliers();
        m.push("m axial".into());
        m
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        if k == RATE { UnknownKind::VelocityConstraint } else { UnknownKind::Multiplier }
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        self.hinge.residual(st, out);
        let p = Pair::new(&self.hinge.a, &self.hinge.b, st);
        let e3 = p.q_a.column(2).into_owned();
        out.add(Row::Constraint(RATE), e3.dot(&(p.omega_b - p.omega_a)) - self.omega.value_in(st));
        p.add_moment(out, &(e3 * st.multiplier(RATE)));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        self.hinge.jacobian(st, out);
        let p = Pair::new(&self.hinge.a, &self.hinge.b, st);
        let e3 = p.q_a.column(2).into_owned();
        let w = p.omega_b - p.omega_a;
        // δψ = e₃ₐ · (δω_b − δω_a) + (e₃ₐ × w) · δθ_a  (δe₃ₐ = δθ_a × e₃ₐ).
        let row = Row::Constraint(RATE);
        let d_theta_a: Vec3 = e3.cross(&w);
        for i in 0..3 {
            out.add(row, Col::AngularVelocity { slot: p.slot_b, comp: i }, e3[i]);
            if let Some(a) = p.slot_a {
                out.add(row, Col::AngularVelocity { slot: a, comp: i }, -e3[i]);
                out.add(row, Col::Rotation { slot: a, comp: i }, d_theta_a[i]);
            }
        }
        p.add_reaction_column(out, Col::Multiplier(RATE), &Vec3::zeros(), &e3);
        // δ(e₃ₐ μ) = −μ [e₃ₐ×] δθ_a.
        if let Some(a) = p.slot_a {
            let k = -st.multiplier(RATE) * skew(&e3);
            add_block(out, Row::moment(p.slot_b), Col::rotation(a), &k);
            add_block(out, Row::moment(a), Col::rotation(a), &(-k));
        }
    }
}

impl Outputs for AxialRotation {
    /// `rz` the hinge's relative rotation, `wz` the imposed Ω(t) (planej.cc,
    /// `AxialRotationJoint::dGetPrivData`: `dGet()`, not the measured spin).
    fn private_data(&self, name: &str) -> Option<super::contract::PrivateDatum> {
        if name == "wz" {
            let omega = self.omega.clone();
            return Some(super::contract::PrivateDatum::new(move |st: &dyn ElementState| Some(omega.value_in(st))));
        }
        self.hinge.private_datum(name)
    }
}
