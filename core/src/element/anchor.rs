//! The two frames an element connects: anchors on nodes (with offset and orientation) or
//! fixed in space, and their relative kinematics.

use super::contract::{add_block, add_vec, Col, ElementState, JacobianSink, ResidualSink, Row};
use crate::kinematics::{skew, Mat3, Vec3};
use super::contract::Label;

/// One side of a two-frame element.
#[derive(Clone, Debug)]
pub enum Anchor {
    /// A point and frame fixed in space.
    Ground { position: Vec3, orientation: Mat3 },
    /// A point and frame attached to a node (offset and orientation in the node frame).
    Node { label: Label, offset: Vec3, orientation: Mat3 },
}

/// Up to four derivative blocks `(columns, ∂/∂columns)`, one node's positions or rotations
/// each (both sides' positions and rotations), held without allocation: the joints form
/// them at every Jacobian.
#[derive(Clone, Copy)]
pub(super) struct Blocks {
    items: [([Col; 3], Mat3); 4],
    len: usize,
}

impl Blocks {
    pub fn new() -> Self {
        Blocks { items: [(Col::position(0), Mat3::zeros()); 4], len: 0 }
    }

    /// Appends a block (at most four).
    pub fn push(&mut self, cols: [Col; 3], m: Mat3) {
        self.items[self.len] = (cols, m);
        self.len += 1;
    }
}

impl std::ops::Deref for Blocks {
    type Target = [([Col; 3], Mat3)];
    fn deref(&self) -> &Self::Target {
        &self.items[..self.len]
    }
}

/// Frame kinematics of both anchors (A may be fixed in space).
pub(super) struct Pair {
    pub slot_a: Option<usize>,
    pub slot_b: usize,
    pub f_a: Vec3,
    pub f_b: Vec3,
    pub q_a: Mat3,
    pub q_b: Mat3,
    /// `p_b − p_a`.
    pub d: Vec3,
    /// `p_b − x_a`.
    pub h: Vec3,
    pub omega_a: Vec3,
    pub omega_b: Vec3,
    /// `ṗ_b − ṗ_a − ω_a × d` … in the form `ẋ_b + ω_b × f_b − ẋ_a − ω_a × h`.
    pub u: Vec3,
}

fn side(anchor: &Anchor, slot: Option<usize>, st: &dyn ElementState) -> (Vec3, Vec3, Mat3, Vec3, Vec3) {
    match (anchor, slot) {
        (Anchor::Node { offset, orientation, .. }, Some(s)) => {
            let n = st.node(s);
            (n.x, n.r * offset, n.r * orientation, n.xdot, n.omega)
        }
        (Anchor::Ground { position, orientation }, _) => (*position, Vec3::zeros(), *orientation, Vec3::zeros(), Vec3::zeros()),
        (Anchor::Node { .. }, None) => unreachable!("a node anchor always has a slot"),
    }
}

pub(super) fn node_labels(a: &Anchor, b: &Anchor) -> Vec<Label> {
    [a, b].into_iter().filter_map(|x| if let Anchor::Node { label, .. } = x { Some(*label) } else { None }).collect()
}

impl Pair {
    pub fn new(a: &Anchor, b: &Anchor, st: &dyn ElementState) -> Self {
        let slot_a = matches!(a, Anchor::Node { .. }).then_some(0);
        let slot_b = usize::from(slot_a.is_some());
        let (x_a, f_a, q_a, v_a, omega_a) = side(a, slot_a, st);
        let (x_b, f_b, q_b, v_b, omega_b) = side(b, Some(slot_b), st);
        // Node positions first, as MBDyn's joints do (`x1 + d1 − x2 − d2`): nearby nodes
        // subtract exactly, so only the rounding of the positions as written remains.
        let h = (x_b - x_a) + f_b;
        Pair { slot_a, slot_b, f_a, f_b, q_a, q_b, d: h - f_a, h, omega_a, omega_b, u: v_b + omega_b.cross(&f_b) - v_a - omega_a.cross(&h) }
    }

    /// Residual of a force `F` at `p_b` on B, and `−F` (also at `p_b`) on A.
    pub fn add_force(&self, out: &mut dyn ResidualSink, force: &Vec3) {
        add_vec(out, Row::force(self.slot_b), force);
        add_vec(out, Row::moment(self.slot_b), &self.f_b.cross(force));
        if let Some(a) = self.slot_a {
            add_vec(out, Row::force(a), &(-force));
            add_vec(out, Row::moment(a), &(-self.h.cross(force)));
        }
    }

    /// Residual of a moment `m` on B and `−m` on A.
    pub fn add_moment(&self, out: &mut dyn ResidualSink, m: &Vec3) {
        add_vec(out, Row::moment(self.slot_b), m);
        if let Some(a) = self.slot_a {
            add_vec(out, Row::moment(a), &(-m));
        }
    }

    /// The column of a multiplier whose unit reaction is the force `df` at `p_b` and the
    /// moment `dm` on B (both opposite on A, the force with its arm from `x_a`).
    pub fn add_reaction_column(&self, out: &mut dyn JacobianSink, col: Col, df: &Vec3, dm: &Vec3) {
        let (b, mb, ma) = (self.slot_b, self.f_b.cross(df) + dm, self.h.cross(df) + dm);
        for i in 0..3 {
            out.add(Row::Equilibrium { slot: b, comp: i }, col, df[i]);
            out.add(Row::Equilibrium { slot: b, comp: 3 + i }, col, mb[i]);
            if let Some(a) = self.slot_a {
                out.add(Row::Equilibrium { slot: a, comp: i }, col, -df[i]);
                out.add(Row::Equilibrium { slot: a, comp: 3 + i }, col, -ma[i]);
            }
        }
    }

    /// Jacobian of [`Pair::add_force`] for `F = Q_a φ`: geometric terms at fixed `φ`, plus
    /// `∂(reaction)/∂φ · dφ` for the given derivative blocks of `φ`.
    pub fn add_force_jacobian(&self, out: &mut dyn JacobianSink, force: &Vec3, dphi: &[([Col; 3], Mat3)]) {
        let (b, fx, fbx, hx) = (self.slot_b, skew(force), skew(&self.f_b), skew(&self.h));
        add_block(out, Row::moment(b), Col::rotation(b), &(fx * fbx));
        if let Some(a) = self.slot_a {
            add_block(out, Row::force(b), Col::rotation(a), &(-fx));
            add_block(out, Row::moment(b), Col::rotation(a), &(-fbx * fx));
            add_block(out, Row::force(a), Col::rotation(a), &fx);
            add_block(out, Row::moment(a), Col::position(b), &fx);
            add_block(out, Row::moment(a), Col::rotation(b), &(-fx * fbx));
            add_block(out, Row::moment(a), Col::position(a), &(-fx));
            add_block(out, Row::moment(a), Col::rotation(a), &(hx * fx));
        }
        if dphi.is_empty() {
            return;
        }
        let mut rows = vec![(Row::force(b), self.q_a), (Row::moment(b), fbx * self.q_a)];
        if let Some(a) = self.slot_a {
            rows.push((Row::force(a), -self.q_a));
            rows.push((Row::moment(a), -hx * self.q_a));
        }
        for (r, dr) in &rows {
            for (c, dc) in dphi {
                add_block(out, *r, *c, &(dr * dc));
            }
        }
    }

    /// `∂(Q_aᵀ d)/∂q` blocks.
    pub fn strain_derivatives(&self) -> Vec<([Col; 3], Mat3)> {
        self.strain_blocks().to_vec()
    }

    /// [`Pair::strain_derivatives`] without allocation.
    pub fn strain_blocks(&self) -> Blocks {
        let qt = self.q_a.transpose();
        let mut v = Blocks::new();
        v.push(Col::position(self.slot_b), qt);
        v.push(Col::rotation(self.slot_b), -qt * skew(&self.f_b));
        if let Some(a) = self.slot_a {
            v.push(Col::position(a), -qt);
            v.push(Col::rotation(a), qt * skew(&self.h));
        }
        v
    }

    /// `∂(Q_aᵀ u)/∂q` blocks, with `u = ẋ_b + ω_b × f_b − ẋ_a − ω_a × h`.
    pub fn rate_derivatives(&self) -> Vec<([Col; 3], Mat3)> {
        let (qt, b) = (self.q_a.transpose(), self.slot_b);
        let (fbx, wax, wbx) = (skew(&self.f_b), skew(&self.omega_a), skew(&self.omega_b));
        let mut v = vec![
            (Col::velocity(b), qt),
            (Col::angular_velocity(b), -qt * fbx),
            (Col::position(b), -qt * wax),
            (Col::rotation(b), qt * (wax - wbx) * fbx),
        ];
        if let Some(a) = self.slot_a {
            v.push((Col::velocity(a), -qt));
            v.push((Col::angular_velocity(a), qt * skew(&self.h)));
            v.push((Col::position(a), qt * wax));
            v.push((Col::rotation(a), qt * skew(&self.u)));
        }
        v
    }
}

