//! Holonomic joints between two frames: clamp, spherical hinge, revolute hinge, and the
//! total joint that locks any subset of relative displacement and rotation components.
//!
//! Frame A is `p_a = x_a + R_a o_a`, `Q_a = R_a H_a` (a node, or fixed in space); frame B
//! is `p_b = x_b + R_b o_b`, `Q_b = R_b H_b`. Constraints, in frame A:
//! position `c = Q_aᵀ (p_b − p_a)`, rotation `r = ax(Q_aᵀ Q_b)` (zero for aligned frames,
//! `(0, 0, sin φ)` for a rotation φ about the common z axis). Each locked component adds a
//! multiplier (the revolute hinge's position constraint is global instead, `p_b − p_a`, with
//! `F = λ_p`, as MBDyn's planej.cc); the reactions `Φ_/qᵀ λ` are a force `F = Q_a λ_p` at `p_b` and a moment
//! `m = Q_a Pᵀ λ_r` with `P = ½ (tr M I − M)`, `M = Q_aᵀ Q_b`, equal and opposite on A.

use super::anchor::{node_labels, Anchor, Blocks, Pair};
use super::contract::{add_block, Col, Element, ElementState, JacobianSink, ResidualSink, Row};
use crate::kinematics::{axial_of_skew_part, skew, skew_part_jacobian, Mat3, Vec3};
use super::contract::Label;
use crate::element::Outputs;

/// Which joint, for names and counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    Clamp,
    SphericalHinge,
    RevoluteHinge,
    TotalJoint,
    /// A point of B on the line through A's point along A's axis 3 (MBDyn's `in line`).
    InLine,
    /// A point of B in the plane through A's point normal to A's axis 3 (`in plane`).
    InPlane,
    /// All relative rotation locked (`prismatic`).
    Prismatic,
    /// Relative rotation only about the common axis 3, position free (`revolute rotation`).
    RevoluteRotation,
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

    /// Relative rotation only about the common z axis, relative position free (2
    /// multipliers: MBDyn's `revolute rotation`, planej.cc `PlaneRotationJoint`).
    pub fn revolute_rotation(label: Label, a: Anchor, b: Anchor) -> Self {
        Joint { label, kind: JointKind::RevoluteRotation, a, b, position_locked: [false; 3], rotation_locked: [true, true, false] }
    }

    /// B's point on A's axis 3 (2 multipliers: the force across the line).
    pub fn in_line(label: Label, a: Anchor, b: Anchor) -> Self {
        Joint { label, kind: JointKind::InLine, a, b, position_locked: [true, true, false], rotation_locked: [false; 3] }
    }

    /// B's point in A's 1-2 plane (1 multiplier: the force along the normal).
    pub fn in_plane(label: Label, a: Anchor, b: Anchor) -> Self {
        Joint { label, kind: JointKind::InPlane, a, b, position_locked: [false, false, true], rotation_locked: [false; 3] }
    }

    /// The two frames keep their relative orientation (3 multipliers: the moment).
    pub fn prismatic(label: Label, a: Anchor, b: Anchor) -> Self {
        Joint { label, kind: JointKind::Prismatic, a, b, position_locked: [false; 3], rotation_locked: [true; 3] }
    }

    /// Locks the chosen components of relative position and rotation (in frame A).
    pub fn total(label: Label, a: Anchor, b: Anchor, position_locked: [bool; 3], rotation_locked: [bool; 3]) -> Self {
        Joint { label, kind: JointKind::TotalJoint, a, b, position_locked, rotation_locked }
    }

    /// Whether the position constraint and its reaction are in the global frame, `p_b − p_a
    /// = 0` with `F = λ_p` (MBDyn's revolute hinge, planej.cc), rather than in frame A.
    /// The same zero set; the Newton iterates differ where frame A turns.
    fn global_position(&self) -> bool {
        self.kind == JointKind::RevoluteHinge
    }

    /// Whether the two rotation constraints are MBDyn's `e₃ₐ · e₂ᵦ = 0`, `−e₃ₐ · e₁ᵦ = 0`
    /// (planej.cc; in frame A, `M₃₂` and `−M₃₁`) rather than the skew part of `M`: the skew
    /// part's rows lose their rank where the free relative rotation about axis 3 passes
    /// half a turn (`M = R_z(π)`: `P = ½ (tr M I − M)` has zero rows x and y), and
    /// MBDyn's `tests/joints/screw/screw_test_1.mbd` stopped there (t = 2.51 s, θ = π).
    fn axis_rotation(&self) -> bool {
        matches!(self.kind, JointKind::RevoluteHinge | JointKind::RevoluteRotation)
    }

    /// The rotation constraint `r(M)`, its derivative `P` (`δr = P δη` for `δM = [δη×] M`)
    /// and `K` (`δ(Pᵀ λ_r) = K δη`).
    fn rotation_rows(&self, m: &Mat3, lambda_r: &Vec3) -> (Vec3, Mat3, Mat3) {
        if !self.axis_rotation() {
            let r = axial_of_skew_part(m);
            return (r, skew_part_jacobian(m), -(lambda_r * r.transpose() + 0.5 * m.transpose() * skew(lambda_r)));
        }
        // δM_ij = δη · (m_j × e_i), m_j = M e_j; δ(m_j × e₃) = [e₃×][m_j×] δη.
        let (m1, m2, e3) = (m.column(0).into_owned(), m.column(1).into_owned(), Vec3::z());
        let r = Vec3::new(m[(2, 1)], -m[(2, 0)], 0.0);
        let (gx, gy) = (m2.cross(&e3), -m1.cross(&e3));
        let pm = Mat3::from_rows(&[gx.transpose(), gy.transpose(), Vec3::zeros().transpose()]);
        let e3x = skew(&e3);
        let k = lambda_r[0] * e3x * skew(&m2) - lambda_r[1] * e3x * skew(&m1);
        (r, pm, k)
    }

    fn locked(&self) -> impl Iterator<Item = (bool, usize)> + '_ {
        let p = (0..3).filter(|&k| self.position_locked[k]).map(|k| (true, k));
        let r = (0..3).filter(|&k| self.rotation_locked[k]).map(|k| (false, k));
        p.chain(r)
    }
}

/// Multipliers of the locked components as 3-vectors in frame A (zeros where free).
fn lambdas(joint: &Joint, st: &dyn ElementState) -> (Vec3, Vec3) {
    let (mut p, mut r) = (Vec3::zeros(), Vec3::zeros());
    for (k, (is_pos, comp)) in joint.locked().enumerate() {
        if is_pos {
            p[comp] = st.multiplier(k);
        } else {
            r[comp] = st.multiplier(k);
        }
    }
    (p, r)
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
            JointKind::InLine => "in line",
            JointKind::InPlane => "in plane",
            JointKind::Prismatic => "prismatic",
            JointKind::RevoluteRotation => "revolute rotation",
        }
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.a, &self.b)
    }
    fn multipliers(&self) -> Vec<String> {
        self.locked().map(|(p, k)| format!("{} {}", if p { "f" } else { "m" }, ["x", "y", "z"][k])).collect()
    }

    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let m_rel = p.q_a.transpose() * p.q_b;
        let c = if self.global_position() { p.d } else { p.q_a.transpose() * p.d };
        let (lambda_p, lambda_r) = lambdas(self, st);
        let (r, pm, _) = self.rotation_rows(&m_rel, &lambda_r);
        for (k, (is_pos, comp)) in self.locked().enumerate() {
            out.add(Row::Constraint(k), if is_pos { c[comp] } else { r[comp] });
        }
        p.add_force(out, &(if self.global_position() { lambda_p } else { p.q_a * lambda_p }));
        p.add_moment(out, &(p.q_a * pm.transpose() * lambda_r));
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (b, qt) = (p.slot_b, p.q_a.transpose());
        let m_rel = qt * p.q_b;
        let (lambda_p, lambda_r) = lambdas(self, st);
        let (_, pm, k) = self.rotation_rows(&m_rel, &lambda_r);
        let global = self.global_position();
        let force = if global { lambda_p } else { p.q_a * lambda_p };

        // Constraint rows: ∂c/∂q from the anchors, ∂r/∂θ_b = P Q_aᵀ = −∂r/∂θ_a.
        let dc = if global { global_position_derivatives(&p) } else { p.strain_blocks() };
        let mut dr = Blocks::new();
        dr.push(Col::rotation(b), pm * qt);
        if let Some(a) = p.slot_a {
            dr.push(Col::rotation(a), -pm * qt);
        }
        for (row, (is_pos, comp)) in self.locked().enumerate() {
            for (cols, m) in if is_pos { dc.iter() } else { dr.iter() } {
                for (j, col) in cols.iter().enumerate() {
                    out.add(Row::Constraint(row), *col, m[(comp, j)]);
                }
            }
        }

        // The force reaction F = Q_a λ_p: geometric terms, then its multiplier columns.
        if global {
            add_global_force_jacobian(&p, out, &force);
        } else {
            p.add_force_jacobian(out, &force, &[]);
        }
        let ptq = p.q_a * pm.transpose();
        for (col, (is_pos, comp)) in self.locked().enumerate() {
            let df = if global { Vec3::ith(comp, 1.0) } else { p.q_a.column(comp).into_owned() };
            let (df, dm) = if is_pos { (df, Vec3::zeros()) } else { (Vec3::zeros(), ptq.column(comp).into_owned()) };
            p.add_reaction_column(out, Col::Multiplier(col), &df, &dm);
        }

        // The moment reaction m = Q_a Pᵀ λ_r: δm = −[m×] δθ_a + Q_a K Q_aᵀ (δθ_b − δθ_a),
        // K from `rotation_rows`.
        let moment = ptq * lambda_r;
        let qkq = p.q_a * k * qt;
        add_block(out, Row::moment(b), Col::rotation(b), &qkq);
        if let Some(a) = p.slot_a {
            let d_theta_a = -skew(&moment) - qkq;
            add_block(out, Row::moment(b), Col::rotation(a), &d_theta_a);
            add_block(out, Row::moment(a), Col::rotation(b), &(-qkq));
            add_block(out, Row::moment(a), Col::rotation(a), &(-d_theta_a));
        }
    }
}

impl Outputs for Joint {
    fn private_data(&self, name: &str) -> Option<super::contract::PrivateDatum> {
        self.private_datum(name)
    }
}

/// `∂(p_b − p_a)/∂q` blocks: `δd = δx_b − [f_b×] δθ_b − δx_a + [f_a×] δθ_a`.
fn global_position_derivatives(p: &Pair) -> Blocks {
    let mut v = Blocks::new();
    v.push(Col::position(p.slot_b), Mat3::identity());
    v.push(Col::rotation(p.slot_b), -skew(&p.f_b));
    if let Some(a) = p.slot_a {
        v.push(Col::position(a), -Mat3::identity());
        v.push(Col::rotation(a), skew(&p.f_a));
    }
    v
}

/// Geometric terms of [`Pair::add_force`] for a force fixed in the global frame: the arms
/// `f_b` (on B) and `h = p_b − x_a` (on A) turn and move, the force does not.
fn add_global_force_jacobian(p: &Pair, out: &mut dyn JacobianSink, force: &Vec3) {
    let (b, fx, fbx) = (p.slot_b, skew(force), skew(&p.f_b));
    add_block(out, Row::moment(b), Col::rotation(b), &(fx * fbx));
    if let Some(a) = p.slot_a {
        add_block(out, Row::moment(a), Col::position(b), &fx);
        add_block(out, Row::moment(a), Col::rotation(b), &(-fx * fbx));
        add_block(out, Row::moment(a), Col::position(a), &(-fx));
    }
}
