//! Deformable elements with linear elastic / viscoelastic laws: the deformable
//! displacement joint (3-D spring–damper between two points), the deformable hinge
//! (angular spring–damper) and the rod (axial spring).

use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, ResidualSink, Row};
use super::anchor::{node_labels, Anchor, Pair};
use crate::kinematics::{rotation_vector, skew, Mat3, Vec3};
use super::contract::Label;
use crate::element::Outputs;

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

/// Angular spring–damper as MBDyn's deformable hinge (vehj.cc, `ElasticHingeJoint`,
/// `ViscousHingeJoint`): relative rotation `θ = rotvec(Q_aᵀ Q_b)` (the exact rotation
/// vector, in frame A), rate `w = Q_aᵀ (ω_b − ω_a)`; moment `Q_a (K θ + C w)` on B, opposite
/// on A.
#[derive(Clone, Debug)]
pub struct DeformableHinge {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    pub law: LinearViscoelastic,
}

/// `Γ⁻¹(θ)`: `θ' = θ + Γ⁻¹(θ) δφ` when `exp(θ×)` is turned to `exp(δφ×) exp(θ×)`
/// (MBDyn's `RotManip::DRot_I`): `I − ½ [θ×] + (1/φ² − (1 + cos φ)/(2 φ sin φ)) [θ×]²`.
pub(super) fn inverse_rotation_jacobian(theta: &Vec3) -> Mat3 {
    let phi = theta.norm();
    let c = if phi < 1e-4 { 1.0 / 12.0 + phi * phi / 720.0 } else { 1.0 / (phi * phi) - (1.0 + phi.cos()) / (2.0 * phi * phi.sin()) };
    let t = skew(theta);
    Mat3::identity() - 0.5 * t + c * t * t
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
        let (theta, w) = hinge_strains(&p);
        add_hinge_moment(out, &p, &(self.law.stiffness * theta + self.law.viscosity * w));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (theta, w) = hinge_strains(&p);
        let (k, c) = (self.law.stiffness, self.law.viscosity);
        add_hinge_jacobian(out, &p, &(k * theta + c * w), &theta, &k, &c);
    }
}

/// A hinge's relative rotation vector `θ = rotvec(Q_aᵀ Q_b)` and rate `w = Q_aᵀ (ω_b − ω_a)`.
pub(super) fn hinge_strains(p: &Pair) -> (Vec3, Vec3) {
    let qt = p.q_a.transpose();
    (rotation_vector(&(qt * p.q_b)), qt * (p.omega_b - p.omega_a))
}

/// The moment `Q_a φ` on B and `−Q_a φ` on A, `φ` the law's moment in frame A.
pub(super) fn add_hinge_moment(out: &mut dyn ResidualSink, p: &Pair, phi: &Vec3) {
    let m = p.q_a * phi;
    add_vec(out, Row::moment(p.slot_b), &m);
    if let Some(a) = p.slot_a {
        add_vec(out, Row::moment(a), &(-m));
    }
}

/// The Jacobian of [`add_hinge_moment`] for a law `φ(θ, w)` with `K = ∂φ/∂θ`, `C = ∂φ/∂w`.
pub(super) fn add_hinge_jacobian(out: &mut dyn JacobianSink, p: &Pair, phi: &Vec3, theta: &Vec3, k: &Mat3, c: &Mat3) {
    let (qa, qt) = (p.q_a, p.q_a.transpose());
    let m = qa * phi;
    // δθ = Γ⁻¹(θ) Q_aᵀ (δθ_b − δθ_a), δw = Q_aᵀ (δω_b − δω_a) + Q_aᵀ [(ω_b − ω_a)×] δθ_a,
    // δm = −[m×] δθ_a + Q_a (K δθ + C δw).
    let d_rel = qa * k * inverse_rotation_jacobian(theta) * qt;
    let d_omega = qa * c * qt;
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

/// Axial spring–damper between two points (MBDyn's `rod`, rodj.cc): `N = (EA/l₀)(l − l₀)`
/// (or a function of the strain) plus, for a viscous or viscoelastic law, `C ε̇` with `ε̇ = d·ḋ/(l L₀)` (MBDyn's
/// `ViscoElasticRod`), along the line of the points, applied at each point.
#[derive(Clone, Debug)]
pub struct Rod {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    /// Axial stiffness EA [N].
    pub axial_stiffness: f64,
    /// Unstretched length l₀ [m].
    pub length: f64,
    pub viscous: Option<RodViscosity>,
    /// A nonlinear elastic law `N = f(l/l₀ − 1)` [N] (MBDyn's `scalar function elastic`),
    /// in place of `EA`.
    pub elastic: Option<super::drive::ScalarFunction>,
}

/// The viscous part of a rod's law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RodViscosity {
    /// `C` of `N = C ε̇` [N s].
    pub coefficient: f64,
    /// The length `L₀` the strain rate is measured against (the file's rod length) [m].
    pub length: f64,
}

impl Rod {
    /// `F = (EA/l₀)(1 − l₀/l) d` (the force on A from B's side), or `F = f(ε) d/l` with
    /// `ε = l/l₀ − 1`, and `∂F/∂d`.
    fn force(&self, d: &Vec3) -> (Vec3, Mat3) {
        if let Some(f) = &self.elastic {
            let l = d.norm();
            let e = d / l;
            let (n, dn) = f.value_and_derivative(l / self.length - 1.0);
            let ee = e * e.transpose();
            return (n * e, n / l * (Mat3::identity() - ee) + dn / self.length * ee);
        }
        let (k, l0, l) = (self.axial_stiffness / self.length, self.length, d.norm());
        (k * (1.0 - l0 / l) * d, k * ((1.0 - l0 / l) * Mat3::identity() + (l0 / l.powi(3)) * d * d.transpose()))
    }

    /// The viscous force `F_v = (C/L₀)(d·ḋ) d/l²` with `∂F_v/∂d` and `∂F_v/∂ḋ`.
    fn viscous_force(&self, d: &Vec3, d_dot: &Vec3) -> (Vec3, Mat3, Mat3) {
        let Some(v) = self.viscous else { return (Vec3::zeros(), Mat3::zeros(), Mat3::zeros()) };
        let (k, l2, r) = (v.coefficient / v.length, d.norm_squared(), d.dot(d_dot));
        let f = k * r / l2 * d;
        let dd = k * (r / l2 * Mat3::identity() + d * d_dot.transpose() / l2 - 2.0 * r / (l2 * l2) * d * d.transpose());
        (f, dd, k / l2 * d * d.transpose())
    }
}

/// `ḋ = u + ω_a × d` of a pair, and its derivatives `∂ḋ/∂(v, ω, θ)` of both sides.
pub(super) fn distance_rate(p: &Pair) -> (Vec3, Vec<([Col; 3], Mat3)>) {
    let (b, fbx, wbx) = (p.slot_b, skew(&p.f_b), skew(&p.omega_b));
    let mut blocks = vec![(Col::velocity(b), Mat3::identity()), (Col::angular_velocity(b), -fbx), (Col::rotation(b), -wbx * fbx)];
    if let Some(a) = p.slot_a {
        let (fax, wax) = (skew(&p.f_a), skew(&p.omega_a));
        blocks.extend([(Col::velocity(a), -Mat3::identity()), (Col::angular_velocity(a), fax), (Col::rotation(a), wax * fax)]);
    }
    (p.u + p.omega_a.cross(&p.d), blocks)
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
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (fe, _) = self.force(&p.d);
        let (fv, _, _) = self.viscous_force(&p.d, &distance_rate(&p).0);
        let f = fe + fv;
        add_pair_force(out, &p, &f);
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (fe, kd) = self.force(&p.d);
        let (d_dot, rate_blocks) = distance_rate(&p);
        let (fv, cd, c_rate) = self.viscous_force(&p.d, &d_dot);
        add_pair_force_jacobian(out, &p, &(fe + fv), &(kd + cd));
        if self.viscous.is_none() {
            return;
        }
        let (b, fbx) = (p.slot_b, skew(&p.f_b));
        for (c, m) in &rate_blocks {
            let block = c_rate * m;
            add_block(out, Row::force(b), *c, &block);
            add_block(out, Row::moment(b), *c, &(fbx * block));
            if let Some(a) = p.slot_a {
                add_block(out, Row::force(a), *c, &(-block));
                add_block(out, Row::moment(a), *c, &(-skew(&p.f_a) * block));
            }
        }
    }
}

impl Outputs for Rod {
    /// rodj.cc, `Rod::dGetPrivData`: "L" the distance `l = |d|` between the points, "LPrime"
    /// its rate `d·ḋ/l` (MBDyn's `dL0 dEpsilonPrime`).
    fn private_data(&self, name: &str) -> Option<super::contract::PrivateDatum> {
        match name {
            "L" => Some(super::private_data::of_pair(&self.a, &self.b, |p| p.d.norm())),
            "LPrime" => Some(super::private_data::of_pair(&self.a, &self.b, |p| p.d.dot(&distance_rate(p).0) / p.d.norm())),
            _ => None,
        }
    }
}

/// Residual of a force `f` along the line of the points: `f` at `p_b` on B, `−f` at `p_a`
/// on A (rods, distance joints; [`add_pair_force_jacobian`] is its Jacobian).
pub(super) fn add_pair_force(out: &mut dyn ResidualSink, p: &Pair, f: &Vec3) {
    add_vec(out, Row::force(p.slot_b), f);
    add_vec(out, Row::moment(p.slot_b), &p.f_b.cross(f));
    if let Some(a) = p.slot_a {
        add_vec(out, Row::force(a), &(-f));
        add_vec(out, Row::moment(a), &(-p.f_a.cross(f)));
    }
}

/// Jacobian of a force `f(d)` (with `∂f/∂d = kd`) applied at the point `f_b` of node b and,
/// opposite, at `f_a` of node a, `d` being the distance vector between the points:
/// `δd = δx_b − [f_b×] δθ_b − δx_a + [f_a×] δθ_a`. Returns those `δd` blocks.
pub(super) fn add_pair_force_jacobian(out: &mut dyn JacobianSink, p: &Pair, f: &Vec3, kd: &Mat3) -> Vec<([Col; 3], Mat3)> {
    let (fx, fax, fbx) = (skew(f), skew(&p.f_a), skew(&p.f_b));
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
    dd
}
