//! MBDyn's `cardano hinge` (also `universal hinge`; univj.cc, `UniversalHingeJoint`): the
//! points coincide and axis 3 of frame A stays normal to axis 2 of frame B, `e₃ₐ · e₂ᵦ = 0`
//! (a Hooke joint transmitting the moment about both axes 1); the pin to a frame fixed in
//! space, and `cardano rotation` without the position constraint.

use super::contract::{add_block, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::anchor::Pair;
use super::{Anchor, Joint};
use crate::kinematics::{skew, Vec3};

/// Position constraints of `joint` (none for `cardano rotation`) and `e₃ₐ · e₂ᵦ = 0`.
#[derive(Clone, Debug)]
pub struct CardanoHinge {
    joint: Joint,
    name: &'static str,
}

impl CardanoHinge {
    /// The hinge (`with_position`, 4 multipliers) or the rotation alone (1 multiplier).
    pub fn new(label: Label, a: Anchor, b: Anchor, with_position: bool, name: &'static str) -> Self {
        CardanoHinge { joint: Joint::total(label, a, b, [with_position; 3], [false; 3]), name }
    }

    fn index(&self) -> usize {
        self.joint.multipliers().len()
    }
}

/// `e₃ₐ`, `e₂ᵦ` and the gradient `g = e₂ᵦ × e₃ₐ` of `e₃ₐ · e₂ᵦ` in `δθ_b` (−g in `δθ_a`).
fn axes(p: &Pair) -> (Vec3, Vec3, Vec3) {
    let (e3a, e2b) = (p.q_a.column(2).into_owned(), p.q_b.column(1).into_owned());
    (e3a, e2b, e2b.cross(&e3a))
}

impl Element for CardanoHinge {
    fn label(&self) -> Label {
        self.joint.label
    }
    fn type_name(&self) -> &'static str {
        self.name
    }
    fn nodes(&self) -> Vec<Label> {
        self.joint.nodes()
    }
    fn multipliers(&self) -> Vec<String> {
        let mut m = self.joint.multipliers();
        m.push("m cardano".into());
        m
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        self.joint.residual(st, out);
        let p = Pair::new(&self.joint.a, &self.joint.b, st);
        let (e3a, e2b, g) = axes(&p);
        let k = self.index();
        out.add(Row::Constraint(k), e3a.dot(&e2b));
        p.add_moment(out, &(g * st.multiplier(k)));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        self.joint.jacobian(st, out);
        let p = Pair::new(&self.joint.a, &self.joint.b, st);
        let (e3a, e2b, g) = axes(&p);
        let (k, b) = (self.index(), p.slot_b);
        let mu = st.multiplier(k);
        for i in 0..3 {
            out.add(Row::Constraint(k), Col::Rotation { slot: b, comp: i }, g[i]);
            if let Some(a) = p.slot_a {
                out.add(Row::Constraint(k), Col::Rotation { slot: a, comp: i }, -g[i]);
            }
        }
        p.add_reaction_column(out, Col::Multiplier(k), &Vec3::zeros(), &g);
        // δg = [e₃ₐ×][e₂ᵦ×] δθ_b − [e₂ᵦ×][e₃ₐ×] δθ_a; the moment is g μ on B, −g μ on A.
        let (d_b, d_a) = (mu * skew(&e3a) * skew(&e2b), -mu * skew(&e2b) * skew(&e3a));
        add_block(out, Row::moment(b), Col::rotation(b), &d_b);
        if let Some(a) = p.slot_a {
            add_block(out, Row::moment(b), Col::rotation(a), &d_a);
            add_block(out, Row::moment(a), Col::rotation(b), &(-d_b));
            add_block(out, Row::moment(a), Col::rotation(a), &(-d_a));
        }
    }
}
