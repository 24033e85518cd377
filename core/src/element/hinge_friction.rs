//! MBDyn's `modlugre` friction with the `simple` shape function on a `revolute hinge`
//! (input manual, §Revolute hinge: `friction, r, [preload, P,] MODEL, SHAPE`; planej.cc,
//! `PlaneHingeJoint::AssRes`/`AssJac` with a friction): the model of [`super::friction`]
//! with the sliding velocity of the hinge's contact circle of radius `r`,
//!
//! ```text
//! v = r (ω₁ − ω₂) · e₃,       N = max(|F|, preload),       M = f N r,
//! ```
//!
//! `e₃` the hinge axis (axis 3 of node 1's hinge frame), `F` the hinge's reaction force
//! (its three position multipliers; the norm is the same in any frame), `f = σ₀ z + σ₁ ż +
//! σ₂ v` the friction coefficient, and the friction moment `M` acting along `−e₃` on node 1
//! and `+e₃` on node 2.
//!
//! The same element is MBDyn's `brake` (input manual, §Brake; brake.cc): the friction
//! moment alone, with no constraint of its own (a revolute hinge between the same nodes
//! holds the rest), and the normal force given by a drive, `N = max(N(t), preload)`
//! (brake.cc `modF`; no absolute value).

use super::anchor::{node_labels, Pair};
use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::friction::ModLugre;
use super::joint::{Joint, JointKind};
use super::drive::Drive;
use crate::kinematics::{skew, Vec3};
use super::UnknownKind;
use crate::element::NonSmooth;
use crate::element::Outputs;

/// Where the friction's normal force comes from.
#[derive(Clone, Debug)]
pub enum HingeNormalForce {
    /// The hinge's reaction `|F|` (a `revolute hinge` with `friction`).
    Reaction,
    /// A drive `N(t)` [N], the hinge's constraint left out (a `brake`).
    Brake(Drive),
}

/// A revolute hinge with `modlugre` friction. Unknowns: the hinge's five multipliers (three
/// forces, two moments), then the friction state `z` [m]; a brake has only `z` (the joint
/// then gives only the frames).
#[derive(Clone, Debug)]
pub struct RevoluteHingeFriction {
    joint: Joint,
    normal: HingeNormalForce,
    /// The contact radius `r` [m]: the sliding velocity is `r` times the relative angular
    /// velocity, and the moment `r` times the friction force.
    radius: f64,
    /// MBDyn's `preload`: the least normal force [N].
    preload: f64,
    model: ModLugre,
}


/// Sliding speed below which the joint is at rest for [`Element::non_smooth`] [m/s].
const STILL: f64 = 1e-6;

impl RevoluteHingeFriction {
    /// `joint` must be a revolute hinge (five multipliers).
    pub fn new(joint: Joint, radius: f64, preload: f64, model: ModLugre) -> Self {
        debug_assert_eq!(joint.kind, JointKind::RevoluteHinge);
        RevoluteHingeFriction { joint, normal: HingeNormalForce::Reaction, radius, preload, model }
    }

    /// MBDyn's `brake` between the frames of `frames` (a revolute hinge's anchors; its
    /// constraint is not applied), pressed by `normal_force(t)` [N].
    pub fn brake(frames: Joint, radius: f64, preload: f64, model: ModLugre, normal_force: Drive) -> Self {
        RevoluteHingeFriction { joint: frames, normal: HingeNormalForce::Brake(normal_force), radius, preload, model }
    }

    fn is_brake(&self) -> bool {
        matches!(self.normal, HingeNormalForce::Brake(_))
    }

    /// Index of the friction state among the element's unknowns (after the hinge's five
    /// multipliers, or alone for a brake).
    fn state_index(&self) -> usize {
        if self.is_brake() { 0 } else { 5 }
    }

    /// Hinge axis `e₃`, sliding velocity `v = r (ω₁ − ω₂)·e₃` and `ω₁ − ω₂`.
    fn sliding(&self, p: &Pair) -> (Vec3, f64, Vec3) {
        let e3 = p.q_a.column(2).into_owned();
        let w = p.omega_a - p.omega_b;
        (e3, self.radius * w.dot(&e3), w)
    }

    /// `N = max(|F|, preload)` and `∂N/∂λ` over the three force multipliers (zero below the
    /// preload, as planej.cc).
    fn normal_force(&self, st: &dyn ElementState) -> (f64, [f64; 3]) {
        if let HingeNormalForce::Brake(drive) = &self.normal {
            return (drive.value_in(st).max(self.preload), [0.0; 3]);
        }
        let l = Vec3::new(st.multiplier(0), st.multiplier(1), st.multiplier(2));
        let norm = l.norm();
        if norm < self.preload || norm == 0.0 {
            (self.preload, [0.0; 3])
        } else {
            (norm, [l.x / norm, l.y / norm, l.z / norm])
        }
    }
}

impl Element for RevoluteHingeFriction {
    fn label(&self) -> Label {
        self.joint.label
    }
    fn type_name(&self) -> &'static str {
        if self.is_brake() { "brake" } else { "revolute hinge" }
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.joint.a, &self.joint.b)
    }
    fn multipliers(&self) -> Vec<String> {
        let mut m = if self.is_brake() { Vec::new() } else { self.joint.multipliers() };
        m.push("friction state z".to_string());
        m
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        if k == self.state_index() { UnknownKind::State } else { UnknownKind::Multiplier }
    }
    fn reads_state(&self) -> bool {
        matches!(&self.normal, HingeNormalForce::Brake(d) if d.reads_state())
    }
    fn assembly_form(&self) -> Option<&dyn Element> {
        // A brake is left out of the initial assembly (its type name), as brake.cc adds nothing there.
        (!self.is_brake()).then_some(&self.joint as &dyn Element)
    }
    fn non_smoothness(&self) -> Option<&dyn NonSmooth> {
        Some(self)
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let state = self.state_index();
        if !self.is_brake() {
            self.joint.residual(st, out);
        }
        let p = Pair::new(&self.joint.a, &self.joint.b, st);
        let (e3, v, _) = self.sliding(&p);
        let (z, zdot) = (st.multiplier(state), st.rate(state));
        out.add(Row::Constraint(state), zdot + self.model.state_equation(z, v).value);
        // Applied moment +e₃ M on node 2, −e₃ M on node 1; residual rows are `… − M`.
        let moment = e3 * (self.model.coefficient(z, zdot, v) * self.normal_force(st).0 * self.radius);
        add_vec(out, Row::moment(p.slot_b), &(-moment));
        if let Some(a) = p.slot_a {
            add_vec(out, Row::moment(a), &moment);
        }
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let state = self.state_index();
        if !self.is_brake() {
            self.joint.jacobian(st, out);
        }
        let p = Pair::new(&self.joint.a, &self.joint.b, st);
        let (e3, v, w) = self.sliding(&p);
        let (z, zdot) = (st.multiplier(state), st.rate(state));
        let (n, dn) = self.normal_force(st);
        let (m, r) = (&self.model, self.radius);
        let f = m.coefficient(z, zdot, v);
        let psi = m.state_equation(z, v);
        // δv = r e₃·(δω₁ − δω₂) + r (e₃ × w)·δθ₁ (δe₃ = δθ₁ × e₃).
        let mut dv: Vec<(Col, f64)> = Vec::new();
        for k in 0..3 {
            dv.push((Col::AngularVelocity { slot: p.slot_b, comp: k }, -r * e3[k]));
        }
        if let Some(a) = p.slot_a {
            let t = e3.cross(&w) * r;
            for k in 0..3 {
                dv.push((Col::AngularVelocity { slot: a, comp: k }, r * e3[k]));
                dv.push((Col::Rotation { slot: a, comp: k }, t[k]));
            }
        }
        // State row: δψ = δż + ψ_/z δz + ψ_/v δv.
        let row = Row::Constraint(state);
        out.add(row, Col::Rate(state), 1.0);
        out.add(row, Col::Multiplier(state), psi.d_z);
        for &(col, d) in &dv {
            out.add(row, col, psi.d_v * d);
        }
        // δM = r [N (σ₀ δz + σ₁ δż + σ₂ δv) + f ∂N/∂λ δλ]; node 1's row is +e₃ M, node 2's −.
        let mut dmoment: Vec<(Col, f64)> = vec![(Col::Multiplier(state), r * n * m.sigma0), (Col::Rate(state), r * n * m.sigma1)];
        if !self.is_brake() {
            dmoment.extend((0..3).map(|k| (Col::Multiplier(k), r * f * dn[k])));
        }
        dmoment.extend(dv.iter().map(|&(col, d)| (col, r * n * m.sigma2 * d)));
        for (col, d) in dmoment {
            for k in 0..3 {
                out.add(Row::Equilibrium { slot: p.slot_b, comp: 3 + k }, col, -e3[k] * d);
                if let Some(a) = p.slot_a {
                    out.add(Row::Equilibrium { slot: a, comp: 3 + k }, col, e3[k] * d);
                }
            }
        }
        // The axis turns with node 1: δ(e₃ M) = −M [e₃×] δθ₁ + …
        if let Some(a) = p.slot_a {
            let turn = -skew(&e3) * (f * n * r);
            add_block(out, Row::moment(a), Col::rotation(a), &turn);
            add_block(out, Row::moment(p.slot_b), Col::rotation(a), &(-turn));
        }
    }
}

impl Outputs for RevoluteHingeFriction {
    fn private_data(&self, name: &str) -> Option<super::private_data::PrivateDatum> {
        self.joint.private_data(name)
    }
}

impl NonSmooth for RevoluteHingeFriction {
    fn non_smooth(&self, st: &dyn ElementState) -> Option<String> {
        let p = Pair::new(&self.joint.a, &self.joint.b, st);
        let (_, v, _) = self.sliding(&p);
        let z = st.multiplier(self.state_index());
        (v.abs() < STILL && self.model.past_breakaway(z)).then(|| format!("its friction state z = {z:e} m is past the breakaway deflection at sliding velocity {v:.1e} m/s (at rest), where the modlugre state equation is not differentiable"))
    }
    fn kink_crossed(&self, from: &dyn ElementState, to: &dyn ElementState) -> Option<String> {
        let v = |st: &dyn ElementState| (self.sliding(&Pair::new(&self.joint.a, &self.joint.b, st)).1, st.multiplier(self.state_index()));
        self.model.kink_crossed(v(from), v(to))
    }
    fn reaction_dependence(&self, st: &dyn ElementState) -> Option<String> {
        let (n, dn) = self.normal_force(st);
        (dn != [0.0; 3]).then(|| format!("its friction moment and stiffness scale with the normal force |F| = {n:.9e} N, the hinge's reaction multipliers as integrated, which steps accepted within the tolerance without a Newton iteration leave noisy; the eigenvalues carry that noise, which a tighter `tolerance` narrows"))
    }
}
