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
use faer::sparse::linalg::lu::simplicial::{self, SimplicialLu};
use faer::reborrow::ReborrowMut;
use faer::{c64, Col, ColMut, ColRef, Mat, MatMut, Par};

use super::pencil::Pencil;
use super::KrylovError;
use crate::linear::{contiguous, contiguous_mut};
use crate::linear::SparseMatrix;
use crate::lu::PatternLu;

enum Factor {
    Real(PatternLu<f64>),
    /// A real simplicial LU held whole: [`Simplicial`].
    RealSimplicial(Box<Simplicial>),
    Complex(PatternLu<c64>),
}

/// faer's simplicial LU `P_r A P_cᵀ = L U` with its permutations in the open, so that an
/// application of the operator permutes no more than it must: faer's solve gathers the
/// right-hand side by `P_r` into scratch and copies it back, solves, then does the same by
/// `P_c⁻¹` (four passes over the vector, a third of the solve at 10⁵ unknowns); here `E`'s
/// rows are stored in `P_r`'s order (and `Eᵀ`'s in `P_c`'s for the transposed operator), so
/// the product lands permuted, and one gather writes the result. The same factorization
/// (faer's own simplicial routine on the same column order), the same sums: the same bits.
struct Simplicial {
    lu: SimplicialLu<usize, f64>,
    row_fwd: Vec<usize>,
    row_inv: Vec<usize>,
    col_fwd: Vec<usize>,
    col_inv: Vec<usize>,
    /// Row `i`: row `row_fwd[i]` of `E`.
    e_rows: SparseMatrix,
    /// Row `i`: column `col_fwd[i]` of `E`.
    et_rows: SparseMatrix,
    /// `1 / U[j, j]` (faer's solves multiply by the reciprocal: the same values).
    u_recip: Vec<f64>,
}

impl Simplicial {
    /// `x ← A⁻¹ x` (or `A⁻ᵀ`) for the columns of `x` (column-major), `t` scratch of the same size.
    fn solve(&self, mut x: MatMut<'_, f64>, transpose: bool, t: &mut Mat<f64>) {
        let (first, last) = if transpose { (&self.col_fwd, &self.row_inv) } else { (&self.row_fwd, &self.col_inv) };
        for c in 0..x.ncols() {
            for (i, &p) in first.iter().enumerate() {
                t[(i, c)] = x[(p, c)];
            }
        }
        self.triangular(t.as_mut().submatrix_mut(0, 0, x.nrows(), x.ncols()), transpose);
        for c in 0..x.ncols() {
            for (i, &p) in last.iter().enumerate() {
                x[(i, c)] = t[(p, c)];
            }
        }
    }

    /// `L U` (or `Uᵀ Lᵀ`) solved in place, column by column: the loops of faer's
    /// `solve_unit_lower_triangular_in_place`, `solve_upper_triangular_in_place` and their
    /// transposes (`sparse::linalg::triangular_solve`) for one right-hand side, the same
    /// operations in the same order (so the same bits: faer's multi-column loops treat each
    /// column alike), on the factors' raw arrays: faer's took 18 instructions a non-zero
    /// here, these about a third of that.
    fn triangular(&self, mut t: MatMut<'_, f64>, transpose: bool) {
        let (l, u) = (self.lu.l_factor_unsorted(), self.lu.u_factor_unsorted());
        let lf = (l.symbolic().col_ptr(), l.symbolic().row_idx(), l.val());
        let uf = (u.symbolic().col_ptr(), u.symbolic().row_idx(), u.val());
        for c in 0..t.ncols() {
            let x = contiguous_mut(t.rb_mut().col_mut(c));
            if transpose {
                upper_transpose(uf, &self.u_recip, x);
                unit_lower_transpose(lf, x);
            } else {
                unit_lower(lf, x);
                upper(uf, &self.u_recip, x);
            }
        }
    }

    /// `out = A⁻¹ E x` (or `A⁻ᵀ Eᵀ x`), `t` scratch of length n.
    fn apply(&self, x: &[f64], out: &mut [f64], transpose: bool, t: &mut [f64]) {
        let n = x.len();
        let (rows, last) = if transpose { (&self.et_rows, &self.row_inv) } else { (&self.e_rows, &self.col_inv) };
        rows.mul_into(x, t);
        self.triangular(MatMut::from_column_major_slice_mut(t, n, 1), transpose);
        for (o, &p) in out.iter_mut().zip(last.iter()) {
            *o = t[p];
        }
    }
}

/// One factorization of `K + σ E` and the operator it gives.
pub(super) struct ShiftInvert<'a> {
    pub sigma: c64,
    pencil: &'a Pencil,
    factor: Factor,
    /// Scratch of one solve with two real or one complex right-hand side.
    scratch: StackReq,
}

/// The scratch one caller's solves use (one per thread: the factorization is shared, read
/// only), and the real and imaginary parts of a complex vector for a real factorization.
pub(super) struct Workspace {
    stack: MemBuffer,
    parts: Mat<f64>,
    /// Scratch of [`Simplicial`]'s solves (two columns).
    t: Mat<f64>,
}

/// Largest relative residual of the test solve that accepts a factorization.
const FACTOR_TOLERANCE: f64 = 1e-9;

impl<'a> ShiftInvert<'a> {
    /// Factors `K + σ E`; an error when it is singular or its solves are not accurate
    /// (σ on or next to an eigenvalue).
    pub fn new(pencil: &'a Pencil, sigma: c64) -> Result<Self, KrylovError> {
        let n = pencil.dim();
        let singular = || KrylovError::Singular(sigma);
        let shifted = pencil.shifted();
        let symbolic = || pencil.symbolic().cloned().ok_or_else(singular);
        let (factor, scratch) = if sigma.im == 0.0 {
            let mut values = Vec::new();
            shifted.values_into(&mut values, |k, e| k + sigma.re * e);
            let a = shifted.matrix(&values);
            let mut lu = PatternLu::<f64>::with_symbolic(symbolic()?, Par::Seq);
            let numeric_scratch = lu.factor_scratch();
            let scratch = lu.solve_scratch(2);
            // faer chose its simplicial factorization when its numeric scratch is the
            // simplicial one (the supernodal one adds arrays of A's non-zeros): then the
            // same routine is called here, keeping the factors and permutations at hand.
            if numeric_scratch == simplicial::factorize_simplicial_numeric_lu_scratch::<usize, f64>(n, n) {
                let mut buf = MemBuffer::try_new(numeric_scratch).map_err(|_| singular())?;
                let (mut row_fwd, mut row_inv) = (vec![0usize; n], vec![0usize; n]);
                let mut simplicial_lu = SimplicialLu::new();
                simplicial::factorize_simplicial_numeric_lu(&mut row_fwd, &mut row_inv, &mut simplicial_lu, a, lu.symbolic().col_perm(), MemStack::new(&mut buf)).map_err(|_| singular())?;
                let (col_fwd, col_inv) = lu.symbolic().col_perm().arrays();
                let (col_fwd, col_inv) = (col_fwd.to_vec(), col_inv.to_vec());
                let (e_rows, et_rows) = (pencil.e.rows_in_order(&row_fwd), pencil.e.transpose_rows_in_order(&col_fwd));
                let u = simplicial_lu.u_factor_unsorted();
                let u_recip = (0..n).map(|j| 1.0 / u.val()[u.symbolic().col_ptr()[j + 1] - 1]).collect();
                (Factor::RealSimplicial(Box::new(Simplicial { lu: simplicial_lu, row_fwd, row_inv, col_fwd, col_inv, e_rows, et_rows, u_recip })), scratch)
            } else {
                let mut buf = MemBuffer::try_new(numeric_scratch).map_err(|_| singular())?;
                lu.factor(a, MemStack::new(&mut buf)).map_err(|_| singular())?;
                (Factor::Real(lu), scratch)
            }
        } else {
            let mut values = Vec::new();
            shifted.values_into(&mut values, |k, e| c64::new(k, 0.0) + sigma * e);
            let mut lu = PatternLu::<c64>::with_symbolic(symbolic()?, Par::Seq);
            let mut buf = MemBuffer::try_new(lu.factor_scratch()).map_err(|_| singular())?;
            lu.factor(shifted.matrix(&values), MemStack::new(&mut buf)).map_err(|_| singular())?;
            let scratch = lu.solve_scratch(1);
            (Factor::Complex(lu), scratch)
        };
        let op = ShiftInvert { sigma, pencil, factor, scratch };
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
        let n = self.pencil.dim();
        let real = !matches!(self.factor, Factor::Complex(_));
        let parts = if real { Mat::zeros(n, 2) } else { Mat::zeros(0, 2) };
        let t = if matches!(self.factor, Factor::RealSimplicial(_)) { Mat::zeros(n, 2) } else { Mat::zeros(0, 2) };
        Workspace { stack: MemBuffer::new(self.scratch), parts, t }
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
        if T::apply_fused(self, x, out.rb_mut(), transpose, ws) {
            return;
        }
        let (x, o) = (contiguous(x), contiguous_mut(out.rb_mut()));
        if transpose {
            self.pencil.e.mul_t_into(x, o);
        } else {
            self.pencil.e.mul_into(x, o);
        }
        T::solve_in_place(self, out, transpose, ws);
    }

    /// `T xᵢ` (or `Tᵀ xᵢ`) for every vector of a block: the products `E xᵢ` column by
    /// column, then one solve of all of them. A complex factorization is read once for the
    /// whole block (faer's triangular solves sweep each column of the factors for up to four
    /// right-hand sides at a time, each with the operations of a single one, so every column
    /// gets the bits [`Self::apply_into`] gives it; `block_application_equals_one_by_one`);
    /// the factors, tens of megabytes at 10⁵ unknowns, are read by one pass instead of one
    /// per vector. A real factorization solves them one by one.
    pub fn apply_block(&self, xs: &[Col<c64>], transpose: bool, ws: &mut Workspace) -> Vec<Col<c64>> {
        let n = self.pencil.dim();
        let Factor::Complex(lu) = &self.factor else {
            return xs
                .iter()
                .map(|x| {
                    let mut out = Col::<c64>::zeros(n);
                    self.apply_into(x.as_ref(), out.as_mut(), transpose, ws);
                    out
                })
                .collect();
        };
        let mut block = Mat::<c64>::zeros(n, xs.len());
        for (c, x) in xs.iter().enumerate() {
            let (x, o) = (contiguous(x.as_ref()), contiguous_mut(block.col_mut(c)));
            if transpose {
                self.pencil.e.mul_t_into(x, o);
            } else {
                self.pencil.e.mul_into(x, o);
            }
        }
        if xs.len() > 1 {
            let mut stack = MemBuffer::new(lu.solve_scratch(xs.len()));
            lu.solve_in_place(block.as_mut(), transpose, MemStack::new(&mut stack));
        } else if xs.len() == 1 {
            lu.solve_in_place(block.as_mut(), transpose, MemStack::new(&mut ws.stack));
        }
        (0..xs.len()).map(|c| block.col(c).to_owned()).collect()
    }

    /// λ of an eigenvalue θ of T: `λ = σ − 1/θ`.
    pub fn lambda(&self, theta: c64) -> c64 {
        self.sigma - c64::new(1.0, 0.0) / theta
    }
}

/// A triangular factor in compressed columns: column pointers, row indices, values.
type Factor64<'a> = (&'a [usize], &'a [usize], &'a [f64]);

/// `x ← L⁻¹ x`, `L` unit lower triangular with its diagonal stored first in each column
/// (faer's simplicial `L`).
fn unit_lower((cp, ri, v): Factor64<'_>, x: &mut [f64]) {
    for j in 0..x.len() {
        let xj = x[j];
        for k in cp[j] + 1..cp[j + 1] {
            x[ri[k]] -= v[k] * xj;
        }
    }
}

/// `x ← U⁻¹ x`, `U` upper triangular with its diagonal stored last in each column (faer's
/// simplicial `U`); the diagonal applied as faer does, times its reciprocal `recip[j]`.
fn upper((cp, ri, v): Factor64<'_>, recip: &[f64], x: &mut [f64]) {
    for j in (0..x.len()).rev() {
        let (a, b) = (cp[j], cp[j + 1]);
        let xj = x[j] * recip[j];
        x[j] = xj;
        for k in (a..b - 1).rev() {
            x[ri[k]] -= v[k] * xj;
        }
    }
}

/// `x ← U⁻ᵀ x`.
fn upper_transpose((cp, ri, v): Factor64<'_>, recip: &[f64], x: &mut [f64]) {
    for j in 0..x.len() {
        let (a, b) = (cp[j], cp[j + 1]);
        let mut acc = 0.0;
        for k in a..b - 1 {
            acc += v[k] * x[ri[k]];
        }
        x[j] = (x[j] - acc) * recip[j];
    }
}

/// `x ← L⁻ᵀ x`.
fn unit_lower_transpose((cp, ri, v): Factor64<'_>, x: &mut [f64]) {
    for j in (0..x.len()).rev() {
        let (a, b) = (cp[j], cp[j + 1]);
        let mut acc = 0.0;
        for k in (a + 1..b).rev() {
            acc += v[k] * x[ri[k]];
        }
        x[j] -= acc;
    }
}

/// The entries the operator applies to: `f64` (a real shift only) or `c64`.
pub(super) trait Entry: crate::linear::SparseScalar {
    fn solve_in_place(op: &ShiftInvert, x: ColMut<'_, Self>, transpose: bool, ws: &mut Workspace);
    /// [`ShiftInvert::apply_into`] by [`Simplicial::apply`] when the factorization is one;
    /// `false` (nothing done) otherwise.
    fn apply_fused(_: &ShiftInvert, _: ColRef<'_, Self>, _: ColMut<'_, Self>, _: bool, _: &mut Workspace) -> bool {
        false
    }
}

impl Entry for f64 {
    fn solve_in_place(op: &ShiftInvert, x: ColMut<'_, f64>, transpose: bool, ws: &mut Workspace) {
        let n = x.nrows();
        let rhs = MatMut::from_column_major_slice_mut(contiguous_mut(x), n, 1);
        match &op.factor {
            Factor::Real(lu) => lu.solve_in_place(rhs, transpose, MemStack::new(&mut ws.stack)),
            Factor::RealSimplicial(f) => f.solve(rhs, transpose, &mut ws.t),
            Factor::Complex(_) => unreachable!("a real vector is solved with the factorization of a real shift"),
        }
    }
    fn apply_fused(op: &ShiftInvert, x: ColRef<'_, f64>, out: ColMut<'_, f64>, transpose: bool, ws: &mut Workspace) -> bool {
        let Factor::RealSimplicial(f) = &op.factor else { return false };
        let t = contiguous_mut(ws.t.col_mut(0));
        f.apply(contiguous(x), contiguous_mut(out), transpose, t);
        true
    }
}

impl Entry for c64 {
    fn solve_in_place(op: &ShiftInvert, mut x: ColMut<'_, c64>, transpose: bool, ws: &mut Workspace) {
        let n = x.nrows();
        match &op.factor {
            Factor::Real(_) | Factor::RealSimplicial(_) => {
                let parts = &mut ws.parts;
                for i in 0..n {
                    parts[(i, 0)] = x[i].re;
                    parts[(i, 1)] = x[i].im;
                }
                match &op.factor {
                    Factor::Real(lu) => lu.solve_in_place(parts.as_mut(), transpose, MemStack::new(&mut ws.stack)),
                    Factor::RealSimplicial(f) => f.solve(parts.as_mut(), transpose, &mut ws.t),
                    Factor::Complex(_) => unreachable!("matched above"),
                }
                for i in 0..n {
                    x[i] = c64::new(parts[(i, 0)], parts[(i, 1)]);
                }
            }
            Factor::Complex(lu) => lu.solve_in_place(MatMut::from_column_major_slice_mut(contiguous_mut(x), n, 1), transpose, MemStack::new(&mut ws.stack)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::linalg::lu::factorize_symbolic_lu;
    use faer::sparse::SparseColMat;
    use faer::Conj;

    /// A xorshift sequence from `seed`, uniform in [−0.5, 0.5): the tests' random matrices.
    fn uniform_around_zero(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        }
    }

    /// The four triangular loops against faer's own solves (independent code) on the
    /// simplicial LU of a random sparse matrix: the same bits.
    #[test]
    fn triangular_loops_match_faers_solves_bit_for_bit() {
        use faer::sparse::linalg::triangular_solve as ts;
        use faer::sparse::Triplet;
        let n = 60;
        let mut next = uniform_around_zero(0x2545_F491_4F6C_DD1D);
        let mut t = Vec::new();
        for i in 0..n {
            t.push(Triplet::new(i, i, 0.1 + next()));
            for _ in 0..3 {
                let j = ((next() + 0.5) * n as f64) as usize % n;
                t.push(Triplet::new(i, j, next()));
            }
        }
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &t).unwrap();
        let symbolic = factorize_symbolic_lu(a.symbolic(), Default::default()).unwrap();
        let mut buf = MemBuffer::new(simplicial::factorize_simplicial_numeric_lu_scratch::<usize, f64>(n, n));
        let (mut row_fwd, mut row_inv) = (vec![0usize; n], vec![0usize; n]);
        let mut lu = SimplicialLu::new();
        simplicial::factorize_simplicial_numeric_lu(&mut row_fwd, &mut row_inv, &mut lu, a.as_ref(), symbolic.col_perm(), MemStack::new(&mut buf)).unwrap();
        let (l, u) = (lu.l_factor_unsorted(), lu.u_factor_unsorted());
        let lf = (l.symbolic().col_ptr(), l.symbolic().row_idx(), l.val());
        let uf = (u.symbolic().col_ptr(), u.symbolic().row_idx(), u.val());
        let recip: Vec<f64> = (0..n).map(|j| 1.0 / u.val()[u.symbolic().col_ptr()[j + 1] - 1]).collect();
        let x0: Vec<f64> = (0..n).map(|_| next()).collect();
        for transpose in [false, true] {
            let mut theirs = Mat::<f64>::from_fn(n, 1, |i, _| x0[i]);
            if transpose {
                ts::solve_upper_triangular_transpose_in_place(u, Conj::No, theirs.as_mut(), Par::Seq);
                ts::solve_unit_lower_triangular_transpose_in_place(l, Conj::No, theirs.as_mut(), Par::Seq);
            } else {
                ts::solve_unit_lower_triangular_in_place(l, Conj::No, theirs.as_mut(), Par::Seq);
                ts::solve_upper_triangular_in_place(u, Conj::No, theirs.as_mut(), Par::Seq);
            }
            let mut ours = x0.clone();
            if transpose {
                upper_transpose(uf, &recip, &mut ours);
                unit_lower_transpose(lf, &mut ours);
            } else {
                unit_lower(lf, &mut ours);
                upper(uf, &recip, &mut ours);
            }
            for i in 0..n {
                assert_eq!(ours[i].to_bits(), theirs[(i, 0)].to_bits(), "transpose {transpose}, row {i}");
            }
        }
    }

    /// [`ShiftInvert::apply_block`] on a block of 1 to 6 complex vectors (faer's solves take
    /// four columns at a time, then the rest) against [`ShiftInvert::apply_into`] one by one
    /// at a complex shift: the same bits, both sides; and each result `y` solves
    /// `(K + σ E) y = E x` (`(K + σ E)ᵀ y = Eᵀ x`) to rounding, checked by products of the
    /// matrices as stored (independent of the factorization).
    #[test]
    fn block_application_equals_one_by_one() {
        use crate::linear::SparseLinearDae;
        let n = 80;
        let mut next = uniform_around_zero(0x9E37_79B9_7F4A_7C15);
        let (mut e, mut k) = (Vec::new(), Vec::new());
        for i in 0..n {
            e.push((i, i, 1.0 + next()));
            k.push((i, i, 2.0 + next()));
            for _ in 0..3 {
                let j = ((next() + 0.5) * n as f64) as usize % n;
                k.push((i, j, next()));
                e.push((j, i, 0.1 * next()));
            }
        }
        let (fyd, fy) = (SparseMatrix::from_triplets(n, n, e).unwrap(), SparseMatrix::from_triplets(n, n, k).unwrap());
        let dae = SparseLinearDae { fyd, fy, b: Mat::zeros(n, 0), c: Mat::zeros(0, n), c_rate: None, unknown_names: (0..n).map(|i| format!("y{i}")).collect(), input_names: Vec::new(), output_names: Vec::new(), constraint_form: None, multipliers: Vec::new() };
        let pencil = Pencil::new(&dae).unwrap();
        let sigma = c64::new(0.3, 0.7);
        let op = ShiftInvert::new(&pencil, sigma).unwrap();
        let mut ws = op.workspace();
        for size in 1..=6 {
            let xs: Vec<Col<c64>> = (0..size).map(|_| Col::from_fn(n, |_| c64::new(next(), next()))).collect();
            for transpose in [false, true] {
                let block = op.apply_block(&xs, transpose, &mut ws);
                assert_eq!(block.len(), size);
                for (x, y) in xs.iter().zip(&block) {
                    let mut one = Col::<c64>::zeros(n);
                    op.apply_into(x.as_ref(), one.as_mut(), transpose, &mut ws);
                    for i in 0..n {
                        assert!(y[i].re.to_bits() == one[i].re.to_bits() && y[i].im.to_bits() == one[i].im.to_bits(), "size {size}, transpose {transpose}, row {i}");
                    }
                    let ex = if transpose { pencil.e.mul_t_complex(x) } else { pencil.e.mul_complex(x) };
                    let ay = op.shifted(y, transpose);
                    let r = (0..n).map(|i| (ay[i] - ex[i]).norm_sqr()).sum::<f64>().sqrt();
                    assert!(r <= 1e-13 * ex.norm_l2().max(1.0), "size {size}, transpose {transpose}: residual {r:e}");
                }
            }
        }
    }
}
