//! Sparse Jacobians as triplets, and the LU of Newton's method: its ordering and symbolic
//! part computed once per sparsity pattern and reused across Newton iterations and time
//! steps, the values scattered straight into the factorization's storage; banded after a
//! reverse Cuthill–McKee renumbering when the band is narrow, faer's sparse LU otherwise.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::reborrow::ReborrowMut;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, NumericLu, SymbolicLu};
use faer::sparse::{Pair, SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, Mat, MatMut, Par};

use super::band::{BandLu, BandOrdering};
use super::eliminate::Eliminated;

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
    General { csc: SymbolicSparseColMat<usize>, lu: SymbolicLu<usize>, numeric: NumericLu<usize, f64>, values: Vec<f64>, scratch: MemBuffer },
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
                let lu = BandLu::new(n, ordering.kl, ordering.ku);
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
        let lu = factorize_symbolic_lu(csc.as_ref(), Default::default()).map_err(|e| structure(&e))?;
        let req = lu.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()).or(lu.solve_in_place_scratch::<f64>(1, Par::Seq));
        let values = vec![0.0; csc.row_idx().len()];
        let factorization = Factorization::General { csc, lu, numeric: NumericLu::new(), values, scratch: MemBuffer::new(req) };
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
        match &mut self.factorization {
            Factorization::Band { ordering, lu, rhs: x } => {
                lu.clear();
                assemble(lu.storage_mut());
                lu.factorize().map_err(|_| SparseError::Singular)?;
                for (i, &p) in ordering.position.iter().enumerate() {
                    x[p] = rhs[i];
                }
                lu.solve_in_place(x);
                for (i, &p) in ordering.position.iter().enumerate() {
                    rhs[i] = x[p];
                }
            }
            Factorization::General { csc, lu, numeric, values: stored, scratch } => {
                stored.iter_mut().for_each(|v| *v = 0.0);
                assemble(stored);
                let a = SparseColMatRef::new(csc.as_ref(), stored);
                let factors = lu.factorize_numeric_lu(numeric, a, Par::Seq, MemStack::new(scratch), Default::default()).map_err(|_| SparseError::Singular)?;
                let mut b = MatMut::from_column_major_slice_mut(rhs, self.n, 1);
                factors.solve_in_place_with_conj(Conj::No, b.rb_mut(), Par::Seq, MemStack::new(scratch));
            }
        }
        Ok(())
    }
}

/// How a pattern is solved: directly, or with some unknowns eliminated first (and the
/// direct factorization built only if a pivot of the elimination turns out zero).
enum Solver {
    Direct(Factored),
    Eliminated { reduced: Box<Eliminated>, direct: Option<Factored> },
}

/// A triplet's position as one number, `row · 2³² + col` (8 bytes a triplet where the two
/// indices took 16: the pattern's copy lives as long as Newton's workspace).
fn position_key(row: usize, col: usize) -> u64 {
    ((row as u64) << 32) | col as u64
}

/// A sparsity pattern: the triplet positions it was made from and its solver.
struct Pattern {
    positions: Vec<u64>,
    solver: Solver,
}

impl Pattern {
    fn new(j: &Triplets, path: LuPath, eliminate: &[(usize, usize)]) -> Result<Self, SparseError> {
        if j.n > u32::MAX as usize {
            return Err(SparseError::Structure(format!("{} unknowns: more than the 2^32 the sparse solver indexes", j.n)));
        }
        let reduced = if eliminate.is_empty() { None } else { Eliminated::new(j, eliminate, path)? };
        let solver = match reduced {
            Some(r) => Solver::Eliminated { reduced: Box::new(r), direct: None },
            None => Solver::Direct(Factored::new(j.n, &j.rows, &j.cols, path)?),
        };
        let positions = j.rows.iter().zip(&j.cols).map(|(&r, &c)| position_key(r, c)).collect();
        Ok(Pattern { positions, solver })
    }

    /// Whether `j`'s triplets sit at the positions this pattern was made from.
    fn is_pattern_of(&self, j: &Triplets) -> bool {
        self.positions.len() == j.rows.len() && self.positions.iter().zip(j.rows.iter().zip(&j.cols)).all(|(&p, (&r, &c))| p == position_key(r, c))
    }

    /// Assembles `j`'s values, factors and solves `J x = rhs` in place.
    fn solve(&mut self, j: &Triplets, rhs: &mut [f64], path: LuPath) -> Result<(), SparseError> {
        match &mut self.solver {
            Solver::Direct(f) => f.solve(&j.values, rhs),
            Solver::Eliminated { reduced, direct } => {
                if reduced.solve(&j.values, rhs).is_ok() {
                    return Ok(());
                }
                if direct.is_none() {
                    *direct = Some(Factored::new(j.n, &j.rows, &j.cols, path)?);
                }
                let Some(f) = direct else { unreachable!("set above") };
                f.solve(&j.values, rhs)
            }
        }
    }
}

/// The linear solver of Newton's method: the pattern (ordering, band or symbolic
/// factorization) is kept while the triplet positions stay the same, and the numeric
/// factors, values and scratch memory are reused from one solve to the next.
#[derive(Default)]
pub struct SparseLu {
    pattern: Option<Pattern>,
    path: LuPath,
    /// `(equation, unknown)` pairs to eliminate before factoring (see [`SparseLu::eliminating`]).
    eliminate: Vec<(usize, usize)>,
    /// Number of symbolic factorizations done (1 for a fixed pattern).
    pub symbolic_factorizations: usize,
}

impl SparseLu {
    pub fn new() -> Self {
        Self::default()
    }

    /// A solver that always takes `path`.
    pub fn with_path(path: LuPath) -> Self {
        SparseLu { path, ..Self::default() }
    }

    /// Eliminates, before factoring, unknown `p` through equation `m` for each pair
    /// `(m, p)` (a dynamic node's momenta through their definitions: [`DofMap::momentum_pairs`]),
    /// when in every such equation the only entry among these unknowns is its own `p`;
    /// otherwise (or for a zero pivot) solves the whole system. Keeps the pattern when the
    /// pairs are the same as before.
    ///
    /// [`DofMap::momentum_pairs`]: super::DofMap::momentum_pairs
    pub fn eliminating(&mut self, pairs: &[(usize, usize)]) {
        if self.eliminate != pairs {
            self.eliminate = pairs.to_vec();
            self.pattern = None;
        }
    }

    /// Whether the current pattern is factored by the banded path.
    pub fn is_banded(&self) -> bool {
        match &self.pattern {
            Some(Pattern { solver: Solver::Direct(f), .. }) => f.is_banded(),
            Some(Pattern { solver: Solver::Eliminated { reduced, .. }, .. }) => reduced.is_banded(),
            None => false,
        }
    }

    /// Number of unknowns eliminated before factoring in the current pattern.
    pub fn eliminated(&self) -> usize {
        match &self.pattern {
            Some(Pattern { solver: Solver::Eliminated { reduced, .. }, .. }) => reduced.eliminated(),
            _ => 0,
        }
    }

    /// Solves `J x = rhs` in place.
    pub fn solve(&mut self, j: &Triplets, rhs: &mut [f64]) -> Result<(), SparseError> {
        let same = matches!(&self.pattern, Some(p) if p.is_pattern_of(j));
        if !same {
            self.pattern = Some(Pattern::new(j, self.path, &self.eliminate)?);
            self.symbolic_factorizations += 1;
        }
        let Some(p) = &mut self.pattern else { unreachable!("set above") };
        p.solve(j, rhs, self.path)?;
        if rhs.iter().any(|x| !x.is_finite()) {
            return Err(SparseError::Singular);
        }
        Ok(())
    }
}
