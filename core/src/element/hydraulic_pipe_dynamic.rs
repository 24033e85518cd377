//! MBDyn's `dynamic pipe` (input manual §Dynamic pipe; hydr/pipe.cc, `DynamicPipe`): a pipe
//! with the fluid's inertia and compressibility, in two halves of length `L/2` around its
//! middle.
//!
//! Own unknowns, all differential (MBDyn's order): the pressures at the pipe's ends `p₁`,
//! `p₂` [Pa] and the mass flows at the ends `q₁`, `q₂` [kg/s] (from node 1 towards node
//! 2). With `ρₖ = ρ(pₖ)`, `ρ₀ = ρ((p₁ + p₂)/2)`, the flow at the middle `q̄ = (q₁ + q₂)/2`
//! and the flows at the quarter points `q̃₁ = (3q₁ + q₂)/4`, `q̃₂ = (q₁ + 3q₂)/4`:
//!
//! - mass balance of each half, into its node's equation (the flow out of the node):
//!   `q̄ + (A L/8) ρ'(3ṗ₁ + ṗ₂)` at node 1, `−q̄ + (A L/8) ρ'(ṗ₁ + 3ṗ₂)` at node 2
//!   (`ρ' = dρ/dp` at the quarter points);
//! - momentum balance of each half: `(L/8)(3q̇₁ + q̇₂) + q̄²/(ρ₀A) − q₁²/(ρ₁A) + (A/2)(p₂ −
//!   p₁) + f₁ = 0` and `(L/8)(q̇₁ + 3q̇₂) + q₂²/(ρ₂A) − q̄²/(ρ₀A) + (A/2)(p₂ − p₁) + f₂ = 0`,
//!   `fₖ = g(q̃ₖ)/((ρₖ + ρ₀)/2)` the friction of the half [N] in the regime of the pipe's
//!   Reynolds number `Re = |q̄| D/(A μ)` ([`Regime`], latched as the `pipe`'s): laminar
//!   `g = 16 L μ q̃/D²`, turbulent (Blasius) `g = 0.0791 L μ^{1/4} q̃|q̃|^{3/4}/(D^{5/4}
//!   A^{3/4})`, transition `g = L/(4 D A) q̃ |q̃| (((a|q̃| + b)|q̃| + c)|q̃| + d)`;
//! - `pₖ − pₙₖ = 0`, the ends' pressures equal their nodes'.
//!
//! Linearized at rest with a closed end (node 2 on nothing else) and node 1 held, it is the
//! oscillator `L q̄̇ + A δp₂ + 2 f'q̄ = 0`, `(3 A L ρ'/8) δṗ₂ = q̄`: its acoustic mode is
//! `ω² = 8 β/(3 ρ L²)` (`β = ρ/ρ'`, `c² = β/ρ`), `√(8/3) c/L`, the quarter-wave `π c/(2L)`
//! of the continuous pipe to 4 % (a chain of dynamic pipes converges to it).
//!
//! MBDyn starts `q₂` at the opposite of `q₁`'s initial value (`initial value, Q0`: `q₁ =
//! Q0`, `q₂ = −Q0`, pipe.cc's `SetValue`); romdyn does the same.

use super::contract::{Col, Element, ElementState, Events, JacobianSink, Label, Latched, Outputs, ResidualSink, Row, ScalarNodeId, UnknownKind};
use super::hydraulic::{HydraulicFluid, Regime};

/// `hydraulic: L, dynamic pipe, P1, P2, DIAMETER, [area, A,] LENGTH, [turbulent,] [initial
/// value, Q0,] fluid, …` (see the module's equations).
pub struct DynamicPipe {
    pub label: Label,
    pub pressures: [ScalarNodeId; 2],
    /// The hydraulic diameter `D` [m].
    pub diameter: f64,
    /// The area `A` [m²].
    pub area: f64,
    /// The length `L` [m].
    pub length: f64,
    pub fluid: HydraulicFluid,
    /// The regime before the first step (`turbulent`).
    pub turbulent: bool,
    /// The nodes' initial pressures [Pa] and `Q0` [kg/s], where the own unknowns start.
    pub initial_pressures: [f64; 2],
    pub initial_flow: f64,
    /// Whether it writes its `.hyd` row.
    pub output: bool,
}

/// The quantities of one state that the residual, the Jacobian and the output share.
struct Pipe2 {
    p: [f64; 2],
    q: [f64; 2],
    /// `ρ₁`, `ρ₂`, `ρ₀`.
    rho: [f64; 3],
    /// `q̄`, `Re`.
    mean: f64,
    re: f64,
}

impl DynamicPipe {
    fn at(&self, st: &dyn ElementState) -> Pipe2 {
        let p = [st.multiplier(0), st.multiplier(1)];
        let q = [st.multiplier(2), st.multiplier(3)];
        let rho = [self.fluid.density(p[0]), self.fluid.density(p[1]), self.fluid.density(0.5 * (p[0] + p[1]))];
        let mean = 0.5 * (q[0] + q[1]);
        Pipe2 { p, q, rho, mean, re: self.reynolds(mean) }
    }

    fn reynolds(&self, mean: f64) -> f64 {
        mean.abs() / self.area * self.diameter / self.fluid.viscosity()
    }

    fn turbulent_at(&self, st: &dyn ElementState) -> bool {
        st.latched().and_then(|l| l.downcast_ref::<bool>()).copied().unwrap_or(self.turbulent)
    }

    /// The friction numerator `g(q̃)` [N kg/m³] of one half and its slope, in `regime`.
    fn friction(&self, regime: Regime, x: f64) -> (f64, f64) {
        let (l, d, a, mu) = (self.length, self.diameter, self.area, self.fluid.viscosity());
        match regime {
            Regime::Laminar => {
                let k = 16.0 * l / (d * d) * mu;
                (k * x, k)
            }
            Regime::Turbulent => {
                let k = 0.5 * l * 0.1582 / (d.powf(1.25) * a.powf(0.75)) * mu.powf(0.25);
                (k * x * x.abs().powf(0.75), 1.75 * k * x.abs().powf(0.75))
            }
            Regime::Transition { a: ca, b, c, d: cd } => {
                let k = 0.25 * l / (d * a);
                let y = x.abs();
                (k * x * (((ca * y + b) * y + c) * y + cd) * y, k * (((5.0 * ca * y + 4.0 * b) * y + 3.0 * c) * y + 2.0 * cd) * y)
            }
        }
    }

    fn regime(&self, st: &dyn ElementState, re: f64) -> Regime {
        Regime::of(re, self.turbulent_at(st), self.diameter / (self.fluid.viscosity() * self.area))
    }
}

impl Element for DynamicPipe {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "dynamic pipe"
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.pressures.to_vec()
    }
    fn multipliers(&self) -> Vec<String> {
        ["pressure 1", "pressure 2", "mass flow 1", "mass flow 2"].map(String::from).to_vec()
    }
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::State
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        vec![(0, self.initial_pressures[0], 0.0), (1, self.initial_pressures[1], 0.0), (2, self.initial_flow, 0.0), (3, -self.initial_flow, 0.0)]
    }
    fn events(&self) -> Option<&dyn Events> {
        Some(self)
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let s = self.at(st);
        let (a, l) = (self.area, self.length);
        let slope = self.fluid.density_slope();
        let (pd, qd) = ([st.rate(0), st.rate(1)], [st.rate(2), st.rate(3)]);
        let storage = a * l / 8.0 * slope;
        out.add(Row::Scalar { slot: 0 }, -s.mean - storage * (3.0 * pd[0] + pd[1]));
        out.add(Row::Scalar { slot: 1 }, s.mean - storage * (pd[0] + 3.0 * pd[1]));
        let regime = self.regime(st, s.re);
        let quarter = [0.75 * s.q[0] + 0.25 * s.q[1], 0.25 * s.q[0] + 0.75 * s.q[1]];
        let halves = [0.5 * (s.rho[0] + s.rho[2]), 0.5 * (s.rho[2] + s.rho[1])];
        let f = [self.friction(regime, quarter[0]).0 / halves[0], self.friction(regime, quarter[1]).0 / halves[1]];
        let middle = s.mean * s.mean / (s.rho[2] * a);
        let pressure = 0.5 * a * (s.p[1] - s.p[0]);
        out.add(Row::Constraint(0), l / 8.0 * (3.0 * qd[0] + qd[1]) + middle - s.q[0] * s.q[0] / (s.rho[0] * a) + pressure + f[0]);
        out.add(Row::Constraint(1), l / 8.0 * (qd[0] + 3.0 * qd[1]) + s.q[1] * s.q[1] / (s.rho[1] * a) - middle + pressure + f[1]);
        out.add(Row::Constraint(2), s.p[0] - st.scalar_value(0));
        out.add(Row::Constraint(3), s.p[1] - st.scalar_value(1));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let s = self.at(st);
        let (a, l) = (self.area, self.length);
        let slope = self.fluid.density_slope();
        let storage = a * l / 8.0 * slope;
        for (row, sign, weights) in [(0, -1.0, [3.0, 1.0]), (1, 1.0, [1.0, 3.0])] {
            out.add(Row::Scalar { slot: row }, Col::Multiplier(2), 0.5 * sign);
            out.add(Row::Scalar { slot: row }, Col::Multiplier(3), 0.5 * sign);
            out.add(Row::Scalar { slot: row }, Col::Rate(0), -storage * weights[0]);
            out.add(Row::Scalar { slot: row }, Col::Rate(1), -storage * weights[1]);
        }
        let regime = self.regime(st, s.re);
        let quarter = [0.75 * s.q[0] + 0.25 * s.q[1], 0.25 * s.q[0] + 0.75 * s.q[1]];
        let halves = [0.5 * (s.rho[0] + s.rho[2]), 0.5 * (s.rho[2] + s.rho[1])];
        // ∂(half density)/∂(p₁, p₂): ρ' (3/4, 1/4) and ρ' (1/4, 3/4).
        let half_slopes = [[0.75 * slope, 0.25 * slope], [0.25 * slope, 0.75 * slope]];
        let quarter_weights = [[0.75, 0.25], [0.25, 0.75]];
        // ∂(q̄²/(ρ₀A))/∂(q₁, q₂, p₁, p₂), ∂(qₖ²/(ρₖA))/∂(qₖ, pₖ).
        let m = s.mean / (s.rho[2] * a);
        let middle = [m, m, -m * s.mean / s.rho[2] * 0.5 * slope, -m * s.mean / s.rho[2] * 0.5 * slope];
        let end = |k: usize| (2.0 * s.q[k] / (s.rho[k] * a), -s.q[k] * s.q[k] / (s.rho[k] * s.rho[k] * a) * slope);
        for k in 0..2 {
            let r = Row::Constraint(k);
            let (g, dg) = self.friction(regime, quarter[k]);
            // Inertia.
            out.add(r, Col::Rate(2), l / 8.0 * quarter_weights[k][0] * 4.0);
            out.add(r, Col::Rate(3), l / 8.0 * quarter_weights[k][1] * 4.0);
            // Convection: +middle in row 0, −middle in row 1; −end₁ in row 0, +end₂ in row 1.
            let sign = if k == 0 { 1.0 } else { -1.0 };
            let (dq_end, dp_end) = end(k);
            out.add(r, Col::Multiplier(2), sign * middle[0] + dg * quarter_weights[k][0] / halves[k] - if k == 0 { dq_end } else { 0.0 });
            out.add(r, Col::Multiplier(3), sign * middle[1] + dg * quarter_weights[k][1] / halves[k] + if k == 1 { dq_end } else { 0.0 });
            // Pressures: (A/2)(p₂ − p₁), the densities of the convection and the friction.
            let friction_p = [-g / (halves[k] * halves[k]) * half_slopes[k][0], -g / (halves[k] * halves[k]) * half_slopes[k][1]];
            out.add(r, Col::Multiplier(0), -0.5 * a + sign * middle[2] + friction_p[0] - if k == 0 { dp_end } else { 0.0 });
            out.add(r, Col::Multiplier(1), 0.5 * a + sign * middle[3] + friction_p[1] + if k == 1 { dp_end } else { 0.0 });
        }
        for k in 0..2 {
            out.add(Row::Constraint(2 + k), Col::Multiplier(k), 1.0);
            out.add(Row::Constraint(2 + k), Col::ScalarValue { slot: k }, -1.0);
        }
    }
}

impl Events for DynamicPipe {
    /// The regime of the accepted state, kept in the transition (pipe.cc, `AfterConvergence`).
    fn latch(&self, now: &dyn ElementState, before: &dyn ElementState) -> Option<Latched> {
        let old = self.turbulent_at(now);
        let new = Regime::latched(self.at(before).re, old);
        (new != old).then(|| std::sync::Arc::new(new) as Latched)
    }
}

/// pipe.cc's `DynamicPipe::Output`: `p₁`, `p₂` [Pa], their rates [Pa/s], `q₁`, `q₂` [kg/s],
/// their rates [kg/s²], `ρ₁`, `ρ₀`, `ρ₂` [kg/m³], `ρ'` at the quarter points [kg/(m³ Pa)],
/// `Re` and the regime the next step comes from (1 turbulent, 0 laminar).
impl Outputs for DynamicPipe {
    fn writes_hydraulic_row(&self) -> bool {
        self.output
    }
    fn hydraulic_row(&self, st: &dyn ElementState) -> Vec<f64> {
        let s = self.at(st);
        let slope = self.fluid.density_slope();
        // MBDyn writes after `AfterConvergence`: the regime this state leaves.
        let turbulent = if Regime::latched(s.re, self.turbulent_at(st)) { 1.0 } else { 0.0 };
        vec![s.p[0], s.p[1], st.rate(0), st.rate(1), s.q[0], s.q[1], st.rate(2), st.rate(3), s.rho[0], s.rho[2], s.rho[1], slope, slope, s.re, turbulent]
    }
}
