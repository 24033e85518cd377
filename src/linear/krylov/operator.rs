//! The shift-invert operator `T = (K + σ E)⁻¹ E` (and its transpose `(K + σ E)⁻ᵀ Eᵀ` for
//! the adjoint problem, eq. 11), applied through one sparse LU of `K + σ E` (faer), never
//! formed. `T v = θ v` with `θ = −1/(λ − σ)`: the eigenvalues nearest the shift are the
//! largest θ, the infinite ones map to θ = 0. A real shift is factored in real arithmetic,
//! a complex one in complex arithmetic.
//!
//! The Krylov iterations apply `T` in place ([`ShiftInvert::apply_into`]: `E x` written
//! straight into the output column, the LU solved on it with the caller's [`Workspace`]),
//! so an application allocates nothing. faer's solve permutes the right-hand side's rows
//! before and after the triangular solves; it is handed as an `n x 1` column-major matrix
//! (column stride `n`), for which that permutation is one gather per entry (a column view
//! with stride 0 took faer's row-by-row path, 90 instructions an entry: 56 % of the solve
//! at N = 1000).

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::reborrow::ReborrowMut;
use faer::{c64, Col, ColMut, ColRef, Conj, Mat, MatMut, Par};

use super::pencil::Pencil;
use super::KrylovError;
use crate::linear::sparse::{contiguous, contiguous_mut};

enum Factor {
    Real(NumericLu<usize, f64>),
    Complex(NumericLu<usize, c64>),
}

/// One factorization of `K + σ E` and the operator it gives.
pub(super) struct ShiftInvert<'a> {
    pub sigma: c64,
    pencil: &'a Pencil,
    symbolic: SymbolicLu<usize>,
    factor: Factor,
    /// Scratch of one solve with two real or one complex right-hand side.
    scratch: StackReq,
}

/// The scratch one caller's solves use (one per thread: the factorization is shared, read
/// only), and the real and imaginary parts of a complex vector for a real factorization.
pub(super) struct Workspace {
    stack: MemBuffer,
    parts: Mat<f64>,
}

/// Largest relative residual of the test solve that accepts a factorization.
const FACTOR_TOLERANCE: f64 = 1e-9;

impl<'a> ShiftInvert<'a> {
    /// Factors `K + σ E`; an error when it is singular or its solves are not accurate
    /// (σ on or next to an eigenvalue).
    pub fn new(pencil: &'a Pencil, sigma: c64) -> Result<Self, KrylovError> {
        let n = pencil.dim();
        let singular = || KrylovError::Singular(sigma);
        let (symbolic, factor, scratch) = if sigma.im == 0.0 {
            let (col_ptr, row_idx, values) = pencil.k.csc_sum(&pencil.e, |v| v, |v| sigma.re * v, |x, y| x + y);
            let a = SparseColMat::<usize, f64>::new(SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx), values);
            let symbolic = factorize_symbolic_lu(a.symbolic(), Default::default()).map_err(|_| singular())?;
            let mut numeric = NumericLu::new();
            let mut buf = MemBuffer::try_new(symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default())).map_err(|_| singular())?;
            symbolic.factorize_numeric_lu(&mut numeric, a.as_ref(), Par::Seq, MemStack::new(&mut buf), Default::default()).map_err(|_| singular())?;
            let scratch = symbolic.solve_in_place_scratch::<f64>(2, Par::Seq);
            (symbolic, Factor::Real(numeric), scratch)
        } else {
            let (col_ptr, row_idx, values) = pencil.k.csc_sum(&pencil.e, |v| c64::new(v, 0.0), |v| sigma * v, |x, y| x + y);
            let a = SparseColMat::<usize, c64>::new(SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx), values);
            let symbolic = factorize_symbolic_lu(a.symbolic(), Default::default()).map_err(|_| singular())?;
            let mut numeric = NumericLu::new();
            let mut buf = MemBuffer::try_new(symbolic.factorize_numeric_lu_scratch::<c64>(Par::Seq, Default::default())).map_err(|_| singular())?;
            symbolic.factorize_numeric_lu(&mut numeric, a.as_ref(), Par::Seq, MemStack::new(&mut buf), Default::default()).map_err(|_| singular())?;
            let scratch = symbolic.solve_in_place_scratch::<c64>(1, Par::Seq);
            (symbolic, Factor::Complex(numeric), scratch)
        };
        let op = ShiftInvert { sigma, pencil, symbolic, factor, scratch };
        // A test solve against a fixed right-hand side: ‖A x − r‖ / (‖A‖ ‖x‖ + ‖r‖).
        let r = Col::<c64>::from_fn(n, |i| c64::new(1.0 + (i % 7) as f64 * 0.1, (i % 3) as f64 * 0.2));
        let mut x = r.clone();
        op.solve_in_place(x.as_mut(), false, &mut op.workspace());
        let ax = op.shifted(&x, false);
        let res = (0..n).map(|i| (ax[i] - r[i]).norm_sqr()).sum::<f64>().sqrt();
        let norm_a = pencil.k.norm_l2() + sigma.norm() * pencil.e.norm_l2();
        let rel = res / (norm_a * x.norm_l2() + r.norm_l2());
        if !(rel <= FACTOR_TOLERANCE) {
            return Err(KrylovError::Inaccurate { sigma, residual: rel });
        }
        Ok(op)
    }

    /// A workspace for [`Self::apply_into`] and [`Self::solve_in_place`].
    pub fn workspace(&self) -> Workspace {
        let parts = if matches!(self.factor, Factor::Real(_)) { Mat::zeros(self.pencil.dim(), 2) } else { Mat::zeros(0, 2) };
        Workspace { stack: MemBuffer::new(self.scratch), parts }
    }

    /// `(K + σ E) x` (or `(K + σ E)ᵀ x`).
    fn shifted(&self, x: &Col<c64>, transpose: bool) -> Col<c64> {
        let (kx, ex) = if transpose { (self.pencil.k.mul_t_complex(x), self.pencil.e.mul_t_complex(x)) } else { (self.pencil.k.mul_complex(x), self.pencil.e.mul_complex(x)) };
        Col::from_fn(x.nrows(), |i| kx[i] + self.sigma * ex[i])
    }

    /// `x ← (K + σ E)⁻¹ x` (or `⁻ᵀ`), for a real or complex `x` (a complex one for a real
    /// factorization goes through its real and imaginary parts).
    pub fn solve_in_place<T: Entry>(&self, x: ColMut<'_, T>, transpose: bool, ws: &mut Workspace) {
        T::solve_in_place(self, x, transpose, ws);
    }

    /// `out = T x = (K + σ E)⁻¹ E x`, or the `Tᵀ`-side `(K + σ E)⁻ᵀ Eᵀ x` for the left
    /// vectors; a real `x` needs a real shift.
    pub fn apply_into<T: Entry>(&self, x: ColRef<'_, T>, mut out: ColMut<'_, T>, transpose: bool, ws: &mut Workspace) {
        let (x, o) = (contiguous(x), contiguous_mut(out.rb_mut()));
        if transpose {
            self.pencil.e.mul_t_into(x, o);
        } else {
            self.pencil.e.mul_into(x, o);
        }
        T::solve_in_place(self, out, transpose, ws);
    }

    /// λ of an eigenvalue θ of T: `λ = σ − 1/θ`.
    pub fn lambda(&self, theta: c64) -> c64 {
        self.sigma - c64::new(1.0, 0.0) / theta
    }
}

/// The entries the operator applies to: `f64` (a real shift only) or `c64`.
pub(super) trait Entry: crate::linear::SparseScalar {
    fn solve_in_place(op: &ShiftInvert, x: ColMut<'_, Self>, transpose: bool, ws: &mut Workspace);
}

/// `rhs ← A⁻¹ rhs` (or `A⁻ᵀ`) by faer's LU, `rhs` an `n x k` column-major block.
fn lu_solve<T: faer::traits::ComplexField>(symbolic: &SymbolicLu<usize>, numeric: &NumericLu<usize, T>, rhs: MatMut<'_, T>, transpose: bool, ws: &mut MemBuffer) {
    let lu = LuRef::new_unchecked(symbolic, numeric);
    if transpose {
        lu.solve_transpose_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(ws));
    } else {
        lu.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(ws));
    }
}

impl Entry for f64 {
    fn solve_in_place(op: &ShiftInvert, x: ColMut<'_, f64>, transpose: bool, ws: &mut Workspace) {
        let Factor::Real(numeric) = &op.factor else { unreachable!("a real vector is solved with the factorization of a real shift") };
        let n = x.nrows();
        lu_solve(&op.symbolic, numeric, MatMut::from_column_major_slice_mut(contiguous_mut(x), n, 1), transpose, &mut ws.stack);
    }
}

impl Entry for c64 {
    fn solve_in_place(op: &ShiftInvert, mut x: ColMut<'_, c64>, transpose: bool, ws: &mut Workspace) {
        let n = x.nrows();
        match &op.factor {
            Factor::Real(numeric) => {
                let parts = &mut ws.parts;
                for i in 0..n {
                    parts[(i, 0)] = x[i].re;
                    parts[(i, 1)] = x[i].im;
                }
                lu_solve(&op.symbolic, numeric, parts.as_mut(), transpose, &mut ws.stack);
                for i in 0..n {
                    x[i] = c64::new(parts[(i, 0)], parts[(i, 1)]);
                }
            }
            Factor::Complex(numeric) => lu_solve(&op.symbolic, numeric, MatMut::from_column_major_slice_mut(contiguous_mut(x), n, 1), transpose, &mut ws.stack),
        }
    }
}
