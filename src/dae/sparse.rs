//! Sparse Jacobians as triplets, and a sparse LU whose symbolic factorization is computed
//! once per sparsity pattern and reused across Newton iterations and time steps.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::reborrow::ReborrowMut;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, NumericLu, SymbolicLu};
use faer::sparse::{Pair, SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, Mat, MatMut, Par};

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
    /// Empties the triplets (keeping their storage) for an `n`x`n` matrix.
    pub fn clear(&mut self, n: usize) {
        self.n = n;
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

/// A sparsity pattern with its symbolic factorization: the triplet positions it was made
/// from, the CSC structure, where each triplet lands in it, and the symbolic LU
/// (fill-reducing ordering included).
struct Pattern {
    rows: Vec<usize>,
    cols: Vec<usize>,
    csc: SymbolicSparseColMat<usize>,
    /// CSC value index of each triplet (duplicates share one).
    position: Vec<usize>,
    lu: SymbolicLu<usize>,
}

impl Pattern {
    fn new(j: &Triplets) -> Result<Self, SparseError> {
        let structure = |e: &dyn std::fmt::Debug| SparseError::Structure(format!("{e:?}"));
        let idx: Vec<Pair<usize, usize>> = j.rows.iter().zip(&j.cols).map(|(&row, &col)| Pair { row, col }).collect();
        let (csc, _) = SymbolicSparseColMat::try_new_from_indices(j.n, j.n, &idx).map_err(|e| structure(&e))?;
        let (ptr, rows) = (csc.col_ptr(), csc.row_idx());
        let position = idx
            .iter()
            .map(|p| ptr[p.col] + rows[ptr[p.col]..ptr[p.col + 1]].binary_search(&p.row).unwrap_or_else(|_| unreachable!("the pattern holds every triplet")))
            .collect();
        let lu = factorize_symbolic_lu(csc.as_ref(), Default::default()).map_err(|e| structure(&e))?;
        Ok(Pattern { rows: j.rows.clone(), cols: j.cols.clone(), csc, position, lu })
    }
}

/// Sparse LU with symbolic reuse: the pattern (its fill-reducing ordering and symbolic
/// factorization) is kept while the triplet positions stay the same, and the numeric
/// factors, values and scratch memory are reused from one solve to the next.
pub struct SparseLu {
    pattern: Option<Pattern>,
    numeric: NumericLu<usize, f64>,
    values: Vec<f64>,
    scratch: MemBuffer,
    /// Number of symbolic factorizations done (1 for a fixed pattern).
    pub symbolic_factorizations: usize,
}

impl Default for SparseLu {
    fn default() -> Self {
        SparseLu { pattern: None, numeric: NumericLu::new(), values: Vec::new(), scratch: MemBuffer::new(faer::dyn_stack::StackReq::EMPTY), symbolic_factorizations: 0 }
    }
}

impl SparseLu {
    pub fn new() -> Self {
        Self::default()
    }

    /// Solves `J x = rhs` in place.
    pub fn solve(&mut self, j: &Triplets, rhs: &mut [f64]) -> Result<(), SparseError> {
        let same = matches!(&self.pattern, Some(p) if p.rows == j.rows && p.cols == j.cols);
        if !same {
            let p = Pattern::new(j)?;
            let req = p.lu.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()).or(p.lu.solve_in_place_scratch::<f64>(1, Par::Seq));
            self.scratch = MemBuffer::new(req);
            self.values = vec![0.0; p.csc.row_idx().len()];
            self.pattern = Some(p);
            self.symbolic_factorizations += 1;
        }
        let Some(p) = &self.pattern else { unreachable!("set above") };
        self.values.iter_mut().for_each(|v| *v = 0.0);
        for (&k, v) in p.position.iter().zip(&j.values) {
            self.values[k] += v;
        }
        let a = SparseColMatRef::new(p.csc.as_ref(), &self.values);
        let stack = MemStack::new(&mut self.scratch);
        let lu = p.lu.factorize_numeric_lu(&mut self.numeric, a, Par::Seq, stack, Default::default()).map_err(|_| SparseError::Singular)?;
        let mut b = MatMut::from_column_major_slice_mut(rhs, j.n, 1);
        lu.solve_in_place_with_conj(Conj::No, b.rb_mut(), Par::Seq, MemStack::new(&mut self.scratch));
        if rhs.iter().any(|x| !x.is_finite()) {
            return Err(SparseError::Singular);
        }
        Ok(())
    }
}
