//! The beam family of issue 30 (finding 3) in MBDyn syntax: a cantilever of N `beam3`
//! elements with a tip mass, every node dynamic and free in 3-D; shared by
//! tests/eigen/dense_eigen_scaling.rs, tests/eigen/beam_family.rs and
//! benches/dense_beam_family.rs; and the family's independent reference, the undamped
//! mass–stiffness problem ([`MassStiffness`]).

use romdyn::linear::Compensated;

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
    cantilever_with_inertia(elements, ea, ej, &beam_inertia(elements))
}

/// [`cantilever`] with the nodes' masses and inertias `inertia` (`(m, J_x, J_y, J_z)` node by
/// node, a zero allowed: a massless direction).
pub fn cantilever_with_inertia(elements: usize, ea: f64, ej: f64, inertia: &[[f64; 4]]) -> String {
    let n = 2 * elements + 1;
    let dl = 1.0 / (n - 1) as f64;
    let mut nodes = String::new();
    let mut elems = String::from("joint: 1, clamp, 1, node, node;\n");
    for (i, &[m, jx, jy, jz]) in inertia.iter().enumerate() {
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
/// the largest eigenvalues: `M^(1/2) K⁻¹ M^(1/2) x = x / ω²`, by an LU inverse and faer's
/// Hessenberg QR (no QZ, no pencil, no Krylov space, no deflation, no labels). In double
/// precision that is not enough at EA/EJ = 1e7: `K⁻¹`'s rounding (cond K ≈ 1e10) moved the
/// lowest bending pair by up to 2.2e-7 (64 elements), 3e-9 at 8. So the lowest
/// [`REFINED`] are then refined to the exact eigenvalues of the stored doubles
/// ([`refine_eigenvalue`]: inverse iteration with compensated residuals).
pub struct MassStiffness {
    /// Every ω [rad/s], ascending; the lowest [`REFINED`] (and the other copies of the last
    /// one's double eigenvalue) refined.
    pub omega: Vec<f64>,
}

/// How many of the lowest eigenvalues [`MassStiffness`] refines.
pub const REFINED: usize = 20;

/// The free nodes' stiffness `K` as stored, row by row: `(column, value)`.
type SparseRows = Vec<Vec<(usize, f64)>>;

impl MassStiffness {
    /// From the dense linearization of [`cantilever`]`(elements, ..)` at rest and each
    /// node's first unknown.
    pub fn of(dae: &romdyn::linear::LinearDae, node_first: &[usize], elements: usize) -> Self {
        Self::with_inertia(dae, node_first, elements, &beam_inertia(elements))
    }

    /// The same for [`cantilever_with_inertia`]`(elements, .., inertia)`. A massless direction
    /// (a zero in `inertia`) has `M^(1/2) = 0`: its row and column of `M^(1/2) K⁻¹ M^(1/2)`
    /// vanish (ω = ∞), and the others are the eigenvalues of `K` condensed on the massless
    /// directions, exactly.
    pub fn with_inertia(dae: &romdyn::linear::LinearDae, node_first: &[usize], elements: usize, inertia: &[[f64; 4]]) -> Self {
        use faer::linalg::solvers::DenseSolveCore;
        let (_, fy) = dae.jacobians.derivatives();
        let free = 1..2 * elements + 1;
        let dof = |node: usize, k: usize| (node - 1) * 6 + k;
        let size = 6 * (2 * elements);
        let mut k = faer::Mat::<f64>::zeros(size, size);
        let mut m_sqrt = vec![0.0; size];
        for a in free.clone() {
            let [m, jx, jy, jz] = inertia[a];
            for (c, mass) in [m, m, m, jx, jy, jz].into_iter().enumerate() {
                m_sqrt[dof(a, c)] = mass.sqrt();
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
        let flexible = faer::Mat::<f64>::from_fn(size, size, |i, j| k_inv[(i, j)] * m_sqrt[i] * m_sqrt[j]);
        let nu: Vec<faer::c64> = flexible.as_ref().eigenvalues().unwrap();
        let mut omega: Vec<f64> = nu.iter().map(|x| 1.0 / x.norm().sqrt()).collect();
        omega.sort_by(f64::total_cmp);
        let mass: Vec<f64> = m_sqrt.iter().map(|x| x * x).collect();
        let rows: SparseRows = (0..size).map(|i| (0..size).filter(|&j| k[(i, j)] != 0.0).map(|j| (j, k[(i, j)])).collect()).collect();
        // The lowest REFINED and the other copies of the last one's (a bending pair).
        let last = omega[REFINED.min(size) - 1];
        let count = omega.iter().filter(|&&w| w <= last * (1.0 + 1e-6)).count();
        // Each group of copies (within 1e-6, e.g. the y and z bending of a pair) refined
        // vector by vector, or, where a single vector drifts between two copies that are
        // not exactly equal (128 elements, EA/EJ 1e7: 1.7e-10 per sweep), as one block.
        let copies = |index: usize, window: f64| omega.iter().skip(index).take_while(|&&w| (w * w / (omega[index] * omega[index]) - 1.0).abs() <= window).count();
        let mut refined: Vec<f64> = Vec::with_capacity(count);
        while refined.len() < count {
            let (first, m) = (refined.len(), copies(refined.len(), 1e-6));
            let one_by_one: Option<Vec<f64>> = (first..first + m).map(|index| refine_eigenvalue(&k, &rows, &mass, &omega, index).ok()).collect();
            // A block over every eigenvalue within 1e-4: the starting estimates (LU inverse
            // and QR) can be further from a close neighbour than the shift's distance.
            let group = one_by_one.unwrap_or_else(|| refine_copies(&k, &rows, &mass, &omega, first, copies(first, 1e-4), 1e-4));
            refined.extend(group.iter().map(|l| l.sqrt()));
        }
        omega[..refined.len()].copy_from_slice(&refined);
        MassStiffness { omega }
    }

    /// The refined eigenvalues' error bound: 1e-13 ω (the refinement, vector by vector or by
    /// block over a group of copies, stops when two sweeps agree to 1e-15 in ω²; romdyn's dense route, its eigenvalues compensated two-sided
    /// quotients, agrees within it at 8 to 64 elements, EA/EJ 1e3 to 1e7).
    pub fn error(&self, w: f64) -> f64 {
        1e-13 * w
    }
}

/// `b − (K − σM) y`, each row summed in compensated arithmetic ([`Compensated`]; `K`, `M`,
/// `σ`, `y` exact doubles: the residual of the stored matrices, not of rounded products).
fn residual(rows: &SparseRows, mass: &[f64], sigma: f64, y: &[f64], b: &[f64]) -> Vec<f64> {
    (0..y.len())
        .map(|i| {
            let mut s = Compensated::default();
            s.add(b[i]);
            for &(j, kij) in &rows[i] {
                s.add_product(-kij, y[j]);
            }
            let mut my = Compensated::default();
            my.add_product(mass[i], y[i]);
            s.add_scaled(sigma, my);
            s.value()
        })
        .collect()
}

/// The eigenvalue `ω²` of `K q = ω² M q` next to `omega[index]²`, to the stored matrices'
/// own accuracy: shifted inverse iteration at `σ = ω²(1 − δ)`, `δ` a quarter of the relative
/// gap to the next distinct eigenvalue (at most 1e-3), each solve `(K − σM) y = M x` by the
/// double LU with iterative refinement on compensated residuals (Higham, Accuracy and
/// Stability of Numerical Algorithms, 2nd ed., §12.1: the forward error reaches the working
/// precision when cond(K − σM) ε < 1), and `ω² = σ + xᵀM x / xᵀM y` once `x` has converged.
fn refine_eigenvalue(k: &faer::Mat<f64>, rows: &SparseRows, mass: &[f64], omega: &[f64], index: usize) -> Result<f64, f64> {
    let lambda = omega[index] * omega[index];
    let (sigma, solve) = shifted_solve(k, rows, mass, omega, lambda, 1e-6);
    let n = mass.len();
    // Start from a vector with every component (a few sweeps bring the wanted direction).
    let mut x: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64 * 0.618).sin()).collect();
    let mut estimate = lambda;
    let mut converged = false;
    for sweep in 0..40 {
        let b: Vec<f64> = x.iter().zip(mass).map(|(a, m)| a * m).collect();
        let y = solve(&b);
        let (mut num, mut den) = (Compensated::default(), Compensated::default());
        for i in 0..n {
            num.add_product(x[i], b[i]);
            den.add_product(b[i], y[i]);
        }
        let next = sigma + num.value() / den.value();
        let norm = y.iter().map(|v| v * v).sum::<f64>().sqrt();
        x = y.iter().map(|v| v / norm).collect();
        converged = sweep >= 3 && (next - estimate).abs() <= 1e-15 * next;
        estimate = next;
        if converged {
            break;
        }
    }
    if converged { Ok(estimate) } else { Err(estimate) }
}

/// The shift `σ = ω²(1 − δ)` below the eigenvalue `lambda` (`δ` a quarter of the relative gap
/// to the next eigenvalue beyond `window`, at most 1e-3) and the solve of `(K − σM) y = b` by the
/// double LU with iterative refinement on compensated residuals.
fn shifted_solve<'a>(k: &faer::Mat<f64>, rows: &'a SparseRows, mass: &'a [f64], omega: &[f64], lambda: f64, window: f64) -> (f64, impl Fn(&[f64]) -> Vec<f64> + 'a) {
    use faer::linalg::solvers::Solve;
    let gap = omega
        .iter()
        .map(|w| ((w * w - lambda) / lambda).abs())
        .filter(|&g| g > window)
        .fold(f64::INFINITY, f64::min);
    let sigma = lambda * (1.0 - (gap / 4.0).min(1e-3));
    let n = mass.len();
    let shifted = faer::Mat::<f64>::from_fn(n, n, |i, j| k[(i, j)] - if i == j { sigma * mass[i] } else { 0.0 });
    let lu = shifted.partial_piv_lu();
    let solve = move |b: &[f64]| -> Vec<f64> {
        let mut y: Vec<f64> = lu.solve(faer::Col::<f64>::from_fn(n, |i| b[i])).iter().copied().collect();
        for _ in 0..30 {
            let r = residual(rows, mass, sigma, &y, b);
            let d = lu.solve(faer::Col::<f64>::from_fn(n, |i| r[i]));
            let (dn, yn) = (d.norm_l2(), y.iter().map(|v| v * v).sum::<f64>().sqrt());
            y.iter_mut().zip(d.iter()).for_each(|(a, b)| *a += b);
            if dn <= 1e-17 * yn {
                break;
            }
        }
        y
    };
    (sigma, solve)
}

/// The `m` eigenvalues `omega[first..first + m]` within `window` of each other (copies of a
/// near-multiple eigenvalue, or neighbours closer than their starting estimates' error),
/// refined as one block: subspace iteration `Z = (K − σM)⁻¹ M Q` on an orthonormal `Q` of `m` columns, with
/// the Rayleigh–Ritz values `θ` of `H = Qᵀ Z` giving `ω² = σ + 1/θ` (Saad, Numerical Methods
/// for Large Eigenvalue Problems, 2nd ed., §5.1), until two sweeps agree to 1e-15.
fn refine_copies(k: &faer::Mat<f64>, rows: &SparseRows, mass: &[f64], omega: &[f64], first: usize, m: usize, window: f64) -> Vec<f64> {
    let lambda = omega[first] * omega[first];
    let (sigma, solve) = shifted_solve(k, rows, mass, omega, lambda, window);
    let n = mass.len();
    let orthonormal = |mut q: Vec<Vec<f64>>| {
        for _ in 0..2 {
            for c in 0..q.len() {
                for p in 0..c {
                    let dot: f64 = (0..n).map(|i| q[p][i] * q[c][i]).sum();
                    for i in 0..n {
                        q[c][i] -= dot * q[p][i];
                    }
                }
                let norm = q[c].iter().map(|v| v * v).sum::<f64>().sqrt();
                q[c].iter_mut().for_each(|v| *v /= norm);
            }
        }
        q
    };
    let mut q = orthonormal((0..m).map(|c| (0..n).map(|i| 1.0 + (i as f64 * 0.618 + c as f64 * 1.3).sin()).collect()).collect());
    let mut estimate = vec![lambda; m];
    for sweep in 0..40 {
        let z: Vec<Vec<f64>> = q.iter().map(|x| solve(&x.iter().zip(mass).map(|(a, w)| a * w).collect::<Vec<_>>())).collect();
        let h = faer::Mat::<f64>::from_fn(m, m, |i, j| {
            let mut s = Compensated::default();
            (0..n).for_each(|r| s.add_product(q[i][r], z[j][r]));
            s.value()
        });
        let mut next: Vec<f64> = h.as_ref().eigenvalues().unwrap().iter().map(|t| sigma + 1.0 / t.re).collect();
        next.sort_by(f64::total_cmp);
        q = orthonormal(z);
        let converged = sweep >= 3 && next.iter().zip(&estimate).all(|(a, b)| (a - b).abs() <= 1e-15 * a);
        estimate = next;
        if converged {
            return estimate;
        }
    }
    panic!("the reference's eigenvalues {first}..{} did not converge as a block: {estimate:?} after 40 sweeps", first + m);
}
