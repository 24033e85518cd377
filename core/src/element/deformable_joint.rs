//! MBDyn's `deformable joint` (vehj3.cc, `ElasticJoint`, `ViscoElasticJoint`): a 6-D
//! linear viscoelastic law between two frames, strain `k = [Q_aᵀ (p_b − p_a), rotvec(Q_aᵀ
//! Q_b)]` and its rate `k̇ = [Q_aᵀ (ṗ_b − ṗ_a − ω_a × (p_b − p_a)), Q_aᵀ (ω_b − ω_a)]` in
//! frame A, generalized force `φ = K (k − k_p) + C k̇ + φ_p`; the force `Q_a φ₁₋₃` acts at
//! `p_b` and the moment `Q_a φ₄₋₆` on B, both opposite on A. Also MBDyn's `deformable axial
//! joint` (vehj4.cc): the law only on the rotation about axis 3 of frame A; and the
//! `deformable hinge` with prestrain or prestress: the law only on the rotation. The axial
//! joint also takes MBDyn's `nlsf` 1-D laws (constltp_nlsf.cc): `M = k (θ₃ − θ_p) + f′(θ₃ −
//! θ_p) + c ω₃ + f″(ω₃) + M_p` with scalar functions `f′`, `f″`; each variant takes the
//! `nlsf` and `scalar function elastic` laws of its dimension ([`LawFunctions`] in its
//! [`SectionLaw`]), and so does the `deformable displacement joint` with such a law (the
//! law only on the position part).

use nalgebra::{Matrix6, SMatrix, Vector6};

use super::anchor::{node_labels, Anchor, Pair};
use super::beam::SectionLaw;
use super::contract::{add_block, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::deformable::inverse_rotation_jacobian;
use super::LawFunctions;
use super::drive::ScalarFunction;
use crate::kinematics::{rotation_vector, skew, Mat3, Vec3};

type Block = ([Col; 3], SMatrix<f64, 6, 3>);

/// A deformable joint with a 6-D law (or the axial one, a law on the rotation about axis 3).
#[derive(Clone, Debug)]
pub struct DeformableJoint {
    label: Label,
    a: Anchor,
    b: Anchor,
    law: SectionLaw,
    name: &'static str,
}

impl DeformableJoint {
    /// The 6-D `deformable joint`; `law` in frame A, strains `[ε₁ ε₂ ε₃ θ₁ θ₂ θ₃]`.
    pub fn new(label: Label, a: Anchor, b: Anchor, law: SectionLaw) -> Self {
        DeformableJoint { label, a, b, law, name: "deformable joint" }
    }
    /// MBDyn's `deformable hinge` with a `prestrain` `θ_p` and a `prestress` `M_p`: moment
    /// `Q_a (K (θ − θ_p) + C w + M_p)`, the 6-D law's rotation block alone.
    pub fn hinge(label: Label, a: Anchor, b: Anchor, law: &super::LinearViscoelastic, prestrain: Vec3, prestress: Vec3) -> Self {
        let block = |m: &Mat3| Matrix6::from_fn(|i, j| if i >= 3 && j >= 3 { m[(i - 3, j - 3)] } else { 0.0 });
        let mut six = SectionLaw::viscoelastic(block(&law.stiffness), block(&law.viscosity));
        for k in 0..3 {
            six.prestrain[3 + k] = prestrain[k];
            six.prestress[3 + k] = prestress[k];
        }
        DeformableJoint { label, a, b, law: six, name: "deformable hinge" }
    }
    /// The `deformable axial joint`: moment `M = k (θ₃ − θ_p) + c ω₃ + M_p` about axis 3 of
    /// frame A, `θ₃` the third component of `rotvec(Q_aᵀ Q_b)`, `ω₃ = e₃ₐ · (ω_b − ω_a)`.
    pub fn axial(label: Label, a: Anchor, b: Anchor, stiffness: f64, viscosity: f64, prestrain: f64, prestress: f64) -> Self {
        let one = |x: f64| Matrix6::from_fn(|i, j| if i == 5 && j == 5 { x } else { 0.0 });
        let mut law = SectionLaw::viscoelastic(one(stiffness), one(viscosity));
        law.prestrain[5] = prestrain;
        law.prestress[5] = prestress;
        DeformableJoint { label, a, b, law, name: "deformable axial joint" }
    }
    /// MBDyn's `deformable displacement joint` with a nonlinear law: force `Q_a φ` at `p_b`,
    /// `φ = K (ε − ε_p) + C ε̇ + f_p` plus the law's functions, `ε = Q_aᵀ (p_b − p_a)` (the
    /// 6-D joint's position part; no moment).
    pub fn displacement(label: Label, a: Anchor, b: Anchor, law: &super::LinearViscoelastic, prestrain: Vec3, prestress: Vec3) -> Self {
        let block = |m: &Mat3| Matrix6::from_fn(|i, j| if i < 3 && j < 3 { m[(i, j)] } else { 0.0 });
        let mut six = SectionLaw::viscoelastic(block(&law.stiffness), block(&law.viscosity));
        for k in 0..3 {
            six.prestrain[k] = prestrain[k];
            six.prestress[k] = prestress[k];
        }
        DeformableJoint { label, a, b, law: six, name: "deformable displacement joint" }
    }
    /// The axial joint with MBDyn's `nlsf` terms: `f′(θ₃ − θ_p)` (`elastic`) and `f″(ω₃)`
    /// (`viscous`) added to its moment.
    pub fn with_axial_functions(mut self, elastic: Option<ScalarFunction>, viscous: Option<ScalarFunction>) -> Self {
        self.law.functions = LawFunctions { elastic: vec![elastic], viscous: vec![viscous] }.placed(5, 6);
        self
    }
    /// The joint with the nonlinear terms `functions` of its 6-D law (components `[ε₁ ε₂ ε₃
    /// θ₁ θ₂ θ₃]`; [`LawFunctions::placed`] puts a hinge's or an axial joint's there).
    pub fn with_functions(mut self, functions: LawFunctions) -> Self {
        self.law.functions = functions;
        self
    }

    /// The joint whose law's stiffness and viscosity are scaled in time by `variance`'s
    /// drives (MBDyn's `linear time variant viscoelastic generic`).
    pub fn with_time_variance(mut self, variance: Option<super::TimeVariance>) -> Self {
        self.law.time_variance = variance;
        self
    }

    /// The law at the state `st`, strain `k` and rate `k̇`: `φ` and its derivatives `K =
    /// ∂φ/∂k`, `C = ∂φ/∂k̇`.
    fn law_at(&self, st: &dyn ElementState, k: &Vector6<f64>, k_rate: &Vector6<f64>) -> (Vector6<f64>, Matrix6<f64>, Matrix6<f64>) {
        self.law.evaluate_in(st, k, Some(k_rate))
    }

    /// Generalized force `φ` in frame A and its derivatives `K`, `C`, relative rotation vector
    /// `θ`, relative angular velocity.
    fn phi(&self, st: &dyn ElementState, p: &Pair) -> (Vector6<f64>, Matrix6<f64>, Matrix6<f64>, Vec3, Vec3) {
        let qt = p.q_a.transpose();
        let theta = rotation_vector(&(qt * p.q_b));
        let w = p.omega_b - p.omega_a;
        let (e, e_rate) = (qt * p.d, qt * p.u);
        let k = Vector6::new(e[0], e[1], e[2], theta[0], theta[1], theta[2]);
        let w_a = qt * w;
        let k_rate = Vector6::new(e_rate[0], e_rate[1], e_rate[2], w_a[0], w_a[1], w_a[2]);
        let (phi, kk, cc) = self.law_at(st, &k, &k_rate);
        (phi, kk, cc, theta, w)
    }
}

fn split(phi: &Vector6<f64>) -> (Vec3, Vec3) {
    (Vec3::new(phi[0], phi[1], phi[2]), Vec3::new(phi[3], phi[4], phi[5]))
}

/// `[m₁; m₂]` (the derivative of the 6-D strain in the given columns) times the law's
/// columns: `L[:, 0..3] m₁` for a position part, `L[:, 3..6] m₂` for a rotation part.
fn through(law: &Matrix6<f64>, cols: [Col; 3], m: &Mat3, rotation_part: bool) -> Block {
    let c0 = if rotation_part { 3 } else { 0 };
    (cols, law.fixed_view::<6, 3>(0, c0) * m)
}

impl Element for DeformableJoint {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        self.name
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.a, &self.b)
    }
    fn reads_state(&self) -> bool {
        self.law.reads_state()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (f, m) = split(&self.phi(st, &p).0);
        p.add_force(out, &(p.q_a * f));
        p.add_moment(out, &(p.q_a * m));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (phi, k, c, theta, w) = self.phi(st, &p);
        let (k, c) = (&k, &c);
        let qt = p.q_a.transpose();
        // δθ = Γ⁻¹(θ) Q_aᵀ (δθ_b − δθ_a); δ(Q_aᵀ w) = Q_aᵀ (δω_b − δω_a) + Q_aᵀ [w×] δθ_a.
        let d_rel = inverse_rotation_jacobian(&theta) * qt;
        let mut dphi: Vec<Block> = Vec::new();
        dphi.extend(p.strain_derivatives().into_iter().map(|(cols, m)| through(k, cols, &m, false)));
        dphi.extend(p.rate_derivatives().into_iter().map(|(cols, m)| through(c, cols, &m, false)));
        dphi.push(through(k, Col::rotation(p.slot_b), &d_rel, true));
        dphi.push(through(c, Col::angular_velocity(p.slot_b), &qt, true));
        if let Some(a) = p.slot_a {
            dphi.push(through(k, Col::rotation(a), &(-d_rel), true));
            dphi.push(through(c, Col::angular_velocity(a), &(-qt), true));
            dphi.push(through(c, Col::rotation(a), &(qt * skew(&w)), true));
        }
        let top = |m: &SMatrix<f64, 6, 3>| Mat3::from_fn(|i, j| m[(i, j)]);
        let bottom = |m: &SMatrix<f64, 6, 3>| Mat3::from_fn(|i, j| m[(3 + i, j)]);
        let (f, m) = split(&phi);
        let force_blocks: Vec<([Col; 3], Mat3)> = dphi.iter().map(|(cols, m)| (*cols, top(m))).collect();
        p.add_force_jacobian(out, &(p.q_a * f), &force_blocks);
        // δ(Q_a φ_m) = −[(Q_a φ_m)×] δθ_a + Q_a δφ_m.
        let moment = p.q_a * m;
        for (sign, slot) in [(1.0, Some(p.slot_b)), (-1.0, p.slot_a)] {
            let Some(s) = slot else { continue };
            for (cols, d) in &dphi {
                add_block(out, Row::moment(s), *cols, &(sign * p.q_a * bottom(d)));
            }
            if let Some(a) = p.slot_a {
                add_block(out, Row::moment(s), Col::rotation(a), &(-sign * skew(&moment)));
            }
        }
    }
}
