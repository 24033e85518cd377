//! A joint with imposed motion: the holonomic constraints of a [`Joint`] with a time-varying
//! relative position `D(t)` (in frame A) and relative rotation `Θ(t)`, plus velocity-level
//! constraints on the relative velocity and angular velocity in frame A (MBDyn's `total
//! joint` and `total pin joint` with drives and `velocity`/`angular velocity` constraints,
//! totalj.cc; its `drive displacement`, `imposed displacement` and `drive hinge` are total
//! joints of this kind).
//!
//! The imposed position moves A's point: `p_a(t) = x_a + R_a o_a + Q_a D(t)`, so the
//! position constraint reads `Q_aᵀ (p_b − p_a₀) − D(t)`. The imposed rotation turns B's
//! frame back, `Q_b(t) = R_b H_b exp(Θ(t))ᵀ`, so the rotation constraint `ax(Q_aᵀ Q_b(t))`
//! vanishes where `Q_aᵀ R_b H_b = exp(Θ(t))`: MBDyn's `RotManip::VecRot(R1rᵀ R2r R0ᵀ) = 0`,
//! with the same zero set. Velocity constraints (not divided by dCoef): `(Q_aᵀ u)_k = V_k(t)`
//! with `u = ẋ_b + ω_b × f_b − ẋ_a − ω_a × (p_b − x_a)`, reaction `Q_a λ` at `p_b`, and
//! `(Q_aᵀ (ω_b − ω_a))_k = W_k(t)`, reaction moment `Q_a μ`.
//!
//! Some rotation components locked, not all three ([`DrivenJoint::rotation_remnant`]): MBDyn's
//! rows are the locked components of `Θ_Δ = rotvec(Q_aᵀ Q_b R₀ᵀ)`, `R₀ = exp(Θ_l(t) + r)`,
//! `Θ_l` the imposed rotation on the locked components and `r` the remnant, whose free
//! components add up `Θ_Δ`'s free components at every converged solution (zero at the
//! start), so that `Θ_Δ` stays small; the reaction moment is `Q_a μ` (totalj.cc,
//! `TotalJoint::AssRes`, `AfterConvergence`: "correct ThetaDrv to keep ThetaDelta small").
//! The remnant is kept as the element's latched data ([`Element::latch`]).

use super::anchor::Pair;
use super::contract::{add_block, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::contract::Latched;
use super::deformable::inverse_rotation_jacobian;
use super::{Anchor, Joint};
use super::drive::Drive;
use crate::kinematics::{rotation_vector, skew, Vec3};
use std::sync::Arc;
use super::UnknownKind;
use crate::element::Events;
use crate::element::Outputs;

/// A 3-vector function of time `Σ v_k d_k(t)` (MBDyn's template drive caller).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VectorDrive(pub Vec<(Vec3, Drive)>);

impl VectorDrive {
    pub fn value(&self, t: f64) -> Vec3 {
        self.0.iter().map(|(v, d)| v * d.value(t)).sum()
    }
    /// The value in an element's residual (drives may read the state, see [`Drive::value_in`]).
    pub fn value_in(&self, st: &dyn super::ElementState) -> Vec3 {
        self.0.iter().map(|(v, d)| v * d.value_in(st)).sum()
    }
    /// Whether a drive reads the model's state.
    pub fn reads_state(&self) -> bool {
        self.0.iter().any(|(_, d)| d.reads_state())
    }
    /// The same drives with each vector turned by `m` (the value in another frame).
    pub fn turned(self, m: &crate::kinematics::Mat3) -> Self {
        VectorDrive(self.0.into_iter().map(|(v, d)| (m * v, d)).collect())
    }
    pub fn is_zero(&self) -> bool {
        self.0.iter().all(|(v, d)| *v == Vec3::zeros() || *d == Drive::Const(0.0))
    }
}

/// A joint with imposed relative motion (see the module documentation).
#[derive(Clone, Debug)]
pub struct DrivenJoint {
    joint: Joint,
    name: &'static str,
    /// Imposed relative position `D(t)` in frame A [m] (its locked components matter).
    pub position: VectorDrive,
    /// Imposed relative rotation vector `Θ(t)` [rad] (all three rotations locked).
    pub rotation: VectorDrive,
    /// Components of the relative velocity in frame A held at `velocity(t)` [m/s].
    pub velocity_locked: [bool; 3],
    pub velocity: VectorDrive,
    /// Components of the relative angular velocity held at `angular_velocity(t)` [rad/s].
    pub angular_velocity_locked: [bool; 3],
    pub angular_velocity: VectorDrive,
    /// How a hint's position and rotation drives become [`Self::position`] and
    /// [`Self::rotation`], as the reader made the card's: the components held, and the turns
    /// into the constraint frame (identity, all held, unless the reader says otherwise).
    pub hint_position_held: [bool; 3],
    pub hint_position_turn: crate::kinematics::Mat3,
    pub hint_rotation_turn: crate::kinematics::Mat3,
    /// Whether all three rotations are held (a hint's imposed rotation applies only so).
    pub hint_rotation_held: bool,
    /// Whether the locked rotation components (some, not all three) are MBDyn's, with the
    /// remnant of the free ones (module documentation), rather than the skew part of the
    /// relative rotation.
    pub rotation_remnant: bool,
}

/// The remnant `r` of a joint with some rotation components locked (module documentation),
/// in frame A [rad], as of its last converged solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotationRemnant(pub Vec3);

/// Which reaction a velocity constraint has.
#[derive(Clone, Copy)]
enum Rate {
    Linear(usize),
    Angular(usize),
}

impl DrivenJoint {
    /// `joint` (its kind names the locked holonomic components) with no imposed motion yet;
    /// `name` is the MBDyn card it comes from.
    pub fn new(joint: Joint, name: &'static str) -> Self {
        DrivenJoint {
            joint,
            name,
            position: VectorDrive::default(),
            rotation: VectorDrive::default(),
            velocity_locked: [false; 3],
            velocity: VectorDrive::default(),
            angular_velocity_locked: [false; 3],
            angular_velocity: VectorDrive::default(),
            hint_position_held: [true; 3],
            hint_position_turn: crate::kinematics::Mat3::identity(),
            hint_rotation_turn: crate::kinematics::Mat3::identity(),
            hint_rotation_held: false,
            rotation_remnant: false,
        }
    }

    /// The joint with a drive of a hint in place of the card's (MBDyn's
    /// `TotalJoint::SetValue`, `TotalPinJoint::SetValue`: `position-drive3` and
    /// `orientation-drive3` replace the imposed position and rotation; `DriveHingeJoint::SetValue`:
    /// `drive3` the drive hinge's rotation). `None` where the hint does not apply.
    pub fn with_hint(&self, hint: &super::HintValue) -> Option<Self> {
        use super::HintValue;
        let mut j = self.clone();
        let total = matches!(self.name, "total joint" | "total pin joint");
        match hint {
            HintValue::PositionDrive3(v) if total => {
                let held = self.hint_position_held;
                let mask = |x: &Vec3| Vec3::from_fn(|k, _| if held[k] { x[k] } else { 0.0 });
                j.position = VectorDrive(v.0.iter().map(|(x, d)| (mask(x), d.clone())).filter(|(x, _)| *x != Vec3::zeros()).collect()).turned(&self.hint_position_turn);
            }
            HintValue::OrientationDrive3(v) if total && self.hint_rotation_held => j.rotation = v.clone().turned(&self.hint_rotation_turn),
            HintValue::Drive3(v) if self.name == "drive hinge" => j.rotation = v.clone(),
            _ => return None,
        }
        Some(j)
    }

    fn holonomic(&self) -> usize {
        self.joint.multipliers().len()
    }

    fn rates(&self) -> impl Iterator<Item = Rate> + '_ {
        let v = (0..3).filter(|&k| self.velocity_locked[k]).map(Rate::Linear);
        let w = (0..3).filter(|&k| self.angular_velocity_locked[k]).map(Rate::Angular);
        v.chain(w)
    }

    /// The joint with its anchors where they are at time `t` (drives that read the model's
    /// state give NaN here: see [`Self::joint_in`]).
    pub fn joint_at(&self, t: f64) -> Joint {
        self.placed(self.position.value(t), self.rotation.value(t))
    }

    /// The joint with its anchors where the drives put them in the state `st` (at its time,
    /// reading the state as MBDyn's drive callers do, their derivatives in no Jacobian).
    pub fn joint_in(&self, st: &dyn ElementState) -> Joint {
        self.placed(self.position.value_in(st), self.rotation.value_in(st))
    }

    fn placed(&self, d: Vec3, theta: Vec3) -> Joint {
        let mut j = self.joint.clone();
        if !self.position.0.is_empty() {
            match &mut j.a {
                Anchor::Node { offset, orientation, .. } => *offset += *orientation * d,
                Anchor::Ground { position, orientation } => *position += *orientation * d,
            }
        }
        if !self.rotation.0.is_empty() || theta != Vec3::zeros() {
            let back = nalgebra::Rotation3::new(theta).into_inner().transpose();
            match &mut j.b {
                Anchor::Node { orientation, .. } | Anchor::Ground { orientation, .. } => *orientation *= back,
            }
        }
        j
    }

    /// Reactions of the velocity constraints: force `Q_a λ` (at `p_b`), moment `Q_a μ`.
    fn rate_reactions(&self, p: &Pair, st: &dyn ElementState) -> (Vec3, Vec3) {
        let (mut lambda, mut mu) = (Vec3::zeros(), Vec3::zeros());
        for (i, r) in self.rates().enumerate() {
            let x = st.multiplier(self.holonomic() + i);
            match r {
                Rate::Linear(k) => lambda[k] = x,
                Rate::Angular(k) => mu[k] = x,
            }
        }
        (p.q_a * lambda, p.q_a * mu)
    }

    /// The locked rotation components, in order (their rows follow the position rows).
    fn locked_rotations(&self) -> impl Iterator<Item = usize> + '_ {
        (0..3).filter(|&k| self.joint.rotation_locked[k])
    }

    /// In MBDyn's form with the remnant: the joint placed with `R₀ = exp(Θ_l(t) + r)`, its
    /// holonomic position part alone, and `Θ_Δ = rotvec(Q_aᵀ Q_b R₀ᵀ)` with the frames.
    fn remnant_parts(&self, st: &dyn ElementState, remnant: &Vec3) -> (Joint, Pair, Vec3) {
        let j = self.placed(self.position.value_in(st), self.rotation.value_in(st) + remnant);
        let p = Pair::new(&j.a, &j.b, st);
        let theta = rotation_vector(&(p.q_a.transpose() * p.q_b));
        let mut positions = j;
        positions.rotation_locked = [false; 3];
        (positions, p, theta)
    }

    /// The remnant the state carries (zero before the first convergence).
    fn remnant(st: &dyn ElementState) -> Vec3 {
        st.latched().and_then(|l| l.downcast_ref::<RotationRemnant>()).map_or(Vec3::zeros(), |r| r.0)
    }

    /// The reaction moment `Q_a μ` of the locked rotations, `μ` their multipliers.
    fn remnant_moment(&self, p: &Pair, st: &dyn ElementState) -> Vec3 {
        let first = self.joint.multipliers().len() - self.locked_rotations().count();
        let mut mu = Vec3::zeros();
        for (i, k) in self.locked_rotations().enumerate() {
            mu[k] = st.multiplier(first + i);
        }
        p.q_a * mu
    }

    fn remnant_residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (positions, p, theta) = self.remnant_parts(st, &Self::remnant(st));
        positions.residual(st, out);
        let first = positions.multipliers().len();
        for (i, k) in self.locked_rotations().enumerate() {
            out.add(Row::Constraint(first + i), theta[k]);
        }
        p.add_moment(out, &self.remnant_moment(&p, st));
    }

    fn remnant_jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (positions, p, theta) = self.remnant_parts(st, &Self::remnant(st));
        positions.jacobian(st, out);
        let first = positions.multipliers().len();
        // δΘ_Δ = Γ⁻¹(Θ_Δ) Q_aᵀ (δθ_b − δθ_a) (a left turn of Q_aᵀ Q_b R₀ᵀ by Q_aᵀ (δθ_b − δθ_a)).
        let d = inverse_rotation_jacobian(&theta) * p.q_a.transpose();
        let b = p.slot_b;
        for (i, k) in self.locked_rotations().enumerate() {
            for c in 0..3 {
                out.add(Row::Constraint(first + i), Col::rotation(b)[c], d[(k, c)]);
                if let Some(a) = p.slot_a {
                    out.add(Row::Constraint(first + i), Col::rotation(a)[c], -d[(k, c)]);
                }
            }
            p.add_reaction_column(out, Col::Multiplier(first + i), &Vec3::zeros(), &p.q_a.column(k).into_owned());
        }
        // δ(Q_a μ) = −[(Q_a μ)×] δθ_a.
        if let Some(a) = p.slot_a {
            let m = skew(&self.remnant_moment(&p, st));
            add_block(out, Row::moment(b), Col::rotation(a), &(-m));
            add_block(out, Row::moment(a), Col::rotation(a), &m);
        }
    }
}

impl Element for DrivenJoint {
    fn reads_state(&self) -> bool {
        self.position.reads_state() || self.rotation.reads_state() || self.velocity.reads_state() || self.angular_velocity.reads_state()
    }
    fn label(&self) -> Label {
        self.joint.label
    }
    fn hinted(&self, hint: &super::HintValue) -> Option<Box<dyn Element>> {
        self.with_hint(hint).map(|j| Box::new(j) as Box<dyn Element>)
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn type_name(&self) -> &'static str {
        self.name
    }
    fn nodes(&self) -> Vec<Label> {
        self.joint.nodes()
    }
    fn multipliers(&self) -> Vec<String> {
        let mut m = self.joint.multipliers();
        m.extend(self.rates().map(|r| match r {
            Rate::Linear(k) => format!("v {}", ["x", "y", "z"][k]),
            Rate::Angular(k) => format!("w {}", ["x", "y", "z"][k]),
        }));
        m
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        if k >= self.holonomic() { UnknownKind::VelocityConstraint } else { UnknownKind::Multiplier }
    }
    fn events(&self) -> Option<&dyn Events> {
        if self.rotation_remnant { Some(self) } else { None }
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let j = self.joint_in(st);
        if self.rotation_remnant {
            self.remnant_residual(st, out);
        } else {
            j.residual(st, out);
        }
        if self.rates().next().is_none() {
            return;
        }
        let p = Pair::new(&j.a, &j.b, st);
        let qt = p.q_a.transpose();
        let (v, w) = (qt * p.u, qt * (p.omega_b - p.omega_a));
        let (v0, w0) = (self.velocity.value_in(st), self.angular_velocity.value_in(st));
        for (i, r) in self.rates().enumerate() {
            let value = match r {
                Rate::Linear(k) => v[k] - v0[k],
                Rate::Angular(k) => w[k] - w0[k],
            };
            out.add(Row::Constraint(self.holonomic() + i), value);
        }
        let (force, moment) = self.rate_reactions(&p, st);
        p.add_force(out, &force);
        p.add_moment(out, &moment);
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let j = self.joint_in(st);
        if self.rotation_remnant {
            self.remnant_jacobian(st, out);
        } else {
            j.jacobian(st, out);
        }
        if self.rates().next().is_none() {
            return;
        }
        let p = Pair::new(&j.a, &j.b, st);
        let qt = p.q_a.transpose();
        let (b, n) = (p.slot_b, self.holonomic());
        // Rows: ∂(Q_aᵀ u)/∂q, and ∂(Q_aᵀ (ω_b − ω_a))/∂q.
        let linear = p.rate_derivatives();
        let mut angular = vec![(Col::angular_velocity(b), qt)];
        if let Some(a) = p.slot_a {
            angular.push((Col::angular_velocity(a), -qt));
            angular.push((Col::rotation(a), qt * skew(&(p.omega_b - p.omega_a))));
        }
        for (i, r) in self.rates().enumerate() {
            let (blocks, k) = match r {
                Rate::Linear(k) => (&linear, k),
                Rate::Angular(k) => (&angular, k),
            };
            for (cols, m) in blocks {
                for (c, col) in cols.iter().enumerate() {
                    out.add(Row::Constraint(n + i), *col, m[(k, c)]);
                }
            }
        }
        // Reactions: geometric terms, then the multipliers' columns.
        let (force, moment) = self.rate_reactions(&p, st);
        p.add_force_jacobian(out, &force, &[]);
        if let Some(a) = p.slot_a {
            add_block(out, Row::moment(b), Col::rotation(a), &(-skew(&moment)));
            add_block(out, Row::moment(a), Col::rotation(a), &skew(&moment));
        }
        for (i, r) in self.rates().enumerate() {
            let (df, dm) = match r {
                Rate::Linear(k) => (p.q_a.column(k).into_owned(), Vec3::zeros()),
                Rate::Angular(k) => (Vec3::zeros(), p.q_a.column(k).into_owned()),
            };
            p.add_reaction_column(out, Col::Multiplier(n + i), &df, &dm);
        }
    }
}

impl Outputs for DrivenJoint {
    fn private_data(&self, name: &str) -> Option<super::contract::PrivateDatum> {
        self.joint.private_datum(name)
    }
}

impl Events for DrivenJoint {
    /// The remnant after the last converged solution `before` (MBDyn's `AfterConvergence`):
    /// `Θ_Δ`'s free components there added; zero at the first latch (the derivatives
    /// phase's, before any convergence).
    fn latch(&self, _now: &dyn ElementState, before: &dyn ElementState) -> Option<Latched> {
        if !self.rotation_remnant {
            return None;
        }
        let Some(used) = before.latched().and_then(|l| l.downcast_ref::<RotationRemnant>()).map(|r| r.0) else {
            return Some(Arc::new(RotationRemnant(Vec3::zeros())));
        };
        let (_, _, theta) = self.remnant_parts(before, &used);
        let free = Vec3::from_fn(|k, _| if self.joint.rotation_locked[k] { 0.0 } else { theta[k] });
        Some(Arc::new(RotationRemnant(used + free)))
    }
}
