//! Sparse Jacobians as triplets, and a sparse LU whose symbolic factorization is computed
//! once per sparsity pattern and reused across Newton iterations and time steps.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use faer::Mat;

/// Entries `(row, col, value)` in a fixed order for a fixed model (duplicates are summed).
#[derive(Clone, Debug, Default)]
pub struct Triplets {
    pub n: usize,
    pub rows: Vec<usize>,
    pub cols: Vec<usize>,
    pub values: Vec<f64>,
}

impl Triplets {
    pub fn new(n: usize) -> Self {
        Triplets { n, ..Default::default() }
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

/// Sparse LU with symbolic reuse: the pattern (and its fill-reducing ordering and symbolic
/// factorization) is kept while the triplet positions stay the same.
#[derive(Default)]
pub struct SparseLu {
    pattern: Option<(Vec<usize>, Vec<usize>, SymbolicSparseColMat<usize>, Argsort<usize>, SymbolicLu<usize>)>,
    /// Number of symbolic factorizations done (1 for a fixed pattern).
    pub symbolic_factorizations: usize,
}

impl SparseLu {
    pub fn new() -> Self {
        Self::default()
    }

    /// Solves `J x = rhs` in place.
    pub fn solve(&mut self, j: &Triplets, rhs: &mut [f64]) -> Result<(), SparseError> {
        let same = matches!(&self.pattern, Some((r, c, ..)) if *r == j.rows && *c == j.cols);
        if !same {
            let idx: Vec<Pair<usize, usize>> = j.rows.iter().zip(&j.cols).map(|(&row, &col)| Pair { row, col }).collect();
            let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(j.n, j.n, &idx).map_err(|e| SparseError::Structure(format!("{e:?}")))?;
            let lu = SymbolicLu::try_new(symbolic.as_ref()).map_err(|e| SparseError::Structure(format!("{e:?}")))?;
            self.pattern = Some((j.rows.clone(), j.cols.clone(), symbolic, argsort, lu));
            self.symbolic_factorizations += 1;
        }
        let Some((_, _, symbolic, argsort, symbolic_lu)) = &self.pattern else { unreachable!() };
        let a = SparseColMat::new_from_argsort(symbolic.clone(), argsort, &j.values).map_err(|e| SparseError::Structure(format!("{e:?}")))?;
        let lu = Lu::try_new_with_symbolic(symbolic_lu.clone(), a.as_ref()).map_err(|_| SparseError::Singular)?;
        let mut b = Mat::from_fn(j.n, 1, |i, _| rhs[i]);
        lu.solve_in_place(b.as_mut());
        if (0..j.n).any(|i| !b[(i, 0)].is_finite()) {
            return Err(SparseError::Singular);
        }
        for (i, x) in rhs.iter_mut().enumerate() {
            *x = b[(i, 0)];
        }
        Ok(())
    }
}
