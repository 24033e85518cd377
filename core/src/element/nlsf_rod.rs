//! MBDyn's `rod` with a 1-D `nlsf elastic | viscous | viscoelastic` law (rodj.cc,
//! `ViscoElasticRod`; constltp_nlsf.cc): the axial force
//! `N = k (ε − ε_p) + f′(ε − ε_p) + c ε̇ + f″(ε̇) + N_p` of the strain `ε = l/l₀ − 1` and its
//! rate `ε̇ = d·ḋ/(l l₀)` (`l₀` the rod's length as written), along the line of the points:
//! `N d/l` at B, the opposite at A, as [`Rod`](super::Rod).

use super::anchor::{node_labels, Anchor, Pair};
use super::contract::{add_block, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::deformable::{add_pair_force, add_pair_force_jacobian, distance_rate};
use super::drive::ScalarFunction;
use crate::kinematics::{skew, Mat3, Vec3};

/// A rod with MBDyn's 1-D `nlsf` law.
#[derive(Clone, Debug)]
pub struct NlsfRod {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    /// `l₀` [m].
    pub length: f64,
    /// `k` [N] and `c` [N s].
    pub stiffness: f64,
    pub viscosity: f64,
    /// `ε_p` and `N_p` [N].
    pub prestrain: f64,
    pub prestress: f64,
    /// `f′` of `ε − ε_p` and `f″` of `ε̇` [N].
    pub elastic: Option<ScalarFunction>,
    pub viscous: Option<ScalarFunction>,
}

impl NlsfRod {
    /// `N` and its derivatives `∂N/∂ε`, `∂N/∂ε̇` at `ε`, `ε̇`.
    fn law(&self, e: f64, rate: f64) -> (f64, f64, f64) {
        let el = e - self.prestrain;
        let (mut n, mut ne, mut nr) = (self.stiffness * el + self.viscosity * rate + self.prestress, self.stiffness, self.viscosity);
        if let Some(f) = &self.elastic {
            let (v, d) = f.value_and_derivative(el);
            n += v;
            ne += d;
        }
        if let Some(f) = &self.viscous {
            let (v, d) = f.value_and_derivative(rate);
            n += v;
            nr += d;
        }
        (n, ne, nr)
    }

    /// The force `N d/l` with `∂/∂d` and `∂/∂ḋ`.
    fn force(&self, d: &Vec3, d_dot: &Vec3) -> (Vec3, Mat3, Mat3) {
        let (l, l0) = (d.norm(), self.length);
        let e = d / l;
        let rate = d.dot(d_dot) / (l * l0);
        let (n, ne, nr) = self.law(l / l0 - 1.0, rate);
        // ∂ε/∂d = e/l₀, ∂ε̇/∂d = ḋ/(l l₀) − ε̇ e/l, ∂ε̇/∂ḋ = e/l₀.
        let dn_dd = ne * e / l0 + nr * (d_dot / (l * l0) - rate * e / l);
        let kd = n / l * (Mat3::identity() - e * e.transpose()) + e * dn_dd.transpose();
        (n * e, kd, nr / l0 * e * e.transpose())
    }
}

impl Element for NlsfRod {
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
        add_pair_force(out, &p, &self.force(&p.d, &distance_rate(&p).0).0);
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (d_dot, rate_blocks) = distance_rate(&p);
        let (f, kd, c_rate) = self.force(&p.d, &d_dot);
        add_pair_force_jacobian(out, &p, &f, &kd);
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
