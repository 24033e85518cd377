//! Joint friction: MBDyn's `modlugre` friction model with the `simple` shape function
//! (input manual, §Friction; friction.cc) on an `in line` joint without offset (the only
//! joint the manual's §In line allows it on; inline.cc).
//!
//! The model (Dupont, Hayward, Armstrong, Altpeter 2002, "Single state elastoplastic
//! friction models", as friction.cc writes it) has one differential state, the bristle
//! deflection `z` [m], with its own equation
//!
//! ```text
//! ż − v + α(z, v) v z σ₀ / f_s(v) = 0,      f_s(v) = μ(|v|) sign v,
//! ```
//!
//! `μ` the static friction coefficient (a `scalar function` of the sliding speed), and the
//! friction coefficient `f = σ₀ z + σ₁ ż + σ₂ v`. `α` is 0 while `|z|` is below the breakaway
//! deflection `κ z_ss` (`z_ss = f_s(v)/σ₀`, pure stick: the bristle is a spring `σ₀` with a
//! damper `σ₁`), 1 above `z_ss` (steady sliding: `f → μ sign v + σ₂ v`), a half sine wave in
//! between (C¹), and 0 whenever `z` and `v` have opposite signs (`sign 0 = +1`).
//!
//! On the in line joint (inline.cc) `v = (ẋ₁ − ẋ₂) · e₃` with `e₃` the line's direction
//! (axis 3 of node 1's line frame), the normal force is `N = max(|λ|, preload)` with `λ` the
//! joint's two reaction multipliers, and the friction force `f N` acts along `−e₃` on node 1
//! and `+e₃` on node 2, applied at the nodes (no moment: MBDyn's `AssRes` adds none).
//!
//! Linearized, the model is smooth wherever the state is off the switching points: in stick
//! (`|z| < κ z_ss`) it is the bristle spring `σ₀ N` and damper `(σ₁ + σ₂) N` along the line;
//! in steady sliding (`v ≠ 0`, `|z| ≥ z_ss`) a viscous `σ₂ N` plus the state's decay
//! `ż = −σ₀ |v| z / μ(|v|) + …`. At `v = 0` with `α ≠ 0` the term `α |v| z σ₀ / μ` is not
//! differentiable (the Jacobian takes the one-sided derivative of `v > 0`).

use super::anchor::{node_labels, Pair};
use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::joint::{Joint, JointKind};
use super::drive::ScalarFunction;
use crate::kinematics::{skew, Vec3};
use super::UnknownKind;
use crate::element::NonSmooth;
use crate::element::Outputs;

/// MBDyn's `modlugre, σ₀, σ₁, σ₂, κ, "μ(|v|)"` (input manual, §Friction models).
#[derive(Clone, Debug)]
pub struct ModLugre {
    /// Bristle stiffness per unit normal force [1/m].
    pub sigma0: f64,
    /// Bristle damping per unit normal force [s/m].
    pub sigma1: f64,
    /// Viscous friction per unit normal force [s/m].
    pub sigma2: f64,
    /// Breakaway fraction of the steady-state deflection, `0 < κ < 1`.
    pub kappa: f64,
    /// Static friction coefficient as a function of the sliding speed `|v|`.
    pub static_friction: ScalarFunction,
}

/// MBDyn's `sign` (friction.cc): `+1` at zero.
fn sign(x: f64) -> f64 {
    if x >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// The state equation's value and its derivatives `(ψ, ψ_/z, ψ_/v)`; `ψ_/ż = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StateEquation {
    pub value: f64,
    pub d_z: f64,
    pub d_v: f64,
}

impl ModLugre {
    /// `f_s(v) = μ(|v|) sign v` and `f_s'(v) = μ'(|v|)` (for `v ≠ 0`).
    fn fs(&self, v: f64) -> (f64, f64) {
        let (mu, dmu) = self.static_friction.value_and_derivative(v.abs());
        (mu * sign(v), dmu)
    }

    /// `(α, α_/z, α_/v)`.
    pub(super) fn alpha(&self, z: f64, v: f64) -> (f64, f64, f64) {
        let (fs, dfs) = self.fs(v);
        let zss = fs / self.sigma0;
        let zba = self.kappa * zss;
        if sign(v) != sign(z) || z.abs() <= zba.abs() {
            return (0.0, 0.0, 0.0);
        }
        if z.abs() > zss.abs() {
            return (1.0, 0.0, 0.0);
        }
        let k = 1.0 - self.kappa;
        let phase = std::f64::consts::PI * self.sigma0 * z / (fs * k) - std::f64::consts::PI * (1.0 + self.kappa) / (2.0 * k);
        let half_cos = 0.5 * phase.cos();
        let d_phase_z = std::f64::consts::PI * self.sigma0 / (fs * k);
        let d_phase_v = -std::f64::consts::PI * self.sigma0 * z / (fs * fs * k) * dfs;
        (0.5 * phase.sin() + 0.5, half_cos * d_phase_z, half_cos * d_phase_v)
    }

    /// `ψ = ż − v + α v z σ₀ / f_s(v)` without its `ż`, with derivatives.
    pub fn state_equation(&self, z: f64, v: f64) -> StateEquation {
        let (fs, dfs) = self.fs(v);
        let (a, a_z, a_v) = self.alpha(z, v);
        let s0 = self.sigma0;
        StateEquation {
            value: -v + a * v * z * s0 / fs,
            d_z: s0 * v / fs * (a_z * z + a),
            d_v: -1.0 + s0 * z * (a_v * v / fs + a / fs - a * v * dfs / (fs * fs)),
        }
    }

    /// Whether the friction state `z` is past the breakaway deflection at rest, in either
    /// sliding direction (`α ≠ 0` for `v = 0` or just below): there the state equation's
    /// `α |v| z σ₀/μ(|v|)` has a kink at `v = 0`.
    pub fn past_breakaway(&self, z: f64) -> bool {
        self.alpha(z, 0.0).0.max(self.alpha(z, -f64::MIN_POSITIVE).0) != 0.0
    }

    /// The points where the state equation is not differentiable that the state crosses from
    /// `(v_a, z_a)` to `(v_b, z_b)` (sliding velocity and friction state), as a sentence:
    /// `v = 0` with `z` past the breakaway deflection on either side (the kink of `α |v| z
    /// σ₀/μ(|v|)`, as [`Element::non_smooth`]), and the kinks of `μ(|v|)`
    /// ([`ScalarFunction::kinks`]), where `f_s'` jumps and with it the derivative in `v` by
    /// `α z σ₀ v Δμ'/μ²`. Newton's iterates on the two sides of such a point can cycle
    /// (tests/multibody/joint_friction.rs, stick_slip_kink.mbd).
    pub fn kink_crossed(&self, (v_a, z_a): (f64, f64), (v_b, z_b): (f64, f64)) -> Option<String> {
        let mut why = Vec::new();
        if sign(v_a) != sign(v_b) && (self.past_breakaway(z_a) || self.past_breakaway(z_b)) {
            why.push(format!("its sliding velocity went from {v_a:.6e} to {v_b:.6e} m/s across 0 with its friction state (z = {z_a:.6e}, {z_b:.6e} m) past the breakaway deflection, where the modlugre state equation's α |v| z σ₀/μ(|v|) has a kink"));
        }
        let (lo, hi) = (v_a.abs().min(v_b.abs()), v_a.abs().max(v_b.abs()));
        if let Some(x) = self.static_friction.kinks().into_iter().find(|&x| lo < x && x < hi) {
            let slope = |s: f64| self.static_friction.derivative(s);
            let h = 1e-9 * x.abs().max(1e-9);
            why.push(format!("its sliding speed |v| went from {:.6e} to {:.6e} m/s across {x:e} m/s, a kink of its static friction coefficient μ(|v|) (slope {:.6e} below, {:.6e} above), where the friction state equation is not differentiable (a `cubic spline` μ has no such point)", v_a.abs(), v_b.abs(), slope(x - h), slope(x + h)));
        }
        (!why.is_empty()).then(|| why.join(", and "))
    }

    /// The friction coefficient `f = σ₀ z + σ₁ ż + σ₂ v`.
    pub fn coefficient(&self, z: f64, zdot: f64, v: f64) -> f64 {
        self.sigma0 * z + self.sigma1 * zdot + self.sigma2 * v
    }
}

/// An `in line` joint (without offset) with `modlugre` friction and the `simple` shape
/// function. Unknowns: the joint's two reaction multipliers, then the friction state `z`.
#[derive(Clone, Debug)]
pub struct InLineFriction {
    joint: Joint,
    /// MBDyn's `preload`: the least normal force [N].
    preload: f64,
    model: ModLugre,
}

/// Index of the friction state among the element's unknowns.
const STATE: usize = 2;

/// Sliding speed below which the joint is at rest for [`Element::non_smooth`] [m/s].
const STILL: f64 = 1e-6;

impl InLineFriction {
    /// `joint` must be an in line joint (two multipliers).
    pub fn new(joint: Joint, preload: f64, model: ModLugre) -> Self {
        debug_assert_eq!(joint.kind, JointKind::InLine);
        InLineFriction { joint, preload, model }
    }

    /// Line direction `e₃`, sliding velocity `v = (ẋ₁ − ẋ₂)·e₃` and `ẋ₁ − ẋ₂`.
    fn sliding(&self, p: &Pair, st: &dyn ElementState) -> (Vec3, f64, Vec3) {
        let e3 = p.q_a.column(2).into_owned();
        let v1 = p.slot_a.map_or(Vec3::zeros(), |a| st.node(a).xdot);
        let w = v1 - st.node(p.slot_b).xdot;
        (e3, w.dot(&e3), w)
    }

    /// `N = max(|λ|, preload)` and `∂N/∂λ` (zero below the preload, as inline.cc).
    fn normal_force(&self, st: &dyn ElementState) -> (f64, [f64; 2]) {
        let l = [st.multiplier(0), st.multiplier(1)];
        let norm = l[0].hypot(l[1]);
        if norm < self.preload || norm == 0.0 {
            (self.preload, [0.0; 2])
        } else {
            (norm, [l[0] / norm, l[1] / norm])
        }
    }
}

impl Element for InLineFriction {
    fn label(&self) -> Label {
        self.joint.label
    }
    fn type_name(&self) -> &'static str {
        "in line"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.joint.a, &self.joint.b)
    }
    fn multipliers(&self) -> Vec<String> {
        let mut m = self.joint.multipliers();
        m.push("friction state z".to_string());
        m
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        if k == STATE { UnknownKind::State } else { UnknownKind::Multiplier }
    }
    fn assembly_form(&self) -> Option<&dyn Element> {
        Some(&self.joint)
    }
    fn non_smoothness(&self) -> Option<&dyn NonSmooth> {
        Some(self)
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        self.joint.residual(st, out);
        let p = Pair::new(&self.joint.a, &self.joint.b, st);
        let (e3, v, _) = self.sliding(&p, st);
        let (z, zdot) = (st.multiplier(STATE), st.rate(STATE));
        out.add(Row::Constraint(STATE), zdot + self.model.state_equation(z, v).value);
        // Applied force +e₃ f N on node 2, −e₃ f N on node 1; residual rows are `… − f`.
        let force = e3 * (self.model.coefficient(z, zdot, v) * self.normal_force(st).0);
        add_vec(out, Row::force(p.slot_b), &(-force));
        if let Some(a) = p.slot_a {
            add_vec(out, Row::force(a), &force);
        }
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        self.joint.jacobian(st, out);
        let p = Pair::new(&self.joint.a, &self.joint.b, st);
        let (e3, v, w) = self.sliding(&p, st);
        let (z, zdot) = (st.multiplier(STATE), st.rate(STATE));
        let (n, dn) = self.normal_force(st);
        let m = &self.model;
        let f = m.coefficient(z, zdot, v);
        let psi = m.state_equation(z, v);
        // δv = e₃·(δẋ₁ − δẋ₂) + (e₃ × w)·δθ₁ (δe₃ = δθ₁ × e₃).
        let mut dv: Vec<(Col, f64)> = Vec::new();
        for k in 0..3 {
            dv.push((Col::Velocity { slot: p.slot_b, comp: k }, -e3[k]));
        }
        if let Some(a) = p.slot_a {
            let t = e3.cross(&w);
            for k in 0..3 {
                dv.push((Col::Velocity { slot: a, comp: k }, e3[k]));
                dv.push((Col::Rotation { slot: a, comp: k }, t[k]));
            }
        }
        // State row: δψ = δż + ψ_/z δz + ψ_/v δv.
        let row = Row::Constraint(STATE);
        out.add(row, Col::Rate(STATE), 1.0);
        out.add(row, Col::Multiplier(STATE), psi.d_z);
        for &(col, d) in &dv {
            out.add(row, col, psi.d_v * d);
        }
        // δ(f N) = N (σ₀ δz + σ₁ δż + σ₂ δv) + f ∂N/∂λ δλ; node 1's row is +e₃ f N, node 2's −.
        let mut dforce: Vec<(Col, f64)> = vec![(Col::Multiplier(STATE), n * m.sigma0), (Col::Rate(STATE), n * m.sigma1), (Col::Multiplier(0), f * dn[0]), (Col::Multiplier(1), f * dn[1])];
        dforce.extend(dv.iter().map(|&(col, d)| (col, n * m.sigma2 * d)));
        for (col, d) in dforce {
            for k in 0..3 {
                out.add(Row::Equilibrium { slot: p.slot_b, comp: k }, col, -e3[k] * d);
                if let Some(a) = p.slot_a {
                    out.add(Row::Equilibrium { slot: a, comp: k }, col, e3[k] * d);
                }
            }
        }
        // The direction turns with node 1: δ(e₃ f N) = −f N [e₃×] δθ₁ + …
        if let Some(a) = p.slot_a {
            let turn = -skew(&e3) * (f * n);
            add_block(out, Row::force(a), Col::rotation(a), &turn);
            add_block(out, Row::force(p.slot_b), Col::rotation(a), &(-turn));
        }
    }
}

impl Outputs for InLineFriction {
    fn private_data(&self, name: &str) -> Option<super::private_data::PrivateDatum> {
        self.joint.private_data(name)
    }
}

impl NonSmooth for InLineFriction {
    fn non_smooth(&self, st: &dyn ElementState) -> Option<String> {
        let p = Pair::new(&self.joint.a, &self.joint.b, st);
        let (_, v, _) = self.sliding(&p, st);
        let z = st.multiplier(STATE);
        // α(z, ±0) ≠ 0: the term α |v| z σ₀ / μ(|v|) has a kink in v at v = 0. "At v = 0":
        // below 1e-6 m/s, the velocity a converged step at rest leaves (Newton's tolerance
        // over a bristle's stiffness and damping), below which any motion crosses the kink.
        (v.abs() < STILL && self.model.past_breakaway(z)).then(|| format!("its friction state z = {z:e} m is past the breakaway deflection at sliding velocity {v:.1e} m/s (at rest), where the modlugre state equation is not differentiable"))
    }
    fn kink_crossed(&self, from: &dyn ElementState, to: &dyn ElementState) -> Option<String> {
        let v = |st: &dyn ElementState| (self.sliding(&Pair::new(&self.joint.a, &self.joint.b, st), st).1, st.multiplier(STATE));
        self.model.kink_crossed(v(from), v(to))
    }
    fn reaction_dependence(&self, st: &dyn ElementState) -> Option<String> {
        // Above the preload the friction force f N and its stiffness σ₀ N scale with the
        // reaction multipliers' values. Their integration noise: a step accepted on its
        // predictor (no Newton iteration, its residual already below the tolerance; MBDyn
        // does the same) leaves the multipliers and the momenta as extrapolated, and runs of
        // such steps let a constrained direction's momentum drift within the tolerance (on
        // tests/multibody/joint_friction.rs's block, up to 1.9e-7 kg m/s vertically at tolerance 1e-6), whose
        // derivative the reaction balances (3e-4 N of 98.1 N at t = 1.9 s).
        let (n, dn) = self.normal_force(st);
        (dn != [0.0; 2]).then(|| format!("its friction force and stiffness scale with the normal force |λ| = {n:.9e} N, the joint's reaction multipliers as integrated, which steps accepted within the tolerance without a Newton iteration leave noisy (up to 1e-5 relative on a block resting on a line at tolerance 1e-6, its bristle eigenvalue then 1.6e-6 off the closed form); the eigenvalues carry that noise, which a tighter `tolerance` narrows"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model() -> ModLugre {
        ModLugre { sigma0: 2000.0, sigma1: 2.8, sigma2: 0.0, kappa: 0.71, static_friction: ScalarFunction::Const(0.3) }
    }

    /// `α` is 0 below the breakaway deflection `κ μ/σ₀`, 1 above `μ/σ₀`, ½ half way
    /// (the half sine wave of friction.cc), and 0 against the sliding direction.
    #[test]
    fn alpha_switches_between_stick_and_slip() {
        let m = model();
        let zss = 0.3 / 2000.0;
        assert_eq!(m.alpha(0.7 * zss, 1.0).0, 0.0);
        assert_eq!(m.alpha(1.01 * zss, 1.0).0, 1.0);
        assert!((m.alpha(0.855 * zss, 1.0).0 - 0.5).abs() < 1e-12);
        assert_eq!(m.alpha(-1.01 * zss, 1.0).0, 0.0);
        assert_eq!(m.alpha(-1.01 * zss, -1.0).0, 1.0);
    }

    /// The state equation's derivatives against central differences, in the transition
    /// region (both signs) and in full slip, with a speed-dependent `μ`.
    #[test]
    fn state_equation_derivatives_match_finite_differences() {
        let mut m = model();
        m.static_friction = ScalarFunction::Multilinear { points: vec![(0.0, 0.6), (0.1, 0.3), (1.0, 0.2)], extrapolate: false };
        for (z, v) in [(2.0e-4, 0.05), (-2.0e-4, -0.05), (4e-4, 0.5), (1e-5, 0.3), (2.0e-4, 0.5)] {
            let e = m.state_equation(z, v);
            let (hz, hv) = (1e-10, 1e-7);
            let fz = (m.state_equation(z + hz, v).value - m.state_equation(z - hz, v).value) / (2.0 * hz);
            let fv = (m.state_equation(z, v + hv).value - m.state_equation(z, v - hv).value) / (2.0 * hv);
            assert!((e.d_z - fz).abs() <= 1e-5 * (1.0 + fz.abs()), "z {z} v {v}: {} vs {fz}", e.d_z);
            assert!((e.d_v - fv).abs() <= 1e-5 * (1.0 + fv.abs()), "z {z} v {v}: {} vs {fv}", e.d_v);
        }
    }

    /// The points where the state equation is not differentiable, named when two states lie
    /// on their two sides: a kink of `μ(|v|)` in either sliding direction, and `v = 0` only
    /// with `z` past the breakaway deflection.
    #[test]
    fn kinks_crossed_between_two_states_are_named() {
        let mut m = model();
        m.static_friction = ScalarFunction::Multilinear { points: vec![(0.0, 0.6), (0.1, 0.3), (1.0, 0.3)], extrapolate: true };
        let slip = 2.0 * 0.6 / 2000.0;
        for sign in [1.0, -1.0] {
            let why = m.kink_crossed((sign * 0.05, sign * slip), (sign * 0.2, sign * slip)).unwrap();
            assert!(why.contains("across 1e-1 m/s, a kink of its static friction coefficient μ(|v|) (slope -3.000000e0 below, 0.000000e0 above)"), "{why}");
            assert!(!why.contains("across 0"), "{why}");
        }
        assert_eq!(m.kink_crossed((0.02, slip), (0.08, slip)), None);
        let why = m.kink_crossed((0.05, slip), (-0.05, slip)).unwrap();
        assert!(why.starts_with("its sliding velocity went from 5.000000e-2 to -5.000000e-2 m/s across 0"), "{why}");
        // In stick (|z| below κ μ/σ₀ on both sides) the state equation is smooth at v = 0.
        assert_eq!(m.kink_crossed((0.05, 1e-5), (-0.05, 1e-5)), None);
    }
}
