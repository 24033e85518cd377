//! MBDyn's `deformable hinge` with a `scalar function elastic isotropic` or `orthotropic`
//! law (ScalarFunctionsImpl.cc, `ScalarFunctionIsotropicCL`, `…OrthotropicCL`): each
//! component of the moment a function of the same component of the relative rotation
//! vector, `φ_i = F_i(θ_i)` (`F_i = F` for all three when isotropic, zero where orthotropic
//! writes `null`), `θ = rotvec(Q_aᵀ Q_b)` in frame A as the linear hinge's (vehj.cc). The
//! MBDyn reader builds these laws, with the `nlsf` ones, as [`super::DeformableJoint::hinge`]
//! with [`super::LawFunctions`] (the same moment).

use super::anchor::{node_labels, Anchor, Pair};
use super::contract::{Element, ElementState, JacobianSink, Label, ResidualSink};
use super::deformable::{add_hinge_jacobian, add_hinge_moment, hinge_strains};
use super::drive::ScalarFunction;
use crate::kinematics::{Mat3, Vec3};

/// A deformable hinge whose moment components are functions of the rotation's.
#[derive(Clone, Debug)]
pub struct FunctionHinge {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    pub functions: [Option<ScalarFunction>; 3],
}

impl FunctionHinge {
    /// `φ(θ)` and `diag(F_i′(θ_i))`.
    fn law(&self, theta: &Vec3) -> (Vec3, Mat3) {
        let (mut phi, mut k) = (Vec3::zeros(), Mat3::zeros());
        for (i, f) in self.functions.iter().enumerate() {
            if let Some(f) = f {
                (phi[i], k[(i, i)]) = f.value_and_derivative(theta[i]);
            }
        }
        (phi, k)
    }
}

impl Element for FunctionHinge {
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
        add_hinge_moment(out, &p, &self.law(&hinge_strains(&p).0).0);
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let theta = hinge_strains(&p).0;
        let (phi, k) = self.law(&theta);
        add_hinge_jacobian(out, &p, &phi, &theta, &k, &Mat3::zeros());
    }
}
