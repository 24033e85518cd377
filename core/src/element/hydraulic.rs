//! MBDyn's hydraulic fluids and elements (input manual §Hydraulic fluid, §Hydraulic
//! Element; hydr/hfluid_.h, hydr/actuator.cc, hydr/hminor.cc): a two-chamber linear
//! actuator coupling two pressure nodes to a structural node pair, and the turbulent minor
//! loss between two pressure nodes.
//!
//! A hydraulic node's equation is its mass balance [kg/s]: each element adds the mass flow
//! it takes out of the node (MBDyn's `AssRes` adds it; romdyn's residual, its negative,
//! subtracts it). Pressures are in Pa, densities in kg/m³, areas in m², volumes in m³.

use super::contract::{add_block, Col, Element, ElementState, EnergyStore, Events, JacobianSink, Label, Latched, Outputs, ResidualSink, Row, ScalarNodeId, UnknownKind};
use crate::kinematics::{skew, Vec3};

/// A hydraulic fluid (hfluid_.h): the density as a function of the pressure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HydraulicFluid {
    /// `incompressible`: `ρ` constant [kg/m³], the viscosity `μ` [Pa s].
    Incompressible { density: f64, viscosity: f64 },
    /// `linear compressible`: `ρ(p) = ρ₀ + (p − p₀) ρ₀/β`, `β` the bulk modulus [Pa]
    /// (`ρ₀ c²` when written as a sound celerity `c`), `p₀` the reference pressure [Pa], `μ`
    /// the viscosity [Pa s].
    LinearCompressible { density: f64, bulk_modulus: f64, pressure: f64, viscosity: f64 },
}

impl HydraulicFluid {
    /// `ρ(p)` [kg/m³].
    pub fn density(&self, p: f64) -> f64 {
        match *self {
            HydraulicFluid::Incompressible { density, .. } => density,
            HydraulicFluid::LinearCompressible { density, bulk_modulus, pressure, .. } => density + (p - pressure) * density / bulk_modulus,
        }
    }
    /// The reference density `ρ₀` [kg/m³] (MBDyn's `dGetDensity()` without a pressure).
    pub fn reference_density(&self) -> f64 {
        match *self {
            HydraulicFluid::Incompressible { density, .. } | HydraulicFluid::LinearCompressible { density, .. } => density,
        }
    }
    /// The viscosity `μ` [Pa s].
    pub fn viscosity(&self) -> f64 {
        match *self {
            HydraulicFluid::Incompressible { viscosity, .. } | HydraulicFluid::LinearCompressible { viscosity, .. } => viscosity,
        }
    }
    /// `dρ/dp` [kg/(m³ Pa)], a constant of both kinds.
    pub fn density_slope(&self) -> f64 {
        match *self {
            HydraulicFluid::Incompressible { .. } => 0.0,
            HydraulicFluid::LinearCompressible { density, bulk_modulus, .. } => density / bulk_modulus,
        }
    }
}

/// `hydraulic: L, actuator, P1, P2, NODE1, OFFSET1, NODE2, OFFSET2, [direction, DIR,] A1,
/// A2, LENGTH, fluid, …, {same | fluid, …}` (Actuator, actuator.cc). Chamber 1 lies between
/// the point `o₁` of node 1 (the cylinder) and `o₂` of node 2 (the piston), its length the
/// stroke `d = a·(x₂ + R₂o₂ − x₁ − R₁o₁)` along the axis `a = R₁ dir`; chamber 2 is the rest
/// of the cylinder `l − d`. Volumes `V₁ = A₁ d`, `V₂ = A₂ (l − d)`; the force `a (A₁p₁ −
/// A₂p₂)` pushes node 2 (and its moment about each node's offset, as MBDyn writes it), its
/// opposite node 1; each chamber takes the mass flow `d(ρV)/dt = ρ'(p) ṗ V + ρ V̇` out of
/// its node, with `ḋ = a·(ẋ₂ + ω₂ × R₂o₂ − ẋ₁ − ω₁ × R₁o₁) + (ω₁ × a)·(x₂ + R₂o₂ − x₁ −
/// R₁o₁)`. The pressures' rates come from two own differential unknowns `π₁`, `π₂` with
/// `π − p = 0` (MBDyn's internal states), which start at the nodes' pressures.
pub struct Actuator {
    pub label: Label,
    pub pressures: [ScalarNodeId; 2],
    pub nodes: [Label; 2],
    pub offsets: [Vec3; 2],
    /// Unit axis in node 1's frame.
    pub axis: Vec3,
    pub areas: [f64; 2],
    /// The largest stroke of chamber 1 (the cylinder's length less the piston's) [m]: `V₂ = A₂ (l − d)`.
    pub length: f64,
    pub fluids: [HydraulicFluid; 2],
    /// The nodes' initial pressures, where `π₁`, `π₂` start.
    pub initial_pressures: [f64; 2],
    /// Whether it writes its `.hyd` row.
    pub output: bool,
}

/// The actuator's kinematics at a state.
struct Stroke {
    axis: Vec3,
    arms: [Vec3; 2],
    /// `x₂ + R₂o₂ − x₁ − R₁o₁`.
    gap: Vec3,
    /// `ẋ₂ + ω₂ × R₂o₂ − ẋ₁ − ω₁ × R₁o₁`.
    relative_velocity: Vec3,
    /// `d`, `ḋ`.
    length: f64,
    rate: f64,
}

impl Actuator {
    fn stroke(&self, st: &dyn ElementState) -> Stroke {
        let (n1, n2) = (st.node(0), st.node(1));
        let axis = n1.r * self.axis;
        let arms = [n1.r * self.offsets[0], n2.r * self.offsets[1]];
        let gap = n2.x + arms[1] - n1.x - arms[0];
        let relative_velocity = n2.xdot + n2.omega.cross(&arms[1]) - n1.xdot - n1.omega.cross(&arms[0]);
        let rate = axis.dot(&relative_velocity) + gap.dot(&n1.omega.cross(&axis));
        Stroke { axis, arms, gap, relative_velocity, length: axis.dot(&gap), rate }
    }

    /// The chambers' volumes [m³] at a state.
    pub fn volumes(&self, st: &dyn ElementState) -> [f64; 2] {
        let d = self.stroke(st).length;
        [self.areas[0] * d, self.areas[1] * (self.length - d)]
    }

    /// The mass flows into the chambers [kg/s], `d(ρV)/dt` each: out of nodes 1 and 2.
    fn flows(&self, st: &dyn ElementState, s: &Stroke) -> [f64; 2] {
        let [a1, a2] = self.areas;
        let [f1, f2] = self.fluids;
        let (p1, p2) = (st.scalar_value(0), st.scalar_value(1));
        [a1 * (f1.density_slope() * st.rate(0) * s.length + f1.density(p1) * s.rate), a2 * (f2.density_slope() * st.rate(1) * (self.length - s.length) - f2.density(p2) * s.rate)]
    }
}

/// actuator.cc's `Output`: the chambers' mass flows [kg/s] (out of nodes 1, 2), the internal
/// pressures `π₁`, `π₂` [Pa] and their rates [Pa/s], the volumes [m³], the densities at the
/// nodes' pressures [kg/m³].
impl Outputs for Actuator {
    /// Each chamber's compression energy `½ (V/β) p²` [J] on its pressure unknown `π`, with
    /// `V/β = V ρ'(p)/ρ₀` (the fluid's `dρ/dp = ρ₀/β`; zero for an incompressible fluid).
    fn energy_stores(&self, st: &dyn ElementState) -> Vec<EnergyStore> {
        let volumes = self.volumes(st);
        (0..2)
            .map(|k| {
                let f = self.fluids[k];
                EnergyStore { unknown: k, weight: volumes[k].abs() * f.density_slope() / f.reference_density(), rate: false, name: format!("chamber {} pressure", k + 1), mode: None }
            })
            .collect()
    }
    fn writes_hydraulic_row(&self) -> bool {
        self.output
    }
    fn hydraulic_row(&self, st: &dyn ElementState) -> Vec<f64> {
        let s = self.stroke(st);
        let [flow1, flow2] = self.flows(st, &s);
        let [v1, v2] = [self.areas[0] * s.length, self.areas[1] * (self.length - s.length)];
        let densities = [self.fluids[0].density(st.scalar_value(0)), self.fluids[1].density(st.scalar_value(1))];
        vec![flow1, flow2, st.multiplier(0), st.multiplier(1), st.rate(0), st.rate(1), v1, v2, densities[0], densities[1]]
    }
}

impl Element for Actuator {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "actuator"
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.to_vec()
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.pressures.to_vec()
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["pressure 1".into(), "pressure 2".into()]
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::State
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        vec![(0, self.initial_pressures[0], 0.0), (1, self.initial_pressures[1], 0.0)]
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let s = self.stroke(st);
        let [a1, a2] = self.areas;
        let (p1, p2) = (st.scalar_value(0), st.scalar_value(1));
        let force = s.axis * (a1 * p1 - a2 * p2);
        let moments = [s.arms[0].cross(&force), s.arms[1].cross(&force)];
        for k in 0..3 {
            out.add(Row::Equilibrium { slot: 0, comp: k }, force[k]);
            out.add(Row::Equilibrium { slot: 0, comp: 3 + k }, moments[0][k]);
            out.add(Row::Equilibrium { slot: 1, comp: k }, -force[k]);
            out.add(Row::Equilibrium { slot: 1, comp: 3 + k }, -moments[1][k]);
        }
        let [flow1, flow2] = self.flows(st, &s);
        out.add(Row::Scalar { slot: 0 }, -flow1);
        out.add(Row::Scalar { slot: 1 }, -flow2);
        out.add(Row::Constraint(0), st.multiplier(0) - p1);
        out.add(Row::Constraint(1), st.multiplier(1) - p2);
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let s = self.stroke(st);
        let [a1, a2] = self.areas;
        let (p1, p2) = (st.scalar_value(0), st.scalar_value(1));
        let net = a1 * p1 - a2 * p2;
        let force = s.axis * net;
        let (ax, fx) = (skew(&s.axis), skew(&force));
        let [arm1, arm2] = [skew(&s.arms[0]), skew(&s.arms[1])];
        // Forces and moments: δa = −[a×] δθ₁, δ(Rₖoₖ) = −[Rₖoₖ×] δθₖ.
        add_block(out, Row::force(0), Col::rotation(0), &(-net * ax));
        add_block(out, Row::force(1), Col::rotation(0), &(net * ax));
        add_block(out, Row::moment(0), Col::rotation(0), &(fx * arm1 - net * arm1 * ax));
        add_block(out, Row::moment(1), Col::rotation(0), &(net * arm2 * ax));
        add_block(out, Row::moment(1), Col::rotation(1), &(-fx * arm2));
        let lever = [s.arms[0].cross(&s.axis), s.arms[1].cross(&s.axis)];
        for (slot, area) in [(0, a1), (1, -a2)] {
            for k in 0..3 {
                out.add(Row::Equilibrium { slot: 0, comp: k }, Col::ScalarValue { slot }, area * s.axis[k]);
                out.add(Row::Equilibrium { slot: 1, comp: k }, Col::ScalarValue { slot }, -area * s.axis[k]);
                out.add(Row::Equilibrium { slot: 0, comp: 3 + k }, Col::ScalarValue { slot }, area * lever[0][k]);
                out.add(Row::Equilibrium { slot: 1, comp: 3 + k }, Col::ScalarValue { slot }, -area * lever[1][k]);
            }
        }
        // The stroke's and its rate's derivatives.
        let (n1, n2) = (st.node(0), st.node(1));
        let d_theta = [s.axis.cross(&(s.gap + s.arms[0])), s.arms[1].cross(&s.axis)];
        let w_theta = [s.axis.cross(&(s.relative_velocity + s.gap.cross(&n1.omega))), s.arms[1].cross(&s.axis.cross(&(n2.omega - n1.omega)))];
        let w_omega = [s.axis.cross(&(s.gap + s.arms[0])), s.arms[1].cross(&s.axis)];
        let w_x = n1.omega.cross(&s.axis);
        let [f1, f2] = self.fluids;
        // Row k: −A_k (ρ'_k π̇_k V_k/A_k + σ_k ρ_k ḋ), σ = +1, −1 and V₂/A₂ = l − d: the
        // coefficients of δd and δḋ.
        let coefs = [(-a1 * f1.density_slope() * st.rate(0), -a1 * f1.density(p1)), (a2 * f2.density_slope() * st.rate(1), a2 * f2.density(p2))];
        for (row, (cd, cw)) in coefs.into_iter().enumerate() {
            let r = Row::Scalar { slot: row };
            for (slot, sign) in [(0, -1.0), (1, 1.0)] {
                for k in 0..3 {
                    out.add(r, Col::Position { slot, comp: k }, sign * (cd * s.axis[k] + cw * w_x[k]));
                    out.add(r, Col::Rotation { slot, comp: k }, cd * d_theta[slot][k] + cw * w_theta[slot][k]);
                    out.add(r, Col::Velocity { slot, comp: k }, sign * cw * s.axis[k]);
                    out.add(r, Col::AngularVelocity { slot, comp: k }, cw * w_omega[slot][k]);
                }
            }
        }
        out.add(Row::Scalar { slot: 0 }, Col::ScalarValue { slot: 0 }, -a1 * f1.density_slope() * s.rate);
        out.add(Row::Scalar { slot: 1 }, Col::ScalarValue { slot: 1 }, a2 * f2.density_slope() * s.rate);
        out.add(Row::Scalar { slot: 0 }, Col::Rate(0), -a1 * f1.density_slope() * s.length);
        out.add(Row::Scalar { slot: 1 }, Col::Rate(1), -a2 * f2.density_slope() * (self.length - s.length));
        for k in 0..2 {
            out.add(Row::Constraint(k), Col::Multiplier(k), 1.0);
            out.add(Row::Constraint(k), Col::ScalarValue { slot: k }, -1.0);
        }
    }
}


/// `hydraulic: L, minor loss, P1, P2, K12, K21, AREA, fluid, …` (MinorLoss, hminor.cc): the
/// turbulent mass flow from node 1 to node 2, `q = A √(2ρ/κ) sign(p₁ − p₂) √|p₁ − p₂|`, `κ`
/// = `K12` when `p₁ > p₂`, `K21` otherwise, `ρ` at the mean pressure.
pub struct MinorLoss {
    pub label: Label,
    pub pressures: [ScalarNodeId; 2],
    /// The loss coefficients from 1 to 2 and from 2 to 1 [-].
    pub loss: [f64; 2],
    pub area: f64,
    pub fluid: HydraulicFluid,
    /// Whether it writes its `.hyd` row.
    pub output: bool,
}

/// MBDyn's floor on `|p₁ − p₂|` in the flow's derivative (hminor.cc, valve.cc: 10⁸ ε Pa),
/// where the square root's slope is infinite.
pub(super) const LEAST_PRESSURE_DROP: f64 = 1e8 * f64::EPSILON;

/// A turbulent orifice's mass flow `q = a √(2ρ|Δp|) sign(Δp)` [kg/s] (`a` the effective
/// area [m²]) and its slope `∂q/∂Δp = a √(2ρ) / (2 √|Δp|)`, `|Δp|` floored as MBDyn's.
pub(super) fn orifice(area: f64, rho: f64, drop: f64) -> (f64, f64) {
    let coef = area * (2.0 * rho).sqrt();
    (coef * drop.signum() * drop.abs().sqrt(), coef / (2.0 * drop.abs().max(LEAST_PRESSURE_DROP).sqrt()))
}

impl MinorLoss {
    /// The flow [kg/s], its slope in `Δp`, the density and `Δp`.
    fn flow(&self, st: &dyn ElementState) -> (f64, f64, f64) {
        let (p1, p2) = (st.scalar_value(0), st.scalar_value(1));
        let drop = p1 - p2;
        let kappa = if drop > 0.0 { self.loss[0] } else { self.loss[1] };
        let rho = self.fluid.density(0.5 * (p1 + p2));
        let (q, slope) = orifice(self.area / kappa.sqrt(), rho, drop);
        (q, slope, rho)
    }
}

impl Element for MinorLoss {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "minor loss"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.pressures.to_vec()
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (q, ..) = self.flow(st);
        out.add(Row::Scalar { slot: 0 }, -q);
        out.add(Row::Scalar { slot: 1 }, q);
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (q, slope, rho) = self.flow(st);
        // q ∝ √ρ, ρ at the mean pressure: ∂q/∂pₖ gains q ρ'/(4ρ).
        let density = q * self.fluid.density_slope() / (4.0 * rho);
        for (slot, dq) in [(0, slope + density), (1, -slope + density)] {
            out.add(Row::Scalar { slot: 0 }, Col::ScalarValue { slot }, -dq);
            out.add(Row::Scalar { slot: 1 }, Col::ScalarValue { slot }, dq);
        }
    }
}

/// hminor.cc's `Output`: the mean velocity `q/(ρ A)` [m/s] and the mass flow `q` [kg/s]
/// from node 1 to node 2.
impl Outputs for MinorLoss {
    fn writes_hydraulic_row(&self) -> bool {
        self.output
    }
    fn hydraulic_row(&self, st: &dyn ElementState) -> Vec<f64> {
        let (q, _, rho) = self.flow(st);
        vec![q / (rho * self.area), q]
    }
}

/// `hydraulic: L, control valve, P1, P2, P3, P4, AREA [, loss, LOSS], STATE, fluid, …`
/// (Control_valve, valve.cc): a four-way valve of four turbulent orifices `Cd a √(2ρ|Δp|)`,
/// `Cd = π/(π + 2)` (Merritt, as MBDyn), `ρ` the fluid's reference density. The state `s(t)`
/// (a drive, held in [−1, 1]) opens `1 → 2` and `3 → 4` by `s AREA` when positive, `1 → 3`
/// and `2 → 4` by `−s AREA` when negative; at rest the orifices leak `2 LOSS AREA` (`1 →
/// 2`, `3 → 4`) and `LOSS AREA` (`1 → 3`, `2 → 4`), as MBDyn's minimum areas.
pub struct ControlValve {
    pub label: Label,
    pub pressures: [ScalarNodeId; 4],
    pub area: f64,
    pub loss: f64,
    pub state: super::drive::Drive,
    /// The fluid's reference density [kg/m³].
    pub density: f64,
    /// Whether it writes its `.hyd` row.
    pub output: bool,
}

impl ControlValve {
    /// Each orifice: (from slot, to slot, area [m²]) at the state's valve position.
    fn orifices(&self, st: &dyn ElementState) -> [(usize, usize, f64); 4] {
        let s = self.state.value_in(st).clamp(-1.0, 1.0);
        let (open, leak) = (s.abs() * self.area, self.loss * self.area);
        let (forward, backward) = if s > 0.0 { (open, 0.0) } else { (0.0, open) };
        [(0, 1, forward + 2.0 * leak), (0, 2, backward + leak), (1, 3, backward + leak), (2, 3, forward + 2.0 * leak)]
    }
}

/// `π/(π + 2)`: the discharge coefficient of MBDyn's control valve.
const VALVE_DISCHARGE: f64 = std::f64::consts::PI / (std::f64::consts::PI + 2.0);

impl Element for ControlValve {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "control valve"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.pressures.to_vec()
    }
    fn reads_state(&self) -> bool {
        self.state.reads_state()
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        for (from, to, area) in self.orifices(st) {
            let (q, _) = orifice(VALVE_DISCHARGE * area, self.density, st.scalar_value(from) - st.scalar_value(to));
            out.add(Row::Scalar { slot: from }, -q);
            out.add(Row::Scalar { slot: to }, q);
        }
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        for (from, to, area) in self.orifices(st) {
            let (_, slope) = orifice(VALVE_DISCHARGE * area, self.density, st.scalar_value(from) - st.scalar_value(to));
            for (row, sign) in [(from, -1.0), (to, 1.0)] {
                out.add(Row::Scalar { slot: row }, Col::ScalarValue { slot: from }, sign * slope);
                out.add(Row::Scalar { slot: row }, Col::ScalarValue { slot: to }, -sign * slope);
            }
        }
    }
}

/// valve.cc's `Output`: the valve's state (held in [−1, 1]) and the net mass flows into
/// nodes 1 to 4 [kg/s].
impl Outputs for ControlValve {
    fn writes_hydraulic_row(&self) -> bool {
        self.output
    }
    fn hydraulic_row(&self, st: &dyn ElementState) -> Vec<f64> {
        let mut row = vec![self.state.value_in(st).clamp(-1.0, 1.0), 0.0, 0.0, 0.0, 0.0];
        for (from, to, area) in self.orifices(st) {
            let (q, _) = orifice(VALVE_DISCHARGE * area, self.density, st.scalar_value(from) - st.scalar_value(to));
            row[1 + from] -= q;
            row[1 + to] += q;
        }
        row
    }
}

/// `hydraulic: L, pipe, P1, P2, DIAMETER, [area, A,] LENGTH, [turbulent,] [initial value,
/// Q0,] fluid, …` (Pipe, pipe.cc): an own algebraic unknown, the mass flow `q` from node 1 to
/// node 2 [kg/s], and the pressure drop of the flow's regime, `p₁ − p₂ = f(q)`, by the
/// Reynolds number `Re = |q| D/(A μ)`: laminar `k_lam q` below 2000, turbulent `k_trb
/// sign(q) |q|^{7/4}` (Blasius) above 4000, and in between MBDyn's transition: laminar below
/// 2500 coming from laminar, turbulent above 3100 coming from turbulent, else the quartic
/// `q k_tra (a|q|⁴ + b|q|³ + c|q|² + d|q|)` of the regime it comes from. The regime it comes
/// from is latched at each step from the accepted state (MBDyn's `AfterConvergence`). The
/// coefficients use the density at the nodes' initial mean pressure, as MBDyn's
/// constructor: `k_lam = 32 L μ/(D² A ρ)`, `k_tra = L/(2 D ρ A²)`, `k_trb = 0.1582 μ^{1/4}
/// L/(D^{5/4} A^{7/4} ρ)`.
pub struct Pipe {
    pub label: Label,
    pub pressures: [ScalarNodeId; 2],
    pub diameter: f64,
    pub area: f64,
    pub viscosity: f64,
    /// `k_lam`, `k_tra`, `k_trb`.
    pub coefficients: [f64; 3],
    /// The regime before the first step (`turbulent`).
    pub turbulent: bool,
    pub initial_flow: f64,
    /// The density at the mean of its nodes' pressures [kg/m³] (for the velocity it writes).
    pub fluid: HydraulicFluid,
    /// Whether it writes its `.hyd` row.
    pub output: bool,
}

/// A pipe's flow regime (pipe.cc): laminar below `Re` 2000, turbulent above 4000, and in
/// between laminar below 2500 coming from laminar, turbulent above 3100 coming from
/// turbulent, else MBDyn's transition quartic `g(x) = ((a x + b) x + c) x + d` in `x =
/// |q|`, coefficients of the regime it comes from (`dva = D/(μ A)` [s/kg]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Regime {
    Laminar,
    Turbulent,
    Transition { a: f64, b: f64, c: f64, d: f64 },
}

impl Regime {
    pub(super) fn of(re: f64, turbulent: bool, dva: f64) -> Regime {
        if re < 2000.0 || (!turbulent && re < 2000.0 * 1.25) {
            return Regime::Laminar;
        }
        if re > 4000.0 || (turbulent && re > 4000.0 * 0.775) {
            return Regime::Turbulent;
        }
        let c = -1.8e-5 * dva;
        if turbulent {
            Regime::Transition { a: 9e-13 * dva.powi(3), b: 2e-9 * dva * dva, c, d: 0.0528 }
        } else {
            Regime::Transition { a: 7e-13 * dva.powi(3), b: 8e-10 * dva * dva, c, d: 0.0542 }
        }
    }

    /// The regime a pipe comes from after an accepted step of Reynolds number `re`
    /// (MBDyn's `AfterConvergence`): kept in the transition.
    pub(super) fn latched(re: f64, before: bool) -> bool {
        if re < 2000.0 {
            false
        } else if re > 4000.0 {
            true
        } else {
            before
        }
    }
}

impl Pipe {
    /// `k_lam`, `k_tra`, `k_trb` of a pipe of diameter `d`, area `a`, length `l` for a fluid
    /// of density `rho` and viscosity `mu`.
    pub fn coefficients(d: f64, a: f64, l: f64, rho: f64, mu: f64) -> [f64; 3] {
        [32.0 * l * mu / (d * d * a * rho), 0.5 * l / (d * rho * a * a), 0.1582 * mu.powf(0.25) * l / (d.powf(1.25) * a.powf(1.75) * rho)]
    }

    fn reynolds(&self, q: f64) -> f64 {
        q.abs() * self.diameter / (self.area * self.viscosity)
    }

    fn turbulent_at(&self, st: &dyn ElementState) -> bool {
        st.latched().and_then(|l| l.downcast_ref::<bool>()).copied().unwrap_or(self.turbulent)
    }

    /// The pressure drop `f(q)` [Pa] and its slope, in the regime the pipe comes from.
    fn drop(&self, q: f64, turbulent: bool) -> (f64, f64) {
        let [lam, tra, trb] = self.coefficients;
        let dva = self.diameter / (self.viscosity * self.area);
        match Regime::of(self.reynolds(q), turbulent, dva) {
            Regime::Laminar => (lam * q, lam),
            Regime::Turbulent => (trb * q.signum() * q.abs().powf(1.75), 1.75 * trb * q.abs().powf(0.75)),
            Regime::Transition { a, b, c, d } => {
                let x = q.abs();
                let g = tra * (((a * x + b) * x + c) * x + d) * x;
                let dg = tra * (((4.0 * a * x + 3.0 * b) * x + 2.0 * c) * x + d);
                (q * g, g + x * dg)
            }
        }
    }
}

/// pipe.cc's `Output`: the mean velocity `q/(ρ A)` [m/s] (`ρ` at the nodes' mean
/// pressure), the mass flow `q` [kg/s] from node 1 to node 2 and the Reynolds number.
impl Outputs for Pipe {
    fn writes_hydraulic_row(&self) -> bool {
        self.output
    }
    fn hydraulic_row(&self, st: &dyn ElementState) -> Vec<f64> {
        let q = st.multiplier(0);
        let rho = self.fluid.density(0.5 * (st.scalar_value(0) + st.scalar_value(1)));
        vec![q / (rho * self.area), q, self.reynolds(q)]
    }
}

impl Element for Pipe {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "pipe"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.pressures.to_vec()
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["mass flow".into()]
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        // An algebraic unknown of its own (MBDyn's `DofOrder::ALGEBRAIC`), not a multiplier.
        UnknownKind::VelocityConstraint
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        vec![(0, self.initial_flow, 0.0)]
    }
    fn events(&self) -> Option<&dyn Events> {
        Some(self)
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let q = st.multiplier(0);
        out.add(Row::Scalar { slot: 0 }, -q);
        out.add(Row::Scalar { slot: 1 }, q);
        let (f, _) = self.drop(q, self.turbulent_at(st));
        out.add(Row::Constraint(0), st.scalar_value(0) - st.scalar_value(1) - f);
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let q = st.multiplier(0);
        out.add(Row::Scalar { slot: 0 }, Col::Multiplier(0), -1.0);
        out.add(Row::Scalar { slot: 1 }, Col::Multiplier(0), 1.0);
        let (_, slope) = self.drop(q, self.turbulent_at(st));
        out.add(Row::Constraint(0), Col::Multiplier(0), -slope);
        out.add(Row::Constraint(0), Col::ScalarValue { slot: 0 }, 1.0);
        out.add(Row::Constraint(0), Col::ScalarValue { slot: 1 }, -1.0);
    }
}

impl Events for Pipe {
    /// The regime of the accepted state, kept in the transition (pipe.cc, `AfterConvergence`).
    fn latch(&self, now: &dyn ElementState, before: &dyn ElementState) -> Option<Latched> {
        let old = self.turbulent_at(now);
        let new = Regime::latched(self.reynolds(before.multiplier(0)), old);
        (new != old).then(|| std::sync::Arc::new(new) as Latched)
    }
}
