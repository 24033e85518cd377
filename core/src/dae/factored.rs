//! The pieces of Newton's sparse LU: Jacobian triplets, the factorization of one pattern
//! (banded after a reverse Cuthill–McKee renumbering when the band is narrow, faer's sparse
//! LU otherwise: both from [`crate::lu`]) and its errors. [`super::sparse::SparseLu`] chooses and reuses them;
//! [`super::eliminate`] factors its reduced system with them.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::{Pair, SparseColMatRef, SymbolicSparseColMat};
use faer::{Mat, MatMut, Par};

use crate::lu::{BandLu, BandOrdering, PatternLu};

/// Entries `(row, col, value)` in a fixed order for a fixed model (duplicates are summed).
#[derive(Clone, Debug, Default)]
pub struct Triplets {
    pub n: usize,
    pub rows: Vec<usize>,
    pub cols: Vec<usize>,
    pub values: Vec<f64>,
    /// The fingerprint of the element calls the assembler made these triplets from
    /// ([`super::Assembler::jacobian_at`]); `None` for triplets made otherwise.
    pub shape: Option<super::Shape>,
}

impl Triplets {
    pub fn new(n: usize) -> Self {
        Triplets { n, ..Default::default() }
    }
    /// Empties the triplets (keeping their storage) for an `n`x`n` matrix.
    pub fn clear(&mut self, n: usize) {
        self.n = n;
        self.shape = None;
        self.rows.clear();
        self.cols.clear();
        self.values.clear();
    }
    pub fn push(&mut self, row: usize, col: usize, value: f64) {
        self.rows.push(row);
        self.cols.push(col);
        self.values.push(value);
    }
    /// Dense copy.
    pub fn to_dense(&self) -> Mat<f64> {
        let mut m = Mat::zeros(self.n, self.n);
        for k in 0..self.values.len() {
            m[(self.rows[k], self.cols[k])] += self.values[k];
        }
        m
    }
}

/// Why a sparse solve failed.
#[derive(Debug, thiserror::Error)]
pub enum SparseError {
    #[error("the Jacobian is singular (sparse LU failed)")]
    Singular,
    #[error("sparse structure: {0}")]
    Structure(String),
}

/// Which factorization [`SparseLu`] uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LuPath {
    /// Banded LU after a reverse Cuthill–McKee renumbering when the band is narrow
    /// (work at most [`BAND_WORK_PER_ENTRY`] multiply–adds per stored entry), else faer's
    /// general sparse LU.
    #[default]
    Auto,
    /// Always faer's sparse LU (COLAMD ordering, simplicial or supernodal by faer's choice).
    General,
}

/// Largest banded-LU work, in multiply–adds per distinct entry of the matrix, for which
/// [`LuPath::Auto`] takes the banded path. Measured on the pendulum chains and beams
/// (issue 14): a banded multiply–add costs about 1/20 of faer's sparse LU per
/// multiply–add, and chains need about 70 per entry.
pub const BAND_WORK_PER_ENTRY: usize = 256;

/// The factorization a pattern uses, with where each triplet lands in its storage.
enum Factorization {
    Band { ordering: BandOrdering, lu: BandLu, rhs: Vec<f64> },
    General { csc: SymbolicSparseColMat<usize>, lu: PatternLu<f64>, values: Vec<f64>, scratch: MemBuffer },
}

/// The factorization of one sparsity pattern: the storage index of each entry
/// (duplicates share one) and the factorization's fixed part (ordering, band or symbolic LU).
pub(super) struct Factored {
    n: usize,
    position: Vec<usize>,
    factorization: Factorization,
}

impl Factored {
    /// The pattern of the `n`x`n` matrix with entries at `(rows[k], cols[k])`.
    pub(super) fn new(n: usize, rows: &[usize], cols: &[usize], path: LuPath) -> Result<Self, SparseError> {
        let structure = |e: &dyn std::fmt::Debug| SparseError::Structure(format!("{e:?}"));
        let idx: Vec<Pair<usize, usize>> = rows.iter().zip(cols).map(|(&row, &col)| Pair { row, col }).collect();
        let (csc, _) = SymbolicSparseColMat::try_new_from_indices(n, n, &idx).map_err(|e| structure(&e))?;
        if path == LuPath::Auto {
            let ordering = BandOrdering::reverse_cuthill_mckee(n, rows, cols);
            if ordering.factorization_work() <= BAND_WORK_PER_ENTRY * csc.row_idx().len().max(1) {
                let lu = BandLu::with_pattern(n, ordering.kl, ordering.ku, rows.iter().zip(cols).map(|(&r, &c)| (ordering.position[r], ordering.position[c])));
                let position = rows.iter().zip(cols).map(|(&r, &c)| lu.index(ordering.position[r], ordering.position[c])).collect();
                let factorization = Factorization::Band { ordering, lu, rhs: vec![0.0; n] };
                return Ok(Factored { n, position, factorization });
            }
        }
        let (ptr, row_idx) = (csc.col_ptr(), csc.row_idx());
        let position = idx
            .iter()
            .map(|p| ptr[p.col] + row_idx[ptr[p.col]..ptr[p.col + 1]].binary_search(&p.row).unwrap_or_else(|_| unreachable!("the pattern holds every triplet")))
            .collect();
        let lu = PatternLu::<f64>::analyze(csc.as_ref(), Par::Seq).map_err(|e| SparseError::Structure(e.to_string()))?;
        let req = lu.factor_scratch().or(lu.solve_scratch(1));
        let values = vec![0.0; csc.row_idx().len()];
        let factorization = Factorization::General { csc, lu, values, scratch: MemBuffer::new(req) };
        Ok(Factored { n, position, factorization })
    }

    pub(super) fn is_banded(&self) -> bool {
        matches!(self.factorization, Factorization::Band { .. })
    }

    /// Storage index of each entry of the pattern, in the order given to [`Factored::new`].
    pub(super) fn positions(&self) -> &[usize] {
        &self.position
    }

    /// Assembles `values` (one per entry of the pattern, in its order), factors and solves
    /// `A x = rhs` in place.
    pub(super) fn solve(&mut self, values: &[f64], rhs: &mut [f64]) -> Result<(), SparseError> {
        let position = std::mem::take(&mut self.position);
        let done = self.solve_with(
            |storage| {
                for (&k, &v) in position.iter().zip(values) {
                    storage[k] += v;
                }
            },
            rhs,
        );
        self.position = position;
        done
    }

    /// Zeroes the storage, lets `assemble` add the values at storage indices (from
    /// [`Factored::positions`]), factors and solves `A x = rhs` in place.
    pub(super) fn solve_with(&mut self, assemble: impl FnOnce(&mut [f64]), rhs: &mut [f64]) -> Result<(), SparseError> {
        self.factor_with(assemble)?;
        self.solve_factored(rhs);
        Ok(())
    }

    /// Zeroes the storage, lets `assemble` add the values at storage indices and factors.
    pub(super) fn factor_with(&mut self, assemble: impl FnOnce(&mut [f64])) -> Result<(), SparseError> {
        match &mut self.factorization {
            Factorization::Band { lu, .. } => {
                lu.clear();
                assemble(lu.storage_mut());
                lu.factorize().map_err(|_| SparseError::Singular)?;
            }
            Factorization::General { csc, lu, values: stored, scratch } => {
                stored.iter_mut().for_each(|v| *v = 0.0);
                assemble(stored);
                lu.factor(SparseColMatRef::new(csc.as_ref(), stored), MemStack::new(scratch)).map_err(|_| SparseError::Singular)?;
            }
        }
        Ok(())
    }

    /// Solves `A x = rhs` in place with the factors of the last successful
    /// [`Factored::factor_with`] (the caller keeps track that there is one).
    pub(super) fn solve_factored(&mut self, rhs: &mut [f64]) {
        match &mut self.factorization {
            Factorization::Band { ordering, lu, rhs: x } => {
                for (i, &p) in ordering.position.iter().enumerate() {
                    x[p] = rhs[i];
                }
                lu.solve_in_place(x);
                for (i, &p) in ordering.position.iter().enumerate() {
                    rhs[i] = x[p];
                }
            }
            Factorization::General { lu, scratch, .. } => {
                lu.solve_in_place(MatMut::from_column_major_slice_mut(rhs, self.n, 1), false, MemStack::new(scratch));
            }
        }
    }
}
