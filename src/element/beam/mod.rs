//! The 3-node finite-volume beam (Ghiringhelli, Masarati, Mantegazza, "A multibody
//! implementation of finite volume C0 beams", AIAA J. 38(1), 2000; paper §6.2): a
//! geometrically exact, shear-deformable beam whose internal forces are evaluated at
//! ξ = ∓1/√3 through a 6x6 section law. Each node's finite volume (ξ from its end to the
//! next evaluation point) is in equilibrium under the internal forces at its boundaries:
//! the force `F_s` and moment `M_s` at point `s` act with `+` on the volume before it and
//! `−` on the volume after it, with arms `p_s − x_i` about the nodes. The beam carries no
//! inertia: lump masses on its nodes with rigid bodies (see [`shape::volume_fractions`]).

mod law;
mod section;
pub mod shape;

pub use law::SectionLaw;

use nalgebra::{SMatrix, Vector6};

use super::contract::{Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row, SectionState};
use crate::kinematics::{gibbs_from_rotation, gibbs_rotation, skew, Mat3, Vec3};
use section::{combine, put, NodeTerms, SectionKinematics, SectionReference, Tangent, POSITION};

/// One end or the middle of a beam: a node with its initial position and orientation (they
/// define the unstrained configuration), the offset of the reference line from the node and
/// the orientation of the beam frame relative to the node (both in the node frame).
#[derive(Clone, Debug)]
pub struct BeamNode {
    pub label: Label,
    pub initial_position: Vec3,
    pub initial_orientation: Mat3,
    pub offset: Vec3,
    pub orientation: Mat3,
}

impl BeamNode {
    /// Node `label`, initially at `position` with `orientation`; the reference line passes
    /// through its point at `offset` (node frame).
    pub fn new(label: Label, position: Vec3, orientation: Mat3, offset: Vec3) -> Self {
        BeamNode { label, initial_position: position, initial_orientation: orientation, offset, orientation: Mat3::identity() }
    }

    /// The beam frame at this node, relative to the node frame (used by
    /// [`SectionOrientation::FromNodes`]).
    pub fn with_orientation(mut self, orientation: Mat3) -> Self {
        self.orientation = orientation;
        self
    }
}

/// How the frame of an evaluation point is given.
#[derive(Clone, Debug)]
pub enum SectionOrientation {
    /// Global orientation in the initial configuration (axis 1 along the beam).
    Given(Mat3),
    /// Interpolated from the nodes' beam frames (MBDyn's `from nodes`).
    FromNodes,
}

/// A beam that cannot be built.
#[derive(Debug, thiserror::Error)]
pub enum BeamError {
    #[error("beam {0}: the reference line has zero length at evaluation point {1}")]
    ZeroLength(Label, &'static str),
    #[error("beam {0}: the orientation of evaluation point {1} is not a rotation matrix")]
    BadOrientation(Label, &'static str),
}

/// Three-node beam (MBDyn's `beam3`).
#[derive(Clone, Debug)]
pub struct Beam3 {
    pub label: Label,
    nodes: [Label; 3],
    offsets: [Vec3; 3],
    /// Node orientations in the initial configuration.
    initial: [Mat3; 3],
    sections: [SectionReference; 2],
    laws: [SectionLaw; 2],
    viscous: bool,
}

const POINT_NAMES: [&str; 2] = ["I", "II"];

impl Beam3 {
    /// A beam on three nodes, unstrained in their initial configuration, with a section law
    /// per evaluation point.
    pub fn new(label: Label, nodes: [BeamNode; 3], orientations: [SectionOrientation; 2], laws: [SectionLaw; 2]) -> Result<Self, BeamError> {
        let y: [Vec3; 3] = std::array::from_fn(|i| nodes[i].initial_position + nodes[i].initial_orientation * nodes[i].offset);
        let frames: [Mat3; 3] = std::array::from_fn(|i| nodes[i].initial_orientation * nodes[i].orientation);
        let mut sections = Vec::with_capacity(2);
        for (k, orientation) in orientations.iter().enumerate() {
            let xi = shape::EVALUATION_POINTS[k];
            let d = shape::derivatives(xi);
            let dsdxi = combine(&d, &y).norm();
            if dsdxi <= f64::EPSILON * (y[0].norm() + y[2].norm() + 1.0) {
                return Err(BeamError::ZeroLength(label, POINT_NAMES[k]));
            }
            // p′⁰ by the very operations SectionKinematics applies to the nodes, so that
            // the strain is exactly zero in the initial configuration (as MBDyn's: a
            // 1000-element cantilever otherwise starts with 1e-4 N of rounding per node).
            let tangent = combine(&d.map(|d| d / dsdxi), &y);
            let r0 = match orientation {
                SectionOrientation::Given(r) => *r,
                SectionOrientation::FromNodes => interpolate_frames(&frames, xi),
            };
            if ((r0.transpose() * r0) - Mat3::identity()).norm() > 1e-9 || r0.determinant() < 0.0 {
                return Err(BeamError::BadOrientation(label, POINT_NAMES[k]));
            }
            sections.push(SectionReference { xi, orientation: r0, dsdxi, initial_strain: r0.transpose() * tangent });
        }
        let viscous = laws.iter().any(SectionLaw::is_viscous);
        Ok(Beam3 {
            label,
            nodes: std::array::from_fn(|i| nodes[i].label),
            offsets: std::array::from_fn(|i| nodes[i].offset),
            initial: std::array::from_fn(|i| nodes[i].initial_orientation),
            sections: [sections[0].clone(), sections[1].clone()],
            laws,
            viscous,
        })
    }

    fn evaluate(&self, st: &dyn ElementState) -> (NodeTerms, [SectionKinematics; 2]) {
        let terms = NodeTerms::new(st, &self.offsets, &self.initial, self.viscous);
        let k = [SectionKinematics::new(&terms, &self.sections[0]), SectionKinematics::new(&terms, &self.sections[1])];
        (terms, k)
    }

    /// Local generalized forces `[F; M] = K ([ε; κ] − e_p) + V [ε̇; κ̇] + f_p`.
    fn local_forces(&self, s: usize, k: &SectionKinematics) -> Vector6<f64> {
        let law = &self.laws[s];
        let mut out = law.stiffness * (stack(&k.strain, &k.curvature) - law.prestrain) + law.prestress;
        if self.viscous {
            out += law.viscosity * stack(&k.strain_rate, &k.curvature_rate);
        }
        out
    }

}

/// `[a; b]`.
fn stack(a: &Vec3, b: &Vec3) -> Vector6<f64> {
    Vector6::new(a.x, a.y, a.z, b.x, b.y, b.z)
}

/// Orientation at ξ interpolated from three frames, relative to the middle one:
/// `R(Σ N_i g_i) F_2` with `R(g_i) = F_i F_2ᵀ`.
fn interpolate_frames(frames: &[Mat3; 3], xi: f64) -> Mat3 {
    let n = shape::values(xi);
    let g = n[0] * gibbs_from_rotation(&(frames[0] * frames[1].transpose())) + n[2] * gibbs_from_rotation(&(frames[2] * frames[1].transpose()));
    gibbs_rotation(&g) * frames[1]
}

/// Rows 6 i..6 i + 6 of the element residual's derivative: node `i`'s force and moment.
type ElementJacobian = SMatrix<f64, 18, 36>;

impl Element for Beam3 {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "beam3"
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.to_vec()
    }

    /// Node `s` (the volume before point `s`) receives `F_s` and `M_s + (p_s − x_s) × F_s`;
    /// node `s + 1` the opposite with arm `p_s − x_{s+1}`. The residual holds `−` what a
    /// node receives.
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (terms, ks) = self.evaluate(st);
        for (s, k) in ks.iter().enumerate() {
            let f = self.local_forces(s, k);
            let force = k.r * Vec3::new(f[0], f[1], f[2]);
            let moment = k.r * Vec3::new(f[3], f[4], f[5]);
            for (node, sign) in [(s, -1.0), (s + 1, 1.0)] {
                let m = moment + (k.p - terms.x(node)).cross(&force);
                for c in 0..3 {
                    out.add(Row::Equilibrium { slot: node, comp: c }, sign * force[c]);
                    out.add(Row::Equilibrium { slot: node, comp: 3 + c }, sign * m[c]);
                }
            }
        }
    }

    /// Points I and II: forces and moments `K ([ε; κ] − e_p) + V [ε̇; κ̇] + f_p`, strains and
    /// curvatures, all in the section frame.
    fn sections(&self, st: &dyn ElementState) -> Vec<SectionState> {
        let (_, ks) = self.evaluate(st);
        ks.iter()
            .enumerate()
            .map(|(s, k)| {
                let f = self.local_forces(s, k);
                SectionState { position: k.p, orientation: k.r, strain: k.strain, curvature: k.curvature, force: f.fixed_rows::<3>(0).into(), moment: f.fixed_rows::<3>(3).into() }
            })
            .collect()
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (terms, ks) = self.evaluate(st);
        let node_tangents = terms.tangents();
        let mut jac = ElementJacobian::zeros();
        for (s, k) in ks.iter().enumerate() {
            let d = k.tangents(&terms, &node_tangents);
            let law = &self.laws[s];
            let f = self.local_forces(s, k);
            let (fl, ml) = (Vec3::new(f[0], f[1], f[2]), Vec3::new(f[3], f[4], f[5]));
            let (force, moment) = (k.r * fl, k.r * ml);
            // δ(local forces) = K [δε; δκ] + V [δε̇; δκ̇].
            let block = |m: &nalgebra::Matrix6<f64>, i: usize, j: usize| -> Mat3 { m.fixed_view::<3, 3>(i, j).into() };
            let (kk, vv) = (&law.stiffness, &law.viscosity);
            let mut dfl = block(kk, 0, 0) * d.dstrain + block(kk, 0, 3) * d.dcurvature;
            let mut dml = block(kk, 3, 0) * d.dstrain + block(kk, 3, 3) * d.dcurvature;
            if self.viscous {
                dfl += block(vv, 0, 0) * d.dstrain_rate + block(vv, 0, 3) * d.dcurvature_rate;
                dml += block(vv, 3, 0) * d.dstrain_rate + block(vv, 3, 3) * d.dcurvature_rate;
            }
            let dforce = k.r * dfl - skew(&force) * d.dtheta;
            let dmoment = k.r * dml - skew(&moment) * d.dtheta;
            for (node, sign) in [(s, -1.0), (s + 1, 1.0)] {
                let arm = k.p - terms.x(node);
                let mut darm = d.dp;
                put(&mut darm, node, POSITION, &-Mat3::identity());
                let dm: Tangent = dmoment + skew(&arm) * dforce - skew(&force) * darm;
                let mut rows = jac.fixed_view_mut::<3, 36>(6 * node, 0);
                rows += sign * dforce;
                let mut rows = jac.fixed_view_mut::<3, 36>(6 * node + 3, 0);
                rows += sign * dm;
            }
        }
        let kinds = if self.viscous { 4 } else { 2 };
        for node in 0..3 {
            for (half, rows) in [Row::force(node), Row::moment(node)].into_iter().enumerate() {
                let r = 6 * node + 3 * half;
                for slot in 0..3 {
                    let cols = [Col::position(slot), Col::rotation(slot), Col::velocity(slot), Col::angular_velocity(slot)];
                    for (kind, c) in cols.into_iter().enumerate().take(kinds) {
                        let block: Mat3 = jac.fixed_view::<3, 3>(r, 12 * slot + 3 * kind).into();
                        out.add_block(rows, c, &block);
                    }
                }
            }
        }
    }
}
