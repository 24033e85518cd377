//! The 3-node finite-volume beam (Ghiringhelli, Masarati, Mantegazza, "A multibody
//! implementation of finite volume C0 beams", AIAA J. 38(1), 2000; paper §6.2): a
//! geometrically exact, shear-deformable beam whose internal forces are evaluated at
//! ξ = ∓1/√3 through a 6x6 section law. Each node's finite volume (ξ from its end to the
//! next evaluation point) is in equilibrium under the internal forces at its boundaries:
//! the force `F_s` and moment `M_s` at point `s` act with `+` on the volume before it and
//! `−` on the volume after it, with arms `p_s − x_i` about the nodes. The beam carries no
//! inertia: lump masses on its nodes with rigid bodies (see [`shape::volume_fractions`]).

mod finite_volume;
mod incremental;
mod law;
mod piezo;
mod section;
pub mod shape;
mod two_node;

pub use incremental::BeamUpdate;
pub use law::SectionLaw;
pub use piezo::{PiezoActuator, PiezoError};
pub use two_node::Beam2;

use nalgebra::{Matrix6, SMatrix, Vector6};

use super::contract::{Element, ElementState, JacobianSink, Label, Latched, ResidualSink, ScalarNodeId, SectionState};
use crate::kinematics::{gibbs_from_rotation, gibbs_rotation, Mat3, Vec3};
use finite_volume::PointTangents;
use incremental::StepHistory;
use section::{combine, NodeTerms, SectionKinematics, SectionReference};
use crate::element::Events;
use crate::element::Outputs;

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
    #[error("beam {0}: a viscous or viscoelastic section law on a {1} is not supported by romdyn (elastic laws only)")]
    Viscous(Label, &'static str),
    #[error("beam {0}: the incremental beam update with a viscous or viscoelastic section law is not supported by romdyn (elastic laws only; the path-independent update takes them)")]
    IncrementalViscous(Label),
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
    update: BeamUpdate,
    /// The sections' voltage-driven forces ([`piezo`]), when the card has them.
    piezo: Option<PiezoActuator>,
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
            sections.push(SectionReference { xi, orientation: r0, dsdxi, initial_strain: r0.transpose() * tangent, accumulated_curvature: None });
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
            update: BeamUpdate::PathIndependent,
            piezo: None,
        })
    }

    /// The beam with MBDyn's `piezoelectric actuator` ([`piezo`]): one actuation matrix
    /// per evaluation point (two).
    pub fn with_piezo(mut self, piezo: PiezoActuator) -> Result<Self, PiezoError> {
        piezo.check_points(self.label, 2)?;
        self.piezo = Some(piezo);
        Ok(self)
    }

    /// The beam with `update` ([`BeamUpdate`]); the incremental update refuses viscous laws.
    pub fn with_update(mut self, update: BeamUpdate) -> Result<Self, BeamError> {
        self.check_update(update)?;
        self.update = update;
        Ok(self)
    }

    /// Whether the beam can take `update`: the incremental update refuses viscous laws.
    pub fn check_update(&self, update: BeamUpdate) -> Result<(), BeamError> {
        if update == BeamUpdate::Incremental && self.viscous {
            return Err(BeamError::IncrementalViscous(self.label));
        }
        Ok(())
    }

    /// The history of the incremental update before any step: the initial configuration.
    fn initial_history(&self) -> StepHistory<3, 2> {
        StepHistory { base: self.initial, frames: [self.sections[0].orientation, self.sections[1].orientation], curvatures: [Vec3::zeros(); 2] }
    }

    /// Node terms and points of the incremental update with history `h`.
    fn evaluate_incremental(&self, st: &dyn ElementState, h: &StepHistory<3, 2>) -> (NodeTerms, [SectionKinematics; 2]) {
        let terms = NodeTerms::incremental(st, &self.offsets, &h.base);
        let k = std::array::from_fn(|s| {
            let reference = SectionReference { orientation: h.frames[s], accumulated_curvature: Some(h.curvatures[s]), ..self.sections[s].clone() };
            SectionKinematics::new(&terms, &reference)
        });
        (terms, k)
    }

    fn evaluate(&self, st: &dyn ElementState) -> (NodeTerms, [SectionKinematics; 2]) {
        if self.update == BeamUpdate::Incremental {
            return self.evaluate_incremental(st, &StepHistory::of(st, || self.initial_history()));
        }
        let terms = NodeTerms::new(st, &self.offsets, &self.initial, self.viscous);
        let k = [SectionKinematics::new(&terms, &self.sections[0]), SectionKinematics::new(&terms, &self.sections[1])];
        (terms, k)
    }

    /// Local generalized forces `[F; M] = K ([ε; κ] − e_p) + V [ε̇; κ̇] + f_p (+ T_s V)`.
    fn local_forces(&self, st: &dyn ElementState, s: usize, k: &SectionKinematics) -> Vector6<f64> {
        let rates = self.viscous.then_some((&k.strain_rate, &k.curvature_rate));
        let mut f = finite_volume::force_at(&self.laws[s], st, &k.strain, &k.curvature, rates);
        if let Some(piezo) = &self.piezo {
            f += piezo.local_forces(s, st);
        }
        f
    }

    /// The local forces (a piezoelectric actuator's `T_s V` included) and the law's
    /// tangents at point `s`.
    fn law_at(&self, st: &dyn ElementState, s: usize, k: &SectionKinematics) -> (Vector6<f64>, Matrix6<f64>, Matrix6<f64>) {
        let rates = self.viscous.then_some((&k.strain_rate, &k.curvature_rate));
        let (mut f, kk, vv) = finite_volume::law_at(&self.laws[s], st, &k.strain, &k.curvature, rates);
        if let Some(piezo) = &self.piezo {
            f += piezo.local_forces(s, st);
        }
        (f, kk, vv)
    }
}

/// Orientation at ξ interpolated from three frames, relative to the middle one:
/// `R(Σ N_i g_i) F_2` with `R(g_i) = F_i F_2ᵀ`.
fn interpolate_frames(frames: &[Mat3; 3], xi: f64) -> Mat3 {
    let n = shape::values(xi);
    let g = n[0] * gibbs_from_rotation(&(frames[0] * frames[1].transpose())) + n[2] * gibbs_from_rotation(&(frames[2] * frames[1].transpose()));
    gibbs_rotation(&g) * frames[1]
}

/// Rows 6 i..6 i + 6 of the element residual's derivative: node `i`'s force and moment;
/// the `C` columns of [`finite_volume::column`].
type ElementJacobian<const C: usize> = SMatrix<f64, 18, C>;

impl Element for Beam3 {
    fn label(&self) -> Label {
        self.label
    }
    fn reads_state(&self) -> bool {
        self.laws.iter().any(SectionLaw::reads_state)
    }
    fn type_name(&self) -> &'static str {
        "beam3"
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.to_vec()
    }
    /// A piezoelectric actuator's electrodes (abstract nodes), else none.
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.piezo.as_ref().map_or_else(Vec::new, |p| p.electrodes().to_vec())
    }

    fn events(&self) -> Option<&dyn Events> {
        if self.update == BeamUpdate::Incremental { Some(self) } else { None }
    }

    /// Node `s` (the volume before point `s`) receives `F_s` and `M_s + (p_s − x_s) × F_s`;
    /// node `s + 1` the opposite with arm `p_s − x_{s+1}` ([`finite_volume`]).
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (terms, ks) = self.evaluate(st);
        for (s, k) in ks.iter().enumerate() {
            finite_volume::add_point_residual(out, s, &k.p, &k.r, &self.local_forces(st, s, k), terms.x());
        }
    }

    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        // An elastic law's forces do not depend on the velocities: their 18 columns are zero.
        if self.viscous {
            self.jacobian_in::<36>(st, out);
        } else {
            self.jacobian_in::<18>(st, out);
        }
    }
}

impl Beam3 {
    /// The Jacobian with `C` columns: 18 (positions and rotations) or 36 (and velocities).
    fn jacobian_in<const C: usize>(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (terms, ks) = self.evaluate(st);
        let node_tangents = terms.tangents::<C>();
        let mut jac = ElementJacobian::<C>::zeros();
        for (s, k) in ks.iter().enumerate() {
            let d = k.tangents(&terms, &node_tangents);
            let rates = d.rates.as_ref().map(|(dstrain_rate, dcurvature_rate)| (dstrain_rate, dcurvature_rate));
            let point = PointTangents { dp: &d.dp, dtheta: &d.dtheta, dstrain: &d.dstrain, dcurvature: &d.dcurvature, rates };
            finite_volume::add_point_jacobian(&mut jac, s, &k.p, &k.r, &self.law_at(st, s, k), &point, terms.x());
            if let Some(piezo) = &self.piezo {
                piezo.add_voltage_jacobian(out, s, &k.p, &k.r, terms.x());
            }
        }
        finite_volume::scatter_jacobian(&jac, self.viscous, out);
    }
}

impl Outputs for Beam3 {
    /// Points I and II: forces and moments `K ([ε; κ] − e_p) + V [ε̇; κ̇] + f_p`, strains and
    /// curvatures, all in the section frame.
    fn sections(&self, st: &dyn ElementState) -> Vec<SectionState> {
        let (_, ks) = self.evaluate(st);
        ks.iter()
            .enumerate()
            .map(|(s, k)| finite_volume::section_state(&k.p, &k.r, &k.strain, &k.curvature, &self.local_forces(st, s, k)))
            .collect()
    }
}

impl Events for Beam3 {
    /// The incremental update's history of the step ([`incremental`]): the converged
    /// frames and curvatures of `before` (MBDyn's `AfterConvergence`), advanced by the
    /// predicted increments to `now` (`AfterPredict`).
    fn latch(&self, now: &dyn ElementState, before: &dyn ElementState) -> Option<Latched> {
        if self.update != BeamUpdate::Incremental {
            return None;
        }
        let (_, converged) = self.evaluate_incremental(before, &StepHistory::of(before, || self.initial_history()));
        let previous = StepHistory { base: std::array::from_fn(|i| before.node(i).r), frames: [converged[0].r, converged[1].r], curvatures: [converged[0].curvature, converged[1].curvature] };
        let (_, predicted) = self.evaluate_incremental(now, &previous);
        Some(StepHistory::<3, 2> { base: std::array::from_fn(|i| now.node(i).r), frames: [predicted[0].r, predicted[1].r], curvatures: [predicted[0].curvature, predicted[1].curvature] }.latched())
    }
}
