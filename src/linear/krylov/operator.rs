//! The shift-invert operator `T = (K + σ E)⁻¹ E` (and its transpose `(K + σ E)⁻ᵀ Eᵀ` for
//! the adjoint problem, eq. 11), applied through one sparse LU of `K + σ E` (faer), never
//! formed. `T v = θ v` with `θ = −1/(λ − σ)`: the eigenvalues nearest the shift are the
//! largest θ, the infinite ones map to θ = 0. A real shift is factored in real arithmetic,
//! a complex one in complex arithmetic.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Lu;
use faer::sparse::{SparseColMat, Triplet};
use faer::{c64, Col, Mat};

use super::pencil::Pencil;
use super::KrylovError;

enum Factor {
    Real(Lu<usize, f64>),
    Complex(Lu<usize, c64>),
}

/// One factorization of `K + σ E` and the operator it gives.
pub(super) struct ShiftInvert<'a> {
    pub sigma: c64,
    pencil: &'a Pencil,
    factor: Factor,
}

/// Largest relative residual of the test solve that accepts a factorization.
const FACTOR_TOLERANCE: f64 = 1e-9;

impl<'a> ShiftInvert<'a> {
    /// Factors `K + σ E`; an error when it is singular or its solves are not accurate
    /// (σ on or next to an eigenvalue).
    pub fn new(pencil: &'a Pencil, sigma: c64) -> Result<Self, KrylovError> {
        let n = pencil.dim();
        let singular = || KrylovError::Singular(sigma);
        let factor = if sigma.im == 0.0 {
            let t: Vec<Triplet<usize, usize, f64>> = pencil.k.triplets().map(|(i, j, v)| Triplet::new(i, j, v)).chain(pencil.e.triplets().map(|(i, j, v)| Triplet::new(i, j, sigma.re * v))).collect();
            let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &t).map_err(|_| singular())?;
            Factor::Real(a.sp_lu().map_err(|_| singular())?)
        } else {
            let t: Vec<Triplet<usize, usize, c64>> =
                pencil.k.triplets().map(|(i, j, v)| Triplet::new(i, j, c64::new(v, 0.0))).chain(pencil.e.triplets().map(|(i, j, v)| Triplet::new(i, j, sigma * v))).collect();
            let a = SparseColMat::<usize, c64>::try_new_from_triplets(n, n, &t).map_err(|_| singular())?;
            Factor::Complex(a.sp_lu().map_err(|_| singular())?)
        };
        let op = ShiftInvert { sigma, pencil, factor };
        // A test solve against a fixed right-hand side: ‖A x − r‖ / (‖A‖ ‖x‖ + ‖r‖).
        let r = Col::<c64>::from_fn(n, |i| c64::new(1.0 + (i % 7) as f64 * 0.1, (i % 3) as f64 * 0.2));
        let x = op.solve(&r, false);
        let ax = op.shifted(&x, false);
        let res = (0..n).map(|i| (ax[i] - r[i]).norm_sqr()).sum::<f64>().sqrt();
        let norm_a = pencil.k.norm_l2() + sigma.norm() * pencil.e.norm_l2();
        let rel = res / (norm_a * x.norm_l2() + r.norm_l2());
        if !(rel <= FACTOR_TOLERANCE) {
            return Err(KrylovError::Inaccurate { sigma, residual: rel });
        }
        Ok(op)
    }

    /// `(K + σ E) x` (or `(K + σ E)ᵀ x`).
    fn shifted(&self, x: &Col<c64>, transpose: bool) -> Col<c64> {
        let (kx, ex) = if transpose { (self.pencil.k.mul_t_complex(x), self.pencil.e.mul_t_complex(x)) } else { (self.pencil.k.mul_complex(x), self.pencil.e.mul_complex(x)) };
        Col::from_fn(x.nrows(), |i| kx[i] + self.sigma * ex[i])
    }

    /// `(K + σ E)⁻¹ r` (or `⁻ᵀ`).
    pub fn solve(&self, r: &Col<c64>, transpose: bool) -> Col<c64> {
        let n = r.nrows();
        match &self.factor {
            Factor::Real(lu) => {
                let rhs = Mat::<f64>::from_fn(n, 2, |i, j| if j == 0 { r[i].re } else { r[i].im });
                let x = if transpose { lu.solve_transpose(&rhs) } else { lu.solve(&rhs) };
                Col::from_fn(n, |i| c64::new(x[(i, 0)], x[(i, 1)]))
            }
            Factor::Complex(lu) => {
                let rhs = Mat::<c64>::from_fn(n, 1, |i, _| r[i]);
                let x = if transpose { lu.solve_transpose(&rhs) } else { lu.solve(&rhs) };
                Col::from_fn(n, |i| x[(i, 0)])
            }
        }
    }

    /// `T x` (or the `Tᵀ`-side product) of a real vector for a real shift; `None` for a
    /// complex shift.
    pub fn apply_real(&self, x: &Col<f64>, transpose: bool) -> Option<Col<f64>> {
        let Factor::Real(lu) = &self.factor else { return None };
        let ex = if transpose { self.pencil.e.mul_t_real(x) } else { self.pencil.e.mul_real(x) };
        let mut x = ex;
        if transpose {
            lu.solve_transpose_in_place(x.as_mat_mut());
        } else {
            lu.solve_in_place(x.as_mat_mut());
        }
        Some(x)
    }

    /// `T x = (K + σ E)⁻¹ E x`, or `Tᵀ`-side `(K + σ E)⁻ᵀ Eᵀ x` for the left vectors.
    pub fn apply(&self, x: &Col<c64>, transpose: bool) -> Col<c64> {
        let ex = if transpose { self.pencil.e.mul_t_complex(x) } else { self.pencil.e.mul_complex(x) };
        self.solve(&ex, transpose)
    }

    /// λ of an eigenvalue θ of T: `λ = σ − 1/θ`.
    pub fn lambda(&self, theta: c64) -> c64 {
        self.sigma - c64::new(1.0, 0.0) / theta
    }
}
