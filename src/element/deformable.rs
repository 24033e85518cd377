//! Deformable elements with linear elastic / viscoelastic laws: the deformable
//! displacement joint (3-D spring–damper between two points), the deformable hinge
//! (angular spring–damper) and the rod (axial spring).

use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, ResidualSink, Row};
use super::joint::Anchor;
use crate::kinematics::{axial_of_skew_part, skew, skew_part_jacobian, Mat3, Vec3};
use crate::model::Label;

/// `φ = K ε + C ε̇` with 3x3 stiffness and viscosity matrices (linear elastic when `C = 0`).
#[derive(Clone, Debug, PartialEq)]
pub struct LinearViscoelastic {
    pub stiffness: Mat3,
    pub viscosity: Mat3,
}

impl LinearViscoelastic {
    pub fn elastic(stiffness: Mat3) -> Self {
        LinearViscoelastic { stiffness, viscosity: Mat3::zeros() }
    }
    pub fn isotropic(k: f64, c: f64) -> Self {
        LinearViscoelastic { stiffness: k * Mat3::identity(), viscosity: c * Mat3::identity() }
    }
}

/// Frame kinematics of both anchors (A may be fixed in space).
struct Pair {
    slot_a: Option<usize>,
    slot_b: usize,
    f_a: Vec3,
    f_b: Vec3,
    q_a: Mat3,
    q_b: Mat3,
    /// `p_b − p_a`.
    d: Vec3,
    /// `p_b − x_a`.
    h: Vec3,
    omega_a: Vec3,
    omega_b: Vec3,
    /// `ṗ_b − ṗ_a − ω_a × d` … in the form `ẋ_b + ω_b × f_b − ẋ_a − ω_a × h`.
    u: Vec3,
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

fn node_labels(a: &Anchor, b: &Anchor) -> Vec<Label> {
    [a, b].into_iter().filter_map(|x| if let Anchor::Node { label, .. } = x { Some(*label) } else { None }).collect()
}

impl Pair {
    fn new(a: &Anchor, b: &Anchor, st: &dyn ElementState) -> Self {
        let slot_a = matches!(a, Anchor::Node { .. }).then_some(0);
        let slot_b = usize::from(slot_a.is_some());
        let (x_a, f_a, q_a, v_a, omega_a) = side(a, slot_a, st);
        let (x_b, f_b, q_b, v_b, omega_b) = side(b, Some(slot_b), st);
        let h = x_b + f_b - x_a;
        Pair { slot_a, slot_b, f_a, f_b, q_a, q_b, d: h - f_a, h, omega_a, omega_b, u: v_b + omega_b.cross(&f_b) - v_a - omega_a.cross(&h) }
    }

    /// Residual of a force `F` at `p_b` on B, and `−F` (also at `p_b`) on A.
    fn add_force(&self, out: &mut dyn ResidualSink, force: &Vec3) {
        add_vec(out, Row::force(self.slot_b), force);
        add_vec(out, Row::moment(self.slot_b), &self.f_b.cross(force));
        if let Some(a) = self.slot_a {
            add_vec(out, Row::force(a), &(-force));
            add_vec(out, Row::moment(a), &(-self.h.cross(force)));
        }
    }

    /// Jacobian of [`Pair::add_force`] for `F = Q_a φ`: geometric terms at fixed `φ`, plus
    /// `∂(reaction)/∂φ · dφ` for the given derivative blocks of `φ`.
    fn add_force_jacobian(&self, out: &mut dyn JacobianSink, force: &Vec3, dphi: &[([Col; 3], Mat3)]) {
        let (b, fx, fbx, hx) = (self.slot_b, skew(force), skew(&self.f_b), skew(&self.h));
        add_block(out, Row::moment(b), Col::rotation(b), &(fx * fbx));
        let mut rows = vec![(Row::force(b), self.q_a), (Row::moment(b), fbx * self.q_a)];
        if let Some(a) = self.slot_a {
            add_block(out, Row::force(b), Col::rotation(a), &(-fx));
            add_block(out, Row::moment(b), Col::rotation(a), &(-fbx * fx));
            add_block(out, Row::force(a), Col::rotation(a), &fx);
            add_block(out, Row::moment(a), Col::position(b), &fx);
            add_block(out, Row::moment(a), Col::rotation(b), &(-fx * fbx));
            add_block(out, Row::moment(a), Col::position(a), &(-fx));
            add_block(out, Row::moment(a), Col::rotation(a), &(hx * fx));
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
    fn strain_derivatives(&self) -> Vec<([Col; 3], Mat3)> {
        let qt = self.q_a.transpose();
        let mut v = vec![(Col::position(self.slot_b), qt), (Col::rotation(self.slot_b), -qt * skew(&self.f_b))];
        if let Some(a) = self.slot_a {
            v.push((Col::position(a), -qt));
            v.push((Col::rotation(a), qt * skew(&self.h)));
        }
        v
    }

    /// `∂(Q_aᵀ u)/∂q` blocks, with `u = ẋ_b + ω_b × f_b − ẋ_a − ω_a × h`.
    fn rate_derivatives(&self) -> Vec<([Col; 3], Mat3)> {
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

fn scaled(blocks: Vec<([Col; 3], Mat3)>, m: &Mat3) -> Vec<([Col; 3], Mat3)> {
    blocks.into_iter().map(|(c, d)| (c, m * d)).collect()
}

/// 3-D spring–damper between two points; strain `ε = Q_aᵀ (p_b − p_a) − rest` and its
/// rate in frame A; force `Q_a (K ε + C ε̇)` pulls B back toward A.
#[derive(Clone, Debug)]
pub struct DeformableDisplacement {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    pub law: LinearViscoelastic,
    /// Unstrained relative position, frame A [m].
    pub rest: Vec3,
}

impl DeformableDisplacement {
    fn phi(&self, p: &Pair) -> Vec3 {
        let qt = p.q_a.transpose();
        self.law.stiffness * (qt * p.d - self.rest) + self.law.viscosity * (qt * p.u)
    }
}

impl Element for DeformableDisplacement {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "deformable displacement joint"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.a, &self.b)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let p = Pair::new(&self.a, &self.b, st);
        p.add_force(out, &(p.q_a * self.phi(&p)));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let mut dphi = scaled(p.strain_derivatives(), &self.law.stiffness);
        dphi.extend(scaled(p.rate_derivatives(), &self.law.viscosity));
        p.add_force_jacobian(out, &(p.q_a * self.phi(&p)), &dphi);
    }
}

/// Angular spring–damper: relative rotation `r = ax(Q_aᵀ Q_b)` (the rotation vector to
/// first order), rate `ṙ = P(M) Q_aᵀ (ω_b − ω_a)`; moment `Q_a (K r + C ṙ)` on B, opposite
/// on A.
#[derive(Clone, Debug)]
pub struct DeformableHinge {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    pub law: LinearViscoelastic,
}

impl Element for DeformableHinge {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "deformable hinge"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.a, &self.b)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let m_rel = p.q_a.transpose() * p.q_b;
        let w = p.q_a.transpose() * (p.omega_b - p.omega_a);
        let mu = self.law.stiffness * axial_of_skew_part(&m_rel) + self.law.viscosity * skew_part_jacobian(&m_rel) * w;
        let m = p.q_a * mu;
        add_vec(out, Row::moment(p.slot_b), &m);
        if let Some(a) = p.slot_a {
            add_vec(out, Row::moment(a), &(-m));
        }
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (qa, qt) = (p.q_a, p.q_a.transpose());
        let m_rel = qt * p.q_b;
        let (pm, r) = (skew_part_jacobian(&m_rel), axial_of_skew_part(&m_rel));
        let w = qt * (p.omega_b - p.omega_a);
        let (k, c) = (self.law.stiffness, self.law.viscosity);
        let m = qa * (k * r + c * pm * w);
        // δμ = (K P + C (−w rᵀ + ½[(M w)×])) Qᵀ (δθ_b − δθ_a) + C P Qᵀ [(ω_b − ω_a)×] δθ_a
        //      + C P Qᵀ (δω_b − δω_a);  δm = −[m×] δθ_a + Q δμ.
        let d_rel = qa * (k * pm + c * (-w * r.transpose() + 0.5 * skew(&(m_rel * w)))) * qt;
        let d_omega = qa * c * pm * qt;
        let d_theta_a = -skew(&m) - d_rel + d_omega * skew(&(p.omega_b - p.omega_a));
        let (b, sa) = (p.slot_b, p.slot_a);
        for (sign, slot) in [(1.0, Some(b)), (-1.0, sa)] {
            let Some(s) = slot else { continue };
            add_block(out, Row::moment(s), Col::rotation(b), &(sign * d_rel));
            add_block(out, Row::moment(s), Col::angular_velocity(b), &(sign * d_omega));
            if let Some(a) = sa {
                add_block(out, Row::moment(s), Col::rotation(a), &(sign * d_theta_a));
                add_block(out, Row::moment(s), Col::angular_velocity(a), &(-sign * d_omega));
            }
        }
    }
}

/// Axial spring between two points: `N = (EA/l₀)(l − l₀)` along the line of the points,
/// applied at each point.
#[derive(Clone, Debug)]
pub struct Rod {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    /// Axial stiffness EA [N].
    pub axial_stiffness: f64,
    /// Unstretched length l₀ [m].
    pub length: f64,
}

impl Rod {
    /// `F = (EA/l₀)(1 − l₀/l) d` (the force on A from B's side) and `∂F/∂d`.
    fn force(&self, d: &Vec3) -> (Vec3, Mat3) {
        let (k, l0, l) = (self.axial_stiffness / self.length, self.length, d.norm());
        (k * (1.0 - l0 / l) * d, k * ((1.0 - l0 / l) * Mat3::identity() + (l0 / l.powi(3)) * d * d.transpose()))
    }
}

impl Element for Rod {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "rod"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.a, &self.b)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (f, _) = self.force(&p.d);
        add_vec(out, Row::force(p.slot_b), &f);
        add_vec(out, Row::moment(p.slot_b), &p.f_b.cross(&f));
        if let Some(a) = p.slot_a {
            add_vec(out, Row::force(a), &(-f));
            add_vec(out, Row::moment(a), &(-p.f_a.cross(&f)));
        }
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (f, kd) = self.force(&p.d);
        let (fx, fax, fbx) = (skew(&f), skew(&p.f_a), skew(&p.f_b));
        // δd = δx_b − [f_b×] δθ_b − δx_a + [f_a×] δθ_a.
        let mut dd = vec![(Col::position(p.slot_b), Mat3::identity()), (Col::rotation(p.slot_b), -fbx)];
        if let Some(a) = p.slot_a {
            dd.push((Col::position(a), -Mat3::identity()));
            dd.push((Col::rotation(a), fax));
        }
        let b = p.slot_b;
        add_block(out, Row::moment(b), Col::rotation(b), &(fx * fbx));
        for (c, m) in &dd {
            add_block(out, Row::force(b), *c, &(kd * m));
            add_block(out, Row::moment(b), *c, &(fbx * kd * m));
            if let Some(a) = p.slot_a {
                add_block(out, Row::force(a), *c, &(-kd * m));
                add_block(out, Row::moment(a), *c, &(-fax * kd * m));
            }
        }
        if let Some(a) = p.slot_a {
            add_block(out, Row::moment(a), Col::rotation(a), &(-fx * fax));
        }
    }
}
