//! MBDyn's `invariant deformable hinge` (vehj.cc, `ElasticHingeJointInv`,
//! `ViscoElasticHingeJointInv`): the deformable hinge's law referred to the frame halfway
//! between the two, `R̂ = Q_a exp(θ/2)` with `θ = rotvec(Q_aᵀ Q_b)`; strain rate `w = R̂ᵀ (ω_b
//! − ω_a)`; moment `R̂ (K θ + C w)` on B, opposite on A. Exchanging the nodes gives the same
//! moments for an anisotropic law.

use super::anchor::{node_labels, Anchor, Pair};
use super::contract::{add_block, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::deformable::inverse_rotation_jacobian;
use super::LinearViscoelastic;
use crate::kinematics::{rotation_vector, skew, Mat3, Vec3};

/// Angular spring–damper with its law in the intermediate frame.
#[derive(Clone, Debug)]
pub struct InvariantDeformableHinge {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    pub law: LinearViscoelastic,
    /// The drives scaling `K` and `C` in time (MBDyn's `linear time variant viscoelastic
    /// generic`; `None`: constant).
    pub variance: Option<super::TimeVariance>,
}

/// `Γ(φ)`: `exp((φ + δφ)×) = exp((Γ(φ) δφ)×) exp(φ×)` to first order,
/// `I + (1 − cos φ)/φ² [φ×] + (φ − sin φ)/φ³ [φ×]²` (the inverse of
/// `inverse_rotation_jacobian`).
pub(super) fn rotation_jacobian(phi: &Vec3) -> Mat3 {
    let x = phi.norm();
    let (a, b) = if x < 1e-4 { (0.5 - x * x / 24.0, 1.0 / 6.0 - x * x / 120.0) } else { ((1.0 - x.cos()) / (x * x), (x - x.sin()) / (x * x * x)) };
    let t = skew(phi);
    Mat3::identity() + a * t + b * t * t
}

impl InvariantDeformableHinge {
    /// `K` and `C` at the state `st` (scaled by a time variance's drives, held in the
    /// Jacobian).
    fn law_at(&self, st: &dyn ElementState) -> (Mat3, Mat3) {
        let (sk, sc) = super::time_variant_law::scales_of(self.variance.as_ref(), st);
        (sk * self.law.stiffness, sc * self.law.viscosity)
    }
}

/// The intermediate frame `R̂`, `θ` and the rate `w`.
fn frames(p: &Pair) -> (Mat3, Vec3, Vec3) {
    let theta = rotation_vector(&(p.q_a.transpose() * p.q_b));
    let half = nalgebra::Rotation3::new(theta / 2.0).into_inner();
    let r_hat = p.q_a * half;
    (r_hat, theta, r_hat.transpose() * (p.omega_b - p.omega_a))
}

impl Element for InvariantDeformableHinge {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "invariant deformable hinge"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.a, &self.b)
    }
    fn reads_state(&self) -> bool {
        self.variance.as_ref().is_some_and(super::TimeVariance::reads_state)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (r_hat, theta, w) = frames(&p);
        let (k, c) = self.law_at(st);
        p.add_moment(out, &(r_hat * (k * theta + c * w)));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (r_hat, theta, w) = frames(&p);
        let (k, c) = self.law_at(st);
        let m = r_hat * (k * theta + c * w);
        // δθ = D (δθ_b − δθ_a), D = Γ⁻¹(θ) Q_aᵀ; R̂ turns by δφ̂ = δθ_a + H (δθ_b − δθ_a),
        // H = ½ Q_a Γ(θ/2) D; δw = R̂ᵀ (δω_b − δω_a) + R̂ᵀ [(ω_b − ω_a)×] δφ̂;
        // δm = −[m×] δφ̂ + R̂ (K δθ + C δw).
        let d = inverse_rotation_jacobian(&theta) * p.q_a.transpose();
        let h = 0.5 * p.q_a * rotation_jacobian(&(theta / 2.0)) * d;
        let rc = r_hat * c * r_hat.transpose();
        let turn = -skew(&m) + rc * skew(&(p.omega_b - p.omega_a));
        let d_theta_b = turn * h + r_hat * k * d;
        let (b, sa) = (p.slot_b, p.slot_a);
        for (sign, slot) in [(1.0, Some(b)), (-1.0, sa)] {
            let Some(s) = slot else { continue };
            add_block(out, Row::moment(s), Col::rotation(b), &(sign * d_theta_b));
            add_block(out, Row::moment(s), Col::angular_velocity(b), &(sign * rc));
            if let Some(a) = sa {
                add_block(out, Row::moment(s), Col::rotation(a), &(sign * (turn - d_theta_b)));
                add_block(out, Row::moment(s), Col::angular_velocity(a), &(-sign * rc));
            }
        }
    }
}
