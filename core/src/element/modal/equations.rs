//! The modal body's inertia, stiffness, damping and weight ([`super`]): the modal node's
//! momentum definitions and weight, and the element's own rows (Lagrange's equations for
//! `q` in first-order form), all but the interface reactions ([`super::interface`]).
//!
//! In the global frame, with `S = R s(q)`, `J_g = R J(q) Rᵀ`, `aⱼ = R I₃ⱼ`:
//!
//! ```text
//! ∂T/∂ẋ  = m ẋ + ω × S + R I₃ q̇
//! ∂T/∂ω  = S × ẋ + J_g ω + R B(q) q̇
//! ∂T/∂q̇ₖ = aₖ·ẋ + (R Bₖ)·ω + (M q̇)ₖ
//! ∂T/∂qₖ = ẋ·(ω × aₖ) + ½ ωᵀ R ∂J/∂qₖ Rᵀ ω + ω·(R I₅ₖ q̇)
//! ```
//!
//! and the weight `m g` at the node with moment `S × g`, and `aₖ·g` on mode `k`.

use super::ModalBody;
use crate::element::contract::{add_block, add_vec, Col, ElementState, JacobianSink, ResidualSink, Row};
use crate::kinematics::{skew, Mat3, Vec3};

/// The state the equations read.
struct Kin {
    r: Mat3,
    xdot: Vec3,
    omega: Vec3,
    q: Vec<f64>,
    qdot: Vec<f64>,
    /// `S = R s(q)`, `J_g`, `aₖ = R I₃ₖ`, `R Bₖ(q)`.
    s: Vec3,
    j: Mat3,
    a: Vec<Vec3>,
    b: Vec<Vec3>,
}

fn kin(e: &ModalBody, st: &dyn ElementState) -> Kin {
    let (_, r, xdot, omega) = e.floating_frame(st);
    let (q, qdot) = e.coordinates(st);
    let inv = &e.invariants;
    let s = r * inv.static_moment_at(&q);
    let j = r * inv.inertia_at(&q) * r.transpose();
    let a = inv.i3.iter().map(|v| r * v).collect();
    let b = (0..e.modes()).map(|k| r * inv.coupling_column(k, &q)).collect();
    Kin { r, xdot, omega, q, qdot, s, j, a, b }
}

/// Adds a row vector `v` (a 1 × 3 derivative) to one row and three columns.
pub(super) fn add_row(out: &mut dyn JacobianSink, row: Row, cols: [Col; 3], v: &Vec3) {
    for (c, col) in cols.into_iter().enumerate() {
        out.add(row, col, v[c]);
    }
}

pub(super) fn residual(e: &ModalBody, st: &dyn ElementState, out: &mut dyn ResidualSink) {
    let n = e.modes();
    let k = kin(e, st);
    let inv = &e.invariants;
    let g = st.gravity();
    let rq: Vec3 = k.a.iter().zip(&k.qdot).map(|(a, d)| a * *d).sum();
    if matches!(e.frame, super::ModalFrame::Node(_)) {
        add_vec(out, Row::force(0), &(-inv.mass * g));
        add_vec(out, Row::moment(0), &(-k.s.cross(&g)));
        add_vec(out, Row::linear_momentum(0), &(-(inv.mass * k.xdot + k.omega.cross(&k.s) + rq)));
        let bq: Vec3 = k.b.iter().zip(&k.qdot).map(|(b, d)| b * *d).sum();
        add_vec(out, Row::angular_momentum(0), &(-(k.s.cross(&k.xdot) + k.j * k.omega + bq)));
    }
    for m in 0..n {
        let mq: f64 = (0..n).map(|l| e.mass[(m, l)] * k.qdot[l]).sum();
        let kq: f64 = (0..n).map(|l| e.stiffness[(m, l)] * k.q[l]).sum();
        let cq: f64 = (0..n).map(|l| e.damping[(m, l)] * k.qdot[l]).sum();
        let djm = k.r * inv.inertia_derivative(m, &k.q) * k.r.transpose();
        let dt_dq = k.xdot.dot(&k.omega.cross(&k.a[m])) + 0.5 * k.omega.dot(&(djm * k.omega)) + k.omega.dot(&(k.r * inv.i5_times(m, &k.qdot)));
        out.add(Row::Constraint(e.q_index(m)), st.rate(e.p_index(m)) - dt_dq + kq + cq - k.a[m].dot(&g));
        let p = st.multiplier(e.p_index(m));
        out.add(Row::Constraint(e.p_index(m)), p - (k.a[m].dot(&k.xdot) + k.b[m].dot(&k.omega) + mq));
    }
}

pub(super) fn jacobian(e: &ModalBody, st: &dyn ElementState, out: &mut dyn JacobianSink) {
    let n = e.modes();
    let k = kin(e, st);
    let inv = &e.invariants;
    let g = st.gravity();
    let floating = matches!(e.frame, super::ModalFrame::Node(_));
    let (w, xd) = (k.omega, k.xdot);
    if floating {
        let (lin, ang) = (Row::linear_momentum(0), Row::angular_momentum(0));
        let sx = skew(&k.s);
        add_block(out, Row::moment(0), Col::rotation(0), &(-skew(&g) * sx));
        let rq: Vec3 = k.a.iter().zip(&k.qdot).map(|(a, d)| a * *d).sum();
        let bq: Vec3 = k.b.iter().zip(&k.qdot).map(|(b, d)| b * *d).sum();
        add_block(out, lin, Col::velocity(0), &(-inv.mass * Mat3::identity()));
        add_block(out, lin, Col::angular_velocity(0), &sx);
        add_block(out, lin, Col::rotation(0), &(skew(&w) * sx + skew(&rq)));
        add_block(out, ang, Col::velocity(0), &(-sx));
        add_block(out, ang, Col::angular_velocity(0), &(-k.j));
        add_block(out, ang, Col::rotation(0), &(-skew(&xd) * sx + skew(&(k.j * w)) - k.j * skew(&w) + skew(&bq)));
        for j in 0..n {
            let aj = k.a[j];
            let dj = k.r * inv.inertia_derivative(j, &k.q) * k.r.transpose();
            let c5 = k.r * inv.i5_times(j, &k.qdot);
            let col = Col::Multiplier(e.q_index(j));
            let force_q = -aj.cross(&g);
            let lin_q = -w.cross(&aj);
            let ang_q = -(aj.cross(&xd) + dj * w + c5);
            for c in 0..3 {
                out.add(Row::Equilibrium { slot: 0, comp: 3 + c }, col, force_q[c]);
                out.add(Row::Momentum { slot: 0, comp: c }, col, lin_q[c]);
                out.add(Row::Momentum { slot: 0, comp: 3 + c }, col, ang_q[c]);
                out.add(Row::Momentum { slot: 0, comp: c }, Col::Rate(e.q_index(j)), -aj[c]);
                out.add(Row::Momentum { slot: 0, comp: 3 + c }, Col::Rate(e.q_index(j)), -k.b[j][c]);
            }
        }
    }
    for m in 0..n {
        let (dyn_row, def_row) = (Row::Constraint(e.q_index(m)), Row::Constraint(e.p_index(m)));
        out.add(dyn_row, Col::Rate(e.p_index(m)), 1.0);
        out.add(def_row, Col::Multiplier(e.p_index(m)), 1.0);
        let am = k.a[m];
        let djm = k.r * inv.inertia_derivative(m, &k.q) * k.r.transpose();
        let c5 = k.r * inv.i5_times(m, &k.qdot);
        for l in 0..n {
            let mut dq = e.stiffness[(m, l)];
            if let Some(h) = &inv.dd_inertia {
                dq -= 0.5 * w.dot(&(k.r * h[m][l] * k.r.transpose() * w));
            }
            out.add(dyn_row, Col::Multiplier(e.q_index(l)), dq);
            out.add(dyn_row, Col::Rate(e.q_index(l)), e.damping[(m, l)] - w.dot(&(k.r * inv.i5[m][l])));
            out.add(def_row, Col::Rate(e.q_index(l)), -e.mass[(m, l)]);
            out.add(def_row, Col::Multiplier(e.q_index(l)), -w.dot(&(k.r * inv.i5[l][m])));
        }
        if floating {
            // The rotation of R moves every global vector R u by δθ × R u; gravity's aₘ·g too.
            let rot = -(am.cross(&xd.cross(&w)) + (djm * w).cross(&w) + c5.cross(&w)) - am.cross(&g);
            add_row(out, dyn_row, Col::rotation(0), &rot);
            add_row(out, def_row, Col::rotation(0), &(-(am.cross(&xd) + k.b[m].cross(&w))));
            add_row(out, dyn_row, Col::velocity(0), &(-w.cross(&am)));
            add_row(out, dyn_row, Col::angular_velocity(0), &(-(am.cross(&xd) + djm * w + c5)));
            add_row(out, def_row, Col::velocity(0), &(-am));
            add_row(out, def_row, Col::angular_velocity(0), &(-k.b[m]));
        }
    }
}
