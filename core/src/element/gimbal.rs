//! MBDyn's `gimbal rotation` (gimbal.cc, `GimbalRotationJoint`): a homokinetic joint without
//! position constraints, the relative rotation of the two hinge frames restricted to
//!
//! ```text
//! Q_aᵀ Q_b = R(θ, φ) = E(θ) F(φ) E(θ),   E(θ) = exp(θ [e₂×]),  F(φ) = exp(φ [e₁×])
//! ```
//!
//! two Cardano joints 90° apart, each taking half the tilt about axis 2 (input manual
//! §Gimbal rotation). The angles `θ = θ₀ + δθ`, `φ = φ₀ + δφ` are coordinates of the element
//! ([`UnknownKind::Coordinate`]: configuration unknowns with rates, set by the initial
//! assembly), the unknowns their changes from the angles `θ₀`, `φ₀` of the relative
//! orientation as written ([`GimbalRotation::angles_of`]; MBDyn starts from 0, and its
//! initial assembly, "flawed" by gimbal.cc's own comment, fails on a tilted gimbal where
//! its derivatives phase, with `skip initial joint assembly`, finds them). The reaction is
//! a moment `λ` in frame A (3 multipliers).
//!
//! Constraint (same zero set as MBDyn's `VecRot(Q_aᵀ Q_b Rᵀ) = 0` near it):
//! `r = ax(N) = 0`, `N = Q_aᵀ Q_b R(θ, φ)ᵀ`. With `δN = [δη×] N`,
//! `δη = Q_aᵀ (δθ_b − δθ_a) − N (ψ_θ δθ + ψ_φ δφ)`, `δR = [(ψ_θ δθ + ψ_φ δφ)×] R`,
//! `ψ_θ = e₂ + R e₂`, `ψ_φ = E(θ) e₁`: `δr = P δη` (P as in joint.rs). Reactions `Φ_/qᵀ λ`:
//! the moment `Q_a Pᵀ λ` on B (opposite on A), and the equations of the angles
//! `−(N ψ_θ) · Pᵀ λ = 0`, `−(N ψ_φ) · Pᵀ λ = 0` (no moment along the free directions),
//! not divided by dCoef.

use super::anchor::{node_labels, Anchor, Pair};
use super::contract::{add_block, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use crate::kinematics::{axial_of_skew_part, skew, skew_part_jacobian, Mat3, Vec3};
use super::UnknownKind;

/// The gimbal's relative-rotation constraint (module documentation).
#[derive(Clone, Debug)]
pub struct GimbalRotation {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    /// `θ₀`, `φ₀` [rad]: the angles the unknowns are changes from.
    pub angles: [f64; 2],
}

impl GimbalRotation {
    /// The angles `(θ, φ)` whose `R(θ, φ)` is nearest the relative orientation `m = Q_aᵀ Q_b`
    /// (Gauss-Newton on `ax(m Rᵀ)` from 0; exact when `m` is in the joint's set).
    pub fn angles_of(m: &Mat3) -> [f64; 2] {
        let mut x = nalgebra::Vector2::zeros();
        for _ in 0..50 {
            let (r_rel, psi, _) = relative(x[0], x[1]);
            let n = m * r_rel.transpose();
            let r = axial_of_skew_part(&n);
            let p = skew_part_jacobian(&n);
            let j = nalgebra::Matrix3x2::from_columns(&[-(p * n * psi[0]), -(p * n * psi[1])]);
            let Some(inv) = (j.transpose() * j).try_inverse() else { break };
            let step = -(inv * j.transpose() * r);
            x += step;
            if step.norm() < 1e-15 {
                break;
            }
        }
        [x[0], x[1]]
    }
}

/// `R(θ, φ)`, `[ψ_θ, ψ_φ]` and `E(θ)`.
fn relative(theta: f64, phi: f64) -> (Mat3, [Vec3; 2], Mat3) {
    let (e1, e2) = (Vec3::x(), Vec3::y());
    let e_theta = rotation(e2, theta);
    let r_rel = e_theta * rotation(e1, phi) * e_theta;
    (r_rel, [e2 + r_rel * e2, e_theta * e1], e_theta)
}

fn rotation(axis: Vec3, angle: f64) -> Mat3 {
    *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_unchecked(axis), angle).matrix()
}

/// What residual and Jacobian share at one state.
struct Frames {
    p: Pair,
    /// `R(θ, φ)`.
    r_rel: Mat3,
    /// `N = Q_aᵀ Q_b Rᵀ`.
    n: Mat3,
    /// `ψ_θ`, `ψ_φ`.
    psi: [Vec3; 2],
    /// `E(θ)` (for `∂ψ_φ/∂θ`).
    e_theta: Mat3,
}

impl Frames {
    fn new(g: &GimbalRotation, st: &dyn ElementState) -> Self {
        let p = Pair::new(&g.a, &g.b, st);
        let (r_rel, psi, e_theta) = relative(g.angles[0] + st.multiplier(3), g.angles[1] + st.multiplier(4));
        let n = p.q_a.transpose() * p.q_b * r_rel.transpose();
        Frames { psi, r_rel, n, e_theta, p }
    }
}

impl Element for GimbalRotation {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "gimbal rotation"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.a, &self.b)
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["m x".into(), "m y".into(), "m z".into(), "theta".into(), "phi".into()]
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        if k >= 3 { UnknownKind::Coordinate } else { UnknownKind::Multiplier }
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let f = Frames::new(self, st);
        let r = axial_of_skew_part(&f.n);
        for k in 0..3 {
            out.add(Row::Constraint(k), r[k]);
        }
        let lambda = Vec3::new(st.multiplier(0), st.multiplier(1), st.multiplier(2));
        let mu = skew_part_jacobian(&f.n).transpose() * lambda;
        f.p.add_moment(out, &(f.p.q_a * mu));
        for (k, psi) in f.psi.iter().enumerate() {
            out.add(Row::Constraint(3 + k), -(f.n * psi).dot(&mu));
        }
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let f = Frames::new(self, st);
        let (p, n) = (&f.p, &f.n);
        let (qa, qt, b) = (p.q_a, p.q_a.transpose(), p.slot_b);
        let lambda = Vec3::new(st.multiplier(0), st.multiplier(1), st.multiplier(2));
        let (pm, r) = (skew_part_jacobian(n), axial_of_skew_part(n));
        let mu = pm.transpose() * lambda;
        // δμ = K δη + Pᵀ δλ (joint.rs), δη in the columns below.
        let k = -(lambda * r.transpose() + 0.5 * n.transpose() * skew(&lambda));
        let a_dir = [n * f.psi[0], n * f.psi[1]];
        let angle_cols = [Col::Multiplier(3), Col::Multiplier(4)];

        // Constraint rows: P δη.
        for i in 0..3 {
            let row = Row::Constraint(i);
            let g = pm.row(i).into_owned();
            let gb = g * qt;
            for c in 0..3 {
                out.add(row, Col::Rotation { slot: b, comp: c }, gb[c]);
                if let Some(a) = p.slot_a {
                    out.add(row, Col::Rotation { slot: a, comp: c }, -gb[c]);
                }
            }
            for (col, ad) in angle_cols.iter().zip(&a_dir) {
                out.add(row, *col, -(g * ad)[0]);
            }
        }

        // The moment m = Q_a μ on B (−m on A): δm = −[m×] δθ_a + Q_a K δη + Q_a Pᵀ δλ.
        let m = qa * mu;
        let qkq = qa * k * qt;
        add_block(out, Row::moment(b), Col::rotation(b), &qkq);
        if let Some(a) = p.slot_a {
            let d_theta_a = -skew(&m) - qkq;
            add_block(out, Row::moment(b), Col::rotation(a), &d_theta_a);
            add_block(out, Row::moment(a), Col::rotation(b), &(-qkq));
            add_block(out, Row::moment(a), Col::rotation(a), &(-d_theta_a));
        }
        let qpt = qa * pm.transpose();
        for (col, ad) in angle_cols.iter().zip(&a_dir) {
            let dm = -(qa * k * ad);
            for i in 0..3 {
                out.add(Row::Equilibrium { slot: b, comp: 3 + i }, *col, dm[i]);
                if let Some(a) = p.slot_a {
                    out.add(Row::Equilibrium { slot: a, comp: 3 + i }, *col, -dm[i]);
                }
            }
        }
        for j in 0..3 {
            for i in 0..3 {
                out.add(Row::Equilibrium { slot: b, comp: 3 + i }, Col::Multiplier(j), qpt[(i, j)]);
                if let Some(a) = p.slot_a {
                    out.add(Row::Equilibrium { slot: a, comp: 3 + i }, Col::Multiplier(j), -qpt[(i, j)]);
                }
            }
        }

        // The angles' equations s = −a · μ, a = N ψ: δs = g δη − (P a) · δλ + (direct terms),
        // g = −aᵀ K + μᵀ [a×]; δψ_θ = −[(R e₂)×] δψ, δψ_φ = (e₂ × ψ_φ) δθ.
        let re2 = f.r_rel * Vec3::y();
        let e2_x_psi_phi = Vec3::y().cross(&(f.e_theta * Vec3::x()));
        for (kk, ad) in a_dir.iter().enumerate() {
            let row = Row::Constraint(3 + kk);
            let g = -(ad.transpose() * k) + mu.transpose() * skew(ad);
            let gb = g * qt;
            for c in 0..3 {
                out.add(row, Col::Rotation { slot: b, comp: c }, gb[c]);
                if let Some(a) = p.slot_a {
                    out.add(row, Col::Rotation { slot: a, comp: c }, -gb[c]);
                }
            }
            let pa = pm * ad;
            for j in 0..3 {
                out.add(row, Col::Multiplier(j), -pa[j]);
            }
            let direct = if kk == 0 {
                let w = mu.transpose() * n * skew(&re2);
                [(w * f.psi[0])[0], (w * f.psi[1])[0]]
            } else {
                [-(mu.transpose() * n * e2_x_psi_phi)[0], 0.0]
            };
            for (j, (col, ad2)) in angle_cols.iter().zip(&a_dir).enumerate() {
                out.add(row, *col, -(g * ad2)[0] + direct[j]);
            }
        }
    }
}
