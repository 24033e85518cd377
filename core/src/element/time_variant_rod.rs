//! A rod with MBDyn's `linear time variant viscoelastic generic` 1-D law (rodj.cc's
//! `ViscoElasticRod` with constltp_impl.h's `LTVViscoElasticGenericConstitutiveLaw`):
//! `N = F_p + s_K(t) EA (ε − ε_p) + s_C(t) C ε̇` along the rod. The rod's force is linear in
//! `EA`, `C` and `F_p`, so it is the sum of three parts evaluated apart: the elastic rod with
//! its prestrain ([`PrestrainedRod`], a constant prestrain in its rest length) scaled by
//! `s_K`, the viscous rod (no stiffness) scaled by `s_C`, and the prestress `F_p e`, `e = d/l`,
//! whose derivative is `F_p (I − e eᵀ)/l`. The drives are held in the Jacobian, as MBDyn's.

use super::anchor::{node_labels, Pair};
use super::contract::{Element, ElementState, JacobianSink, Label, Outputs, ResidualSink};
use super::deformable::{add_pair_force, add_pair_force_jacobian};
use super::time_variant_law::{Scaled, TimeVariance};
use super::{PrestrainedRod, Rod};
use crate::kinematics::Mat3;

#[derive(Clone, Debug)]
pub struct TimeVariantRod {
    /// `EA (ε − ε_p)`: the rod with the law's stiffness and prestrain, no viscosity.
    pub elastic: PrestrainedRod,
    /// `C ε̇`: the rod with the law's viscosity, no stiffness.
    pub viscous: Rod,
    /// `F_p` [N].
    pub prestress: f64,
    pub variance: TimeVariance,
}

impl TimeVariantRod {
    /// The elastic and the viscous rod with their factors `s_K`, `s_C` at the state `st`.
    fn scaled_parts(&self, st: &dyn ElementState) -> [(&dyn Element, f64); 2] {
        let (sk, sc) = self.variance.scales(st);
        [(&self.elastic, sk), (&self.viscous, sc)]
    }
}

impl Element for TimeVariantRod {
    fn label(&self) -> Label {
        self.elastic.rod.label
    }
    fn type_name(&self) -> &'static str {
        "rod"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.elastic.rod.a, &self.elastic.rod.b)
    }
    fn reads_state(&self) -> bool {
        self.elastic.reads_state() || self.variance.reads_state()
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        self.elastic.rod.outputs()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        for (part, factor) in self.scaled_parts(st) {
            part.residual(st, &mut Scaled { inner: &mut *out, factor });
        }
        if self.prestress != 0.0 {
            let p = Pair::new(&self.elastic.rod.a, &self.elastic.rod.b, st);
            add_pair_force(out, &p, &(self.prestress / p.d.norm() * p.d));
        }
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        for (part, factor) in self.scaled_parts(st) {
            part.jacobian(st, &mut Scaled { inner: &mut *out, factor });
        }
        if self.prestress != 0.0 {
            let p = Pair::new(&self.elastic.rod.a, &self.elastic.rod.b, st);
            let l = p.d.norm();
            let e = p.d / l;
            add_pair_force_jacobian(out, &p, &(self.prestress * e), &(self.prestress / l * (Mat3::identity() - e * e.transpose())));
        }
    }
}
