//! The inertia invariants of a modal body (MBDyn's technical manual, "Modal element";
//! modal.cc, `ReadModal`): integrals of the lumped FEM masses and mode shapes that make
//! the kinetic energy of the floating frame formulation ([`super`]) a function of a few
//! small matrices, independent of the FEM node count.

use crate::kinematics::{skew, Mat3, Vec3};

/// The FEM data the invariants come from, in the floating frame (FEM frame shifted to the
/// origin the element puts at the modal node).
#[derive(Clone, Debug)]
pub struct Component {
    /// FEM node positions [m].
    pub positions: Vec<Vec3>,
    /// Mode shapes, `[mode][node]`: translation [m] and rotation [rad] per unit coordinate.
    pub translations: Vec<Vec<Vec3>>,
    pub rotations: Vec<Vec<Vec3>>,
    /// Lumped nodal mass [kg] and rotational inertias about x, y, z [kg m²] (record 11);
    /// without them the body has no modal–rigid coupling (MBDyn builds no invariants).
    pub lumped: Option<Vec<(f64, Vec3)>>,
    /// Rigid-body inertia when given apart (record 12): mass [kg], centre of mass [m] and
    /// inertia about it [kg m²]; it replaces the lumped masses' in `m`, `I₂`, `I₇`.
    pub rigid: Option<(f64, Vec3, Mat3)>,
    /// `use invariant 9`: keep the inertia's quadratic dependence on `q`.
    pub invariant_9: bool,
}

/// The invariants, in the floating frame.
#[derive(Clone, Debug)]
pub struct Invariants {
    /// Mass [kg] (invariant 1).
    pub mass: f64,
    /// Static moment about the origin, undeformed [kg m] (invariant 2).
    pub static_moment: Vec3,
    /// Inertia about the origin, undeformed [kg m²] (invariant 7).
    pub inertia: Mat3,
    /// `I₃ⱼ = Σ mₙ Φtₙⱼ`: the static moment per unit `qⱼ` (invariant 3).
    pub i3: Vec<Vec3>,
    /// `I₄ⱼ = Σ mₙ f₀ₙ × Φtₙⱼ + Jₙ Φrₙⱼ` (invariant 4, with invariant 11's rotational part).
    pub i4: Vec<Vec3>,
    /// `I₅ⱼₖ = Σ mₙ Φtₙⱼ × Φtₙₖ` (invariant 5), `[j][k]`.
    pub i5: Vec<Vec<Vec3>>,
    /// `dJⱼ = ∂J/∂qⱼ` at `q = 0`: invariant 8 `−Σ mₙ [f₀ₙ×][Φtₙⱼ×]` and invariant 10
    /// `Σ [Φrₙⱼ×] Jₙ`, each with its transpose (symmetric).
    pub d_inertia: Vec<Mat3>,
    /// `Hⱼₖ = ∂²J/∂qⱼ∂qₖ = −Σ mₙ ([Φtₙⱼ×][Φtₙₖ×] + [Φtₙₖ×][Φtₙⱼ×])` (invariant 9), when used.
    pub dd_inertia: Option<Vec<Vec<Mat3>>>,
}

impl Invariants {
    pub fn of(c: &Component) -> Self {
        let modes = c.translations.len();
        let mut inv = Invariants { mass: 0.0, static_moment: Vec3::zeros(), inertia: Mat3::zeros(), i3: vec![Vec3::zeros(); modes], i4: vec![Vec3::zeros(); modes], i5: vec![vec![Vec3::zeros(); modes]; modes], d_inertia: vec![Mat3::zeros(); modes], dd_inertia: c.invariant_9.then(|| vec![vec![Mat3::zeros(); modes]; modes]) };
        if let Some(lumped) = &c.lumped {
            for (n, (m, rot)) in lumped.iter().enumerate() {
                let f = c.positions[n];
                let jn = Mat3::from_diagonal(rot);
                inv.mass += m;
                inv.static_moment += *m * f;
                inv.inertia += jn - *m * skew(&f) * skew(&f);
                for j in 0..modes {
                    let (t, r) = (c.translations[j][n], c.rotations[j][n]);
                    inv.i3[j] += *m * t;
                    inv.i4[j] += *m * f.cross(&t) + jn * r;
                    let d8 = -*m * skew(&f) * skew(&t);
                    let d10 = skew(&r) * jn;
                    inv.d_inertia[j] += d8 + d8.transpose() + d10 + d10.transpose();
                    for k in 0..modes {
                        let tk = c.translations[k][n];
                        inv.i5[j][k] += *m * t.cross(&tk);
                        if let Some(h) = &mut inv.dd_inertia {
                            h[j][k] -= *m * (skew(&t) * skew(&tk) + skew(&tk) * skew(&t));
                        }
                    }
                }
            }
        }
        if let Some((m, cm, j_cm)) = c.rigid {
            inv.mass = m;
            inv.static_moment = m * cm;
            inv.inertia = j_cm - m * skew(&cm) * skew(&cm);
        }
        inv
    }

    pub fn modes(&self) -> usize {
        self.i3.len()
    }

    /// `s(q) = I₂ + I₃ q`.
    pub fn static_moment_at(&self, q: &[f64]) -> Vec3 {
        self.static_moment + self.i3.iter().zip(q).map(|(a, qj)| a * *qj).sum::<Vec3>()
    }

    /// `J(q)`.
    pub fn inertia_at(&self, q: &[f64]) -> Mat3 {
        let mut j = self.inertia;
        for (dj, qj) in self.d_inertia.iter().zip(q) {
            j += dj * *qj;
        }
        if let Some(h) = &self.dd_inertia {
            for (a, qa) in q.iter().enumerate() {
                for (b, qb) in q.iter().enumerate() {
                    j += h[a][b] * (0.5 * qa * qb);
                }
            }
        }
        j
    }

    /// `∂J/∂qⱼ = dJⱼ + Σₖ qₖ Hⱼₖ`.
    pub fn inertia_derivative(&self, j: usize, q: &[f64]) -> Mat3 {
        let mut d = self.d_inertia[j];
        if let Some(h) = &self.dd_inertia {
            for (k, qk) in q.iter().enumerate() {
                d += h[j][k] * *qk;
            }
        }
        d
    }

    /// Column `k` of `B(q) = I₄ + Σⱼ qⱼ I₅ⱼ`.
    pub fn coupling_column(&self, k: usize, q: &[f64]) -> Vec3 {
        self.i4[k] + (0..q.len()).map(|j| self.i5[j][k] * q[j]).sum::<Vec3>()
    }

    /// `I₅ⱼ q̇ = Σₖ I₅ⱼₖ q̇ₖ`.
    pub fn i5_times(&self, j: usize, qdot: &[f64]) -> Vec3 {
        self.i5[j].iter().zip(qdot).map(|(v, d)| v * *d).sum()
    }
}
