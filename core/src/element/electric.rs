//! MBDyn's electric elements (input manual §Electric Elements; elec/motor.cc,
//! elec/displacement.cc, elec/accelerometer.cc): a DC motor coupling a structural node pair
//! to two electric nodes, and the sensors that write a structural measure into an abstract
//! node's equation.
//!
//! Residuals are romdyn's `F` (the negative of MBDyn's `AssRes`); Jacobians are the exact
//! plain derivatives, which the assembler turns into `J(c)` (MBDyn's sensors leave out the
//! structural columns of their Jacobians; romdyn writes them, so a loop closed through a
//! sensor linearizes exactly).

use super::contract::{add_block, Col, Element, ElementState, EnergyStore, JacobianSink, Label, Outputs, PrivateDatum, ResidualSink, Row, ScalarNodeId, UnknownKind};
pub use super::electric_cogging::Cogging;
use crate::kinematics::{skew, Vec3};

/// `electric: L, motor, NODE1, NODE2, DIR, V1, V2, G, L, R [, initial current, I0]` (Motor,
/// motor.cc): a torque `M = G i` about the axis `n = R₁ e` (`e` a unit vector in node 1's
/// frame), `−M n` on node 1 and `+M n` on node 2; the current `i` leaves electric node 1
/// and enters node 2; its own differential unknown `i` obeys the armature equation
///
/// ```text
/// L di/dt + R i + G n·(ω₂ − ω₁) − (V₂ − V₁) = 0
/// ```
///
/// with `G` the torque and back-EMF constant [N m/A = V s/rad], `L` the inductance [H], `R`
/// the resistance [Ω]. With MBDyn's cogging terms (`M0`, `M1`, `terminal pairs`) the torque
/// is `M0(Φₑ) + (G + M1(Φₑ)) i` ([`Cogging`]); a resistance that varies with the current is
/// refused by the reader.
pub struct Motor {
    pub label: Label,
    pub nodes: [Label; 2],
    /// Unit axis in node 1's frame.
    pub axis: Vec3,
    /// Electric nodes 1 and 2.
    pub voltages: [ScalarNodeId; 2],
    pub gain: f64,
    pub inductance: f64,
    pub resistance: f64,
    pub initial_current: f64,
    /// `di/dt` at the initial state, from the armature equation (MBDyn's constructor sets
    /// it so: its derivatives phase then leaves the current as written).
    pub initial_rate: f64,
    /// The cogging torque, when the card has one (`axis` is then its frame's axis 3).
    pub cogging: Option<Cogging>,
}

impl Motor {
    fn axis_at(&self, st: &dyn ElementState) -> Vec3 {
        st.node(0).r * self.axis
    }

    /// The torque `M` [N m], `∂M/∂i` and `∂M/∂δθ₁`, `∂M/∂δθ₂`.
    fn torque(&self, st: &dyn ElementState, i: f64) -> (f64, f64, [Vec3; 2]) {
        let Some(c) = &self.cogging else { return (self.gain * i, self.gain, [Vec3::zeros(); 2]) };
        let s = c.at(st);
        let slope = s.m0_slope + s.m1_slope * i;
        (s.m0 + (self.gain + s.m1) * i, self.gain + s.m1, s.angle_theta.map(|d| d * slope))
    }
}

impl Element for Motor {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "motor"
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.to_vec()
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.voltages.to_vec()
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["current".into()]
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::State
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        vec![(0, self.initial_current, self.initial_rate)]
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let n = self.axis_at(st);
        let i = st.multiplier(0);
        let torque = n * self.torque(st, i).0;
        for k in 0..3 {
            out.add(Row::Equilibrium { slot: 0, comp: 3 + k }, torque[k]);
            out.add(Row::Equilibrium { slot: 1, comp: 3 + k }, -torque[k]);
        }
        out.add(Row::Scalar { slot: 0 }, i);
        out.add(Row::Scalar { slot: 1 }, -i);
        let omega = n.dot(&(st.node(1).omega - st.node(0).omega));
        let voltage = st.scalar_value(1) - st.scalar_value(0);
        out.add(Row::Constraint(0), self.inductance * st.rate(0) + self.resistance * i + self.gain * omega - voltage);
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let n = self.axis_at(st);
        let i = st.multiplier(0);
        let (m, dm_di, dm_dtheta) = self.torque(st, i);
        // δn = δθ₁ × n = −[n×] δθ₁; the cogging torque's angle adds n ⊗ ∂M/∂δθₖ.
        let dn = -skew(&n) * m;
        for (slot, d) in dm_dtheta.iter().enumerate() {
            let block = n * d.transpose() + if slot == 0 { dn } else { crate::kinematics::Mat3::zeros() };
            add_block(out, Row::moment(0), Col::rotation(slot), &block);
            add_block(out, Row::moment(1), Col::rotation(slot), &-block);
        }
        let relative = st.node(1).omega - st.node(0).omega;
        let d_theta = n.cross(&relative) * self.gain;
        for k in 0..3 {
            out.add(Row::Equilibrium { slot: 0, comp: 3 + k }, Col::Multiplier(0), dm_di * n[k]);
            out.add(Row::Equilibrium { slot: 1, comp: 3 + k }, Col::Multiplier(0), -dm_di * n[k]);
            out.add(Row::Constraint(0), Col::AngularVelocity { slot: 1, comp: k }, self.gain * n[k]);
            out.add(Row::Constraint(0), Col::AngularVelocity { slot: 0, comp: k }, -self.gain * n[k]);
            out.add(Row::Constraint(0), Col::Rotation { slot: 0, comp: k }, d_theta[k]);
        }
        out.add(Row::Scalar { slot: 0 }, Col::Multiplier(0), 1.0);
        out.add(Row::Scalar { slot: 1 }, Col::Multiplier(0), -1.0);
        out.add(Row::Constraint(0), Col::Rate(0), self.inductance);
        out.add(Row::Constraint(0), Col::Multiplier(0), self.resistance);
        out.add(Row::Constraint(0), Col::ScalarValue { slot: 1 }, -1.0);
        out.add(Row::Constraint(0), Col::ScalarValue { slot: 0 }, 1.0);
    }
}

impl Outputs for Motor {
    /// The inductance's magnetic energy `½ L i²` [J] (the modal table's shares: a mode that
    /// lives in the current says so).
    fn energy_stores(&self, _s: &dyn ElementState) -> Vec<EnergyStore> {
        vec![EnergyStore { unknown: 0, weight: self.inductance, rate: false, name: "current".into(), mode: None }]
    }
    /// motor.cc, `Motor::dGetPrivData`: "i" the current [A], "iP" its rate [A/s], "omega"
    /// the relative angular velocity about the axis [rad/s], "M" the torque `G i` [N m], "U"
    /// the voltage `V₂ − V₁` [V], "Pmech" `M ω` and "Pel" `U i` [W], "R" the resistance [Ω].
    /// The cogging terms' data (`Phimech`, `Phiel`, `M0`, `M1`) are not computed, nor "M"
    /// and "Pmech" of a motor with a cogging torque.
    fn private_data(&self, name: &str) -> Option<PrivateDatum> {
        if self.cogging.is_some() && matches!(name, "M" | "Pmech") {
            return None;
        }
        let (label, nodes, axis, voltages, gain, resistance) = (self.label, self.nodes, self.axis, self.voltages, self.gain, self.resistance);
        let current = move |st: &dyn ElementState| st.element_unknown("motor", label, 0);
        let omega = move |st: &dyn ElementState| {
            let (n1, n2) = (st.structural_node(nodes[0])?, st.structural_node(nodes[1])?);
            Some((n1.r * axis).dot(&(n2.omega - n1.omega)))
        };
        let voltage = move |st: &dyn ElementState| Some(st.scalar_node(voltages[1])?.0 - st.scalar_node(voltages[0])?.0);
        Some(match name {
            "i" => PrivateDatum::new(move |st| current(st).map(|c| c.0)),
            "iP" => PrivateDatum::new(move |st| current(st).map(|c| c.1)),
            "omega" => PrivateDatum::new(omega),
            "M" => PrivateDatum::new(move |st| current(st).map(|c| gain * c.0)),
            "U" => PrivateDatum::new(voltage),
            "Pmech" => PrivateDatum::new(move |st| Some(gain * current(st)?.0 * omega(st)?)),
            "Pel" => PrivateDatum::new(move |st| Some(voltage(st)? * current(st)?.0)),
            "R" => PrivateDatum::new(move |_| Some(resistance)),
            _ => return None,
        })
    }
}

/// `electric: L, displacement, NODE1, OFFSET1, NODE2, OFFSET2, ABSTRACT` (DispMeasure,
/// displacement.cc): the abstract node's equation `x − |x₂ + R₂ o₂ − x₁ − R₁ o₁| = 0`, the
/// distance [m] between two points of two structural nodes.
pub struct DisplacementSensor {
    pub label: Label,
    pub nodes: [Label; 2],
    /// The points' offsets in their nodes' frames [m].
    pub offsets: [Vec3; 2],
    pub output: ScalarNodeId,
}

impl DisplacementSensor {
    /// The arms `Rₖ oₖ` and the vector between the points.
    fn geometry(&self, st: &dyn ElementState) -> ([Vec3; 2], Vec3) {
        let arms = [0, 1].map(|k| st.node(k).r * self.offsets[k]);
        let d = st.node(1).x + arms[1] - st.node(0).x - arms[0];
        (arms, d)
    }
}

impl Element for DisplacementSensor {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "displacement"
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.to_vec()
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        vec![self.output]
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (_, d) = self.geometry(st);
        out.add(Row::Scalar { slot: 0 }, st.scalar_value(0) - d.norm());
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (arms, d) = self.geometry(st);
        out.add(Row::Scalar { slot: 0 }, Col::ScalarValue { slot: 0 }, 1.0);
        // The distance's gradient is the unit vector u; at coincident points it has none.
        let Some(u) = d.try_normalize(0.0) else { return };
        // ∂|d|/∂x₂ = u, ∂|d|/∂θ₂ = R₂o₂ × u; node 1 with the opposite signs.
        for (slot, sign) in [(0, 1.0), (1, -1.0)] {
            let rot = arms[slot].cross(&u) * sign;
            for k in 0..3 {
                out.add(Row::Scalar { slot: 0 }, Col::Position { slot, comp: k }, sign * u[k]);
                out.add(Row::Scalar { slot: 0 }, Col::Rotation { slot, comp: k }, rot[k]);
            }
        }
    }
}

/// What an accelerometer measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AccelerometerKind {
    /// `translational`: the acceleration of a point of the node along a direction [m/s²].
    Translational,
    /// `rotational`: the angular acceleration about a direction [rad/s²].
    Rotational,
}

/// `electric: L, accelerometer, {translational | rotational}, NODE, ABSTRACT, DIR [,
/// position, OFFSET]` (TranslAccel, RotAccel, accelerometer.cc): an own differential unknown
/// `v`, the measured velocity `v − d·(ẋ + ω × R o) = 0` (or `v − d·ω = 0`, `d = R dir`),
/// and the abstract node's equation `x − v̇ = 0`: the node carries the acceleration.
pub struct Accelerometer {
    pub label: Label,
    pub kind: AccelerometerKind,
    pub node: Label,
    pub output: ScalarNodeId,
    /// Unit direction in the node's frame.
    pub direction: Vec3,
    /// The measured point's offset in the node's frame [m] (translational).
    pub offset: Vec3,
    /// The measured velocity at the initial state (MBDyn's `SetValue` starts `v` there).
    pub initial_velocity: f64,
}

impl Accelerometer {
    /// The direction `d = R dir`, the arm `R o` and the measured velocity's vector.
    fn measure(&self, st: &dyn ElementState) -> (Vec3, Vec3, Vec3) {
        let n = st.node(0);
        let (d, arm) = (n.r * self.direction, n.r * self.offset);
        let velocity = match self.kind {
            AccelerometerKind::Translational => n.xdot + n.omega.cross(&arm),
            AccelerometerKind::Rotational => n.omega,
        };
        (d, arm, velocity)
    }
}

impl Element for Accelerometer {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "accelerometer"
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        vec![self.output]
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["measured velocity".into()]
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::State
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        vec![(0, self.initial_velocity, 0.0)]
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (d, _, velocity) = self.measure(st);
        out.add(Row::Scalar { slot: 0 }, st.scalar_value(0) - st.rate(0));
        out.add(Row::Constraint(0), st.multiplier(0) - d.dot(&velocity));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (d, arm, velocity) = self.measure(st);
        out.add(Row::Scalar { slot: 0 }, Col::ScalarValue { slot: 0 }, 1.0);
        out.add(Row::Scalar { slot: 0 }, Col::Rate(0), -1.0);
        out.add(Row::Constraint(0), Col::Multiplier(0), 1.0);
        // δd = δθ × d: −(d × v)·… written as −(δθ × d)·v = −δθ·(d × v).
        let mut d_theta = -d.cross(&velocity);
        let omega_col = match self.kind {
            AccelerometerKind::Translational => {
                // v = ẋ + ω × arm: ∂/∂ẋ = d, ∂/∂ω: d·(ω × a) = ω·(a × d), and δarm = δθ × arm
                // gives d·(ω × (δθ × arm)) = δθ·(arm × (d × ω)).
                let n = st.node(0);
                d_theta -= arm.cross(&d.cross(&n.omega));
                for k in 0..3 {
                    out.add(Row::Constraint(0), Col::Velocity { slot: 0, comp: k }, -d[k]);
                }
                arm.cross(&d)
            }
            AccelerometerKind::Rotational => d,
        };
        for k in 0..3 {
            out.add(Row::Constraint(0), Col::AngularVelocity { slot: 0, comp: k }, -omega_col[k]);
            out.add(Row::Constraint(0), Col::Rotation { slot: 0, comp: k }, d_theta[k]);
        }
    }
}
