//! Sparse Jacobians as triplets, and the LU of Newton's method: its ordering and symbolic
//! part computed once per sparsity pattern and reused across Newton iterations and time
//! steps, the values scattered straight into the factorization's storage; banded after a
//! reverse Cuthill–McKee renumbering when the band is narrow, faer's sparse LU otherwise.

use super::eliminate::Eliminated;
use super::jacobian_sink::Shape;
pub use super::factored::{LuPath, SparseError, Triplets, BAND_WORK_PER_ENTRY};
use super::factored::Factored;

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
    /// The fingerprint of the assembler's calls behind those positions, when known
    /// ([`Triplets::shape`]): values with the same fingerprint sit at the same positions.
    shape: Option<Shape>,
    solver: Solver,
    /// Which factors the last successful solve left: those of the elimination's reduced
    /// system or of the whole one (`None` after a failed factorization).
    factored: Option<Factors>,
}

/// The factorization a pattern's last successful solve used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Factors {
    Reduced,
    Whole,
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
        Ok(Pattern { positions, shape: j.shape, solver, factored: None })
    }

    /// Whether `j`'s triplets sit at the positions this pattern was made from.
    fn is_pattern_of(&self, j: &Triplets) -> bool {
        self.positions.len() == j.rows.len() && self.positions.iter().zip(j.rows.iter().zip(&j.cols)).all(|(&p, (&r, &c))| p == position_key(r, c))
    }

    /// Assembles `values` (one per triplet of the pattern, in its order), factors and solves
    /// `J x = rhs` in place.
    fn solve(&mut self, n: usize, values: &[f64], rhs: &mut [f64], path: LuPath) -> Result<(), SparseError> {
        self.factored = None;
        match &mut self.solver {
            Solver::Direct(f) => {
                f.solve(values, rhs)?;
                self.factored = Some(Factors::Whole);
            }
            Solver::Eliminated { reduced, direct } => {
                if reduced.solve(values, rhs).is_ok() {
                    self.factored = Some(Factors::Reduced);
                    return Ok(());
                }
                if direct.is_none() {
                    let (rows, cols): (Vec<usize>, Vec<usize>) = self.positions.iter().map(|&p| ((p >> 32) as usize, (p & u32::MAX as u64) as usize)).unzip();
                    *direct = Some(Factored::new(n, &rows, &cols, path)?);
                }
                let Some(f) = direct else { unreachable!("set above") };
                f.solve(values, rhs)?;
                self.factored = Some(Factors::Whole);
            }
        }
        Ok(())
    }

    /// Solves `J x = rhs` in place with the factors of the last successful [`Pattern::solve`];
    /// `false` (and `rhs` untouched) when there are none.
    fn solve_again(&mut self, rhs: &mut [f64]) -> bool {
        match (&mut self.solver, self.factored) {
            (Solver::Direct(f), Some(Factors::Whole)) | (Solver::Eliminated { direct: Some(f), .. }, Some(Factors::Whole)) => f.solve_factored(rhs),
            (Solver::Eliminated { reduced, .. }, Some(Factors::Reduced)) => reduced.solve_factored(rhs),
            _ => return false,
        }
        true
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
            self.pattern = None;
            self.pattern = Some(Pattern::new(j, self.path, &self.eliminate)?);
            self.symbolic_factorizations += 1;
        }
        let Some(p) = &mut self.pattern else { unreachable!("set above") };
        p.shape = j.shape;
        p.solve(j.n, &j.values, rhs, self.path)?;
        if rhs.iter().any(|x| !x.is_finite()) {
            p.factored = None;
            return Err(SparseError::Singular);
        }
        Ok(())
    }

    /// Solves `J x = rhs` in place for `J` given by its values alone, in the order of the
    /// triplets of the current pattern, when `shape` is the fingerprint that pattern was made
    /// with ([`super::Assembler::jacobian_values_at`]); `Ok(false)`, nothing factored and
    /// `rhs` untouched, when there is no such pattern (the caller then assembles triplets
    /// and calls [`SparseLu::solve`]).
    pub fn solve_values(&mut self, n: usize, values: &[f64], shape: Shape, rhs: &mut [f64]) -> Result<bool, SparseError> {
        let Some(p) = &mut self.pattern else { return Ok(false) };
        if p.shape != Some(shape) || p.positions.len() != values.len() {
            return Ok(false);
        }
        p.solve(n, values, rhs, self.path)?;
        if rhs.iter().any(|x| !x.is_finite()) {
            p.factored = None;
            return Err(SparseError::Singular);
        }
        Ok(true)
    }

    /// Whether there is a pattern that values with a fingerprint can be solved on
    /// ([`SparseLu::solve_values`]).
    pub fn knows_shape(&self) -> bool {
        matches!(&self.pattern, Some(Pattern { shape: Some(_), .. }))
    }

    /// Solves `J x = rhs` in place with the factorization of the last successful
    /// [`SparseLu::solve`], without assembling or factoring anything: the same matrix, a new
    /// right-hand side (Newton iterations that keep their Jacobian,
    /// [`crate::solve::NewtonSettings`]). `Ok(false)`, `rhs` untouched, when there is no such
    /// factorization (none yet, the pattern changed, or the last one failed);
    /// `Err(Singular)` when the solution is not finite.
    pub fn solve_again(&mut self, rhs: &mut [f64]) -> Result<bool, SparseError> {
        let Some(p) = &mut self.pattern else { return Ok(false) };
        if !p.solve_again(rhs) {
            return Ok(false);
        }
        if rhs.iter().any(|x| !x.is_finite()) {
            return Err(SparseError::Singular);
        }
        Ok(true)
    }
}
