//! The dynamic part of an undamped structure at rest, solved at half its size (issue 36,
//! point 2).
//!
//! After the deflation ([`super::deflate`]) a structure with positions `q` and momenta `p`,
//! no damping and no velocity at the reference, has the dynamic part
//!
//! ```text
//!   λ [E₁₁  0 ] [q]   [ 0   K₁₂] [q]
//!     [ 0  E₂₂] [p] + [K₂₁   0 ] [p] = 0
//! ```
//!
//! (momentum definitions `λ E₁₁ q + K₁₂ p = 0`, equilibrium `K₂₁ q + λ E₂₂ p = 0`), up to
//! an ordering of its rows and columns that [`split`] finds from the exact zeros alone: a
//! 2-colouring where every nonzero of `E` joins a row and a column of one colour and every
//! nonzero of `K` a row and a column of two colours. Any damping, any velocity term or any
//! other coupling breaks the colouring, and the caller runs QZ on the whole dynamic part.
//!
//! Eliminating `p = −λ K₁₂⁻¹ E₁₁ q` leaves `K₂₁ q = s B q` with `B = −E₂₂ K₁₂⁻¹ E₁₁` (the
//! mass matrix) and `s = −λ²` (ω² of an undamped mode). `K₂₁` need not be symmetric (beam3's
//! finite-volume stiffness is not: 1.2e-3 of its largest entry on the beam family), so the
//! symmetric-definite route does not apply; the general one does, at half the size. Solved
//! in the Cayley form `C = (K₂₁ + σB)⁻¹ (K₂₁ − σB)`, `t = (s − σ)/(s + σ)`, with `σ = 1/c²`
//! from the Λ form's spectral dCoef `c`: the spectrum's logarithmic centre maps to `t = 0`,
//! the slowest and fastest modes towards `−1` and `1`, as eq. 23 does for `λ` (the plain
//! `B⁻¹ K₂₁` would put every slow mode within `ε s_max` of zero). Right and left vectors by
//! two standard eigendecompositions, each vector then mapped through `(K₂₁ + σB)⁻¹` (one step
//! of inverse iteration with the Cayley shift, already factored): right vectors
//! `q = (K₂₁ + σB)⁻¹ z` from the eigenvectors `z` of `C' = (K₂₁ − σB)(K₂₁ + σB)⁻¹` (`C`'s
//! similar matrix acting on `z = (K₂₁ + σB) q`), left vectors `ψ = (K₂₁ + σB)⁻ᵀ y` from those
//! `y` of `Cᵀ`; paired by eigenvalue and made biorthogonal within each cluster. Each `s` gives
//! `λ = ±√(−s)` with the first-order vectors `[q; −λ K₁₂⁻¹ E₁₁ q]` and
//! `[−λ K₁₂⁻ᵀ E₂₂ᵀ ψ; ψ]`. The caller keeps its two-sided quotient on the whole pencil as each
//! dynamic eigenvalue and labels each mode there, as after QZ.
//!
//! Why the step through `(K₂₁ + σB)⁻¹`: it divides an eigenvector's error along mode `j` by
//! `(s_j + σ)/(s_k + σ)`, so the stiff modes' share in a slow mode's vector shrinks by
//! `σ/s_j`. Right vectors taken as `C`'s own eigenvectors (the left ones already took the
//! step) were up to 1e4 times further from the exact ones than QZ's on the beam family
//! (torsion, 16 elements, EA/EJ 1e7: 2.5e-9 against 1.6e-13; with the step 2.5e-12;
//! measured against the independent reference of `tests/eigen/vector_reference.rs`, table in
//! the performance chapter of the book).
//!
//! Work: two real eigendecompositions of size r/2 against QZ with both vector sets at r
//! (LAPACK on the 786-equation beam, single thread: `dgeev` at 384 0.07 s, `dggev` at 768
//! 5.5 s), plus three solves with the factored `K₂₁ + σB`.

use faer::linalg::solvers::{DenseSolveCore, Solve};
use faer::{c64, Col, Mat};

/// A mode of the dynamic part: `λ`, its right and left vectors of `λ E + K`, and whether it
/// stands for a complex conjugate pair.
pub(super) struct HalfSizeMode {
    pub lambda: c64,
    pub right: Col<c64>,
    pub left: Col<c64>,
    pub pair: bool,
}

/// The rows and columns of the two colours: `(R₁, Q, R₂, P)`, `None` when the pattern is
/// not the undamped structure's or the four sets are not of one size.
pub(super) fn split(e: &Mat<f64>, k: &Mat<f64>) -> Option<[Vec<usize>; 4]> {
    let r = e.nrows();
    if r == 0 || r % 2 != 0 || e.ncols() != r || k.nrows() != r || k.ncols() != r {
        return None;
    }
    // Nodes 0..r are rows, r..2r columns; an edge carries whether its ends differ.
    let mut edges: Vec<Vec<(usize, bool)>> = vec![Vec::new(); 2 * r];
    for j in 0..r {
        for i in 0..r {
            let (in_e, in_k) = (e[(i, j)] != 0.0, k[(i, j)] != 0.0);
            if in_e && in_k {
                return None;
            }
            if in_e || in_k {
                edges[i].push((r + j, in_k));
                edges[r + j].push((i, in_k));
            }
        }
    }
    let mut colour: Vec<Option<bool>> = vec![None; 2 * r];
    let mut stack = Vec::new();
    for start in 0..2 * r {
        if colour[start].is_some() {
            continue;
        }
        if edges[start].is_empty() {
            return None;
        }
        colour[start] = Some(false);
        stack.push(start);
        while let Some(a) = stack.pop() {
            let ca = colour[a]?;
            for &(b, differ) in &edges[a] {
                let want = ca ^ differ;
                match colour[b] {
                    None => {
                        colour[b] = Some(want);
                        stack.push(b);
                    }
                    Some(cb) if cb != want => return None,
                    Some(_) => {}
                }
            }
        }
    }
    let pick = |from: usize, c: bool| -> Vec<usize> { (0..r).filter(|&i| colour[from + i] == Some(c)).collect() };
    let sets = [pick(0, false), pick(r, false), pick(0, true), pick(r, true)];
    sets.iter().all(|s| s.len() == r / 2).then_some(sets)
}

/// Whether a partial-pivoting LU's pivots stand clear of rounding (`n ε` of the largest,
/// times a margin): a square block that must be nonsingular for the reduction.
fn pivots_clear(u: faer::MatRef<'_, f64>) -> bool {
    let n = u.nrows();
    let p: Vec<f64> = (0..n).map(|i| u[(i, i)].abs()).collect();
    let top = p.iter().copied().fold(0.0, f64::max);
    top.is_finite() && p.iter().all(|&x| x > 1e3 * n as f64 * f64::EPSILON * top)
}

/// `M Z` for real `M` and complex `Z`.
fn real_times(m: faer::MatRef<'_, f64>, z: &Mat<c64>) -> Mat<c64> {
    let re = m * Mat::<f64>::from_fn(z.nrows(), z.ncols(), |i, j| z[(i, j)].re);
    let im = m * Mat::<f64>::from_fn(z.nrows(), z.ncols(), |i, j| z[(i, j)].im);
    Mat::from_fn(re.nrows(), re.ncols(), |i, j| c64::new(re[(i, j)], im[(i, j)]))
}

/// Solves with a real factorization `solve` on the real and imaginary parts of `z`.
fn solve_complex(z: &Mat<c64>, solve: impl Fn(Mat<f64>) -> Mat<f64>) -> Mat<c64> {
    let re = solve(Mat::from_fn(z.nrows(), z.ncols(), |i, j| z[(i, j)].re));
    let im = solve(Mat::from_fn(z.nrows(), z.ncols(), |i, j| z[(i, j)].im));
    Mat::from_fn(re.nrows(), re.ncols(), |i, j| c64::new(re[(i, j)], im[(i, j)]))
}

/// Left vectors `Y` (columns) paired with the right vectors of the same eigenvalues, made
/// biorthogonal to them within each cluster of equal eigenvalues (`Yᵀ V = I` there): the
/// left eigendecomposition is computed apart, so inside a multiple eigenvalue its basis is
/// not the right one's dual. `None` when a cluster's `Yᵀ V` is singular.
fn paired_left(t_right: &[c64], v: &Mat<c64>, t_left: &[c64], y: &Mat<c64>) -> Option<Mat<c64>> {
    let n = t_right.len();
    let mut used = vec![false; n];
    let mut order = Vec::with_capacity(n);
    for &t in t_right {
        let j = (0..n).filter(|&j| !used[j]).min_by(|&a, &b| (t_left[a] - t).norm().total_cmp(&(t_left[b] - t).norm()))?;
        used[j] = true;
        order.push(j);
    }
    let mut out = Mat::<c64>::from_fn(n, n, |i, k| y[(i, order[k])]);
    let mut done = vec![false; n];
    for a in 0..n {
        if done[a] {
            continue;
        }
        let tol = 1e-8 * t_right[a].norm().max(1e-3);
        let cluster: Vec<usize> = (a..n).filter(|&b| !done[b] && (t_right[b] - t_right[a]).norm() <= tol).collect();
        cluster.iter().for_each(|&b| done[b] = true);
        let m = cluster.len();
        // G = Yᵀ V on the cluster; Y ← Y G⁻ᵀ.
        let g = Mat::<c64>::from_fn(m, m, |i, j| (0..n).fold(c64::new(0.0, 0.0), |s, row| s + out[(row, cluster[i])] * v[(row, cluster[j])]));
        let lu = g.partial_piv_lu();
        let gu = lu.U();
        let (small, big) = (0..m).map(|i| gu[(i, i)].norm()).fold((f64::INFINITY, 0.0f64), |(s, b), x| (s.min(x), b.max(x)));
        if !(small > 1e-8 * big) {
            return None;
        }
        let g_inv = lu.inverse();
        let block = Mat::<c64>::from_fn(n, m, |row, k| (0..m).fold(c64::new(0.0, 0.0), |s, i| s + out[(row, cluster[i])] * g_inv[(k, i)]));
        for (k, &col) in cluster.iter().enumerate() {
            for row in 0..n {
                out[(row, col)] = block[(row, k)];
            }
        }
    }
    Some(out)
}

/// The modes of `λ e + k` at half the size when [`split`] finds the undamped structure and
/// every block it needs is nonsingular; `None` otherwise (the caller runs QZ). `dcoef` is
/// the Λ form's coefficient, `σ = 1/dcoef²` the Cayley shift.
pub(super) fn half_size_modes(e: &Mat<f64>, k: &Mat<f64>, dcoef: f64) -> Option<Vec<HalfSizeMode>> {
    let [r1, q, r2, p] = split(e, k)?;
    let n = q.len();
    let block = |m: &Mat<f64>, rows: &[usize], cols: &[usize]| Mat::<f64>::from_fn(n, n, |i, j| m[(rows[i], cols[j])]);
    let (e11, e22, k12, k21) = (block(e, &r1, &q), block(e, &r2, &p), block(k, &r1, &p), block(k, &r2, &q));
    let k12_lu = k12.partial_piv_lu();
    if !pivots_clear(k12_lu.U()) {
        return None;
    }
    // p = −λ X q with X = K₁₂⁻¹ E₁₁; the mass B = −E₂₂ X.
    let x = k12_lu.solve(&e11);
    let b = -(&e22 * &x);
    let sigma = 1.0 / (dcoef * dcoef);
    if !(sigma.is_finite() && sigma > 0.0) {
        return None;
    }
    let shifted = &k21 + &b * faer::Scale(sigma);
    let s_lu = shifted.partial_piv_lu();
    if !pivots_clear(s_lu.U()) {
        return None;
    }
    // C = (K₂₁ + σB)⁻¹ (K₂₁ − σB), whose transpose gives the left vectors, and its similar
    // C' = (K₂₁ − σB)(K₂₁ + σB)⁻¹ = ((K₂₁ + σB)⁻ᵀ (K₂₁ − σB)ᵀ)ᵀ, the right ones.
    let minus = &k21 - &b * faer::Scale(sigma);
    let c_transposed = s_lu.solve(&minus).transpose().to_owned();
    let c_forces = s_lu.solve_transpose(minus.transpose()).transpose().to_owned();
    if !c_transposed.as_ref().is_all_finite() || !c_forces.as_ref().is_all_finite() {
        return None;
    }
    let (right, left) = rayon::join(|| c_forces.eigen().ok(), || c_transposed.eigen().ok());
    let (right, left) = (right?, left?);
    let t_right: Vec<c64> = right.S().column_vector().iter().copied().collect();
    let t_left: Vec<c64> = left.S().column_vector().iter().copied().collect();
    // q = (K₂₁ + σB)⁻¹ z.
    let v = solve_complex(&right.U().to_owned(), |m| s_lu.solve(m));
    let y = paired_left(&t_right, &v, &t_left, &left.U().to_owned())?;
    // ψ = (K₂₁ + σB)⁻ᵀ y, then K₁₂⁻ᵀ E₂₂ᵀ ψ; X q.
    let psi = solve_complex(&y, |m| s_lu.solve_transpose(m));
    let k12t_e22t_psi = solve_complex(&real_times(e22.transpose(), &psi), |m| k12_lu.solve_transpose(m));
    let xq = real_times(x.as_ref(), &v);
    let r = 2 * n;
    let mut out = Vec::with_capacity(r);
    // Smallest |s| kept: below it λ = 0 is a double root (a free motion's Jordan block),
    // whose vectors the first-order form does not have: QZ labels those.
    let negligible = 1e3 * n as f64 * f64::EPSILON * sigma;
    for (i, &t) in t_right.iter().enumerate() {
        // A real matrix's complex eigenvalues come in conjugate pairs: the one with Im t > 0
        // stands for both (its λ and −λ are each a conjugate pair of the first-order form).
        if t.im < 0.0 {
            continue;
        }
        let one_minus = c64::new(1.0, 0.0) - t;
        if !(one_minus.norm() > 1e3 * f64::EPSILON) {
            return None;
        }
        let s = (c64::new(1.0, 0.0) + t) / one_minus * sigma;
        if !(s.norm() > negligible) || !(s.re.is_finite() && s.im.is_finite()) {
            return None;
        }
        let root = (-s).sqrt();
        // Real s > 0: λ = ±i√s, one conjugate pair (the +i one stands for it). Real s < 0:
        // λ = ±√|s|, two real roots. Complex s: λ = ±√(−s), two conjugate pairs.
        let roots: Vec<(c64, bool)> = if t.im == 0.0 {
            if s.re > 0.0 { vec![(c64::new(0.0, root.im.abs()), true)] } else { vec![(root, false), (-root, false)] }
        } else {
            vec![(root, true), (-root, true)]
        };
        for (lambda, pair) in roots {
            let mut z = Col::<c64>::zeros(r);
            let mut w = Col::<c64>::zeros(r);
            for row in 0..n {
                z[q[row]] = v[(row, i)];
                z[p[row]] = -lambda * xq[(row, i)];
                w[r2[row]] = psi[(row, i)];
                w[r1[row]] = -lambda * k12t_e22t_psi[(row, i)];
            }
            out.push(HalfSizeMode { lambda, right: z, left: w, pair });
        }
    }
    (out.iter().map(|m| if m.pair { 2 } else { 1 }).sum::<usize>() == r).then_some(out)
}
