//! The beam family of issue 30 (finding 3) in MBDyn syntax: a cantilever of N `beam3`
//! elements with a tip mass, every node dynamic and free in 3-D; shared by
//! tests/eigen/dense_eigen_scaling.rs, tests/eigen/beam_family.rs and
//! benches/dense_beam_family.rs; and the family's independent reference, the undamped
//! mass–stiffness problem ([`MassStiffness`]).

/// Lumped masses and inertias of the beam file below, node by node: `(m, J_x, J_y, J_z)`.
pub fn beam_inertia(elements: usize) -> Vec<[f64; 4]> {
    let n = 2 * elements + 1;
    let dl = 1.0 / (n - 1) as f64;
    let mut out: Vec<[f64; 4]> = (0..n)
        .map(|i| {
            let l = if i == 0 || i == n - 1 { dl / 2.0 } else { dl };
            [l, 1e-3 * l, l.powi(3) / 12.0, l.powi(3) / 12.0]
        })
        .collect();
    // Tip mass 0.1 kg with 1e-4 kg m² about every axis on the last node.
    let tip = &mut out[n - 1];
    *tip = [tip[0] + 0.1, tip[1] + 1e-4, tip[2] + 1e-4, tip[3] + 1e-4];
    out
}

/// A cantilever of `elements` beam3 elements along x (L = 1 m, ρA = 1 kg/m, GA = EA,
/// GJ = EJ), clamped at node 1, with a tip mass, every node dynamic and free in 3-D (the
/// model of issue 30: 12 (2N + 1) + 6 equations).
pub fn cantilever(elements: usize, ea: f64, ej: f64) -> String {
    let n = 2 * elements + 1;
    let dl = 1.0 / (n - 1) as f64;
    let mut nodes = String::new();
    let mut elems = String::from("joint: 1, clamp, 1, node, node;\n");
    for (i, [m, jx, jy, jz]) in beam_inertia(elements).into_iter().enumerate() {
        nodes += &format!("structural: {}, dynamic, {:e}, 0., 0., eye, null, null;\n", i + 1, i as f64 * dl);
        elems += &format!("body: {}, {}, {m:e}, null, diag, {jx:e}, {jy:e}, {jz:e};\n", i + 1, i + 1);
    }
    let law = format!("eye, linear elastic generic, diag, {ea:e}, {ea:e}, {ea:e}, {ej:e}, {ej:e}, {ej:e}");
    for e in 0..elements {
        let (a, b, c) = (2 * e + 1, 2 * e + 2, 2 * e + 3);
        elems += &format!("beam3: {}, {a}, null, {b}, null, {c}, null, {law}, {law};\n", e + 1);
    }
    format!("begin: data; problem: initial value; end: data;\nbegin: control data; structural nodes: {n}; rigid bodies: {n}; joints: 1; beams: {elements}; end: control data;\nbegin: nodes;\n{nodes}end: nodes;\nbegin: elements;\n{elems}end: elements;\n")
}

/// The independent reference of the beam family's eigenvalues: the undamped problem
/// `K q = ω² M q` of the cantilever at rest, with `M` the lumped masses and inertias written
/// into the file ([`beam_inertia`], diagonal, built here by hand) and `K` the equilibrium
/// rows' stiffness `F_y[equilibrium, positions]` of the free nodes (the clamped node 1
/// removed). The finite-volume beam's tangent stiffness is not symmetric (3e-3 of its
/// largest entry), so the general standard problem, inverted so that the lowest modes are
/// the largest eigenvalues and keep their relative accuracy whatever EA/EJ (a
/// backward-stable solver errs by ε times the largest eigenvalue):
/// `M^(1/2) K⁻¹ M^(1/2) x = x / ω²`, by an LU inverse and faer's Hessenberg QR (no QZ, no
/// pencil, no Krylov space, no deflation, no labels): `ω = 1/sqrt|ν|`.
pub struct MassStiffness {
    /// Every ω [rad/s], ascending.
    pub omega: Vec<f64>,
    nu_max: f64,
    size: usize,
}

impl MassStiffness {
    /// From the dense linearization of [`cantilever`]`(elements, ..)` at rest and each
    /// node's first unknown.
    pub fn of(dae: &romdyn::linear::LinearDae, node_first: &[usize], elements: usize) -> Self {
        use faer::linalg::solvers::DenseSolveCore;
        let (_, fy) = dae.jacobians.derivatives();
        let inertia = beam_inertia(elements);
        let free = 1..2 * elements + 1;
        let dof = |node: usize, k: usize| (node - 1) * 6 + k;
        let size = 6 * (2 * elements);
        let mut k = faer::Mat::<f64>::zeros(size, size);
        let mut minv_sqrt = vec![0.0; size];
        for a in free.clone() {
            let [m, jx, jy, jz] = inertia[a];
            for (c, mass) in [m, m, m, jx, jy, jz].into_iter().enumerate() {
                minv_sqrt[dof(a, c)] = 1.0 / mass.sqrt();
            }
            for b in free.clone() {
                for r in 0..6 {
                    for c in 0..6 {
                        k[(dof(a, r), dof(b, c))] = fy[(node_first[a] + 6 + r, node_first[b] + c)];
                    }
                }
            }
        }
        let k_inv = k.partial_piv_lu().inverse();
        let flexible = faer::Mat::<f64>::from_fn(size, size, |i, j| k_inv[(i, j)] / (minv_sqrt[i] * minv_sqrt[j]));
        let nu: Vec<faer::c64> = flexible.as_ref().eigenvalues().unwrap();
        let mut omega: Vec<f64> = nu.iter().map(|x| 1.0 / x.norm().sqrt()).collect();
        omega.sort_by(f64::total_cmp);
        let nu_max = nu.iter().map(|x| x.norm()).fold(0.0, f64::max);
        MassStiffness { omega, nu_max, size }
    }

    /// The reference's own rounding at ω: `|δν| ≤ 10 n ε ν_max` with `ν = 1/ω²`, so
    /// `|δω| ≤ 10 n ε ν_max ω³ / 2`.
    pub fn error(&self, w: f64) -> f64 {
        10.0 * self.size as f64 * f64::EPSILON * self.nu_max * w.powi(3) / 2.0
    }
}
