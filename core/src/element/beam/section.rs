//! Strains, curvatures and their rates at one evaluation point of the 3-node beam, with
//! their derivatives with respect to the element's 36 node perturbations.
//!
//! Node `i` has position `x_i`, orientation `R_i` (initially `R_i⁰`), offset `f_i`; the
//! reference line passes through `y_i = x_i + R_i f_i`. Rotations are interpolated relative
//! to the middle node (objective, any rigid rotation): `T = R_2 R_2⁰ᵀ`,
//! `Δ_i = Tᵀ R_i R_i⁰ᵀ = R(g_i)` (`g_2 = 0`), `g(ξ) = Σ N_i g_i` and the section frame
//! `R_s = T R(g) R_s⁰`. Then
//!
//! - `p = Σ N_i y_i`, `p′ = Σ N_i′ y_i / (ds/dξ)`;
//! - strain `ε = R_sᵀ p′ − ε⁰`, with `ε⁰ = R_s⁰ᵀ p′⁰` (the initial state is unstrained);
//! - curvature `κ = R_s⁰ᵀ Gᵀ(g) g′` (the change of `R_sᵀ ax(R_s′ R_sᵀ)`, since `R(g)ᵀ G(g) = Gᵀ(g)`);
//! - rates `ε̇ = R_sᵀ (ṗ′ + p′ × ω_s)`, `κ̇ = R_s⁰ᵀ (∂(Gᵀg′)/∂g ġ + Gᵀ ġ′)`, with
//!   `ġ_i = Γ(g_i) Tᵀ (ω_i − ω_2)` and `ω_s = ω_2 + T G(g) ġ`.
//!
//! With MBDyn's incremental update ([`NodeTerms::incremental`], the opt-in
//! [`super::BeamUpdate::Incremental`]) the rotations are instead interpolated from fixed
//! per-step node orientations `P_i` (the predicted ones, or the previous converged ones
//! for the predictor step): `T = I`, `R(g_i) = R_i P_iᵀ` for all three nodes, `R_s = R(g)
//! R_s,ref` and `κ = R_s,refᵀ Gᵀ(g) g′ + κ_ref` (MBDyn 1.7.3 beam.cc, `AfterPredict` and
//! `AssStiffnessVec`: `R_sᵀ G(g) g′` is the same vector), with `R_s,ref`, `κ_ref` the
//! per-step history in [`SectionReference::orientation`] and
//! [`SectionReference::accumulated_curvature`].
//!
//! Each derivative is a [`Tangent`] with the columns of [`super::finite_volume::column`]:
//! `C = 18` (positions and rotations of the three nodes) for an elastic law, `C = 36` (and
//! the velocities) for a viscous one.

use nalgebra::SMatrix;

use super::shape;
use crate::element::contract::ElementState;
use crate::kinematics::{gibbs_from_rotation, gibbs_g, gibbs_g_inverse, gibbs_g_inverse_derivative, gibbs_gt_apply, gibbs_gt_derivative, gibbs_gt_derivative_in_a, gibbs_gt_second_derivative, gibbs_rate_derivative, gibbs_rotation, skew, Mat3, Vec3};

/// Derivative of a 3-vector with respect to the element's `C` node perturbations.
pub type Tangent<const C: usize> = SMatrix<f64, 3, C>;

use super::finite_volume::{embed, put_rotation, strain_tangent, RotationTangent, ANGULAR_VELOCITY, POSITION, ROTATION, VELOCITY};

/// A tangent on the nine rotation columns ([`RotationTangent`]).
pub type Rotational = RotationTangent<9>;

/// `t[:, block(node, kind)] += m` on the 3-node element.
fn put<const C: usize>(t: &mut Tangent<C>, node: usize, kind: usize, m: &Mat3) {
    super::finite_volume::put(t, 3, node, kind, m);
}

fn single<const C: usize>(node: usize, kind: usize, m: &Mat3) -> Tangent<C> {
    let mut t = Tangent::zeros();
    put(&mut t, node, kind, m);
    t
}

/// What an evaluation point needs from its element's reference configuration.
#[derive(Clone, Debug)]
pub struct SectionReference {
    pub xi: f64,
    /// `R_s⁰`: the section frame in the initial configuration.
    pub orientation: Mat3,
    /// `ds/dξ` in the initial configuration [m].
    pub dsdxi: f64,
    /// `ε⁰ = R_s⁰ᵀ p′⁰` (axis 1 for a beam straight along its section axis).
    pub initial_strain: Vec3,
    /// `κ_ref`, added to the curvature: the history of the incremental update (`None` for
    /// the path-independent beam).
    pub accumulated_curvature: Option<Vec3>,
}

/// Per-element values shared by both evaluation points (no derivatives: the residual
/// needs none; [`NodeTerms::tangents`] adds them for the Jacobian).
pub struct NodeTerms {
    /// `T = R_2 R_2⁰ᵀ` (identity for the incremental update).
    t: Mat3,
    /// Whether the rotations are relative to the middle node (`g_2 = 0`), else to fixed
    /// per-step orientations ([`NodeTerms::incremental`]).
    middle_relative: bool,
    x: [Vec3; 3],
    /// `a_i = R_i f_i`.
    a: [Vec3; 3],
    y: [Vec3; 3],
    g: [Vec3; 3],
    omega: [Vec3; 3],
    /// `ẏ_i`, `ġ_i`, when the law is viscous.
    rates: Option<NodeRates>,
}

struct NodeRates {
    ydot: [Vec3; 3],
    gdot: [Vec3; 3],
}

/// Derivatives of the node terms with respect to the element's perturbations.
pub struct NodeTangents<const C: usize> {
    dy: [Tangent<C>; 3],
    dg: [Rotational; 3],
    /// `∂ẏ_i`, `∂ġ_i`, when the law is viscous.
    rates: Option<([Tangent<C>; 3], [Tangent<C>; 3])>,
}

impl NodeTerms {
    pub fn new(st: &dyn ElementState, offsets: &[Vec3; 3], initial: &[Mat3; 3], with_rates: bool) -> Self {
        let n = [st.node(0), st.node(1), st.node(2)];
        let t = n[1].r * initial[1].transpose();
        let tt = t.transpose();
        let a: [Vec3; 3] = std::array::from_fn(|i| n[i].r * offsets[i]);
        let y = std::array::from_fn(|i| n[i].x + a[i]);
        let mut g = [Vec3::zeros(); 3];
        for i in [0, 2] {
            g[i] = gibbs_from_rotation(&(tt * n[i].r * initial[i].transpose()));
        }
        let omega = std::array::from_fn(|i| n[i].omega);
        let rates = with_rates.then(|| {
            let ydot = std::array::from_fn(|i| n[i].xdot + n[i].omega.cross(&a[i]));
            let mut gdot = [Vec3::zeros(); 3];
            for i in [0, 2] {
                gdot[i] = gibbs_g_inverse(&g[i]) * (tt * (n[i].omega - n[1].omega));
            }
            NodeRates { ydot, gdot }
        });
        NodeTerms { t, middle_relative: true, x: std::array::from_fn(|i| n[i].x), a, y, g, omega, rates }
    }

    /// The node terms of MBDyn's incremental update: `R(g_i) = R_i P_iᵀ` for all three
    /// nodes, `T = I` (no rates: viscous laws are refused with this update).
    pub fn incremental(st: &dyn ElementState, offsets: &[Vec3; 3], base: &[Mat3; 3]) -> Self {
        let n = [st.node(0), st.node(1), st.node(2)];
        let a: [Vec3; 3] = std::array::from_fn(|i| n[i].r * offsets[i]);
        let y = std::array::from_fn(|i| n[i].x + a[i]);
        let g: [Vec3; 3] = std::array::from_fn(|i| gibbs_from_rotation(&(n[i].r * base[i].transpose())));
        let omega = std::array::from_fn(|i| n[i].omega);
        NodeTerms { t: Mat3::identity(), middle_relative: false, x: std::array::from_fn(|i| n[i].x), a, y, g, omega, rates: None }
    }

    /// The nodes' positions `x_i`.
    pub fn x(&self) -> &[Vec3; 3] {
        &self.x
    }

    /// `∂y_i`, `∂g_i` (and `∂ẏ_i`, `∂ġ_i` when viscous).
    pub fn tangents<const C: usize>(&self) -> NodeTangents<C> {
        let (a, tt) = (&self.a, self.t.transpose());
        // `Γ(g_i) = G(g_i)⁻¹` (`g_2 = 0` when relative to the middle node: not needed).
        let mut gamma = [Mat3::identity(); 3];
        for i in 0..3 {
            if !self.middle_relative || i != 1 {
                gamma[i] = gibbs_g_inverse(&self.g[i]);
            }
        }
        let dy = std::array::from_fn(|i| {
            let mut d = single(i, POSITION, &Mat3::identity());
            put(&mut d, i, ROTATION, &-skew(&a[i]));
            d
        });
        let mut dg = [Rotational::zeros(); 3];
        if self.middle_relative {
            for i in [0, 2] {
                // δg_i = Γ(g_i) Tᵀ (δθ_i − δθ_2).
                let m = gamma[i] * tt;
                put_rotation(&mut dg[i], i, &m);
                put_rotation(&mut dg[i], 1, &-m);
            }
        } else {
            for (i, d) in dg.iter_mut().enumerate() {
                // δg_i = Γ(g_i) δθ_i (the base P_i is fixed).
                put_rotation(d, i, &gamma[i]);
            }
        }
        let rates = self.rates.as_ref().map(|_| {
            let omega = &self.omega;
            let dydot = std::array::from_fn(|i| {
                let mut d = single(i, VELOCITY, &Mat3::identity());
                put(&mut d, i, ANGULAR_VELOCITY, &-skew(&a[i]));
                put(&mut d, i, ROTATION, &(-skew(&omega[i]) * skew(&a[i])));
                d
            });
            let mut dgdot = [Tangent::zeros(); 3];
            for i in [0, 2] {
                let rel = omega[i] - omega[1];
                let w = tt * rel;
                // δw = Tᵀ (δω_i − δω_2) + Tᵀ [(ω_i − ω_2)×] δθ_2.
                let mut dw = single(i, ANGULAR_VELOCITY, &tt);
                put(&mut dw, 1, ANGULAR_VELOCITY, &-tt);
                put(&mut dw, 1, ROTATION, &(tt * skew(&rel)));
                dgdot[i] = gibbs_g_inverse_derivative(&self.g[i], &w) * embed::<C, 9>(&dg[i]) + gamma[i] * dw;
            }
            (dydot, dgdot)
        });
        NodeTangents { dy, dg, rates }
    }
}

/// The state of one evaluation point (values, and what its derivatives reuse).
pub struct SectionKinematics {
    /// Position `p` of the reference line [m].
    pub p: Vec3,
    /// Section frame `R_s`.
    pub r: Mat3,
    /// Strain `ε` and curvature `κ` [1/m] in the section frame.
    pub strain: Vec3,
    pub curvature: Vec3,
    pub strain_rate: Vec3,
    pub curvature_rate: Vec3,
    nv: [f64; 3],
    nd: [f64; 3],
    /// `p′`, `g`, `g′`, `R_s⁰ᵀ`.
    pp: Vec3,
    g: Vec3,
    gp: Vec3,
    r0t: Mat3,
    rates: Option<SectionRates>,
}

/// Rate terms of an evaluation point that its derivatives reuse.
struct SectionRates {
    gd: Vec3,
    gpd: Vec3,
    spin: Vec3,
    omega: Vec3,
    u: Vec3,
}

/// Derivatives of an evaluation point's state with respect to the element's perturbations.
pub struct SectionTangents<const C: usize> {
    pub dp: Tangent<C>,
    /// Virtual rotation of the section frame (rotation columns: it depends on the nodes'
    /// rotations alone, as the curvature does).
    pub dtheta: Rotational,
    pub dstrain: Tangent<C>,
    pub dcurvature: Rotational,
    /// `(∂ε̇, ∂κ̇)` when the law is viscous.
    pub rates: Option<(Tangent<C>, Tangent<C>)>,
}

/// `Σ w_i v_i` (interpolation from the nodes).
pub fn combine(w: &[f64; 3], v: &[Vec3; 3]) -> Vec3 {
    w[0] * v[0] + w[1] * v[1] + w[2] * v[2]
}

fn combine_t<const C: usize>(w: &[f64; 3], v: &[SMatrix<f64, 3, C>; 3]) -> SMatrix<f64, 3, C> {
    v[0] * w[0] + v[1] * w[1] + v[2] * w[2]
}

impl SectionKinematics {
    pub fn new(node: &NodeTerms, reference: &SectionReference) -> Self {
        let nv = shape::values(reference.xi);
        let nd = shape::derivatives(reference.xi).map(|d| d / reference.dsdxi);
        let (p, pp) = (combine(&nv, &node.y), combine(&nd, &node.y));
        let (g, gp) = (combine(&nv, &node.g), combine(&nd, &node.g));
        let r0t = reference.orientation.transpose();
        let r = node.t * gibbs_rotation(&g) * reference.orientation;
        let rt = r.transpose();
        let strain = rt * pp - reference.initial_strain;
        let mut curvature = r0t * gibbs_gt_apply(&g, &gp);
        if let Some(kappa_ref) = &reference.accumulated_curvature {
            curvature += kappa_ref;
        }
        let mut s = SectionKinematics { p, r, strain, curvature, strain_rate: Vec3::zeros(), curvature_rate: Vec3::zeros(), nv, nd, pp, g, gp, r0t, rates: None };
        if let Some(rates) = &node.rates {
            let (tg, dgt_gp) = (node.t * gibbs_g(&g), gibbs_gt_derivative(&g, &gp));
            let ppd = combine(&nd, &rates.ydot);
            let (gd, gpd) = (combine(&nv, &rates.gdot), combine(&nd, &rates.gdot));
            let spin = tg * gd;
            let omega = node.omega[1] + spin;
            let u = ppd + pp.cross(&omega);
            s.strain_rate = rt * u;
            s.curvature_rate = r0t * (dgt_gp * gd + gibbs_gt_apply(&g, &gpd));
            s.rates = Some(SectionRates { gd, gpd, spin, omega, u });
        }
        s
    }

    /// The derivatives of this point's state, from its element's node tangents.
    pub fn tangents<const C: usize>(&self, node: &NodeTerms, nt: &NodeTangents<C>) -> SectionTangents<C> {
        let (nv, nd, pp, g, gp) = (&self.nv, &self.nd, &self.pp, &self.g, &self.gp);
        // `G(g)`, `T G(g)`, `∂(Gᵀ(g) g′)/∂g`: what only the derivatives use.
        let gm = &gibbs_g(g);
        let (tg, dgt_gp) = (node.t * gm, gibbs_gt_derivative(g, gp));
        let rt = self.r.transpose();
        let (dp, dpp) = (combine_t(nv, &nt.dy), combine_t(nd, &nt.dy));
        let (dg, dgp) = (combine_t(nv, &nt.dg), combine_t(nd, &nt.dg));
        let mut dtheta = tg * dg;
        if node.middle_relative {
            put_rotation(&mut dtheta, 1, &Mat3::identity());
        }
        let dstrain = strain_tangent(&rt, &dpp, pp, &dtheta);
        let dcurvature = self.r0t * (dgt_gp * dg + gm.transpose() * dgp);
        let mut s = SectionTangents { dp, dtheta, dstrain, dcurvature, rates: None };
        if let (Some(r), Some((dydot, dgdot))) = (&self.rates, &nt.rates) {
            let dppd = combine_t(nd, dydot);
            let (dgd, dgpd) = (combine_t(nv, dgdot), combine_t(nd, dgdot));
            let (dg, dgp) = (embed::<C, 9>(&dg), embed::<C, 9>(&dgp));
            let mut domega = node.t * (gibbs_rate_derivative(g, &r.gd) * dg + gm * dgd);
            put(&mut domega, 1, ANGULAR_VELOCITY, &Mat3::identity());
            put(&mut domega, 1, ROTATION, &-skew(&r.spin));
            let dstrain_rate = rt * (skew(&r.u) * embed::<C, 9>(&s.dtheta) + dppd + skew(pp) * domega - skew(&r.omega) * dpp);
            let dg_total = (gibbs_gt_second_derivative(g, gp, &r.gd) + gibbs_gt_derivative(g, &r.gpd)) * dg;
            let dcurvature_rate = self.r0t * (dg_total + dgt_gp * dgd + gibbs_gt_derivative_in_a(g, &r.gd) * dgp + gm.transpose() * dgpd);
            s.rates = Some((dstrain_rate, dcurvature_rate));
        }
        s
    }
}
