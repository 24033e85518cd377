//! MBDyn's `screw` joint (screwjoint.cc, `ScrewJoint`): the relative displacement along the
//! screw axis follows the relative rotation about it, `p/(2π) (θ − θ₀) − (d − d₀) = 0`,
//! `d = e · (p_b − p_a)` with `e = Q_a e₃` (frame A: node 1's, with its offset and
//! orientation; node 2's point with its offset), `θ` the relative rotation about `e` counted
//! through any number of turns.
//!
//! MBDyn counts the turns as element history (`unwrap`, `nTheta`, updated at each residual).
//! The contract has none, so romdyn makes the turned angle an own coordinate `φ = θ − θ₀`
//! ([`UnknownKind::Coordinate`]), continuous through the state, with its own equation
//! `e₃ · ax(M) = 0`, `M = Q_aᵀ Q_b R(e₃, θ₀ + φ)ᵀ` (`Q_b = R_b Q_a,node`: node 2's frame turned
//! as node 1's hinge, as MBDyn's `R1h`): zero where node 2 has turned by `θ₀ + φ` about
//! `e₃` relative to node 1 (modulo 2π: Newton follows the nearest branch, which moves at most
//! a step's rotation). The screw equation is then `p/(2π) φ − (d − d₀) = 0`, its multiplier
//! `λ`. The reactions are the screw equation's, `λ (p/(2π) ∂θ/∂q − ∂d/∂q)`, with `∂θ/∂q`
//! that of the coordinate's equation: the moment `Q_a Pᵀ (μ e₃)` (`P` as the joints'),
//! `μ = λ p/(2π)`, on node 2, the force `−λ e` at node 2's point, both opposite on node 1.
//! Where `Q_aᵀ Q_b` is a rotation about `e₃` (another joint holds the axes, as in every use
//! of the joint), `θ` is MBDyn's `e₃ · rotvec(R₁ᵀ R₂)`-based angle.

use super::anchor::{node_labels, Anchor, Pair};
use super::contract::{add_block, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use crate::kinematics::{axial_of_skew_part, skew, skew_part_jacobian, Mat3, Vec3};
use super::UnknownKind;

/// A screw joint of pitch `pitch` [m per turn] between frames `a` (axis 3 the screw axis) and
/// `b`; `theta0` [rad] and `d0` [m] the initial relative rotation and displacement.
#[derive(Clone, Debug)]
pub struct Screw {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    pub pitch: f64,
    pub theta0: f64,
    pub d0: f64,
}

fn turn_about_z(angle: f64) -> Mat3 {
    let (s, c) = angle.sin_cos();
    Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

struct Kinematics {
    p: Pair,
    /// `Q_b R(e₃, θ₀ + φ)ᵀ`.
    qb: Mat3,
    /// `Q_aᵀ Q_b R(e₃, θ₀ + φ)ᵀ`.
    m: Mat3,
    e: Vec3,
    lambda: f64,
    mu: f64,
}

impl Screw {
    fn lead(&self) -> f64 {
        self.pitch / (2.0 * std::f64::consts::PI)
    }
    fn kinematics(&self, st: &dyn ElementState) -> Kinematics {
        let p = Pair::new(&self.a, &self.b, st);
        let qb = p.q_b * turn_about_z(self.theta0 + st.multiplier(0)).transpose();
        let m = p.q_a.transpose() * qb;
        let e = p.q_a.column(2).into_owned();
        let lambda = st.multiplier(1);
        Kinematics { p, qb, m, e, lambda, mu: lambda * self.lead() }
    }
}

impl Element for Screw {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "screw"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.a, &self.b)
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["theta".into(), "f".into()]
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        if k == 0 { UnknownKind::Coordinate } else { UnknownKind::Multiplier }
    }

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let k = self.kinematics(st);
        out.add(Row::Constraint(0), axial_of_skew_part(&k.m)[2]);
        out.add(Row::Constraint(1), self.lead() * st.multiplier(0) - (k.e.dot(&k.p.d) - self.d0));
        k.p.add_force(out, &(-k.lambda * k.e));
        k.p.add_moment(out, &(k.p.q_a * skew_part_jacobian(&k.m).transpose() * (k.mu * Vec3::z())));
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let k = self.kinematics(st);
        let (p, qt, b) = (&k.p, k.p.q_a.transpose(), k.p.slot_b);
        let pm = skew_part_jacobian(&k.m);
        let r = axial_of_skew_part(&k.m);
        // φ turns Q_b' as a global rotation −(Q_b' e₃) δφ would.
        let phi_turn = -(k.qb * Vec3::z());
        let theta = Col::Multiplier(0);

        // Coordinate row: e₃ · ax(M), ∂/∂θ_b = e₃ᵀ P Q_aᵀ = −∂/∂θ_a.
        let row = qt.transpose() * pm.transpose() * Vec3::z();
        for i in 0..3 {
            out.add(Row::Constraint(0), Col::Rotation { slot: b, comp: i }, row[i]);
            if let Some(a) = p.slot_a {
                out.add(Row::Constraint(0), Col::Rotation { slot: a, comp: i }, -row[i]);
            }
        }
        out.add(Row::Constraint(0), theta, row.dot(&phi_turn));

        // Screw row: p/(2π) φ − e₃ · Q_aᵀ d.
        out.add(Row::Constraint(1), theta, self.lead());
        for (cols, m) in p.strain_derivatives() {
            for (j, col) in cols.iter().enumerate() {
                out.add(Row::Constraint(1), *col, -m[(2, j)]);
            }
        }

        // The force −λ e at node 2's point.
        p.add_force_jacobian(out, &(-k.lambda * k.e), &[]);
        p.add_reaction_column(out, Col::Multiplier(1), &(-k.e), &Vec3::zeros());

        // The moment Q_a Pᵀ λ_r, λ_r = μ e₃ (the joints' rotation reaction): δm = −[m×] δθ_a
        // + Q_a K Q_aᵀ (δθ_b − δθ_a), K = −(λ_r rᵀ + ½ Mᵀ [λ_r×]); λ and φ columns.
        let lambda_r = k.mu * Vec3::z();
        let ptq = p.q_a * pm.transpose();
        let moment = ptq * lambda_r;
        let kk = -(lambda_r * r.transpose() + 0.5 * k.m.transpose() * skew(&lambda_r));
        let qkq = p.q_a * kk * qt;
        let dm_lambda = ptq * Vec3::z() * self.lead();
        let dm_phi = qkq * phi_turn;
        add_block(out, Row::moment(b), Col::rotation(b), &qkq);
        for i in 0..3 {
            out.add(Row::Equilibrium { slot: b, comp: 3 + i }, Col::Multiplier(1), dm_lambda[i]);
            out.add(Row::Equilibrium { slot: b, comp: 3 + i }, theta, dm_phi[i]);
        }
        if let Some(a) = p.slot_a {
            let d_theta_a = -skew(&moment) - qkq;
            add_block(out, Row::moment(b), Col::rotation(a), &d_theta_a);
            add_block(out, Row::moment(a), Col::rotation(b), &(-qkq));
            add_block(out, Row::moment(a), Col::rotation(a), &(-d_theta_a));
            for i in 0..3 {
                out.add(Row::Equilibrium { slot: a, comp: 3 + i }, Col::Multiplier(1), -dm_lambda[i]);
                out.add(Row::Equilibrium { slot: a, comp: 3 + i }, theta, -dm_phi[i]);
            }
        }
    }
}
