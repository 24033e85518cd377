//! What every finite-volume beam does with its evaluation points, whatever its number of
//! nodes (Ghiringhelli, Masarati, Mantegazza, AIAA J. 38(1), 2000): the section law gives
//! the local generalized forces, and the point between nodes `s` and `s + 1` loads node `s`'s
//! volume with `+(F, M + (p − x_s) × F)` and node `s + 1`'s with the opposite (arm `p −
//! x_{s+1}`); the residual holds `−` what a node receives. The Jacobian is built per point
//! from the derivatives of its position, frame, strains and curvatures with respect to the
//! element's perturbations: a `3 × C` matrix with columns `3 n k + 3 i + c` for node `i` of
//! `n`, kind `k` (0 position, 1 rotation δθ, 2 velocity, 3 angular velocity), component `c`.
//! An elastic beam's tangents hold only the `C = 6 n` columns of positions and rotations;
//! the section frame's rotation and the curvature depend on the nodes' rotations alone, so
//! theirs are `3 × K` matrices of the `K = 3 n` rotation columns (a [`RotationTangent`]).

use nalgebra::{Matrix6, SMatrix, Vector6};

use super::law::SectionLaw;
use crate::element::contract::{Col, ElementState, JacobianSink, ResidualSink, Row, SectionState};
use crate::kinematics::{skew, Mat3, Vec3};

pub const POSITION: usize = 0;
pub const ROTATION: usize = 1;
pub const VELOCITY: usize = 2;
pub const ANGULAR_VELOCITY: usize = 3;

/// The first column of node `node`'s perturbations of kind `kind` on an element of `nodes`
/// nodes.
pub const fn column(nodes: usize, node: usize, kind: usize) -> usize {
    3 * nodes * kind + 3 * node
}

/// `t[:, block(node, kind)] += m` on an element of `nodes` nodes (velocity kinds only in
/// a tangent with `12 nodes` columns).
pub fn put<const C: usize>(t: &mut SMatrix<f64, 3, C>, nodes: usize, node: usize, kind: usize, m: &Mat3) {
    let mut v = t.fixed_view_mut::<3, 3>(0, column(nodes, node, kind));
    v += m;
}

/// The derivative of a 3-vector that depends on the nodes' rotations alone: the `K = 3 n`
/// rotation columns of a tangent.
pub type RotationTangent<const K: usize> = SMatrix<f64, 3, K>;

/// `t[:, block(node)] += m`: node `node`'s rotation columns.
pub fn put_rotation<const K: usize>(t: &mut RotationTangent<K>, node: usize, m: &Mat3) {
    let mut v = t.fixed_view_mut::<3, 3>(0, 3 * node);
    v += m;
}

/// `r` as a tangent with `C` columns (zero outside the rotation columns).
pub fn embed<const C: usize, const K: usize>(r: &RotationTangent<K>) -> SMatrix<f64, 3, C> {
    let mut t = SMatrix::<f64, 3, C>::zeros();
    t.fixed_view_mut::<3, K>(0, K).copy_from(r);
    t
}

/// `a + m r` with `r` on the rotation columns (entries outside them are `a`'s).
pub fn add_rotation_product<const C: usize, const K: usize>(a: &SMatrix<f64, 3, C>, m: &Mat3, r: &RotationTangent<K>) -> SMatrix<f64, 3, C> {
    let mut t = *a;
    let mut v = t.fixed_view_mut::<3, K>(0, K);
    v += m * r;
    t
}

/// `δε = R_sᵀ (δp′ + [p′×] δθ_s)`: the strain's tangent from the tangent of `p′`, `p′` and
/// the section frame's rotation.
pub fn strain_tangent<const C: usize, const K: usize>(rt: &Mat3, dpp: &SMatrix<f64, 3, C>, pp: &Vec3, dtheta: &RotationTangent<K>) -> SMatrix<f64, 3, C> {
    rt * add_rotation_product(dpp, &skew(pp), dtheta)
}

/// `[a; b]`.
pub fn stack(a: &Vec3, b: &Vec3) -> Vector6<f64> {
    Vector6::new(a.x, a.y, a.z, b.x, b.y, b.z)
}

/// The local generalized forces and the law's tangents `∂/∂[ε; κ]`, `∂/∂[ε̇; κ̇]` there
/// (at the state `st`, whose time scales a time-variant law).
pub fn law_at(law: &SectionLaw, st: &dyn ElementState, strain: &Vec3, curvature: &Vec3, rates: Option<(&Vec3, &Vec3)>) -> (Vector6<f64>, Matrix6<f64>, Matrix6<f64>) {
    let rate = rates.map(|(strain_rate, curvature_rate)| stack(strain_rate, curvature_rate));
    law.evaluate_in(st, &stack(strain, curvature), rate.as_ref())
}

/// The local generalized forces alone ([`law_at`]'s first value: a residual's).
pub fn force_at(law: &SectionLaw, st: &dyn ElementState, strain: &Vec3, curvature: &Vec3, rates: Option<(&Vec3, &Vec3)>) -> Vector6<f64> {
    let rate = rates.map(|(strain_rate, curvature_rate)| stack(strain_rate, curvature_rate));
    law.force_in(st, &stack(strain, curvature), rate.as_ref())
}

/// What `.act`/`.bst` write of a point at `p` with frame `r`: local forces `f`, strain and
/// curvature.
pub fn section_state(p: &Vec3, r: &Mat3, strain: &Vec3, curvature: &Vec3, f: &Vector6<f64>) -> SectionState {
    SectionState { position: *p, orientation: *r, strain: *strain, curvature: *curvature, force: f.fixed_rows::<3>(0).into(), moment: f.fixed_rows::<3>(3).into() }
}

/// One evaluation point's state and derivatives, as the assembly needs them.
pub struct PointTangents<'a, const C: usize, const K: usize> {
    pub dp: &'a SMatrix<f64, 3, C>,
    /// Virtual rotation of the section frame.
    pub dtheta: &'a RotationTangent<K>,
    pub dstrain: &'a SMatrix<f64, 3, C>,
    pub dcurvature: &'a RotationTangent<K>,
    /// `(∂ε̇, ∂κ̇)` when the law is viscous.
    pub rates: Option<(&'a SMatrix<f64, 3, C>, &'a SMatrix<f64, 3, C>)>,
}

/// The loads of the point between nodes `s` and `s + 1` at `p` with frame `r` and local
/// forces `f`, added to the residual.
pub fn add_point_residual(out: &mut dyn ResidualSink, s: usize, p: &Vec3, r: &Mat3, f: &Vector6<f64>, x: &[Vec3]) {
    let force = r * Vec3::new(f[0], f[1], f[2]);
    let moment = r * Vec3::new(f[3], f[4], f[5]);
    for (node, sign) in [(s, -1.0), (s + 1, 1.0)] {
        let m = moment + (p - x[node]).cross(&force);
        for c in 0..3 {
            out.add(Row::Equilibrium { slot: node, comp: c }, sign * force[c]);
            out.add(Row::Equilibrium { slot: node, comp: 3 + c }, sign * m[c]);
        }
    }
}

/// The derivative of [`add_point_residual`], added to rows `6 s .. 6 s + 12` of `jac`:
/// `δ(local) = K [δε; δκ] + V [δε̇; δκ̇]` (`K`, `V` the law's tangents there, [`law_at`]),
/// `δF = R δF_l − [F×] δθ`, and the arm's `δp − δx`.
#[allow(clippy::too_many_arguments)]
pub fn add_point_jacobian<const R: usize, const C: usize, const K: usize>(jac: &mut SMatrix<f64, R, C>, s: usize, p: &Vec3, r: &Mat3, law: &(Vector6<f64>, Matrix6<f64>, Matrix6<f64>), d: &PointTangents<C, K>, x: &[Vec3]) {
    debug_assert_eq!(K, 3 * (R / 6), "K: the rotation columns of the element's nodes");
    let (f, kk, vv) = law;
    let (force, moment) = (r * Vec3::new(f[0], f[1], f[2]), r * Vec3::new(f[3], f[4], f[5]));
    let block = |m: &Matrix6<f64>, i: usize, j: usize| -> Mat3 { m.fixed_view::<3, 3>(i, j).into() };
    // The products with δκ and δθ_s only on their rotation columns (the others are zero).
    let mut dfl = add_rotation_product(&(block(kk, 0, 0) * d.dstrain), &block(kk, 0, 3), d.dcurvature);
    let mut dml = add_rotation_product(&(block(kk, 3, 0) * d.dstrain), &block(kk, 3, 3), d.dcurvature);
    if let Some((dstrain_rate, dcurvature_rate)) = d.rates {
        dfl += block(vv, 0, 0) * dstrain_rate + block(vv, 0, 3) * dcurvature_rate;
        dml += block(vv, 3, 0) * dstrain_rate + block(vv, 3, 3) * dcurvature_rate;
    }
    let dforce = add_rotation_product(&(r * dfl), &-skew(&force), d.dtheta);
    let dmoment = add_rotation_product(&(r * dml), &-skew(&moment), d.dtheta);
    for (node, sign) in [(s, -1.0), (s + 1, 1.0)] {
        let arm = p - x[node];
        let mut darm = *d.dp;
        put(&mut darm, R / 6, node, POSITION, &-Mat3::identity());
        let dm = dmoment + skew(&arm) * dforce - skew(&force) * darm;
        let mut rows = jac.fixed_view_mut::<3, C>(6 * node, 0);
        rows += sign * dforce;
        let mut rows = jac.fixed_view_mut::<3, C>(6 * node + 3, 0);
        rows += sign * dm;
    }
}

/// Hands the element Jacobian (rows `6 i + …` node `i`'s force and moment, columns as the
/// tangents') to the sink: positions and rotations, and velocities when `viscous`.
/// Each row of three equations goes to the sink at once ([`JacobianSink::add_blocks`]): its
/// blocks by node, each node's by kind.
pub fn scatter_jacobian<const R: usize, const C: usize>(jac: &SMatrix<f64, R, C>, viscous: bool, out: &mut dyn JacobianSink) {
    let kinds = if viscous { 4 } else { 2 };
    let nodes = R / 6;
    debug_assert!(nodes <= MOST_NODES);
    let mut cols = [[Col::Multiplier(0); 3]; 4 * MOST_NODES];
    let mut blocks = [Mat3::zeros(); 4 * MOST_NODES];
    for node in 0..nodes {
        for (half, rows) in [Row::force(node), Row::moment(node)].into_iter().enumerate() {
            let r = 6 * node + 3 * half;
            let mut k = 0;
            for slot in 0..nodes {
                let slot_cols = [Col::position(slot), Col::rotation(slot), Col::velocity(slot), Col::angular_velocity(slot)];
                for (kind, c) in slot_cols.into_iter().enumerate().take(kinds) {
                    cols[k] = c;
                    blocks[k] = jac.fixed_view::<3, 3>(r, column(nodes, slot, kind)).into();
                    k += 1;
                }
            }
            out.add_blocks(rows, &cols[..k], &blocks[..k]);
        }
    }
}

/// The most nodes of a finite-volume beam (`beam3`).
const MOST_NODES: usize = 3;
