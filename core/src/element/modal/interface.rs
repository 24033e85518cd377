//! The interface nodes of a modal body ([`super`]): each multibody node is clamped to its
//! FEM node (modal.cc's "spherical hinge" and "prismatic" parts), six multipliers: a force
//! `λ` (global frame) and a moment `μ` (the multibody node's frame, `m = R₂ μ` global).
//!
//! ```text
//! x + R (f₀ + Φt q) − x₂ − R₂ d₂ = 0,        ax(skew(R₂ᵀ R (I + [Φr q ×]))) = 0
//! ```
//!
//! `d₂` the offset of the FEM node from the multibody node in the latter's frame. As in
//! MBDyn, the multibody node must be oriented as the FEM node (the floating frame). The
//! reaction `λ`, `m` acts on the multibody node, its opposite on the FEM node: on the modal
//! node with moment `R r × λ + m`, and on the modes as `(R Φtⱼ)·λ + (R Φrⱼ)·m`.

use super::equations::add_row;
use super::ModalBody;
use crate::element::contract::{add_block, add_vec, Col, ElementState, JacobianSink, ResidualSink, Row};
use crate::kinematics::{skew, Mat3, Vec3};

/// `ax(skew(A))`: the axial vector of `(A − Aᵀ)/2`.
fn skew_axial(a: &Mat3) -> Vec3 {
    0.5 * Vec3::new(a[(2, 1)] - a[(1, 2)], a[(0, 2)] - a[(2, 0)], a[(1, 0)] - a[(0, 1)])
}

struct Place {
    /// Unknown index of the interface's first multiplier, its node's slot.
    first: usize,
    slot: usize,
    /// `R r` (FEM node from the origin, global), `R₂ d₂`, `R₂`, `λ`, `m = R₂ μ`,
    /// `A = I + [Φr q ×]`, and the shapes rotated to the global frame.
    rr: Vec3,
    d2: Vec3,
    r2: Mat3,
    lambda: Vec3,
    moment: Vec3,
    a: Mat3,
    t: Vec<Vec3>,
    rot: Vec<Vec3>,
}

fn place(e: &ModalBody, st: &dyn ElementState, i: usize, q: &[f64], r: &Mat3) -> Place {
    let f = &e.interfaces[i];
    let first = 6 * i;
    let slot = e.interface_slot(i);
    let n2 = st.node(slot);
    let local = f.position + f.translation.iter().zip(q).map(|(t, qj)| t * *qj).sum::<Vec3>();
    let phi: Vec3 = f.rotation.iter().zip(q).map(|(t, qj)| t * *qj).sum();
    let lambda = Vec3::new(st.multiplier(first), st.multiplier(first + 1), st.multiplier(first + 2));
    let mu = Vec3::new(st.multiplier(first + 3), st.multiplier(first + 4), st.multiplier(first + 5));
    Place { first, slot, rr: r * local, d2: n2.r * f.offset, r2: n2.r, lambda, moment: n2.r * mu, a: Mat3::identity() + skew(&phi), t: f.translation.iter().map(|t| r * t).collect(), rot: f.rotation.iter().map(|t| r * t).collect() }
}

fn rows(first: usize) -> ([Row; 3], [Row; 3]) {
    ([0, 1, 2].map(|c| Row::Constraint(first + c)), [3, 4, 5].map(|c| Row::Constraint(first + c)))
}

fn cols(first: usize) -> ([Col; 3], [Col; 3]) {
    ([0, 1, 2].map(|c| Col::Multiplier(first + c)), [3, 4, 5].map(|c| Col::Multiplier(first + c)))
}

pub(super) fn residual(e: &ModalBody, st: &dyn ElementState, out: &mut dyn ResidualSink) {
    let (x, r, _, _) = e.floating_frame(st);
    let (q, _) = e.coordinates(st);
    let floating = matches!(e.frame, super::ModalFrame::Node(_));
    for i in 0..e.interfaces.len() {
        let p = place(e, st, i, &q, &r);
        let n2 = st.node(p.slot);
        let (pos, rot) = rows(p.first);
        add_vec(out, pos, &(x + p.rr - n2.x - p.d2));
        add_vec(out, rot, &skew_axial(&(p.r2.transpose() * r * p.a)));
        if floating {
            add_vec(out, Row::force(0), &p.lambda);
            add_vec(out, Row::moment(0), &(p.rr.cross(&p.lambda) + p.moment));
        }
        add_vec(out, Row::force(p.slot), &(-p.lambda));
        add_vec(out, Row::moment(p.slot), &(-(p.d2.cross(&p.lambda)) - p.moment));
        if !e.assembling {
            for j in 0..e.modes() {
                out.add(Row::Constraint(e.q_index(j)), p.t[j].dot(&p.lambda) + p.rot[j].dot(&p.moment));
            }
        }
    }
}

pub(super) fn jacobian(e: &ModalBody, st: &dyn ElementState, out: &mut dyn JacobianSink) {
    let (_, r, _, _) = e.floating_frame(st);
    let (q, _) = e.coordinates(st);
    let floating = matches!(e.frame, super::ModalFrame::Node(_));
    let eye = Mat3::identity();
    for i in 0..e.interfaces.len() {
        let p = place(e, st, i, &q, &r);
        let s = p.slot;
        let (pos, rot) = rows(p.first);
        let (lam, mu) = cols(p.first);
        // Position constraint.
        add_block(out, pos, Col::position(s), &(-eye));
        add_block(out, pos, Col::rotation(s), &skew(&p.d2));
        // Rotation constraint: the axial vector of δE's skew part, E = R₂ᵀ R A.
        let rta = r * p.a;
        let d_theta1 = Mat3::from_columns(&[0, 1, 2].map(|c| skew_axial(&(p.r2.transpose() * skew(&Vec3::ith(c, 1.0)) * rta))));
        add_block(out, rot, Col::rotation(s), &(-d_theta1));
        if floating {
            add_block(out, pos, Col::position(0), &eye);
            add_block(out, pos, Col::rotation(0), &(-skew(&p.rr)));
            add_block(out, rot, Col::rotation(0), &d_theta1);
            add_block(out, Row::force(0), lam, &eye);
            add_block(out, Row::moment(0), Col::rotation(0), &(skew(&p.lambda) * skew(&p.rr)));
            add_block(out, Row::moment(0), lam, &skew(&p.rr));
            add_block(out, Row::moment(0), mu, &p.r2);
            add_block(out, Row::moment(0), Col::rotation(s), &(-skew(&p.moment)));
        }
        add_block(out, Row::force(s), lam, &(-eye));
        add_block(out, Row::moment(s), Col::rotation(s), &(-skew(&p.lambda) * skew(&p.d2) + skew(&p.moment)));
        add_block(out, Row::moment(s), lam, &(-skew(&p.d2)));
        add_block(out, Row::moment(s), mu, &(-p.r2));
        for j in (0..e.modes()).filter(|_| !e.assembling) {
            let col = Col::Multiplier(e.q_index(j));
            let (t, rj) = (p.t[j], p.rot[j]);
            let d_rot = skew_axial(&(p.r2.transpose() * r * skew(&e.interfaces[i].rotation[j])));
            for c in 0..3 {
                out.add(pos[c], col, t[c]);
                out.add(rot[c], col, d_rot[c]);
            }
            let row = Row::Constraint(e.q_index(j));
            if floating {
                let on_moment = t.cross(&p.lambda);
                for c in 0..3 {
                    out.add(Row::Equilibrium { slot: 0, comp: 3 + c }, col, on_moment[c]);
                }
                add_row(out, row, Col::rotation(0), &(t.cross(&p.lambda) + rj.cross(&p.moment)));
            }
            add_row(out, row, Col::rotation(s), &p.moment.cross(&rj));
            add_row(out, row, lam, &t);
            add_row(out, row, mu, &(p.r2.transpose() * rj));
        }
    }
}
