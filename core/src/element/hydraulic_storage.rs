//! MBDyn's hydraulic `accumulator` and `tank` (input manual §Accumulator, §Tank;
//! hydr/hutils.cc), and the `orifice` (hydr/hminor.cc): elements that store fluid or
//! throttle it, on pressure nodes. Rows and signs as in [`super::hydraulic`]: a node's
//! equation takes the mass flow out of the node, romdyn's residual the opposite of MBDyn's.

use super::contract::{Col, Element, ElementState, JacobianSink, Label, Outputs, ResidualSink, Row, ScalarNodeId, UnknownKind};
use super::hydraulic::{orifice, HydraulicFluid};

/// `hydraulic: L, accumulator, P, STROKE, [start, S0,] AREA, PIPE_AREA, MASS, [lossin, H_IN,]
/// [lossout, H_OUT,] [gas, P0, PMAX, KAPPA,] [weight, W,] [spring, K, F0,] C_S, C_V, C_A,
/// fluid, …` (Accumulator, hutils.cc): a piston of mass `m` (plus MBDyn's `weight`, which
/// hutils.cc adds to the mass) between the node's fluid and a gas spring. Own unknowns, both
/// differential: the stroke `s` [m] and the piston's velocity `v` [m/s], with
///
/// - `ṡ − v = 0`;
/// - `(m + w) v̇ − A p + A p_g(s) + F0 + k s + sign(v) h ρ A (A/A_p)² v²/2 + stops = 0`,
///   `p_g = P0 (S/(S − s))^κ` the gas's pressure (`P0` below `s = 0`, `PMAX` above
///   `s_max = 0.999 S − S (P0/PMAX)^{1/κ}`), `h` the loss coefficient `H_IN` while `ṡ > 0`
///   (filling), `H_OUT` otherwise, and MBDyn's end stops: below 0, `C_S s` (and `C_V ṡ`
///   while `ṡ < 0`, `C_A v̇` while `v̇ < 0`), above `s_max`, `C_S (s − s_max)` (and `C_V ṡ`
///   while `ṡ > 0`, `C_A v̇` while `v̇ > 0`);
/// - the node gives the flow `ρ A v` into the accumulator (`ρ` the reference density).
///
/// Linearized at rest at a stroke `s` inside its range, its piston is a spring `k_g = κ A²
/// p_g(s)/V + k` on the mass `m + w` (the gas spring's stiffness, `V = A (S − s)` the
/// gas's volume).
pub struct Accumulator {
    pub label: Label,
    pub pressure: ScalarNodeId,
    /// `S`, the initial stroke, `A`, `A_p`, `m` [m, m, m², m², kg].
    pub stroke: f64,
    pub start: f64,
    pub area: f64,
    pub pipe_area: f64,
    pub mass: f64,
    /// `H_IN`, `H_OUT` [-].
    pub loss: [f64; 2],
    /// `P0`, `PMAX` [Pa] and `κ` [-] (zeros without `gas`).
    pub gas: [f64; 3],
    /// `w` [kg], `k` [N/m], `F0` [N].
    pub weight: f64,
    pub spring: f64,
    pub preload: f64,
    /// `C_S` [N/m], `C_V` [N s/m], `C_A` [kg] of the end stops.
    pub stops: [f64; 3],
    pub fluid: HydraulicFluid,
    /// Whether it writes its `.hyd` row.
    pub output: bool,
}

/// The accumulator's terms at a state: the gas pressure and its slope, the stop and loss
/// coefficients that apply (hutils.cc's `c1`, `c2`, `c3`, `cf1`, `cf2`, `cf3`, `h`).
struct Piston {
    gas: f64,
    gas_slope: f64,
    /// Coefficients of `s` (and the constant `−C_S s_max` above the range), `ṡ`, `v̇`.
    stop: [f64; 3],
    stop_offset: f64,
    loss: f64,
}

impl Accumulator {
    /// `s_max` (hutils.cc's constructor).
    pub fn max_stroke(&self) -> f64 {
        let [p0, pmax, kappa] = self.gas;
        let least_gas = if kappa > 0.0 && pmax > 0.0 { self.stroke * (p0 / pmax).powf(1.0 / kappa) } else { 0.0 };
        0.999 * self.stroke - least_gas
    }

    fn piston(&self, st: &dyn ElementState) -> Piston {
        let (s, sd, vd) = (st.multiplier(0), st.rate(0), st.rate(1));
        let [p0, pmax, kappa] = self.gas;
        let [cs, cv, ca] = self.stops;
        let max = self.max_stroke();
        let (gas, gas_slope) = if s > max {
            (pmax, 0.0)
        } else if s < 0.0 {
            (p0, 0.0)
        } else {
            let g = p0 * (self.stroke / (self.stroke - s)).powf(kappa);
            (g, kappa * g / (self.stroke - s))
        };
        let (stop, stop_offset) = if s < 0.0 {
            ([cs, if sd < 0.0 { cv } else { 0.0 }, if vd < 0.0 { ca } else { 0.0 }], 0.0)
        } else if s > max {
            ([cs, if sd > 0.0 { cv } else { 0.0 }, if vd > 0.0 { ca } else { 0.0 }], -cs * max)
        } else {
            ([0.0; 3], 0.0)
        };
        Piston { gas, gas_slope, stop, stop_offset, loss: if sd > 0.0 { self.loss[0] } else { self.loss[1] } }
    }

    /// `h ρ A (A/A_p)²/2`, the loss's coefficient of `sign(v) v²` before `h`.
    fn loss_coefficient(&self) -> f64 {
        0.5 * self.fluid.reference_density() * self.area * (self.area / self.pipe_area).powi(2)
    }
}

impl Element for Accumulator {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "accumulator"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        vec![self.pressure]
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["stroke".into(), "velocity".into()]
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::State
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        vec![(0, self.start, 0.0)]
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (s, v, sd, vd) = (st.multiplier(0), st.multiplier(1), st.rate(0), st.rate(1));
        let t = self.piston(st);
        let rho = self.fluid.reference_density();
        out.add(Row::Scalar { slot: 0 }, -rho * v * self.area);
        let force = (self.mass + self.weight) * vd - st.scalar_value(0) * self.area + t.gas * self.area + self.preload + self.spring * s + t.loss * self.loss_coefficient() * v * v.abs();
        let stops = t.stop[0] * s + t.stop_offset + t.stop[1] * sd + t.stop[2] * vd;
        out.add(Row::Constraint(0), -(force + stops));
        out.add(Row::Constraint(1), v - sd);
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let v = st.multiplier(1);
        let t = self.piston(st);
        out.add(Row::Scalar { slot: 0 }, Col::Multiplier(1), -self.fluid.reference_density() * self.area);
        let r = Row::Constraint(0);
        out.add(r, Col::ScalarValue { slot: 0 }, self.area);
        out.add(r, Col::Multiplier(0), -(self.area * t.gas_slope + self.spring + t.stop[0]));
        out.add(r, Col::Rate(0), -t.stop[1]);
        out.add(r, Col::Multiplier(1), -2.0 * t.loss * self.loss_coefficient() * v.abs());
        out.add(r, Col::Rate(1), -(self.mass + self.weight + t.stop[2]));
        out.add(Row::Constraint(1), Col::Multiplier(1), 1.0);
        out.add(Row::Constraint(1), Col::Rate(0), -1.0);
    }
}

/// hutils.cc's `Accumulator::Output`: `s` [m], `v` [m/s], `v̇` [m/s²], the gas pressure
/// [Pa], the mass flow into the node [kg/s] and a density column that MBDyn 1.7.3 prints
/// from a member it never sets (hutils.cc's `AssRes` computes a local of that name; its
/// runs print 0): romdyn writes 0 there, so that the files compare column by column.
impl Outputs for Accumulator {
    fn writes_hydraulic_row(&self) -> bool {
        self.output
    }
    fn hydraulic_row(&self, st: &dyn ElementState) -> Vec<f64> {
        let rho = self.fluid.reference_density();
        vec![st.multiplier(0), st.multiplier(1), st.rate(1), self.piston(st).gas, -rho * st.multiplier(1) * self.area, 0.0]
    }
}

/// `hydraulic: L, tank, P1, P2, PRESSURE, PIPE_AREA, TANK_AREA, S_MAX, [startlevel, S0,]
/// [alarmlevel, S_ALARM,] C_S, fluid, …` (Tank, hutils.cc): a tank at the constant
/// pressure `P` filled from node 1 and emptied into node 2 through two turbulent orifices
/// of area `A_p` (loss coefficients 1 in, 0.5 out): `q₁ = A_p √(2ρ) sign(p₁ − P) √|p₁ − P|`
/// out of node 1, `q₂ = A_p √(2ρ/0.5) sign(P − p₂) √|P − p₂|` into node 2, and its own
/// differential unknown, the level `s` [m], with `ṡ = (q₁ − q₂)/(ρ A_t)`. Full (`s >
/// S_MAX` while `q₁ > q₂`), the inflow is cut to the outflow and the level relaxes as `ṡ =
/// −(s − S_MAX)`. `ρ = ρ(p₁ + p₂/2)`, as hutils.cc's `AssRes` writes it. A negative level
/// stops the run (MBDyn 1.7.3: "negative fluid level … impossible"). `C_S` and the alarm
/// level are read and unused, as in MBDyn.
pub struct Tank {
    pub label: Label,
    pub pressures: [ScalarNodeId; 2],
    /// `P` [Pa], `A_p`, `A_t` [m²], `S_MAX`, `S0` [m].
    pub pressure: f64,
    pub pipe_area: f64,
    pub tank_area: f64,
    pub max_level: f64,
    pub level: f64,
    pub fluid: HydraulicFluid,
    /// Whether it writes its `.hyd` row.
    pub output: bool,
}

/// The tank's flows at a state: `(q, ∂q/∂p₁, ∂q/∂p₂)` out of node 1 and into node 2, the
/// density and its slopes, whether it is full.
struct TankFlows {
    inflow: [f64; 3],
    outflow: [f64; 3],
    rho: f64,
    full: bool,
}

impl Tank {
    fn flows(&self, st: &dyn ElementState) -> TankFlows {
        let (p1, p2) = (st.scalar_value(0), st.scalar_value(1));
        let rho = self.fluid.density(p1 + 0.5 * p2);
        let slope = self.fluid.density_slope();
        // ∂q/∂ρ = q/(2ρ), ρ(p₁ + p₂/2).
        let (qi, si) = orifice(self.pipe_area, rho, p1 - self.pressure);
        let (qo, so) = orifice(self.pipe_area / 0.5f64.sqrt(), rho, self.pressure - p2);
        let inflow = [qi, si + qi / (2.0 * rho) * slope, qi / (2.0 * rho) * 0.5 * slope];
        let outflow = [qo, qo / (2.0 * rho) * slope, -so + qo / (2.0 * rho) * 0.5 * slope];
        let full = st.multiplier(0) > self.max_level && qi > qo;
        TankFlows { inflow: if full { outflow } else { inflow }, outflow, rho, full }
    }
}

impl Element for Tank {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "tank"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.pressures.to_vec()
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["level".into()]
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::State
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        vec![(0, self.level, 0.0)]
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn failure(&self, st: &dyn ElementState) -> Option<String> {
        let s = st.multiplier(0);
        (s < 0.0).then(|| format!("tank {}: negative fluid level {s} m (MBDyn 1.7.3 stops there too: \"negative fluid level … impossible\")", self.label))
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let s = st.multiplier(0);
        if s < 0.0 {
            out.add(Row::Constraint(0), f64::NAN);
            return;
        }
        let f = self.flows(st);
        out.add(Row::Scalar { slot: 0 }, -f.inflow[0]);
        out.add(Row::Scalar { slot: 1 }, f.outflow[0]);
        let relax = if f.full { s - self.max_level } else { 0.0 };
        out.add(Row::Constraint(0), -(st.rate(0) - (f.inflow[0] - f.outflow[0]) / (self.tank_area * f.rho) + relax));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let f = self.flows(st);
        let slopes = [self.fluid.density_slope(), 0.5 * self.fluid.density_slope()];
        let net = f.inflow[0] - f.outflow[0];
        for slot in 0..2 {
            out.add(Row::Scalar { slot: 0 }, Col::ScalarValue { slot }, -f.inflow[1 + slot]);
            out.add(Row::Scalar { slot: 1 }, Col::ScalarValue { slot }, f.outflow[1 + slot]);
            let dnet = f.inflow[1 + slot] - f.outflow[1 + slot];
            let d = dnet / (self.tank_area * f.rho) - net / (self.tank_area * f.rho * f.rho) * slopes[slot];
            out.add(Row::Constraint(0), Col::ScalarValue { slot }, d);
        }
        out.add(Row::Constraint(0), Col::Rate(0), -1.0);
        out.add(Row::Constraint(0), Col::Multiplier(0), if f.full { -1.0 } else { 0.0 });
    }
}

/// hutils.cc's `Tank::Output`: the level `s` [m], its rate [m/s], the mass flows into
/// nodes 1 and 2 [kg/s].
impl Outputs for Tank {
    fn writes_hydraulic_row(&self) -> bool {
        self.output
    }
    fn hydraulic_row(&self, st: &dyn ElementState) -> Vec<f64> {
        let f = self.flows(st);
        vec![st.multiplier(0), st.rate(0), -f.inflow[0], f.outflow[0]]
    }
}

/// `hydraulic: L, orifice, P1, P2, DIAMETER, ORIFICE_AREA, [area, PIPE_AREA,] [reynolds,
/// RE_CR,] fluid, …` (Orifice, hminor.cc): the mass flow from node 1 to node 2 through a
/// sharp-edged orifice of area `A_o` in a pipe of diameter `D` and area `A_p` (default `0.785
/// D²`, as MBDyn): laminar `q = 2 δ² D A_o ρ Δp/μ` (`δ` = 0.2) while `|Δp|` is below the
/// critical jump `A_p Re_cr (μ/(D δ))²/(2 ρ_i A_o)` (`Re_cr` default 10, `ρ_i` at the nodes'
/// initial mean pressure), turbulent `q = C_d A_o √(2ρ|Δp|) sign(Δp)` above, `C_d = 0.98
/// C_c/√(1 − (C_c A_o/A_p)²)` with Merritt's contraction `C_c` (a quartic in `A_o/A_p`),
/// `ρ` at the mean pressure.
pub struct Orifice {
    pub label: Label,
    pub pressures: [ScalarNodeId; 2],
    pub diameter: f64,
    pub orifice_area: f64,
    pub pipe_area: f64,
    /// The critical pressure jump [Pa] and `C_d` [-] (hminor.cc's constructor).
    pub critical_jump: f64,
    pub discharge: f64,
    pub fluid: HydraulicFluid,
    /// Whether it writes its `.hyd` row.
    pub output: bool,
}

/// hminor.cc's `δ` for a sharp-edged round orifice (Merritt).
const ORIFICE_DELTA: f64 = 0.2;

impl Orifice {
    /// `(critical jump [Pa], C_d)` of an orifice, `None` where hminor.cc stops ("error
    /// computing Cd": `C_c A_o/A_p` too near 1).
    pub fn coefficients(diameter: f64, orifice_area: f64, pipe_area: f64, reynolds: f64, initial_density: f64, viscosity: f64) -> Option<(f64, f64)> {
        let jump = pipe_area * reynolds * (viscosity / (diameter * ORIFICE_DELTA)).powi(2) / (2.0 * initial_density * orifice_area);
        let ratio = orifice_area / pipe_area;
        let contraction = (((0.4855 * ratio - 0.4971) * ratio + 0.158) * ratio + 0.1707) * ratio + 0.6005;
        let rad = 1.0 - (contraction * ratio).powi(2);
        (rad >= 1e3 * f64::EPSILON).then(|| (jump, 0.98 * contraction / rad.sqrt()))
    }

    /// `(q, ∂q/∂p₁, ∂q/∂p₂, ρ, turbulent)`.
    fn flow(&self, st: &dyn ElementState) -> (f64, f64, f64, f64, bool) {
        let (p1, p2) = (st.scalar_value(0), st.scalar_value(1));
        let drop = p1 - p2;
        let rho = self.fluid.density(0.5 * (p1 + p2));
        let half_slope = 0.5 * self.fluid.density_slope();
        if drop.abs() < self.critical_jump {
            let k = 2.0 * ORIFICE_DELTA * ORIFICE_DELTA * self.diameter * self.orifice_area / self.fluid.viscosity();
            let q = k * rho * drop;
            return (q, k * rho + k * drop * half_slope, -k * rho + k * drop * half_slope, rho, false);
        }
        let (q, slope) = orifice(self.discharge * self.orifice_area, rho, drop);
        let density = q / (2.0 * rho) * half_slope;
        (q, slope + density, -slope + density, rho, true)
    }
}

impl Element for Orifice {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "orifice"
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
        let (_, d1, d2, ..) = self.flow(st);
        for (slot, dq) in [(0, d1), (1, d2)] {
            out.add(Row::Scalar { slot: 0 }, Col::ScalarValue { slot }, -dq);
            out.add(Row::Scalar { slot: 1 }, Col::ScalarValue { slot }, dq);
        }
    }
}

/// hminor.cc's `Orifice::Output`: the velocity `q/(ρ A_p)` [m/s], the mass flow [kg/s],
/// the Reynolds number `|ρ v D/μ|` and the regime (1 turbulent, 0 laminar).
impl Outputs for Orifice {
    fn writes_hydraulic_row(&self) -> bool {
        self.output
    }
    fn hydraulic_row(&self, st: &dyn ElementState) -> Vec<f64> {
        let (q, _, _, rho, turbulent) = self.flow(st);
        let velocity = q / (rho * self.pipe_area);
        vec![velocity, q, (rho * velocity * self.diameter / self.fluid.viscosity()).abs(), if turbulent { 1.0 } else { 0.0 }]
    }
}
