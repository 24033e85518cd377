//! faer's general sparse LU of one sparsity pattern (COLAMD ordering; simplicial or
//! supernodal by faer's choice): the symbolic analysis done once, then any number of
//! numeric factorizations of matrices with that pattern, each solved in place (or
//! transposed) with the caller's scratch. The one wrapper of faer's sparse LU: Newton's
//! general path (`dae::SparseLu`), the sparse DAE's static and frequency-response solves
//! (`linear::SparseLinearDae`) and the shift-invert operator of the Krylov eigensolver
//! (`eigen::krylov`) all factor through it.

use faer::dyn_stack::{MemStack, StackReq};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::traits::ComplexField;
use faer::{Conj, MatMut, Par};

/// Why a sparse LU gave no factors.
#[derive(Debug, thiserror::Error)]
pub enum SparseLuError {
    /// The symbolic analysis of the pattern failed (faer's error, as it words it).
    #[error("{0}")]
    Pattern(String),
    /// The numeric factorization found no pivot: the matrix is singular.
    #[error("the matrix is singular (sparse LU failed)")]
    Singular,
}

/// The LU factors of matrices of one sparsity pattern, in `T` arithmetic (`f64` or `c64`).
pub struct PatternLu<T: ComplexField> {
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, T>,
    par: Par,
}

impl<T: ComplexField> PatternLu<T> {
    /// The symbolic analysis of `pattern` (square); factorizations and solves then run
    /// with `par` (`Par::Seq` for the solvers that run their own threads).
    pub fn analyze(pattern: SymbolicSparseColMatRef<'_, usize>, par: Par) -> Result<Self, SparseLuError> {
        let symbolic = factorize_symbolic_lu(pattern, Default::default()).map_err(|e| SparseLuError::Pattern(format!("{e:?}")))?;
        Ok(PatternLu { symbolic, numeric: NumericLu::new(), par })
    }

    /// Factors of matrices whose pattern `symbolic` analyzed (a copy of an analysis shared
    /// by several factorizations of one pattern in different arithmetic or at different
    /// shifts: the Krylov operator's, `eigen::krylov`).
    pub fn with_symbolic(symbolic: SymbolicLu<usize>, par: Par) -> Self {
        PatternLu { symbolic, numeric: NumericLu::new(), par }
    }

    /// The symbolic analysis (ordering and structure of the factors).
    pub fn symbolic(&self) -> &SymbolicLu<usize> {
        &self.symbolic
    }

    /// Scratch one [`Self::factor`] needs.
    pub fn factor_scratch(&self) -> StackReq {
        self.symbolic.factorize_numeric_lu_scratch::<T>(self.par, Default::default())
    }

    /// Scratch one [`Self::solve_in_place`] of `columns` right-hand sides needs (either side).
    pub fn solve_scratch(&self, columns: usize) -> StackReq {
        self.symbolic.solve_in_place_scratch::<T>(columns, self.par)
    }

    /// Factors `a`, whose pattern is the analyzed one (the previous factors' storage reused).
    pub fn factor(&mut self, a: SparseColMatRef<'_, usize, T>, stack: &mut MemStack) -> Result<(), SparseLuError> {
        self.symbolic.factorize_numeric_lu(&mut self.numeric, a, self.par, stack, Default::default()).map_err(|_| SparseLuError::Singular)?;
        Ok(())
    }

    /// `rhs ← A⁻¹ rhs` (or `A⁻ᵀ rhs`) with the last factors, `rhs` an `n x k` block.
    pub fn solve_in_place(&self, rhs: MatMut<'_, T>, transpose: bool, stack: &mut MemStack) {
        let lu = LuRef::new_unchecked(&self.symbolic, &self.numeric);
        if transpose {
            lu.solve_transpose_in_place_with_conj(Conj::No, rhs, self.par, stack);
        } else {
            lu.solve_in_place_with_conj(Conj::No, rhs, self.par, stack);
        }
    }
}
