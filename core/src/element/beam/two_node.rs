//! The 2-node finite-volume beam (MBDyn's `beam2`): one evaluation point in the middle,
//! linear interpolation of the reference line, each node's volume the half next to it
//! (the loads of [`super::finite_volume`]).
//!
//! Node `i` has position `x_i`, orientation `R_i` (initially `R_i⁰`), offset `f_i`; the
//! reference line passes through `y_i = x_i + R_i f_i`. With the nodes' rotations from the
//! initial configuration `Δ_i = R_i R_i⁰ᵀ` and their relative rotation vector
//! `θ = rotvec(Δ_1ᵀ Δ_2)` (frame `Δ_1`), the section frame is the one halfway between
//! them, `R_s = Δ_1 exp(θ/2) R_s⁰` (the same seen from either node: objective and
//! symmetric), and
//!
//! - `p = (y_1 + y_2)/2`, `p′ = (y_2 − y_1)/ℓ` (`ℓ` the initial `|y_2 − y_1|`);
//! - strain `ε = R_sᵀ p′ − ε⁰`, `ε⁰ = R_s⁰ᵀ p′⁰` (the initial state is unstrained);
//! - curvature `κ = R_s⁰ᵀ θ / ℓ`, exact for a uniformly bent or twisted element whatever
//!   its rotation (`θ` below π per element).
//!
//! MBDyn's beam2.cc interpolates the rotation increments of each step instead (as its
//! beam3, the book's Beams chapter, docs/src/mbdyn/beams.md); for a planar bending by any angle its midpoint frame and
//! curvature, accumulated in small steps, are these. Viscous section laws are refused.
//!
//! With the opt-in [`BeamUpdate::Incremental`] the beam follows beam2.cc (MBDyn 1.7.3,
//! `AfterPredict`, `AssStiffnessVec`; [`super::incremental`]): with per-step node bases
//! `P_i`, `R(g_i) = R_i P_iᵀ`, `g = (g_1 + g_2)/2`, `g′ = (g_2 − g_1)/ℓ`, the section frame
//! `R_s = R(g) R_s,ref` and the curvature `κ = R_s,refᵀ Gᵀ(g) g′ + κ_ref`.

use nalgebra::{Matrix6, SMatrix, Vector6};

use super::finite_volume::{self, put_rotation, strain_tangent, PointTangents, RotationTangent, POSITION, ROTATION};
use super::incremental::StepHistory;
use super::{BeamError, BeamNode, BeamUpdate, PiezoActuator, PiezoError, SectionLaw, SectionOrientation};
use crate::element::contract::{Element, ElementState, JacobianSink, Label, Latched, ResidualSink, ScalarNodeId, SectionState};
use crate::element::deformable::inverse_rotation_jacobian;
use crate::element::invariant_hinge::rotation_jacobian;
use crate::kinematics::{gibbs_from_rotation, gibbs_g, gibbs_g_inverse, gibbs_gt_apply, gibbs_gt_derivative, gibbs_rotation, rotation_vector, skew, Mat3, Vec3};
use crate::element::Events;
use crate::element::Outputs;

/// Derivative of a 3-vector with respect to the element's 12 node perturbations (positions
/// and rotations: the law is elastic).
type Tangent = SMatrix<f64, 3, 12>;

/// `t[:, block(node, kind)] += m` on the 2-node element.
fn put(t: &mut Tangent, node: usize, kind: usize, m: &Mat3) {
    finite_volume::put(t, 2, node, kind, m);
}

/// Two-node beam (MBDyn's `beam2`).
#[derive(Clone, Debug)]
pub struct Beam2 {
    pub label: Label,
    nodes: [Label; 2],
    offsets: [Vec3; 2],
    /// Node orientations in the initial configuration.
    initial: [Mat3; 2],
    /// `R_s⁰`.
    orientation: Mat3,
    /// `ℓ` [m].
    length: f64,
    /// `ε⁰`.
    initial_strain: Vec3,
    law: SectionLaw,
    update: BeamUpdate,
    /// The section's voltage-driven forces ([`super::piezo`]), when the card has them.
    piezo: Option<PiezoActuator>,
}

/// The evaluation point's state.
struct Point {
    x: [Vec3; 2],
    a: [Vec3; 2],
    p: Vec3,
    pp: Vec3,
    r: Mat3,
    /// `D = Γ⁻¹(θ) Δ_1ᵀ`: `δθ = D (δθ_2 − δθ_1)`.
    d: Mat3,
    /// `H = ½ Δ_1 Γ(θ/2) D`: the section frame turns by `δθ_1 + H (δθ_2 − δθ_1)`.
    h: Mat3,
    strain: Vec3,
    curvature: Vec3,
    /// The incremental update's terms, when it is on.
    incremental: Option<IncrementalTerms>,
}

/// What the incremental update's derivatives reuse: `g`, `g′`, `Γ(g_i)` and `R_s,ref`.
struct IncrementalTerms {
    g: Vec3,
    gp: Vec3,
    gamma: [Mat3; 2],
    frame: Mat3,
}

/// The frame halfway from `a` to `b`: `a exp(rotvec(aᵀ b)/2)`, and `rotvec(aᵀ b)`.
fn halfway(a: &Mat3, b: &Mat3) -> (Mat3, Vec3) {
    let theta = rotation_vector(&(a.transpose() * b));
    (a * nalgebra::Rotation3::new(theta / 2.0).into_inner(), theta)
}

impl Beam2 {
    /// A beam on two nodes, unstrained in their initial configuration.
    pub fn new(label: Label, nodes: [BeamNode; 2], orientation: SectionOrientation, law: SectionLaw) -> Result<Self, BeamError> {
        if law.is_viscous() {
            return Err(BeamError::Viscous(label, "beam2"));
        }
        let y: [Vec3; 2] = std::array::from_fn(|i| nodes[i].initial_position + nodes[i].initial_orientation * nodes[i].offset);
        let chord = y[1] - y[0];
        let length = chord.norm();
        if length <= f64::EPSILON * (y[0].norm() + y[1].norm() + 1.0) {
            return Err(BeamError::ZeroLength(label, "I"));
        }
        let r0 = match orientation {
            SectionOrientation::Given(r) => r,
            SectionOrientation::FromNodes => {
                let frames: [Mat3; 2] = std::array::from_fn(|i| nodes[i].initial_orientation * nodes[i].orientation);
                halfway(&frames[0], &frames[1]).0
            }
        };
        if ((r0.transpose() * r0) - Mat3::identity()).norm() > 1e-9 || r0.determinant() < 0.0 {
            return Err(BeamError::BadOrientation(label, "I"));
        }
        Ok(Beam2 {
            label,
            nodes: std::array::from_fn(|i| nodes[i].label),
            offsets: std::array::from_fn(|i| nodes[i].offset),
            initial: std::array::from_fn(|i| nodes[i].initial_orientation),
            orientation: r0,
            length,
            initial_strain: r0.transpose() * (chord / length),
            law,
            update: BeamUpdate::PathIndependent,
            piezo: None,
        })
    }

    /// The beam with MBDyn's `piezoelectric actuator` ([`super::piezo`]): one actuation
    /// matrix, at the evaluation point.
    pub fn with_piezo(mut self, piezo: PiezoActuator) -> Result<Self, PiezoError> {
        piezo.check_points(self.label, 1)?;
        self.piezo = Some(piezo);
        Ok(self)
    }

    /// The beam with `update` ([`BeamUpdate`]).
    pub fn with_update(mut self, update: BeamUpdate) -> Self {
        self.update = update;
        self
    }

    /// The history of the incremental update before any step: the initial configuration.
    fn initial_history(&self) -> StepHistory<2, 1> {
        StepHistory { base: self.initial, frames: [self.orientation], curvatures: [Vec3::zeros()] }
    }

    /// The point of the incremental update with history `h`.
    fn evaluate_incremental(&self, st: &dyn ElementState, h: &StepHistory<2, 1>) -> Point {
        let n = [st.node(0), st.node(1)];
        let a: [Vec3; 2] = std::array::from_fn(|i| n[i].r * self.offsets[i]);
        let y: [Vec3; 2] = std::array::from_fn(|i| n[i].x + a[i]);
        let gi: [Vec3; 2] = std::array::from_fn(|i| gibbs_from_rotation(&(n[i].r * h.base[i].transpose())));
        let (g, gp) = (0.5 * (gi[0] + gi[1]), (gi[1] - gi[0]) / self.length);
        let frame = h.frames[0];
        let r = gibbs_rotation(&g) * frame;
        let pp = (y[1] - y[0]) / self.length;
        Point {
            x: [n[0].x, n[1].x],
            a,
            p: 0.5 * (y[0] + y[1]),
            pp,
            r,
            d: Mat3::zeros(),
            h: Mat3::zeros(),
            strain: r.transpose() * pp - self.initial_strain,
            curvature: frame.transpose() * gibbs_gt_apply(&g, &gp) + h.curvatures[0],
            incremental: Some(IncrementalTerms { g, gp, gamma: std::array::from_fn(|i| gibbs_g_inverse(&gi[i])), frame }),
        }
    }

    fn evaluate(&self, st: &dyn ElementState) -> Point {
        if self.update == BeamUpdate::Incremental {
            return self.evaluate_incremental(st, &StepHistory::of(st, || self.initial_history()));
        }
        let n = [st.node(0), st.node(1)];
        let delta: [Mat3; 2] = std::array::from_fn(|i| n[i].r * self.initial[i].transpose());
        let a: [Vec3; 2] = std::array::from_fn(|i| n[i].r * self.offsets[i]);
        let y: [Vec3; 2] = std::array::from_fn(|i| n[i].x + a[i]);
        let (mid, theta) = halfway(&delta[0], &delta[1]);
        let r = mid * self.orientation;
        let pp = (y[1] - y[0]) / self.length;
        let d = inverse_rotation_jacobian(&theta) * delta[0].transpose();
        let h = 0.5 * delta[0] * rotation_jacobian(&(theta / 2.0)) * d;
        Point {
            x: [n[0].x, n[1].x],
            a,
            p: 0.5 * (y[0] + y[1]),
            pp,
            r,
            d,
            h,
            strain: r.transpose() * pp - self.initial_strain,
            curvature: self.orientation.transpose() * theta / self.length,
            incremental: None,
        }
    }

    fn local_forces(&self, st: &dyn ElementState, k: &Point) -> Vector6<f64> {
        let mut f = finite_volume::force_at(&self.law, st, &k.strain, &k.curvature, None);
        if let Some(piezo) = &self.piezo {
            f += piezo.local_forces(0, st);
        }
        f
    }

    /// The local forces `K ([ε; κ] − e_p) + f_p (+ T V)` and the law's tangents.
    fn law_at(&self, st: &dyn ElementState, k: &Point) -> (Vector6<f64>, Matrix6<f64>, Matrix6<f64>) {
        let (mut f, kk, vv) = finite_volume::law_at(&self.law, st, &k.strain, &k.curvature, None);
        if let Some(piezo) = &self.piezo {
            f += piezo.local_forces(0, st);
        }
        (f, kk, vv)
    }
}

impl Element for Beam2 {
    fn label(&self) -> Label {
        self.label
    }
    fn reads_state(&self) -> bool {
        self.law.reads_state()
    }
    fn type_name(&self) -> &'static str {
        "beam2"
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

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let k = self.evaluate(st);
        finite_volume::add_point_residual(out, 0, &k.p, &k.r, &self.local_forces(st, &k), &k.x);
    }

    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let k = self.evaluate(st);
        let mut dy = [Tangent::zeros(); 2];
        for (i, d) in dy.iter_mut().enumerate() {
            put(d, i, POSITION, &Mat3::identity());
            put(d, i, ROTATION, &-skew(&k.a[i]));
        }
        let dp = 0.5 * (dy[0] + dy[1]);
        let dpp = (dy[1] - dy[0]) / self.length;
        let (dtheta, dcurvature) = match &k.incremental {
            // δg_i = Γ(g_i) δθ_i; δθ_s = G(g) δg; δκ = R_s,refᵀ (∂(Gᵀ(g) g′)/∂g δg + Gᵀ(g) δg′).
            Some(inc) => {
                let (mut dg, mut dgp) = (RotationTangent::<6>::zeros(), RotationTangent::<6>::zeros());
                for i in 0..2 {
                    put_rotation(&mut dg, i, &(0.5 * inc.gamma[i]));
                    put_rotation(&mut dgp, i, &(if i == 0 { -1.0 } else { 1.0 } / self.length * inc.gamma[i]));
                }
                let gm = gibbs_g(&inc.g);
                (gm * dg, inc.frame.transpose() * (gibbs_gt_derivative(&inc.g, &inc.gp) * dg + gm.transpose() * dgp))
            }
            None => {
                let (mut drel, mut dtheta) = (RotationTangent::<6>::zeros(), RotationTangent::<6>::zeros());
                put_rotation(&mut drel, 0, &-k.d);
                put_rotation(&mut drel, 1, &k.d);
                put_rotation(&mut dtheta, 0, &(Mat3::identity() - k.h));
                put_rotation(&mut dtheta, 1, &k.h);
                (dtheta, self.orientation.transpose() * drel / self.length)
            }
        };
        let dstrain = strain_tangent(&k.r.transpose(), &dpp, &k.pp, &dtheta);
        let point = PointTangents { dp: &dp, dtheta: &dtheta, dstrain: &dstrain, dcurvature: &dcurvature, rates: None };
        let mut jac = SMatrix::<f64, 12, 12>::zeros();
        finite_volume::add_point_jacobian(&mut jac, 0, &k.p, &k.r, &self.law_at(st, &k), &point, &k.x);
        finite_volume::scatter_jacobian(&jac, false, out);
        if let Some(piezo) = &self.piezo {
            piezo.add_voltage_jacobian(out, 0, &k.p, &k.r, &k.x);
        }
    }
}

impl Outputs for Beam2 {
    /// The evaluation point: forces and moments `K ([ε; κ] − e_p) + f_p`, strains and
    /// curvatures, in the section frame.
    fn sections(&self, st: &dyn ElementState) -> Vec<SectionState> {
        let k = self.evaluate(st);
        vec![finite_volume::section_state(&k.p, &k.r, &k.strain, &k.curvature, &self.local_forces(st, &k))]
    }
}

impl Events for Beam2 {
    /// The incremental update's history of the step, as [`super::Beam3`]'s.
    fn latch(&self, now: &dyn ElementState, before: &dyn ElementState) -> Option<Latched> {
        if self.update != BeamUpdate::Incremental {
            return None;
        }
        let converged = self.evaluate_incremental(before, &StepHistory::of(before, || self.initial_history()));
        let previous = StepHistory { base: [before.node(0).r, before.node(1).r], frames: [converged.r], curvatures: [converged.curvature] };
        let predicted = self.evaluate_incremental(now, &previous);
        Some(StepHistory { base: [now.node(0).r, now.node(1).r], frames: [predicted.r], curvatures: [predicted.curvature] }.latched())
    }
}
