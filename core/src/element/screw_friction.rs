//! MBDyn's `modlugre` friction with the `screw joint` shape function on a `screw` joint
//! (screwjoint.cc with a friction, friction.h `ScrewJointSh_c`): the model of
//! [`super::friction`] on the thread's flank, at the thread radius `r` with the half thread
//! angle `γ`:
//!
//! ```text
//! v = sign(λ) (r / cos β) e · (ω₂ − ω₁),    N = |λ|,    M = c(f) λ,
//! c(f) = r f sec γ (1 + tan²β) / (f sec γ tan β − 1),      tan β = p / (2π r),
//! ```
//!
//! `e` the screw axis, `λ` the screw's reaction (the axial force on node 2 is `+λ e`), `β`
//! the thread's pitch angle, `f = σ₀ z + σ₁ ż + σ₂ v` the friction coefficient and `M` the
//! friction moment, along `−e` on node 1 and `+e` on node 2. As MBDyn's, `sec γ` is of the
//! half thread angle as written (`ScrewJointSh_c` keeps it from its constructor). MBDyn
//! measures `v` as `e · R₁ᵀ(ω₂ − ω₁)`, the global axis against the relative angular velocity
//! in node 1's frame; romdyn takes both in the global frame (the same while node 1's
//! orientation is the identity, as in the collection's `screw_test_4.mbd`).

use super::anchor::{node_labels, Pair};
use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::friction::ModLugre;
use super::screw::Screw;
use crate::kinematics::{skew, Vec3};
use super::UnknownKind;
use crate::element::NonSmooth;
use crate::element::Outputs;

/// A screw joint with `modlugre` friction. Unknowns: the screw's turned angle and reaction,
/// then the friction state `z` [m].
#[derive(Clone, Debug)]
pub struct ScrewFriction {
    screw: Screw,
    model: ModLugre,
    /// `r / cos β` [m]: the sliding velocity per unit relative angular velocity.
    sliding_radius: f64,
    /// `r sec γ (1 + tan²β)` [m] and `sec γ tan β` of the shape coefficient.
    shape: (f64, f64),
}

/// Index of the friction state among the element's unknowns.
const STATE: usize = 2;

/// Sliding speed below which the joint is at rest for [`Element::non_smooth`] [m/s].
const STILL: f64 = 1e-6;

impl ScrewFriction {
    /// `radius` [m] the thread radius, `half_thread_angle` [rad].
    pub fn new(screw: Screw, model: ModLugre, radius: f64, half_thread_angle: f64) -> Self {
        let tan_pitch = screw.pitch / (2.0 * std::f64::consts::PI * radius);
        let sec_gamma = 1.0 / half_thread_angle.cos();
        let shape = (radius * sec_gamma * (1.0 + tan_pitch * tan_pitch), sec_gamma * tan_pitch);
        ScrewFriction { screw, model, sliding_radius: radius * (1.0 + tan_pitch * tan_pitch).sqrt(), shape }
    }

    /// The shape coefficient `c(f)` and `c'(f)`.
    fn shape_coefficient(&self, f: f64) -> (f64, f64) {
        let (a, b) = self.shape;
        let den = f * b - 1.0;
        (a * f / den, -a / (den * den))
    }

    /// Screw axis `e`, `sign(λ)` (MBDyn's: +1 at 0), sliding velocity `v` and `ω₂ − ω₁`.
    fn sliding(&self, p: &Pair, lambda: f64) -> (Vec3, f64, f64, Vec3) {
        let e = p.q_a.column(2).into_owned();
        let w = p.omega_b - p.omega_a;
        let sign = if lambda < 0.0 { -1.0 } else { 1.0 };
        (e, sign, sign * self.sliding_radius * e.dot(&w), w)
    }
}

impl Element for ScrewFriction {
    fn label(&self) -> Label {
        self.screw.label
    }
    fn type_name(&self) -> &'static str {
        "screw"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.screw.a, &self.screw.b)
    }
    fn multipliers(&self) -> Vec<String> {
        let mut m = self.screw.multipliers();
        m.push("friction state z".to_string());
        m
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        if k == STATE { UnknownKind::State } else { self.screw.unknown_kind(k) }
    }
    fn assembly_form(&self) -> Option<&dyn Element> {
        Some(&self.screw)
    }
    fn non_smoothness(&self) -> Option<&dyn NonSmooth> {
        Some(self)
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        self.screw.residual(st, out);
        let p = Pair::new(&self.screw.a, &self.screw.b, st);
        let lambda = st.multiplier(1);
        let (e, _, v, _) = self.sliding(&p, lambda);
        let (z, zdot) = (st.multiplier(STATE), st.rate(STATE));
        out.add(Row::Constraint(STATE), zdot + self.model.state_equation(z, v).value);
        // Applied moment +e M on node 2, −e M on node 1; residual rows are `… − M`.
        let moment = e * (self.shape_coefficient(self.model.coefficient(z, zdot, v)).0 * lambda);
        add_vec(out, Row::moment(p.slot_b), &(-moment));
        if let Some(a) = p.slot_a {
            add_vec(out, Row::moment(a), &moment);
        }
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        self.screw.jacobian(st, out);
        let p = Pair::new(&self.screw.a, &self.screw.b, st);
        let lambda = st.multiplier(1);
        let (e, sign, v, w) = self.sliding(&p, lambda);
        let (z, zdot) = (st.multiplier(STATE), st.rate(STATE));
        let m = &self.model;
        let f = m.coefficient(z, zdot, v);
        let (c, dc) = self.shape_coefficient(f);
        let psi = m.state_equation(z, v);
        // δv = sign(λ) (r/cos β) [e·(δω₂ − δω₁) + (e × w)·δθ₁] (δe = δθ₁ × e; sign(λ) is
        // constant away from λ = 0).
        let k = sign * self.sliding_radius;
        let mut dv: Vec<(Col, f64)> = Vec::new();
        for i in 0..3 {
            dv.push((Col::AngularVelocity { slot: p.slot_b, comp: i }, k * e[i]));
        }
        if let Some(a) = p.slot_a {
            let t = e.cross(&w) * k;
            for i in 0..3 {
                dv.push((Col::AngularVelocity { slot: a, comp: i }, -k * e[i]));
                dv.push((Col::Rotation { slot: a, comp: i }, t[i]));
            }
        }
        // State row: δψ = δż + ψ_/z δz + ψ_/v δv.
        let row = Row::Constraint(STATE);
        out.add(row, Col::Rate(STATE), 1.0);
        out.add(row, Col::Multiplier(STATE), psi.d_z);
        for &(col, d) in &dv {
            out.add(row, col, psi.d_v * d);
        }
        // δM = c δλ + λ c'(f) (σ₀ δz + σ₁ δż + σ₂ δv); node 1's row is +e M, node 2's −.
        let g = lambda * dc;
        let mut dmoment: Vec<(Col, f64)> = vec![(Col::Multiplier(1), c), (Col::Multiplier(STATE), g * m.sigma0), (Col::Rate(STATE), g * m.sigma1)];
        dmoment.extend(dv.iter().map(|&(col, d)| (col, g * m.sigma2 * d)));
        for (col, d) in dmoment {
            for i in 0..3 {
                out.add(Row::Equilibrium { slot: p.slot_b, comp: 3 + i }, col, -e[i] * d);
                if let Some(a) = p.slot_a {
                    out.add(Row::Equilibrium { slot: a, comp: 3 + i }, col, e[i] * d);
                }
            }
        }
        // The axis turns with node 1: δ(e M) = −M [e×] δθ₁ + …
        if let Some(a) = p.slot_a {
            let turn = -skew(&e) * (c * lambda);
            add_block(out, Row::moment(a), Col::rotation(a), &turn);
            add_block(out, Row::moment(p.slot_b), Col::rotation(a), &(-turn));
        }
    }
}

impl Outputs for ScrewFriction {
    fn private_data(&self, name: &str) -> Option<super::private_data::PrivateDatum> {
        self.screw.outputs()?.private_data(name)
    }
}

impl NonSmooth for ScrewFriction {
    fn non_smooth(&self, st: &dyn ElementState) -> Option<String> {
        let p = Pair::new(&self.screw.a, &self.screw.b, st);
        let (_, _, v, _) = self.sliding(&p, st.multiplier(1));
        let z = st.multiplier(STATE);
        (v.abs() < STILL && self.model.past_breakaway(z)).then(|| format!("its friction state z = {z:e} m is past the breakaway deflection at sliding velocity {v:.1e} m/s (at rest), where the modlugre state equation is not differentiable"))
    }
    fn kink_crossed(&self, from: &dyn ElementState, to: &dyn ElementState) -> Option<String> {
        let v = |st: &dyn ElementState| (self.sliding(&Pair::new(&self.screw.a, &self.screw.b, st), st.multiplier(1)).2, st.multiplier(STATE));
        self.model.kink_crossed(v(from), v(to))
    }
    fn reaction_dependence(&self, st: &dyn ElementState) -> Option<String> {
        let lambda = st.multiplier(1);
        (lambda != 0.0).then(|| format!("its friction moment and stiffness scale with the screw's reaction λ = {lambda:.9e} N as integrated, which steps accepted within the tolerance without a Newton iteration leave noisy; the eigenvalues carry that noise, which a tighter `tolerance` narrows"))
    }
}
