//! Node accelerations for the motion file (MBDyn's `accelerations, yes` on a dynamic
//! structural node; input manual, "Structural Node"; strnode.cc and autostr.cc).
//!
//! As MBDyn does, the accelerations are not unknowns: they come from the momentum
//! derivatives `β̇`, `γ̇` of the converged step and the inertia the elements put on the node.
//! With the node's mass `m`, static moment `S` and inertia `J` about the node (global
//! frame), read from the momentum definitions' rows of `F_/ẏ` (`β = m ẋ − S × ω`,
//! `γ = S × ẋ + J ω`), differentiating the definitions gives
//!
//! ```text
//! β̇ = m a + ω̇ × S + ω × (ω × S)
//! γ̇ = S × a + J ω̇ + ω × (J ω) + (ω × S) × ẋ
//! ```
//!
//! and eliminating `a`: `J_cg ω̇ = γ̇ − S × β̇ / m − ω × (J ω) + S × (ω × (ω × S)) / m
//! + ẋ × (ω × S)` with `J_cg = J + [S×][S×] / m` (the inertia about the centre of mass),
//! then `a = (β̇ − ω̇ × S − ω × (ω × S)) / m`. A node without mass has zero accelerations,
//! and a direction without rotational inertia (a point mass) zero angular acceleration
//! along it (MBDyn 1.7.3 does both: autostr.cc, `ComputeAccelerations`, and the
//! `LDLSolve` of matvec3.cc, which drops pivots below machine epsilon).

use super::{Assembler, Coefficients, State};
use crate::kinematics::{skew, Mat3, Vec3};
use crate::model::ConstraintForm;
use crate::model::NodeKind;

/// Linear and angular acceleration of node `i` (global frame) for every node `wanted`
/// marks that is dynamic; `None` for the others.
pub fn node_accelerations(asm: &Assembler, st: &State, wanted: &[bool]) -> Vec<Option<(Vec3, Vec3)>> {
    let dofs = &asm.dofs;
    let n = dofs.node_first.len();
    let take: Vec<bool> = (0..n).map(|i| wanted.get(i).copied().unwrap_or(false) && dofs.node_kind[i] == NodeKind::Dynamic).collect();
    if !take.iter().any(|t| *t) {
        return vec![None; n];
    }
    // F_/ẏ: the momentum rows' derivatives by ẋ and ġ hold −M (the node's 6x6 mass matrix).
    let fyd = asm.jacobian(st, Coefficients { a: 1.0, b: 0.0, form: ConstraintForm::Plain, dcoef: 1.0 });
    let mut blocks = vec![[[0.0; 6]; 6]; n];
    let mut owner = vec![usize::MAX; dofs.len];
    for i in (0..n).filter(|&i| take[i]) {
        owner[dofs.node_first[i]..dofs.node_first[i] + 6].fill(i);
    }
    for ((&r, &c), &v) in fyd.rows.iter().zip(&fyd.cols).zip(&fyd.values) {
        let i = owner[r];
        if i != usize::MAX && owner[c] == i {
            let f = dofs.node_first[i];
            blocks[i][r - f][c - f] -= v;
        }
    }
    (0..n)
        .map(|i| {
            take[i].then(|| {
                let fr = st.node_frame(dofs, i);
                let f = dofs.node_first[i];
                let b = &blocks[i];
                let block = |r: usize, c: usize| Mat3::from_fn(|j, k| b[r + j][c + k]);
                // ∂/∂ġ = ∂/∂ω G: back to ω's columns.
                let g_inv = fr.g_matrix.try_inverse().unwrap_or_else(Mat3::identity);
                let (m_vv, m_wv, m_ww) = (block(0, 0), block(3, 0), block(3, 3) * g_inv);
                let m = m_vv.trace() / 3.0;
                // M_ωv = [S×].
                let s = Vec3::new(m_wv[(2, 1)] - m_wv[(1, 2)], m_wv[(0, 2)] - m_wv[(2, 0)], m_wv[(1, 0)] - m_wv[(0, 1)]) / 2.0;
                let j = (m_ww + m_ww.transpose()) / 2.0;
                let rates = |k: usize| Vec3::new(st.yp[f + k], st.yp[f + k + 1], st.yp[f + k + 2]);
                accelerations(m, &s, &j, &fr.kin.xdot, &fr.kin.omega, &rates(6), &rates(9))
            })
        })
        .collect()
}

/// `(a, ω̇)` from the node's inertia (`m`, `S`, `J` about the node), velocities and
/// momentum derivatives (module documentation).
pub fn accelerations(m: f64, s: &Vec3, j: &Mat3, v: &Vec3, w: &Vec3, beta_dot: &Vec3, gamma_dot: &Vec3) -> (Vec3, Vec3) {
    if m <= 0.0 {
        return (Vec3::zeros(), Vec3::zeros());
    }
    let ws = w.cross(s);
    let centripetal = w.cross(&ws);
    let jcg = j + skew(s) * skew(s) / m;
    let rhs = gamma_dot - s.cross(beta_dot) / m - w.cross(&(j * w)) + s.cross(&centripetal) / m + v.cross(&ws);
    let wdot = semidefinite_solve(&jcg, &rhs);
    ((beta_dot - wdot.cross(s) - centripetal) / m, wdot)
}

/// `x` with `A x = b` for a symmetric positive semidefinite `A` by `A = L D Lᵀ`, the
/// components at pivots no larger than machine epsilon set to zero.
fn semidefinite_solve(a: &Mat3, b: &Vec3) -> Vec3 {
    let small = |d: f64| d <= f64::EPSILON;
    let mut l = Mat3::identity();
    let mut d = [0.0; 3];
    for k in 0..3 {
        d[k] = a[(k, k)] - (0..k).map(|p| l[(k, p)] * l[(k, p)] * d[p]).sum::<f64>();
        for r in k + 1..3 {
            if !small(d[k]) {
                l[(r, k)] = ((a[(r, k)] + a[(k, r)]) / 2.0 - (0..k).map(|p| l[(r, p)] * l[(k, p)] * d[p]).sum::<f64>()) / d[k];
            }
        }
    }
    let mut z = *b;
    for r in 0..3 {
        for p in 0..r {
            z[r] -= l[(r, p)] * z[p];
        }
    }
    for k in 0..3 {
        z[k] = if small(d[k]) { 0.0 } else { z[k] / d[k] };
    }
    for r in (0..3).rev() {
        for p in r + 1..3 {
            z[r] -= l[(p, r)] * z[p];
        }
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A body with its centre of mass off the node, moving arbitrarily: the momentum
    /// derivatives of a chosen `(a, ω̇)` (the definitions differentiated by hand) give them back.
    #[test]
    fn accelerations_invert_the_momentum_derivatives() {
        let (m, c) = (3.0, Vec3::new(0.3, -0.2, 0.5));
        let s = m * c;
        let j = Mat3::new(2.0, 0.1, 0.0, 0.1, 1.5, -0.2, 0.0, -0.2, 1.0) - m * skew(&c) * skew(&c);
        let (v, w) = (Vec3::new(1.0, -2.0, 0.5), Vec3::new(0.4, 0.7, -1.1));
        let (a, wd) = (Vec3::new(-0.3, 2.0, 9.0), Vec3::new(1.5, -0.25, 0.75));
        let beta_dot = m * a + wd.cross(&s) + w.cross(&w.cross(&s));
        let gamma_dot = s.cross(&a) + j * wd + w.cross(&(j * w)) + w.cross(&s).cross(&v);
        let (a2, wd2) = accelerations(m, &s, &j, &v, &w, &beta_dot, &gamma_dot);
        assert!((a2 - a).norm() < 1e-13 && (wd2 - wd).norm() < 1e-13, "{a2} {wd2}");
    }

    /// A point mass: no rotational inertia, ω̇ = 0 (as MBDyn's LDLSolve), a = β̇ / m.
    #[test]
    fn a_point_mass_has_no_angular_acceleration() {
        let (a, wd) = accelerations(2.0, &Vec3::zeros(), &Mat3::zeros(), &Vec3::x(), &Vec3::z(), &Vec3::new(2.0, 4.0, 6.0), &Vec3::new(1.0, 0.0, 0.0));
        assert_eq!((a, wd), (Vec3::new(1.0, 2.0, 3.0), Vec3::zeros()));
        assert_eq!(accelerations(0.0, &Vec3::x(), &Mat3::identity(), &Vec3::x(), &Vec3::z(), &Vec3::x(), &Vec3::x()), (Vec3::zeros(), Vec3::zeros()));
    }
}
