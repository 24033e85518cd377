//! Holonomic joints between two frames: clamp, spherical hinge, revolute hinge, and the
//! total joint that locks any subset of relative displacement and rotation components.
//!
//! Frame A is `p_a = x_a + R_a o_a`, `Q_a = R_a H_a` (a node, or fixed in space); frame B
//! is `p_b = x_b + R_b o_b`, `Q_b = R_b H_b`. Constraints, in frame A:
//! position `c = Q_aᵀ (p_b − p_a)`, rotation `r = ax(Q_aᵀ Q_b)` (zero for aligned frames,
//! `(0, 0, sin φ)` for a rotation φ about the common z axis). Each locked component adds a
//! multiplier; the reactions `Φ_/qᵀ λ` are a force `F = Q_a λ_p` at `p_b` and a moment
//! `m = Q_a Pᵀ λ_r` with `P = ½ (tr M I − M)`, `M = Q_aᵀ Q_b`, equal and opposite on A.

use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, ResidualSink, Row};
use crate::kinematics::{axial_of_skew_part, skew, skew_part_jacobian, Mat3, Vec3};
use crate::model::Label;

/// One side of a joint.
#[derive(Clone, Debug)]
pub enum Anchor {
    /// A point and frame fixed in space.
    Ground { position: Vec3, orientation: Mat3 },
    /// A point and frame attached to a node (offset and orientation in the node frame).
    Node { label: Label, offset: Vec3, orientation: Mat3 },
}

/// Which joint, for names and counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    Clamp,
    SphericalHinge,
    RevoluteHinge,
    TotalJoint,
}

/// A joint locking the selected components of relative position and rotation.
#[derive(Clone, Debug)]
pub struct Joint {
    pub label: Label,
    pub kind: JointKind,
    pub a: Anchor,
    pub b: Anchor,
    pub position_locked: [bool; 3],
    pub rotation_locked: [bool; 3],
}

impl Joint {
    /// Clamps a node at the given position and orientation (6 multipliers).
    pub fn clamp(label: Label, node: Label, position: Vec3, orientation: Mat3) -> Self {
        Joint {
            label,
            kind: JointKind::Clamp,
            a: Anchor::Ground { position, orientation },
            b: Anchor::Node { label: node, offset: Vec3::zeros(), orientation: Mat3::identity() },
            position_locked: [true; 3],
            rotation_locked: [true; 3],
        }
    }

    /// Coincident points, free relative rotation (3 multipliers).
    pub fn spherical_hinge(label: Label, a: Anchor, b: Anchor) -> Self {
        Joint { label, kind: JointKind::SphericalHinge, a, b, position_locked: [true; 3], rotation_locked: [false; 3] }
    }

    /// Coincident points, relative rotation only about the common z axis of the two hinge
    /// frames (5 multipliers).
    pub fn revolute_hinge(label: Label, a: Anchor, b: Anchor) -> Self {
        Joint { label, kind: JointKind::RevoluteHinge, a, b, position_locked: [true; 3], rotation_locked: [true, true, false] }
    }

    /// Locks the chosen components of relative position and rotation (in frame A).
    pub fn total(label: Label, a: Anchor, b: Anchor, position_locked: [bool; 3], rotation_locked: [bool; 3]) -> Self {
        Joint { label, kind: JointKind::TotalJoint, a, b, position_locked, rotation_locked }
    }

    fn locked(&self) -> impl Iterator<Item = (bool, usize)> + '_ {
        let p = (0..3).filter(|&k| self.position_locked[k]).map(|k| (true, k));
        let r = (0..3).filter(|&k| self.rotation_locked[k]).map(|k| (false, k));
        p.chain(r)
    }
}

/// Everything the residual and Jacobian need, evaluated once.
struct Frames {
    slot_a: Option<usize>,
    slot_b: usize,
    f_b: Vec3,
    q_a: Mat3,
    d: Vec3,
    h: Vec3,
    m_rel: Mat3,
    lambda_p: Vec3,
    lambda_r: Vec3,
}

fn anchor_frame(anchor: &Anchor, slot: Option<usize>, st: &dyn ElementState) -> (Vec3, Vec3, Mat3) {
    match (anchor, slot) {
        (Anchor::Node { offset, orientation, .. }, Some(s)) => {
            let n = st.node(s);
            (n.x, n.r * offset, n.r * orientation)
        }
        (Anchor::Ground { position, orientation }, _) => (*position, Vec3::zeros(), *orientation),
        (Anchor::Node { .. }, None) => unreachable!("a node anchor always has a slot"),
    }
}

impl Joint {
    fn frames(&self, st: &dyn ElementState) -> Frames {
        let slot_a = matches!(self.a, Anchor::Node { .. }).then_some(0);
        let slot_b = usize::from(slot_a.is_some());
        let (x_a, f_a, q_a) = anchor_frame(&self.a, slot_a, st);
        let (x_b, f_b, q_b) = anchor_frame(&self.b, Some(slot_b), st);
        let d = x_b + f_b - x_a - f_a;
        let (mut lambda_p, mut lambda_r) = (Vec3::zeros(), Vec3::zeros());
        for (k, (is_pos, comp)) in self.locked().enumerate() {
            if is_pos {
                lambda_p[comp] = st.multiplier(k);
            } else {
                lambda_r[comp] = st.multiplier(k);
            }
        }
        Frames { slot_a, slot_b, f_b, q_a, d, h: d + f_a, m_rel: q_a.transpose() * q_b, lambda_p, lambda_r }
    }
}

impl Element for Joint {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        match self.kind {
            JointKind::Clamp => "clamp",
            JointKind::SphericalHinge => "spherical hinge",
            JointKind::RevoluteHinge => "revolute hinge",
            JointKind::TotalJoint => "total joint",
        }
    }
    fn nodes(&self) -> Vec<Label> {
        [&self.a, &self.b].into_iter().filter_map(|a| if let Anchor::Node { label, .. } = a { Some(*label) } else { None }).collect()
    }
    fn multipliers(&self) -> Vec<String> {
        self.locked().map(|(p, k)| format!("{} {}", if p { "f" } else { "m" }, ["x", "y", "z"][k])).collect()
    }

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let fr = self.frames(st);
        let c = fr.q_a.transpose() * fr.d;
        let r = axial_of_skew_part(&fr.m_rel);
        for (k, (is_pos, comp)) in self.locked().enumerate() {
            out.add(Row::Constraint(k), if is_pos { c[comp] } else { r[comp] });
        }
        let force = fr.q_a * fr.lambda_p;
        let moment = fr.q_a * skew_part_jacobian(&fr.m_rel).transpose() * fr.lambda_r;
        add_vec(out, Row::force(fr.slot_b), &force);
        add_vec(out, Row::moment(fr.slot_b), &(fr.f_b.cross(&force) + moment));
        if let Some(a) = fr.slot_a {
            add_vec(out, Row::force(a), &(-force));
            add_vec(out, Row::moment(a), &(-fr.h.cross(&force) - moment));
        }
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let fr = self.frames(st);
        let (b, qt) = (fr.slot_b, fr.q_a.transpose());
        let p = skew_part_jacobian(&fr.m_rel);
        let r = axial_of_skew_part(&fr.m_rel);
        let force = fr.q_a * fr.lambda_p;
        let moment = fr.q_a * p.transpose() * fr.lambda_r;
        // δ(Pᵀλ_r) = K Q_aᵀ (δθ_b − δθ_a), K = −(λ_r rᵀ + ½ Mᵀ [λ_r×]).
        let k = -(fr.lambda_r * r.transpose() + 0.5 * fr.m_rel.transpose() * skew(&fr.lambda_r));
        let qkq = fr.q_a * k * qt;
        let (fx, fbx, mx, hx) = (skew(&force), skew(&fr.f_b), skew(&moment), skew(&fr.h));

        // Constraint rows.
        let dc_dtheta_b = -qt * fbx;
        let dr_dtheta_b = p * qt;
        for (row, (is_pos, comp)) in self.locked().enumerate() {
            let row = Row::Constraint(row);
            for j in 0..3 {
                if is_pos {
                    out.add(row, Col::Position { slot: b, comp: j }, qt[(comp, j)]);
                    out.add(row, Col::Rotation { slot: b, comp: j }, dc_dtheta_b[(comp, j)]);
                } else {
                    out.add(row, Col::Rotation { slot: b, comp: j }, dr_dtheta_b[(comp, j)]);
                }
            }
            if let Some(a) = fr.slot_a {
                let dc_dtheta_a = qt * hx;
                for j in 0..3 {
                    if is_pos {
                        out.add(row, Col::Position { slot: a, comp: j }, -qt[(comp, j)]);
                        out.add(row, Col::Rotation { slot: a, comp: j }, dc_dtheta_a[(comp, j)]);
                    } else {
                        out.add(row, Col::Rotation { slot: a, comp: j }, -dr_dtheta_b[(comp, j)]);
                    }
                }
            }
        }

        // Reactions on B: F and f_b × F + m.
        add_block(out, Row::moment(b), Col::rotation(b), &(fx * fbx + qkq));
        // Multiplier columns: ∂F/∂λ_p = Q_a e_k, ∂m/∂λ_r = Q_a Pᵀ e_k.
        let ptq = fr.q_a * p.transpose();
        for (col, (is_pos, comp)) in self.locked().enumerate() {
            let (df, dm) = if is_pos {
                let df = fr.q_a.column(comp).into_owned();
                (df, fr.f_b.cross(&df))
            } else {
                (Vec3::zeros(), ptq.column(comp).into_owned())
            };
            for i in 0..3 {
                out.add(Row::Equilibrium { slot: b, comp: i }, Col::Multiplier(col), df[i]);
                out.add(Row::Equilibrium { slot: b, comp: 3 + i }, Col::Multiplier(col), dm[i]);
                if let Some(a) = fr.slot_a {
                    let dma = if is_pos { fr.h.cross(&df) } else { dm };
                    out.add(Row::Equilibrium { slot: a, comp: i }, Col::Multiplier(col), -df[i]);
                    out.add(Row::Equilibrium { slot: a, comp: 3 + i }, Col::Multiplier(col), -dma[i]);
                }
            }
        }
        if let Some(a) = fr.slot_a {
            add_block(out, Row::force(b), Col::rotation(a), &(-fx));
            add_block(out, Row::moment(b), Col::rotation(a), &(-fbx * fx - mx - qkq));
            // Reactions on A: −F and −h × F − m.
            add_block(out, Row::force(a), Col::rotation(a), &fx);
            add_block(out, Row::moment(a), Col::position(b), &fx);
            add_block(out, Row::moment(a), Col::rotation(b), &(-fx * fbx - qkq));
            add_block(out, Row::moment(a), Col::position(a), &(-fx));
            add_block(out, Row::moment(a), Col::rotation(a), &(hx * fx + mx + qkq));
        }
    }
}
