//! Exact deflation of the eigenvalues that the constraint structure fixes, so that QZ runs
//! on the dynamic part of the pencil `λ F_yd + F_y` only (eqs. 10, 29–30).
//!
//! With `C` the constraint rows and `L` their multipliers (`m` of each, `D` the other
//! indices), three exact steps:
//! 1. Form of eq. 30 → form of eq. 29. In eq. 30 the rows `C` and columns `L` sit in `F_yd`
//!    only, and `F_yd[C, L] = 0`; moving them to `F_y` gives the plain pencil `P₂₉` with
//!    `P₃₀(λ) = Δ(λ) P₂₉(λ) Δ(λ)`, `Δ = diag(λ on C and L, 1 elsewhere)`, so
//!    `det P₃₀ = λ^{2m} det P₂₉`: the 2m zero eigenvalues of the constrained variables
//!    leave, and vectors map as `v₃₀[L] = v₂₉[L]/λ`, `u₃₀[C] = u₂₉[C]/λ`.
//! 2. Eq. 29: `P = [[P_DD(λ), H], [G, 0]]` with `G = F_y[C, D]`, `H = F_y[D, L]` of full
//!    rank. With full QRs `Gᵀ = Q_G R_G`, `H = Q_H R_H`, `N = Q_G[:, m..]`,
//!    `M = Q_H[:, m..]`: `det P = ± det R_G det R_H det(Mᵀ P_DD N)`, which removes 2m
//!    infinite eigenvalues (multipliers and constrained coordinates). The right vector's
//!    multipliers follow from `H v_L = −P_DD v_D`, the left vector's constraint part from
//!    `Gᵀ u_C = −P_DDᵀ u_D`.
//! 3. Index-1 part: with the SVD `E₁ = Mᵀ F_yd N = U diag(Σ, 0) Vᵀ` and
//!    `Uᵀ K₁ V = [[A₁₁, A₁₂], [A₂₁, A₂₂]]`, `A₂₂` nonsingular, the Schur complement
//!    `λ Σ + A₁₁ − A₁₂ A₂₂⁻¹ A₂₁` keeps every finite eigenvalue and drops the infinite ones
//!    (momenta fixed by the momentum-definition rows, static nodes).
//!
//! All steps are orthogonal or exact eliminations of a balanced pencil; any structure they
//! need that is missing (a non-zero where a zero must be, a rank-deficient `G` or `H`, no
//! clear gap in `Σ`, a singular `A₂₂`) returns `None`, and the caller runs QZ on the whole
//! pencil.

use faer::{c64, Mat};

use super::balance::balance_pencil;
use crate::linear::SparseMatrix;
use crate::model::ConstraintForm;

/// The dynamic part `λ E + K` of a pencil and what is needed to lift its vectors back.
pub(super) struct DynamicPart {
    pub e: Mat<f64>,
    pub k: Mat<f64>,
    /// Eigenvalues deflated at λ = 0 (step 1) and at λ = ∞ (steps 2–3).
    pub zeros: usize,
    pub infinities: usize,
    /// The pencil is proven regular: `E₁` nonsingular with a margin (no index-1 part), since
    /// `det(λ E₁ + K₁)` has the leading coefficient `det E₁ ≠ 0`; or, with an index-1 part,
    /// `A₂₂` certified nonsingular by [`crate::lu::certified_partial_lu`] (leading coefficient
    /// `± det A₂₂ det Σ`). A full-pivoting LU's pivots of `A₂₂`, only checked against each
    /// other, do not prove it.
    pub regular: bool,
    n: usize,
    scaled: bool,
    row_scale: Vec<f64>,
    col_scale: Vec<f64>,
    d: Vec<usize>,
    l: Vec<usize>,
    fyd_dd: SparseMatrix,
    fy_dd: SparseMatrix,
    /// Range of `Gᵀ` and of `H` (first m columns of `Q_G`, `Q_H`) and their `R`.
    q_g1: Mat<f64>,
    r_g: Mat<f64>,
    q_h1: Mat<f64>,
    r_h: Mat<f64>,
    /// `N X₂` and `M Y₂`: the dynamic part's right and left bases in the `D` unknowns.
    nx2: Mat<f64>,
    my2: Mat<f64>,
}

/// How far above the rounding level `s ε σ_max` every singular value of a full-rank `E₁`
/// must be for it to count as nonsingular (step 3).
const FULL_RANK_MARGIN: f64 = 1e4;

fn all_zero(m: &Mat<f64>, rows: &[usize], cols: &[usize]) -> bool {
    rows.iter().all(|&i| cols.iter().all(|&j| m[(i, j)] == 0.0))
}

/// Full QR of a tall `p x m` matrix of full column rank: `(Q, R)` with `R` `m x m`.
fn full_rank_qr(a: &Mat<f64>) -> Option<(Mat<f64>, Mat<f64>)> {
    let m = a.ncols();
    let qr = a.qr();
    let r = qr.thin_R().to_owned();
    let diag: Vec<f64> = (0..m).map(|i| r[(i, i)].abs()).collect();
    let big = diag.iter().copied().fold(0.0, f64::max);
    if diag.iter().any(|&x| !(x > big * a.nrows() as f64 * f64::EPSILON)) {
        return None;
    }
    Some((qr.compute_Q(), r))
}

/// Whether bounds prove what step 3's singular values would find: `E₁` (`s x s`) of full
/// rank with its smallest singular value `FULL_RANK_MARGIN` above the rounding level
/// `s ε σ_max`. `σ_min ≥ 1/‖E₁⁻¹‖_F` and `σ_max ≤ √(‖E₁‖₁ ‖E₁‖_∞)`, so the test below
/// implies the singular values' one; an inverse that is not finite, or bounds too loose to
/// decide, leave it to the SVD. One LU and inverse (about 2s³ flops, in blocked products)
/// instead of a bidiagonalization (examples/ham_sas.mbd, s = 132: 8 M of the SVD's
/// instructions saved).
fn provably_full_rank(e1: &Mat<f64>) -> bool {
    let s = e1.nrows();
    if s == 0 || e1.ncols() != s {
        return false;
    }
    use faer::linalg::solvers::DenseSolveCore;
    let inverse = e1.partial_piv_lu().inverse();
    let inv_f = inverse.norm_l2();
    if !(inv_f.is_finite() && inv_f > 0.0) {
        return false;
    }
    let norm_1 = (0..s).map(|j| (0..s).map(|i| e1[(i, j)].abs()).sum::<f64>()).fold(0.0, f64::max);
    let norm_inf = (0..s).map(|i| (0..s).map(|j| e1[(i, j)].abs()).sum::<f64>()).fold(0.0, f64::max);
    let negligible = s as f64 * f64::EPSILON * (norm_1 * norm_inf).sqrt();
    1.0 / inv_f > FULL_RANK_MARGIN * negligible
}

impl DynamicPart {
    /// Deflates the pencil `λ F_yd + F_y` whose constraint rows and multipliers are
    /// `multipliers` (each index both); `None` when the structure is not there.
    pub fn new(fyd: &Mat<f64>, fy: &Mat<f64>, form: Option<ConstraintForm>, multipliers: &[usize]) -> Option<Self> {
        let n = fyd.nrows();
        let mut l = multipliers.to_vec();
        l.sort_unstable();
        l.dedup();
        if l.len() != multipliers.len() || l.last().is_some_and(|&k| k >= n) {
            return None;
        }
        let mut is_l = vec![false; n];
        for &k in &l {
            is_l[k] = true;
        }
        let d: Vec<usize> = (0..n).filter(|&i| !is_l[i]).collect();
        let all: Vec<usize> = (0..n).collect();
        let scaled = form == Some(ConstraintForm::Scaled) && !l.is_empty();
        let (mut pd, mut py) = (fyd.clone(), fy.clone());
        if scaled {
            // Step 1: eq. 30 -> eq. 29.
            if !(all_zero(fy, &l, &all) && all_zero(fy, &all, &l) && all_zero(fyd, &l, &l)) {
                return None;
            }
            for &k in &l {
                for j in 0..n {
                    py[(k, j)] = pd[(k, j)];
                    pd[(k, j)] = 0.0;
                    py[(j, k)] = pd[(j, k)];
                    pd[(j, k)] = 0.0;
                }
            }
        }
        if !(all_zero(&pd, &l, &all) && all_zero(&pd, &all, &l) && all_zero(&py, &l, &l)) {
            return None;
        }
        let bal = balance_pencil(&py, &pd);
        let (a, b) = (&bal.a, &bal.b);
        let (m, nd) = (l.len(), d.len());
        let fyd_dd = SparseMatrix::from_dense_part(b, &d, &d);
        let fy_dd = SparseMatrix::from_dense_part(a, &d, &d);
        // Step 2: N = null(G), M = null(Hᵀ).
        let (q_g, r_g, q_h, r_h) = if m > 0 {
            let gt = Mat::from_fn(nd, m, |i, j| a[(l[j], d[i])]);
            let h = Mat::from_fn(nd, m, |i, j| a[(d[i], l[j])]);
            let (q_g, r_g) = full_rank_qr(&gt)?;
            let (q_h, r_h) = full_rank_qr(&h)?;
            (q_g, r_g, q_h, r_h)
        } else {
            (Mat::identity(nd, nd), Mat::zeros(0, 0), Mat::identity(nd, nd), Mat::zeros(0, 0))
        };
        let (nn, mm) = (q_g.subcols(m, nd - m), q_h.subcols(m, nd - m));
        let e1 = mm.transpose() * fyd_dd.mul_dense(&nn.to_owned());
        let k1 = mm.transpose() * fy_dd.mul_dense(&nn.to_owned());
        // Step 3: index-1 part by the SVD of E₁.
        let s = nd - m;
        // A full rank with the margin below proven by bounds costs one LU; otherwise the
        // singular values decide (U and V are needed only when E₁ is rank deficient).
        let (rank, svd) = if provably_full_rank(&e1) {
            (s, None)
        } else {
            // One SVD with its vectors: bounds that do not prove a full rank mostly mean a
            // rank deficiency, where U and V are needed (the 1712-equation chain: 200 of 700).
            let svd = e1.svd().ok()?;
            let sv: Vec<f64> = (0..s).map(|i| svd.S()[i]).collect();
            let top = sv.first().copied().unwrap_or(0.0);
            let negligible = s as f64 * f64::EPSILON * top;
            let rank = sv.iter().take_while(|&&x| x > negligible).count();
            // The structural zeros sit at rounding level. A full rank is clear when the
            // smallest singular value is FULL_RANK_MARGIN above that level (masses of 1e5 kg
            // next to inertias of 1e-4 kg m², examples/ham_sas.mbd: 1.1e-8 of the largest,
            // 3.7e5 above rounding); a deficient rank when a gap of four decades separates the
            // singular values kept from those dropped and the kept ones stand a decade above
            // rounding. Anything else makes the rank a guess: leave the pencil whole. (The
            // earlier test, any kept value below sqrt(ε) of the largest, refused lumped beams,
            // whose rotary inertias ρA ℓ³/12 sit 5e-10 of the masses' singular values above
            // six exact zeros on 32 elements, and sent the whole 786-equation pencil to QZ:
            // issue 30.)
            let clear = if rank == s { sv[s - 1] > FULL_RANK_MARGIN * negligible } else { rank > 0 && sv[rank - 1] > 10.0 * negligible && sv[rank] <= 1e-4 * sv[rank - 1] };
            if !clear {
                return None;
            }
            (rank, Some((svd, sv)))
        };
        // With an index-1 part, `A₂₂` proven nonsingular by a certified LU makes the pencil
        // regular too: `det(λ E₁ + K₁) = ± det A₂₂ det(λ Σ + K₂)`, leading coefficient
        // `± det A₂₂ det Σ ≠ 0`.
        let (e2, k2, x2, y2, a22_certified) = match svd.filter(|_| rank < s) {
            Some((svd, sv)) => {
                let (u, v) = (svd.U(), svd.V());
                let a_t = u.transpose() * &k1 * v;
                let (a11, a12) = (a_t.submatrix(0, 0, rank, rank), a_t.submatrix(0, rank, rank, s - rank));
                let (a21, a22) = (a_t.submatrix(rank, 0, s - rank, rank), a_t.submatrix(rank, rank, s - rank, s - rank));
                let tolerance = (s - rank) as f64 * f64::EPSILON;
                // Negligible against the whole K₁ (= ‖Uᵀ K₁ V‖_F), not against A₂₂ itself:
                // a singular pencil leaves A₂₂ at rounding level, nonsingular relative to
                // itself (tests/reliability/reliability.rs, a common null vector).
                let k1_norm = a_t.norm_l2();
                use faer::linalg::solvers::Solve;
                let (g21, g12t, certified) = match crate::lu::certified_partial_lu(a22, tolerance, k1_norm) {
                    Some(lu) => (lu.solve(a21.to_owned()), lu.solve_transpose(a12.transpose().to_owned()), true),
                    None => {
                        let lu = a22.full_piv_lu();
                        if !crate::lu::full_pivots_nonsingular(&lu, tolerance) {
                            return None;
                        }
                        (lu.solve(a21.to_owned()), lu.solve_transpose(a12.transpose().to_owned()), false)
                    }
                };
                let k2 = a11 - a12 * &g21;
                let x2 = v.subcols(0, rank) - v.subcols(rank, s - rank) * &g21;
                let y2 = u.subcols(0, rank) - u.subcols(rank, s - rank) * &g12t;
                (Mat::from_fn(rank, rank, |i, j| if i == j { sv[i] } else { 0.0 }), k2, Some(x2), Some(y2), certified)
            }
            // Full rank: no index-1 part, the dynamic part is (E₁, K₁) itself (X₂ = Y₂ = I).
            None => (e1, k1, None, None, false),
        };
        let times = |q: faer::MatRef<'_, f64>, x: Option<Mat<f64>>| x.map_or_else(|| q.to_owned(), |x| q * x);
        Some(DynamicPart {
            e: e2,
            k: k2,
            zeros: if scaled { 2 * m } else { 0 },
            infinities: if scaled { s - rank } else { 2 * m + s - rank },
            regular: rank == s || a22_certified,
            n,
            scaled,
            row_scale: bal.row.clone(),
            col_scale: bal.col.clone(),
            d,
            l,
            fyd_dd,
            fy_dd,
            q_g1: q_g.subcols(0, m).to_owned(),
            r_g,
            q_h1: q_h.subcols(0, m).to_owned(),
            r_h,
            nx2: times(nn, x2),
            my2: times(mm, y2),
        })
    }

    /// Size of the dynamic part.
    pub fn dim(&self) -> usize {
        self.e.nrows()
    }

    /// Right vectors of the whole pencil (given form, unbalanced), one column per right
    /// vector `z` of `λ E + K` (columns of `z`, eigenvalues `lambda`).
    pub fn right(&self, z: &Mat<c64>, lambda: &[c64]) -> Mat<c64> {
        let v_d = real_times_complex(self.nx2.as_ref(), z);
        let v_l = self.multiplier_part(&v_d, lambda, false);
        self.assemble(&v_d, &v_l, lambda, &self.col_scale)
    }

    /// Left vectors of the whole pencil from left vectors `w` of `λ E + K`.
    pub fn left(&self, w: &Mat<c64>, lambda: &[c64]) -> Mat<c64> {
        let u_d = real_times_complex(self.my2.as_ref(), w);
        let u_c = self.multiplier_part(&u_d, lambda, true);
        self.assemble(&u_d, &u_c, lambda, &self.row_scale)
    }

    /// Right: `v_L` from `H v_L = −P_DD(λ) v_D`; left (`transpose`): `u_C` from
    /// `Gᵀ u_C = −P_DD(λ)ᵀ u_D`. Both by `R⁻¹ Q₁ᵀ` of the QR of `H` resp. `Gᵀ`.
    fn multiplier_part(&self, x_d: &Mat<c64>, lambda: &[c64], transpose: bool) -> Mat<c64> {
        let m = self.l.len();
        if m == 0 {
            return Mat::zeros(0, x_d.ncols());
        }
        let (fy, fyd) = if transpose {
            (self.fy_dd.mul_t_complex_mat(x_d), self.fyd_dd.mul_t_complex_mat(x_d))
        } else {
            (self.fy_dd.mul_complex_mat(x_d), self.fyd_dd.mul_complex_mat(x_d))
        };
        let p = Mat::from_fn(x_d.nrows(), x_d.ncols(), |i, j| -(fy[(i, j)] + lambda[j] * fyd[(i, j)]));
        let (q1, r) = if transpose { (&self.q_g1, &self.r_g) } else { (&self.q_h1, &self.r_h) };
        // R⁻¹ (Q₁ᵀ P) on the real and imaginary parts, each one blocked triangular solve.
        let (mut re, mut im) = real_times_complex_parts(q1.transpose(), &p);
        for part in [&mut re, &mut im] {
            faer::linalg::triangular_solve::solve_upper_triangular_in_place(r.as_ref(), part.as_mut(), faer::get_global_parallelism());
        }
        Mat::from_fn(m, x_d.ncols(), |i, j| c64::new(re[(i, j)], im[(i, j)]))
    }

    /// Scatters `D` and multiplier parts into whole vectors, maps the form of eq. 29 back
    /// to eq. 30 (`/λ` on the multipliers or constraint rows) and undoes the balancing.
    fn assemble(&self, x_d: &Mat<c64>, x_l: &Mat<c64>, lambda: &[c64], scale: &[f64]) -> Mat<c64> {
        let mut out = Mat::<c64>::zeros(self.n, x_d.ncols());
        for j in 0..x_d.ncols() {
            for (i, &k) in self.d.iter().enumerate() {
                out[(k, j)] = x_d[(i, j)] * scale[k];
            }
            for (i, &k) in self.l.iter().enumerate() {
                let x = if self.scaled { x_l[(i, j)] / lambda[j] } else { x_l[(i, j)] };
                out[(k, j)] = x * scale[k];
            }
        }
        out
    }
}

/// `M Z` for real `M` and complex `Z` (two real products).
fn real_times_complex(m: faer::MatRef<'_, f64>, z: &Mat<c64>) -> Mat<c64> {
    let (a, b) = real_times_complex_parts(m, z);
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| c64::new(a[(i, j)], b[(i, j)]))
}

/// The real and imaginary parts of `M Z` for real `M` and complex `Z`.
fn real_times_complex_parts(m: faer::MatRef<'_, f64>, z: &Mat<c64>) -> (Mat<f64>, Mat<f64>) {
    let re = Mat::<f64>::from_fn(z.nrows(), z.ncols(), |i, j| z[(i, j)].re);
    let im = Mat::<f64>::from_fn(z.nrows(), z.ncols(), |i, j| z[(i, j)].im);
    (m * &re, m * &im)
}
