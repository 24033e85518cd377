//! MBDyn's 4-node membrane with enhanced assumed strains (`membrane4eas`, MBDyn 1.7.3's
//! membraneeas.cc): in-plane stiffness only, on four nodes' positions (displacement nodes
//! or structural nodes, whose rotations it leaves alone), linear elastic in the
//! Green–Lagrange strains, with 7 enhanced-strain parameters `β` as the element's own
//! algebraic unknowns. It has no inertia: masses go on the nodes (bodies).
//!
//! At Gauss point `i` (2×2, the shells' points and numbering, local Cartesian derivatives
//! `(·)_{,α}` through the initial metric in the initial surface frame), with
//! `y_α = Σ_n x_n L_{n,α}`, the strains are (total Lagrangian)
//!
//! `ε = (½(y₁·y₁ − 1), ½(y₂·y₂ − 1), y₁·y₂) − ε⁰ + P_i β`,
//!
//! the stress resultants `σ = D ε + σ₀` (3×3 `D` on (n₁₁, n₂₂, n₁₂), prestress `σ₀`), the
//! nodes get `Σ_i α_i Bᵢᵀ σ_i` and the `β` equations `Σ_i α_i P_iᵀ σ_i = 0`. The strains are
//! quadratic in the positions: `B` and the geometric stiffness `σ · ∂²ε` are exact in
//! closed form.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use super::enhanced::{self, Sampled};
use super::geometry::{cartesian_derivatives, membrane_enhanced_strain_matrix, metric, surface_frame, EAS, MEMBRANE_EAS, POINT_XI};
use super::ShellError;
use crate::element::contract::{Col, Element, ElementState, JacobianSink, Label, Outputs, ResidualSink, Row, UnknownKind};
use crate::kinematics::Vec3;

/// The membrane's section law: `σ = D ε + σ₀` on (n₁₁, n₂₂, n₁₂) [N/m] against
/// (ε₁₁, ε₂₂, ε₁₂).
#[derive(Clone, Debug)]
pub struct MembraneLaw {
    pub stiffness: Matrix3<f64>,
    pub prestress: Vector3<f64>,
}

impl MembraneLaw {
    /// The isotropic law of MBDyn's reader (membrane.cc, `isotropic`): `C = E h/(1 − ν²)`
    /// on ε₁₁, ε₂₂ with `ν C` between them, `2 G h` on ε₁₂ = `y₁·y₂`, the engineering shear
    /// strain: twice an isotropic sheet's `G h`, as MBDyn has it.
    pub fn isotropic(e: f64, nu: f64, g: f64, h: f64) -> Self {
        let c = e / (1.0 - nu * nu) * h;
        let stiffness = Matrix3::new(c, nu * c, 0.0, nu * c, c, 0.0, 0.0, 0.0, 2.0 * g * h);
        MembraneLaw { stiffness, prestress: Vector3::zeros() }
    }
}

/// Per Gauss point, what the constructor computed.
#[derive(Clone, Debug)]
struct Point {
    /// `∂L_n/∂s_α`, `[n][α]`.
    dl: [[f64; 2]; 4],
    area: f64,
    initial: Vector3<f64>,
    p: SMatrix<f64, 3, EAS>,
}

/// A 4-node EAS membrane (MBDyn's `membrane4eas`).
#[derive(Clone, Debug)]
pub struct Membrane4 {
    pub label: Label,
    nodes: [Label; 4],
    points: [Point; 4],
    law: MembraneLaw,
}

/// One evaluation: `B_i` (3 × 12) and `σ_i` per Gauss point.
struct State {
    b: [SMatrix<f64, 3, 12>; 4],
    stress: [SVector<f64, 3>; 4],
}

const NAME: &str = "membrane4eas";

impl Membrane4 {
    /// A membrane on four nodes (label, initial position), unstrained there.
    pub fn new(label: Label, nodes: [(Label, Vec3); 4], law: MembraneLaw) -> Result<Self, ShellError> {
        let x: [Vec3; 4] = std::array::from_fn(|n| nodes[n].1);
        let s0 = metric(&x, &surface_frame(&x, [0.0, 0.0]), [0.0, 0.0]);
        let area0 = s0.determinant();
        let mut points = Vec::with_capacity(4);
        for xi in POINT_XI {
            let (dl, area) = cartesian_derivatives(&x, &surface_frame(&x, xi), xi).map_err(|area| ShellError::Degenerate(NAME, label, area))?;
            points.push(Point { dl, area, initial: Vector3::zeros(), p: membrane_enhanced_strain_matrix(&s0, xi, area0 / area) });
        }
        let mut membrane = Membrane4 { label, nodes: std::array::from_fn(|n| nodes[n].0), points: points.try_into().expect("four Gauss points"), law };
        for k in 0..4 {
            membrane.points[k].initial = membrane.green_lagrange(k, &x).0;
        }
        Ok(membrane)
    }

    /// At Gauss point `i`: `(½(y₁·y₁ − 1), ½(y₂·y₂ − 1), y₁·y₂)` and `y₁, y₂`.
    fn green_lagrange(&self, i: usize, x: &[Vec3; 4]) -> (Vector3<f64>, [Vec3; 2]) {
        let dl = &self.points[i].dl;
        let y: [Vec3; 2] = std::array::from_fn(|a| (0..4).map(|n| x[n] * dl[n][a]).sum());
        (Vector3::new(0.5 * (y[0].norm_squared() - 1.0), 0.5 * (y[1].norm_squared() - 1.0), y[0].dot(&y[1])), y)
    }

    fn state(&self, s: &dyn ElementState) -> State {
        let x: [Vec3; 4] = std::array::from_fn(|n| s.node(n).x);
        let beta = SVector::<f64, EAS>::from_fn(|k, _| if k < MEMBRANE_EAS { s.multiplier(k) } else { 0.0 });
        let mut b = [SMatrix::<f64, 3, 12>::zeros(); 4];
        let mut stress = [SVector::<f64, 3>::zeros(); 4];
        for (i, p) in self.points.iter().enumerate() {
            let (e, y) = self.green_lagrange(i, &x);
            for n in 0..4 {
                for c in 0..3 {
                    b[i][(0, 3 * n + c)] = y[0][c] * p.dl[n][0];
                    b[i][(1, 3 * n + c)] = y[1][c] * p.dl[n][1];
                    b[i][(2, 3 * n + c)] = y[0][c] * p.dl[n][1] + y[1][c] * p.dl[n][0];
                }
            }
            stress[i] = self.law.stiffness * (e - p.initial + p.p * beta) + self.law.prestress;
        }
        State { b, stress }
    }

    fn sampled_points<'a>(&'a self, st: &'a State) -> impl Iterator<Item = Sampled<'a, 3, 12>> {
        self.points.iter().enumerate().map(|(i, p)| Sampled { b: &st.b[i], p: &p.p, stress: &st.stress[i], area: p.area })
    }
}

impl Element for Membrane4 {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        NAME
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.to_vec()
    }
    fn multipliers(&self) -> Vec<String> {
        (1..=MEMBRANE_EAS).map(|k| format!("enhanced strain parameter {k}")).collect()
    }
    /// As the shells': algebraic unknowns of the configuration (MBDyn's
    /// `DofOrder::ALGEBRAIC`).
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::VelocityConstraint
    }
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink) {
        let st = self.state(s);
        let (fq, fb) = enhanced::internal_forces(self.sampled_points(&st));
        for q in 0..12 {
            out.add(Row::Equilibrium { slot: q / 3, comp: q % 3 }, fq[q]);
        }
        for k in 0..MEMBRANE_EAS {
            out.add(Row::Constraint(k), fb[k]);
        }
    }
    fn jacobian(&self, s: &dyn ElementState, out: &mut dyn JacobianSink) {
        let st = self.state(s);
        let (mut kqq, kqb, kbb) = enhanced::linear_tangent(&self.law.stiffness, self.sampled_points(&st));
        // σ · ∂²ε: σ₁₁ L_{n,1} L_{m,1} + σ₂₂ L_{n,2} L_{m,2} + σ₁₂ (L_{n,1} L_{m,2} + L_{n,2} L_{m,1})
        // on each component.
        for (i, p) in self.points.iter().enumerate() {
            let sigma = &st.stress[i];
            for n in 0..4 {
                for m in 0..4 {
                    let (a, b) = (p.dl[n], p.dl[m]);
                    let g = p.area * (sigma[0] * a[0] * b[0] + sigma[1] * a[1] * b[1] + sigma[2] * (a[0] * b[1] + a[1] * b[0]));
                    for c in 0..3 {
                        kqq[(3 * n + c, 3 * m + c)] += g;
                    }
                }
            }
        }
        let row = |q: usize| Row::Equilibrium { slot: q / 3, comp: q % 3 };
        let col = |q: usize| Col::Position { slot: q / 3, comp: q % 3 };
        enhanced::add_tangent(out, (&kqq, &kqb, &kbb), MEMBRANE_EAS, row, col);
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
}

impl Outputs for Membrane4 {
    /// MBDyn's `.pla` row: `σ_i = D (ε_i + P_i β) + σ₀` (n₁₁, n₂₂, n₁₂) at the four Gauss
    /// points.
    fn plate_resultants(&self, s: &dyn ElementState) -> Vec<f64> {
        self.state(s).stress.iter().flat_map(|v| v.iter().copied()).collect()
    }
}
