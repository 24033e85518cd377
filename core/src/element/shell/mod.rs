//! MBDyn's 4-node shells (MBDyn 1.7.3's shelleas.cc and shelleasans.cc, after Witkowski,
//! "4-node combined shell element with semi-EAS-ANS strain interpolations in 6-parameter
//! shell theories with drilling degrees of freedom", Comput Mech 43 (2009) 307–319): a
//! 6-parameter (drilling) shell on four structural nodes, linear elastic, with
//! enhanced-strain parameters `β` as the element's own algebraic unknowns (not condensed,
//! as MBDyn has them). It has no inertia: masses go on the nodes (bodies). Two variants
//! ([`ShellVariant`]):
//!
//! - `shell4eas`: 13 parameters enhance the membrane and the transverse shear strains;
//! - `shell4easans`: 7 parameters enhance the membrane strains only, and the transverse
//!   shear strains are assumed natural strains (ANS, Witkowski §3.2): sampled at the
//!   midpoints of the edges (tying points A (0, 1), B (−1, 0), C (0, −1), D (1, 0)) and
//!   interpolated to the Gauss points, `ε_13 = ½(1 + ξ₂) ε_13^A + ½(1 − ξ₂) ε_13^C`,
//!   `ε_23 = ½(1 − ξ₁) ε_23^B + ½(1 + ξ₁) ε_23^D`. The tying points' strains are, as
//!   MBDyn has them, components in each point's Cartesian frame (`t₁` along `∂x/∂ξ₁`), not
//!   covariant ones: on rectangles the element converges faster than `shell4eas`, on
//!   skewed thin meshes it locks in shear (tests/multibody/shell_ans.rs).
//!
//! With `T̄` the average of the nodes' initial surface frames, each node's rotation relative
//! to it `φ_n = rotvec(T̄ᵀ R_n T_nᵒ)` (`T_nᵒ` the node's surface frame in its own frame) is
//! interpolated bilinearly to the Gauss points: `T_i = T̄ exp(φ_i) T_iᵒ`. The strains at
//! Gauss point `i` (local Cartesian derivatives `(·)_{,α}` through the initial metric) are
//!
//! - `ε_α = T_iᵀ x_{,α} − ε_α⁰` (membrane `ε_α1, ε_α2`, transverse shear `ε_α3`),
//! - `κ_α = T_iᵀ T̄ Γ(φ_i) φ_{,α} − κ_α⁰` (bending, twist and drilling),
//!
//! plus the enhanced part `P_i β`. The stress resultants `σ = D (ε + P_i β) + σ₀` (12×12
//! `D`, prestress `σ₀`) do virtual work on `δε`: nodes get `Σ_i α_i Bᵢᵀ σ_i` and the `β`
//! equations `Σ_i α_i P_iᵀ σ_i = 0` (`α_i` the area factor).
//!
//! `T̄` stays at its initial value. MBDyn recomputes it from each step's reference
//! rotations; within one step (a static solution in one load step, an eigenanalysis about
//! the initial configuration) the two coincide, over many steps of large rotations they
//! differ in the interpolation of the rotations only.
//!
//! Derivatives are exact: the strains are one function generic over the scalar
//! ([`hyper`]), evaluated with hyper-dual numbers for `B` and for the geometric stiffness
//! `σ · ∂²ε` (MBDyn's tangent of `shell4easans` takes the geometric part at the Gauss
//! points, not through the tying points).

pub mod enhanced;
pub mod geometry;
pub mod hyper;
pub mod membrane;

use nalgebra::{SMatrix, SVector};

use self::enhanced::Sampled;
use self::geometry::{enhanced_strain_matrix, metric, shape, surface_frame, EAS, MEMBRANE_EAS, POINT_XI, TYING_XI};
use self::hyper::{add, cst_m, lift, mat_mat, mat_t_vec, mat_vec, rotation, scale, tangent, Hyper, Real, M3, V3};
use crate::element::contract::{Col, Element, ElementState, JacobianSink, Label, Outputs, ResidualSink, Row, UnknownKind};
use crate::kinematics::{rotation_vector, Mat3, Vec3};

/// The shell's section law: `σ = D ε + σ₀` in MBDyn's order (n₁₁, n₁₂, n₁₃, n₂₁, n₂₂, n₂₃,
/// m₁₁, …, m₂₃) against (ε₁₁, …, ε₂₃, κ₁₁, …, κ₂₃).
#[derive(Clone, Debug)]
pub struct ShellLaw {
    pub stiffness: SMatrix<f64, 12, 12>,
    pub prestress: SVector<f64, 12>,
}

impl ShellLaw {
    /// The isotropic law of MBDyn's reader (shell.cc, `isotropic`): `C = E h/(1 − ν²)`,
    /// `D = C h²/12`, `G h`, `F = G h³/12`; membrane `C`, `ν C`, in-plane shear `2 G h`,
    /// transverse shear `a_s G h`; bending `D`, `−ν D`, twist `2 F`, drilling `a_t F`.
    pub fn isotropic(e: f64, nu: f64, g: f64, h: f64, shear_factor: f64, drilling_factor: f64) -> Self {
        let c = e / (1.0 - nu * nu) * h;
        let d = c * h * h / 12.0;
        let gh = g * h;
        let f = gh * h * h / 12.0;
        Self::from_terms([c, c, c * nu], [2.0 * gh, gh * shear_factor], [d, d, -d * nu], [2.0 * f, f * drilling_factor])
    }

    /// MBDyn's `plane stress orthotropic` law (shell.cc), the orthotropy axes along the
    /// element's first surface direction: with `C = h/(1 − ν_lt² E_t/E_l)`, `D = C h²/12`,
    /// `F = G h³/12`: membrane `C E_l`, `C E_t`, `C ν_lt E_t`, in-plane shear `2 G h`,
    /// transverse shear `a_s G h`; bending `D E_l`, `D E_t`, `−D ν_lt E_t`, twist `2 F`,
    /// drilling `a_t F`.
    pub fn orthotropic(el: f64, et: f64, nu_lt: f64, g: f64, h: f64, shear_factor: f64, drilling_factor: f64) -> Self {
        let c = h / (1.0 - nu_lt * nu_lt * et / el);
        let d = c * h * h / 12.0;
        let gh = g * h;
        let f = gh * h * h / 12.0;
        Self::from_terms([c * el, c * et, c * nu_lt * et], [2.0 * gh, gh * shear_factor], [d * el, d * et, -d * nu_lt * et], [2.0 * f, f * drilling_factor])
    }

    /// The 12×12 law of MBDyn's isotropic and orthotropic readers from its terms:
    /// `membrane` (ε₁₁, ε₂₂ and between them), `shear` (in-plane ε₁₂ and ε₂₁, transverse ε₁₃
    /// and ε₂₃), `bending` (κ₁₂, κ₂₁ and between them), `twist` (κ₁₁ and κ₂₂, drilling κ₁₃ and
    /// κ₂₃).
    fn from_terms(membrane: [f64; 3], shear: [f64; 2], bending: [f64; 3], twist: [f64; 2]) -> Self {
        let mut k = SMatrix::<f64, 12, 12>::zeros();
        for (r, c, v) in [(0, 0, membrane[0]), (4, 4, membrane[1]), (0, 4, membrane[2]), (7, 7, bending[0]), (9, 9, bending[1]), (7, 9, bending[2])] {
            k[(r, c)] = v;
            k[(c, r)] = v;
        }
        for (diagonal, v) in [([1, 3], shear[0]), ([2, 5], shear[1]), ([6, 10], twist[0]), ([8, 11], twist[1])] {
            for i in diagonal {
                k[(i, i)] = v;
            }
        }
        ShellLaw { stiffness: k, prestress: SVector::zeros() }
    }
}

/// Which of MBDyn's 4-node shells.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShellVariant {
    /// `shell4eas`: enhanced membrane and transverse shear strains (13 parameters).
    Eas,
    /// `shell4easans`: enhanced membrane strains (7 parameters), assumed natural
    /// transverse shear strains.
    EasAns,
}

impl ShellVariant {
    /// MBDyn's card name.
    pub fn name(self) -> &'static str {
        match self {
            ShellVariant::Eas => "shell4eas",
            ShellVariant::EasAns => "shell4easans",
        }
    }
    /// The number of enhanced-strain parameters (MBDyn's `iGetNumDof`): the first 7 of
    /// the interpolation enhance the membrane strains, the last 6 the transverse shear.
    fn enhanced(self) -> usize {
        match self {
            ShellVariant::Eas => EAS,
            ShellVariant::EasAns => MEMBRANE_EAS,
        }
    }
}

/// Why a shell cannot be built.
#[derive(Debug, thiserror::Error)]
pub enum ShellError {
    #[error("{0} {1}: the four nodes do not span a quadrilateral (area factor {2:e} at a point where the strains are sampled; MBDyn numbers them counterclockwise seen from the normal, starting at the (+, +) corner)")]
    Degenerate(&'static str, Label, f64),
}

/// A point where the strains are sampled (a Gauss point or a tying point), from the
/// initial configuration.
#[derive(Clone, Debug)]
struct Sample {
    /// `T_iᵒ`: the point's surface frame relative to `T̄ exp(φ_i)`.
    offset: M3<f64>,
    /// `∂L_n/∂s_α` (local Cartesian derivatives), `[n][α]`.
    dl: [[f64; 2]; 4],
    /// `L_n(ξ_i)`.
    l: [f64; 4],
}

/// Per Gauss point, what the constructor computed.
#[derive(Clone, Debug)]
struct Point {
    at: Sample,
    /// Area factor `α_i` (weight 1).
    area: f64,
    /// `ε⁰`, `κ⁰` in strain order.
    initial: [f64; 12],
    p: SMatrix<f64, 12, EAS>,
}

/// An ANS tying point: where, and its initial transverse shear strain.
#[derive(Clone, Debug)]
struct Tying {
    at: Sample,
    initial: f64,
}

/// A 4-node shell (MBDyn's `shell4eas` or `shell4easans`).
#[derive(Clone, Debug)]
pub struct Shell4 {
    pub label: Label,
    variant: ShellVariant,
    nodes: [Label; 4],
    /// `T_nᵒ`: each node's surface frame in the node's frame.
    node_offset: [Mat3; 4],
    /// `T̄`.
    average: Mat3,
    points: [Point; 4],
    /// `shell4easans`'s tying points A, B, C, D (empty for `shell4eas`).
    tying: Vec<Tying>,
    law: ShellLaw,
}

/// Strains of the four Gauss points, in strain order, for nodes at `x` with relative
/// rotation vectors `phi`.
type Strains<T> = [[T; 12]; 4];

/// The strain (in strain order) each tying point gives: ε₁₃ at A and C, ε₂₃ at B and D.
const TYING_STRAIN: [usize; 4] = [2, 5, 2, 5];

impl Shell4 {
    /// A shell on four nodes (label, initial position, initial orientation), unstrained in
    /// their initial configuration.
    pub fn new(variant: ShellVariant, label: Label, nodes: [(Label, Vec3, Mat3); 4], law: ShellLaw) -> Result<Self, ShellError> {
        let x: [Vec3; 4] = std::array::from_fn(|n| nodes[n].1);
        let frames: [Mat3; 4] = std::array::from_fn(|n| surface_frame(&x, geometry::NODE_XI[n]));
        let node_offset: [Mat3; 4] = std::array::from_fn(|n| nodes[n].2.transpose() * frames[n]);
        let average = geometry::average_frame(&frames);
        let phi: [Vec3; 4] = std::array::from_fn(|n| rotation_vector(&(average.transpose() * frames[n])));
        let sample = |xi: [f64; 2]| {
            let phi_i: Vec3 = (0..4).map(|n| phi[n] * shape(n, xi)).sum();
            let interpolated = average * nalgebra::Rotation3::new(phi_i).into_inner();
            let frame = surface_frame(&x, xi);
            let (dl, area) = geometry::cartesian_derivatives(&x, &frame, xi).map_err(|area| ShellError::Degenerate(variant.name(), label, area))?;
            Ok((Sample { offset: lift(&(interpolated.transpose() * frame)), dl, l: std::array::from_fn(|n| shape(n, xi)) }, area))
        };
        let centre_frame = average * nalgebra::Rotation3::new((0..4).map(|n| phi[n] * shape(n, [0.0, 0.0])).sum::<Vec3>()).into_inner();
        let s0 = metric(&x, &centre_frame, [0.0, 0.0]);
        let area0 = s0.determinant();
        let mut points = Vec::with_capacity(4);
        for xi in POINT_XI {
            let (at, area) = sample(xi)?;
            let mut p = enhanced_strain_matrix(&s0, xi, area0 / area);
            p.columns_mut(variant.enhanced(), EAS - variant.enhanced()).fill(0.0);
            points.push(Point { at, area, initial: [0.0; 12], p });
        }
        let tying = match variant {
            ShellVariant::Eas => Vec::new(),
            ShellVariant::EasAns => TYING_XI.iter().map(|&xi| sample(xi).map(|(at, _)| Tying { at, initial: 0.0 })).collect::<Result<_, _>>()?,
        };
        let mut shell = Shell4 {
            label,
            variant,
            nodes: std::array::from_fn(|n| nodes[n].0),
            node_offset,
            average,
            points: points.try_into().expect("four Gauss points"),
            tying,
            law,
        };
        let (xs, ps): ([V3<f64>; 4], [V3<f64>; 4]) = (std::array::from_fn(|n| x[n].into()), std::array::from_fn(|n| phi[n].into()));
        for k in 0..4 {
            shell.points[k].initial = shell.sampled(&shell.points[k].at, &xs, &ps, true);
        }
        for k in 0..shell.tying.len() {
            shell.tying[k].initial = shell.sampled(&shell.tying[k].at, &xs, &ps, false)[TYING_STRAIN[k]];
        }
        Ok(shell)
    }

    /// The strains at a sample point, not minus the initial ones (generic: values, or
    /// hyper-dual derivatives): `T_iᵀ x_{,α}` and, `with_curvature`, `T_iᵀ T̄ Γ(φ_i) φ_{,α}`.
    fn sampled<T: Real>(&self, p: &Sample, x: &[V3<T>; 4], phi: &[V3<T>; 4], with_curvature: bool) -> [T; 12] {
        let tbar: M3<T> = cst_m(&lift(&self.average));
        let comb = |v: &[V3<T>; 4], w: &dyn Fn(usize) -> f64| (0..4).fold([T::cst(0.0); 3], |acc, n| add(&acc, &scale(&v[n], T::cst(w(n)))));
        let phi_i = comb(phi, &|n| p.l[n]);
        let t = mat_mat(&mat_mat(&tbar, &rotation(&phi_i)), &cst_m(&p.offset));
        let gamma = with_curvature.then(|| mat_mat(&tbar, &tangent(&phi_i)));
        let mut e = [T::cst(0.0); 12];
        for a in 0..2 {
            e[3 * a..3 * a + 3].copy_from_slice(&mat_t_vec(&t, &comb(x, &|n| p.dl[n][a])));
            if let Some(gamma) = &gamma {
                let k = mat_vec(gamma, &comb(phi, &|n| p.dl[n][a]));
                e[6 + 3 * a..6 + 3 * a + 3].copy_from_slice(&mat_t_vec(&t, &k));
            }
        }
        e
    }

    /// The strains (minus the initial ones) for node positions `x` and relative rotation
    /// vectors `phi` (generic: values, or hyper-dual derivatives); `shell4easans`'s
    /// transverse shears interpolated from its tying points.
    fn strains<T: Real>(&self, x: &[V3<T>; 4], phi: &[V3<T>; 4]) -> Strains<T> {
        let mut e: Strains<T> = std::array::from_fn(|i| {
            let p = &self.points[i];
            let raw = self.sampled(&p.at, x, phi, true);
            std::array::from_fn(|r| raw[r] - T::cst(p.initial[r]))
        });
        if !self.tying.is_empty() {
            let shear: [T; 4] = std::array::from_fn(|k| self.sampled(&self.tying[k].at, x, phi, false)[TYING_STRAIN[k]] - T::cst(self.tying[k].initial));
            for (i, xi) in POINT_XI.iter().enumerate() {
                let half = |s: f64, v: f64| T::cst(0.5 * (1.0 + s * v));
                e[i][2] = half(1.0, xi[1]) * shear[0] + half(-1.0, xi[1]) * shear[2];
                e[i][5] = half(-1.0, xi[0]) * shear[1] + half(1.0, xi[0]) * shear[3];
            }
        }
        e
    }

    /// Node positions and relative rotation vectors `φ_n = rotvec(T̄ᵀ R_n T_nᵒ)`.
    fn coordinates(&self, s: &dyn ElementState) -> ([Vec3; 4], [Vec3; 4]) {
        let x = std::array::from_fn(|n| s.node(n).x);
        let phi = std::array::from_fn(|n| rotation_vector(&(self.average.transpose() * s.node(n).r * self.node_offset[n])));
        (x, phi)
    }

    /// Strains with hyper-dual parts along coordinates `j` (ε₁) and `k` (ε₂) of the 24
    /// (node n: position 6n..6n+3, rotation vector 6n+3..6n+6).
    fn strains_along(&self, x: &[Vec3; 4], phi: &[Vec3; 4], j: Option<usize>, k: Option<usize>) -> Strains<Hyper> {
        let seed = |q: usize, v: f64| Hyper { a: v, b: if j == Some(q) { 1.0 } else { 0.0 }, c: if k == Some(q) { 1.0 } else { 0.0 }, d: 0.0 };
        let xs = std::array::from_fn(|n| std::array::from_fn(|c| seed(6 * n + c, x[n][c])));
        let ps = std::array::from_fn(|n| std::array::from_fn(|c| seed(6 * n + 3 + c, phi[n][c])));
        self.strains(&xs, &ps)
    }

    /// `B_i = ∂ε_i/∂q` (12 × 24 per Gauss point) and the stresses `σ_i`.
    fn state(&self, s: &dyn ElementState) -> State {
        let (x, phi) = self.coordinates(s);
        let mut b = [SMatrix::<f64, 12, 24>::zeros(); 4];
        let mut strain = [SVector::<f64, 12>::zeros(); 4];
        for q in 0..24 {
            let e = self.strains_along(&x, &phi, Some(q), None);
            for i in 0..4 {
                for r in 0..12 {
                    b[i][(r, q)] = e[i][r].b;
                    strain[i][r] = e[i][r].a;
                }
            }
        }
        let beta = SVector::<f64, EAS>::from_fn(|k, _| if k < self.variant.enhanced() { s.multiplier(k) } else { 0.0 });
        let stress = std::array::from_fn(|i| self.law.stiffness * (strain[i] + self.points[i].p * beta) + self.law.prestress);
        State { x, phi, b, stress }
    }

    /// `A_n = Γ⁻¹(φ_n) T̄ᵀ`: `δφ_n = A_n δθ_n`.
    fn rotation_maps(&self, phi: &[Vec3; 4]) -> [Mat3; 4] {
        std::array::from_fn(|n| {
            let g = Mat3::from_fn(|r, c| tangent(&<[f64; 3]>::from(phi[n]))[r][c]);
            g.try_inverse().unwrap_or_else(Mat3::zeros) * self.average.transpose()
        })
    }

    /// Each Gauss point's `B_i`, `P_i`, `σ_i`, `α_i`.
    fn sampled_points<'a>(&'a self, st: &'a State) -> impl Iterator<Item = Sampled<'a, 12, 24>> {
        self.points.iter().enumerate().map(|(i, p)| Sampled { b: &st.b[i], p: &p.p, stress: &st.stress[i], area: p.area })
    }

    /// Internal forces on the 24 coordinates (positions, rotation vectors) and on `β`.
    fn forces(&self, st: &State) -> (SVector<f64, 24>, SVector<f64, EAS>) {
        enhanced::internal_forces(self.sampled_points(st))
    }
}

/// One evaluation: coordinates, `B_i`, `σ_i`.
struct State {
    x: [Vec3; 4],
    phi: [Vec3; 4],
    b: [SMatrix<f64, 12, 24>; 4],
    stress: [SVector<f64, 12>; 4],
}

fn is_rotation(q: usize) -> bool {
    q % 6 >= 3
}

impl Element for Shell4 {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        self.variant.name()
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.to_vec()
    }
    fn multipliers(&self) -> Vec<String> {
        (1..=self.variant.enhanced()).map(|k| format!("enhanced strain parameter {k}")).collect()
    }
    /// The enhanced-strain parameters are algebraic unknowns of the configuration (MBDyn's
    /// `DofOrder::ALGEBRAIC`): equations not divided by dCoef, Jacobian coefficient that of
    /// the positions.
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::VelocityConstraint
    }
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink) {
        let st = self.state(s);
        let (fq, fb) = self.forces(&st);
        let maps = self.rotation_maps(&st.phi);
        for n in 0..4 {
            let moment = maps[n].transpose() * fq.fixed_rows::<3>(6 * n + 3);
            for c in 0..3 {
                out.add(Row::Equilibrium { slot: n, comp: c }, fq[6 * n + c]);
                out.add(Row::Equilibrium { slot: n, comp: 3 + c }, moment[c]);
            }
        }
        for k in 0..self.variant.enhanced() {
            out.add(Row::Constraint(k), fb[k]);
        }
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn jacobian(&self, s: &dyn ElementState, out: &mut dyn JacobianSink) {
        let st = self.state(s);
        // K_qq = Σ α (Bᵀ D B + σ · ∂²ε), K_qβ, K_ββ.
        let (mut kqq, kqb, kbb) = enhanced::linear_tangent(&self.law.stiffness, self.sampled_points(&st));
        for j in (0..24).filter(|&j| is_rotation(j)) {
            for k in 0..24 {
                if is_rotation(k) && k < j {
                    continue;
                }
                let e = self.strains_along(&st.x, &st.phi, Some(j), Some(k));
                let g: f64 = (0..4).map(|i| self.points[i].area * (0..12).map(|r| st.stress[i][r] * e[i][r].d).sum::<f64>()).sum();
                kqq[(j, k)] += g;
                if k != j {
                    kqq[(k, j)] += g;
                }
            }
        }
        let (fq, _) = self.forces(&st);
        let maps = self.rotation_maps(&st.phi);
        // Columns and rows of rotation vectors to virtual rotations: δφ_n = A_n δθ_n, the
        // moment rows are A_nᵀ (force on φ_n).
        let mut t = SMatrix::<f64, 24, 24>::identity();
        for n in 0..4 {
            t.fixed_view_mut::<3, 3>(6 * n + 3, 6 * n + 3).copy_from(&maps[n]);
        }
        let mut kq = t.transpose() * kqq * t;
        for n in 0..4 {
            let v = fq.fixed_rows::<3>(6 * n + 3).into_owned();
            let dm = self.moment_map_derivative(&st.phi[n], &v);
            let block = dm * maps[n];
            let mut view = kq.fixed_view_mut::<3, 3>(6 * n + 3, 6 * n + 3);
            view += block;
        }
        let kqb = t.transpose() * kqb;
        let col = |q: usize| if is_rotation(q) { Col::Rotation { slot: q / 6, comp: q % 6 - 3 } } else { Col::Position { slot: q / 6, comp: q % 6 } };
        let row = |q: usize| Row::Equilibrium { slot: q / 6, comp: q % 6 };
        enhanced::add_tangent(out, (&kq, &kqb, &kbb), self.variant.enhanced(), row, col);
    }
}

impl Outputs for Shell4 {
    /// MBDyn's `.pla` row: `σ_i = D (ε_i + P_i β) + σ₀` at the four Gauss points.
    fn plate_resultants(&self, s: &dyn ElementState) -> Vec<f64> {
        self.state(s).stress.iter().flat_map(|v| v.iter().copied()).collect()
    }
}

impl Shell4 {
    /// `∂(T̄ Γ⁻ᵀ(φ) v)/∂φ` at fixed `v`: `−T̄ Γ⁻ᵀ (∂Γ/∂φ_k)ᵀ Γ⁻ᵀ v` column by column.
    fn moment_map_derivative(&self, phi: &Vec3, v: &Vec3) -> Mat3 {
        let g = Mat3::from_fn(|r, c| tangent(&<[f64; 3]>::from(*phi))[r][c]);
        let g_inv_t = g.try_inverse().unwrap_or_else(Mat3::zeros).transpose();
        let u = g_inv_t * v;
        let mut out = Mat3::zeros();
        for k in 0..3 {
            let seeded: V3<Hyper> = std::array::from_fn(|c| Hyper { a: phi[c], b: if c == k { 1.0 } else { 0.0 }, c: 0.0, d: 0.0 });
            let dg = tangent(&seeded);
            let dgt_u = Vec3::from_fn(|r, _| (0..3).map(|c| dg[c][r].b * u[c]).sum());
            out.set_column(k, &(-(self.average * g_inv_t * dgt_u)));
        }
        out
    }
}
