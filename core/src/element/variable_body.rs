//! Variable-mass rigid body on a dynamic structural node (MBDyn's `body: …, variable mass`,
//! input manual §Body, "Variable mass"; residual as body_vm.cc, `DynamicVariableBody::AssRes`).
//!
//! Mass `m(t)`, centre of mass `x_cm(t)` (node frame), inertia about the centre of mass
//! `J_m(t) + J_g(t)` (node frame: the mass-related and the geometry-related parts) are
//! drives of time. With `d = R x_cm`, `ḋ_t = R ẋ_cm` (the drive's rate only),
//! `v_cm = ẋ + ω × d + ḋ_t`, `S = m d`, `J = R (J_m + J_g) Rᵀ − m [d×]²`, the body adds
//!
//! - `−m v_cm` to the node's linear momentum definition,
//! - `−(S × ẋ + J ω)` to its angular momentum definition,
//! - `−(m g + ṁ v_cm)` to its force equilibrium (residual `β̇ − f`),
//! - `−(S × g + R J̇_m Rᵀ ω + d × ṁ v_cm + ẋ × m ḋ_t)` to its moment equilibrium.
//!
//! So `d(m v_cm)/dt = m g + ṁ v_cm + f`: the mass that leaves carries the body's velocity
//! (no thrust), and a body whose mass drops falls as a constant one. Two differences
//! from MBDyn 1.7.3's code, where its frames mix: it writes `J = R (J_m + J_g − m [d×]²) Rᵀ`
//! with the global offset `d` inside, and adds `J̇_m ω` with the node-frame `J̇_m`; romdyn
//! uses the node-frame offset and turns `J̇_m` to the global frame. Both agree when the
//! offset is zero or the node unrotated, and for an inertia whose rate is isotropic;
//! [`VariableBody::mbdyn_frames`] gives MBDyn's (tests compare the rest with it).
//! MBDyn's Jacobian leaves out the `ṁ` terms; romdyn's is the full derivative of the
//! residual above.

use super::contract::{add_block, add_vec, Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::drive::Drive;
use crate::kinematics::{skew, Mat3, Vec3};

/// A sum of `matrix · drive(t)` terms (a 3x3 template drive caller).
pub type MatrixTerms = Vec<(Mat3, Drive)>;
/// A sum of `vector · drive(t)` terms (a 3-vector template drive caller).
pub type VectorTerms = Vec<(Vec3, Drive)>;

/// A rigid body whose mass, centre of mass and inertia are drives of time.
#[derive(Clone, Debug)]
pub struct VariableBody {
    pub label: Label,
    pub node: Label,
    /// Mass [kg].
    pub mass: Drive,
    /// Centre of mass in the node frame [m].
    pub offset: VectorTerms,
    /// Mass-related inertia about the centre of mass, node frame [kg m²].
    pub inertia_mass: MatrixTerms,
    /// Geometry-related inertia about the centre of mass, node frame [kg m²].
    pub inertia_geometry: MatrixTerms,
    /// MBDyn 1.7.3's frames (body_vm.cc): `J = R (J_m + J_g − m [d×]²) Rᵀ` with the global
    /// offset `d` inside, and `J̇_m ω` with the node-frame `J̇_m`. Not read from files (the
    /// reader sets `false`); tests set it to compare the rest of the residual with MBDyn's
    /// numbers where the two differ. The Jacobian follows either choice.
    pub mbdyn_frames: bool,
}

/// The body's drives and their rates at one time.
struct Now {
    m: f64,
    m_rate: f64,
    /// Centre of mass and its rate, node frame.
    x_cm: Vec3,
    x_cm_rate: Vec3,
    /// `J_m + J_g` and `J̇_m`, node frame.
    j_cm: Mat3,
    j_m_rate: Mat3,
}

/// `ḋ(t)`; NaN for a drive romdyn does not differentiate (the reader refuses those; a body
/// built through the library with one has a NaN residual, named by [`Element::failure`]).
fn rate(d: &Drive, t: f64) -> f64 {
    d.time_derivative(t).unwrap_or(f64::NAN)
}

impl VariableBody {
    fn now(&self, t: f64) -> Now {
        let sum_v = |f: &dyn Fn(&Drive) -> f64| self.offset.iter().map(|(v, d)| v * f(d)).sum::<Vec3>();
        let sum_m = |terms: &MatrixTerms, f: &dyn Fn(&Drive) -> f64| terms.iter().map(|(m, d)| m * f(d)).sum::<Mat3>();
        Now {
            m: self.mass.value(t),
            m_rate: rate(&self.mass, t),
            x_cm: sum_v(&|d| d.value(t)),
            x_cm_rate: sum_v(&|d| rate(d, t)),
            j_cm: sum_m(&self.inertia_mass, &|d| d.value(t)) + sum_m(&self.inertia_geometry, &|d| d.value(t)),
            j_m_rate: sum_m(&self.inertia_mass, &|d| rate(d, t)),
        }
    }

    /// Whether every drive has a derivative romdyn computes (which drive kinds do does not
    /// depend on the time).
    fn differentiable(&self) -> bool {
        let t = 0.0;
        self.mass.time_derivative(t).is_some()
            && self.offset.iter().all(|(_, d)| d.time_derivative(t).is_some())
            && self.inertia_mass.iter().chain(&self.inertia_geometry).all(|(_, d)| d.time_derivative(t).is_some())
    }
}

/// The body's global quantities at a state: `d`, `ḋ_t`, `v_cm`, `S`, `J`, `R J̇_m Rᵀ`.
struct Global {
    d: Vec3,
    d_rate: Vec3,
    v_cm: Vec3,
    s: Vec3,
    j: Mat3,
    j_m_rate: Mat3,
}

fn global(now: &Now, st: &dyn ElementState, mbdyn_frames: bool) -> Global {
    let n = st.node(0);
    let d = n.r * now.x_cm;
    let d_rate = n.r * now.x_cm_rate;
    let dx = skew(&d);
    Global {
        d,
        d_rate,
        v_cm: n.xdot + n.omega.cross(&d) + d_rate,
        s: now.m * d,
        j: if mbdyn_frames { n.r * (now.j_cm - now.m * dx * dx) * n.r.transpose() } else { n.r * now.j_cm * n.r.transpose() - now.m * dx * dx },
        j_m_rate: if mbdyn_frames { now.j_m_rate } else { n.r * now.j_m_rate * n.r.transpose() },
    }
}

impl Element for VariableBody {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "variable body"
    }
    fn nodes(&self) -> Vec<Label> {
        vec![self.node]
    }
    fn failure(&self, _s: &dyn ElementState) -> Option<String> {
        (!self.differentiable()).then(|| format!("variable body {}: a drive of its mass, centre of mass or inertia has no time derivative romdyn computes (its rate is NaN)", self.label))
    }

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let now = self.now(st.time());
        let n = st.node(0);
        let b = global(&now, st, self.mbdyn_frames);
        let g = st.gravity();
        add_vec(out, Row::linear_momentum(0), &(-now.m * b.v_cm));
        add_vec(out, Row::angular_momentum(0), &(-(b.s.cross(&n.xdot) + b.j * n.omega)));
        add_vec(out, Row::force(0), &(-(now.m * g + now.m_rate * b.v_cm)));
        let moment = b.s.cross(&g) + b.j_m_rate * n.omega + b.d.cross(&(now.m_rate * b.v_cm)) + n.xdot.cross(&(now.m * b.d_rate));
        add_vec(out, Row::moment(0), &(-moment));
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let now = self.now(st.time());
        let n = st.node(0);
        let b = global(&now, st, self.mbdyn_frames);
        let (m, mp) = (now.m, now.m_rate);
        let (dx, wx, vx) = (skew(&b.d), skew(&n.omega), skew(&n.xdot));
        let i = Mat3::identity();
        // δd = −[d×] δθ, δḋ_t = −[ḋ_t×] δθ; δv_cm = δẋ − [d×] δω − ([ω×][d×] + [ḋ_t×]) δθ.
        let vcm_theta = -(wx * dx + skew(&b.d_rate));
        let (lin, ang, force, moment) = (Row::linear_momentum(0), Row::angular_momentum(0), Row::force(0), Row::moment(0));
        let (cth, cv, cw) = (Col::rotation(0), Col::velocity(0), Col::angular_velocity(0));
        // −m v_cm.
        add_block(out, lin, cv, &(-m * i));
        add_block(out, lin, cw, &(m * dx));
        add_block(out, lin, cth, &(-m * vcm_theta));
        // −(S × ẋ + J ω), J = R J_n Rᵀ: δ(J ω) = (J [ω×] − [Jω×]) δθ + J δω.
        let sx = skew(&b.s);
        add_block(out, ang, cv, &(-sx));
        add_block(out, ang, cw, &(-b.j));
        let mut j_omega_theta = b.j * wx - skew(&(b.j * n.omega));
        if self.mbdyn_frames {
            // J = R A Rᵀ, A = J_cm − m [d×]² with δd = −[d×] δθ: R δA Rᵀ ω =
            // −m R ([(d × u)×] + [d×][u×]) [d×] δθ, u = Rᵀ ω.
            let u = n.r.transpose() * n.omega;
            j_omega_theta -= m * n.r * (skew(&b.d.cross(&u)) + dx * skew(&u)) * dx;
        }
        add_block(out, ang, cth, &(-vx * sx - j_omega_theta));
        // −(m g + ṁ v_cm).
        add_block(out, force, cv, &(-mp * i));
        add_block(out, force, cw, &(mp * dx));
        add_block(out, force, cth, &(-mp * vcm_theta));
        // −(S × g + R J̇_m Rᵀ ω + ṁ d × v_cm + m ẋ × ḋ_t).
        let g = st.gravity();
        let (vcmx, drx) = (skew(&b.v_cm), skew(&b.d_rate));
        let jr = b.j_m_rate;
        let jr_theta = if self.mbdyn_frames { Mat3::zeros() } else { skew(&(jr * n.omega)) - jr * wx };
        add_block(out, moment, cth, &(-skew(&g) * sx + jr_theta - mp * vcmx * dx - mp * dx * vcm_theta + m * vx * drx));
        add_block(out, moment, cw, &(-jr + mp * dx * dx));
        add_block(out, moment, cv, &(-mp * dx + m * drx));
    }
}
