//! MBDyn's `viscous body` (vb.cc, `ViscousBody`; input manual, "Elements", §Viscous body): a
//! 6-D viscous law on the absolute velocity of a frame attached to one node, the damping of
//! a body moving through a still fluid. With the frame `Q = R H` and the point `p = x + f`,
//! `f = R o`: the rates in the frame, `u = Qᵀ (ẋ + ω × f)` and `w = Qᵀ ω`, give `φ = C [u;
//! w]`, and the force `−Q φ₁₋₃` acts at `p`, the moment `−Q φ₄₋₆` on the node (MBDyn's
//! `AssVec`). Only viscous laws: the strain is zero (`Update(Zero6, k̇)`).

use nalgebra::{Matrix6, SMatrix, Vector6};

use super::contract::{add_block, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use crate::kinematics::{skew, Mat3, Vec3};

#[derive(Clone, Debug)]
pub struct ViscousBody {
    pub label: Label,
    pub node: Label,
    /// Offset `o` and orientation `H` of the frame in the node frame.
    pub offset: Vec3,
    pub orientation: Mat3,
    /// `C`, in the frame: rows force then moment, columns `u` then `w`.
    pub viscosity: Matrix6<f64>,
}

impl ViscousBody {
    /// `(Q, f, ω, s = ẋ + ω × f, φ)`.
    fn state(&self, st: &dyn ElementState) -> (Mat3, Vec3, Vec3, Vec3, Vector6<f64>) {
        let n = st.node(0);
        let (q, f) = (n.r * self.orientation, n.r * self.offset);
        let s = n.xdot + n.omega.cross(&f);
        let (u, w) = (q.transpose() * s, q.transpose() * n.omega);
        let phi = self.viscosity * Vector6::new(u[0], u[1], u[2], w[0], w[1], w[2]);
        (q, f, n.omega, s, phi)
    }
}

fn top(v: &Vector6<f64>) -> Vec3 {
    Vec3::new(v[0], v[1], v[2])
}

fn bottom(v: &Vector6<f64>) -> Vec3 {
    Vec3::new(v[3], v[4], v[5])
}

impl Element for ViscousBody {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "viscous body"
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (q, f, _, _, phi) = self.state(st);
        let (force, moment) = (q * top(&phi), q * bottom(&phi));
        let m = f.cross(&force) + moment;
        for i in 0..3 {
            out.add(Row::Equilibrium { slot: 0, comp: i }, force[i]);
            out.add(Row::Equilibrium { slot: 0, comp: 3 + i }, m[i]);
        }
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (q, f, omega, s, phi) = self.state(st);
        let (force, moment) = (q * top(&phi), q * bottom(&phi));
        let (qt, fx, wx, sx) = (q.transpose(), skew(&f), skew(&omega), skew(&s));
        // δk̇ = [δu; δw] by δẋ, δω, δθ (δQ = [δθ×] Q, δf = δθ × f).
        let stack = |a: Mat3, b: Mat3| {
            let mut m = SMatrix::<f64, 6, 3>::zeros();
            m.fixed_view_mut::<3, 3>(0, 0).copy_from(&a);
            m.fixed_view_mut::<3, 3>(3, 0).copy_from(&b);
            m
        };
        let dk = [
            (Col::velocity(0), stack(qt, Mat3::zeros())),
            (Col::angular_velocity(0), stack(-qt * fx, qt)),
            (Col::rotation(0), stack(qt * (sx - wx * fx), qt * wx)),
        ];
        for (cols, dk) in dk {
            let dphi = self.viscosity * dk;
            let (dphi1, dphi2): (Mat3, Mat3) = (dphi.fixed_view::<3, 3>(0, 0).into_owned(), dphi.fixed_view::<3, 3>(3, 0).into_owned());
            let dforce = q * dphi1;
            let dmoment = fx * dforce + q * dphi2;
            add_block(out, Row::force(0), cols, &dforce);
            add_block(out, Row::moment(0), cols, &dmoment);
        }
        // The frame and the arm turn: δF = −[F×] δθ, δM = −[M×] δθ, δf × F = [F×][f×] δθ.
        let (ffx, mx) = (skew(&force), skew(&moment));
        add_block(out, Row::force(0), Col::rotation(0), &(-ffx));
        add_block(out, Row::moment(0), Col::rotation(0), &(ffx * fx - fx * ffx - mx));
    }
}
