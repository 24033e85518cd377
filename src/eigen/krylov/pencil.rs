//! The pencil `λ E + K` the shift-invert solver works on: the form of eq. 29.
//!
//! In MBDyn's form (eq. 30) the constraint rows `C` and the multipliers `L` sit in `F_yd`
//! only, so `λ = 0` is an eigenvalue of multiplicity 2m (the constrained variables): a shift
//! near zero would converge to that cluster first. Exactly as the dense deflation's first step
//! ([`crate::eigen::ModalAnalysis::of_dae`]), moving those rows and columns to `K` gives
//! `P₃₀(λ) = Δ(λ) P₂₉(λ) Δ(λ)`, `Δ = diag(λ on C and L, 1 elsewhere)`: the 2m zeros leave,
//! the constrained variables' eigenvalues become infinite (harmless for shift-invert, they map
//! to θ = 0), and vectors map back as `v₃₀[L] = v₂₉[L]/λ`, `u₃₀[C] = u₂₉[C]/λ`.

use std::sync::OnceLock;

use faer::sparse::linalg::lu::{factorize_symbolic_lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{c64, Col};

use super::KrylovError;
use crate::linear::{SparseLinearDae, SparseMatrix};
use crate::model::ConstraintForm;

/// `λ E + K` in the form of eq. 29, and the map of its vectors back to the DAE's form.
pub(super) struct Pencil {
    pub e: SparseMatrix,
    pub k: SparseMatrix,
    /// Constraint rows / multiplier columns moved from `F_yd` (form of eq. 30), else empty.
    moved: Vec<bool>,
    /// The pattern of `K + σ E` and the symbolic LU analysis of it, made once for every
    /// shift and every point of the count (`count.rs`): each factorization is numeric only.
    shifted: OnceLock<Shifted>,
    symbolic: OnceLock<Option<SymbolicLu<usize>>>,
}

/// `K` and `E` on the union of their patterns (faer's compressed columns, row indices
/// ascending; an entry one of them lacks is 0 there), so that `K + σ E`'s values are one
/// pass over two arrays: the same numbers `SparseMatrix::csc_sum` gives (`k + σ·0 = k`,
/// `0 + σ e = σ e`; only the sign of a zero may differ).
pub(super) struct Shifted {
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    k: Vec<f64>,
    e: Vec<f64>,
}

impl Pencil {
    pub fn new(dae: &SparseLinearDae) -> Result<Self, KrylovError> {
        let n = dae.dim();
        let mut moved = vec![false; n];
        if dae.constraint_form == Some(ConstraintForm::Scaled) {
            for &k in &dae.multipliers {
                if k >= n {
                    return Err(KrylovError::Structure(format!("multiplier index {k} of a {n}-equation model")));
                }
                moved[k] = true;
            }
        }
        if moved.iter().any(|&m| m) {
            // Eq. 30 puts the constraint rows and multiplier columns in F_yd only, with F_yd[C, L] = 0.
            if dae.fy.triplets().any(|(i, j, _)| moved[i] || moved[j]) || dae.fyd.triplets().any(|(i, j, _)| moved[i] && moved[j]) {
                return Err(KrylovError::Structure(
                    "the constraint rows and multiplier columns are not those of eq. 30 (entries in F_y or in F_yd[C, L]): the zero eigenvalues of the constrained variables cannot be removed".into(),
                ));
            }
        }
        let e = SparseMatrix::from_triplets(n, n, dae.fyd.triplets().filter(|&(i, j, _)| !(moved[i] || moved[j])));
        let k = SparseMatrix::from_triplets(n, n, dae.fy.triplets().chain(dae.fyd.triplets().filter(|&(i, j, _)| moved[i] || moved[j])));
        match (e, k) {
            (Some(e), Some(k)) => Ok(Pencil { e, k, moved, shifted: OnceLock::new(), symbolic: OnceLock::new() }),
            _ => unreachable!("entries of an n x n model stay inside n x n"),
        }
    }

    /// The entries moved from `F_yd` (constraint rows, multiplier columns): the DAE's vectors
    /// there are the eq. 29 ones divided by λ.
    pub fn moved(&self) -> &[bool] {
        &self.moved
    }

    pub fn dim(&self) -> usize {
        self.k.nrows()
    }

    /// The pattern of `K + σ E` with `K`'s and `E`'s values on it.
    pub fn shifted(&self) -> &Shifted {
        self.shifted.get_or_init(|| {
            let (col_ptr, row_idx, ke) = self.k.csc_sum(&self.e, |v| (v, 0.0), |v| (0.0, v), |x, y| (x.0 + y.0, x.1 + y.1));
            let (k, e) = ke.into_iter().unzip();
            Shifted { col_ptr, row_idx, k, e }
        })
    }

    /// The symbolic LU analysis (COLAMD column ordering, structure of the factors) of the
    /// pattern of `K + σ E`, shared by every shift; `None` when faer's analysis fails.
    pub fn symbolic(&self) -> Option<&SymbolicLu<usize>> {
        self.symbolic
            .get_or_init(|| {
                let s = self.shifted();
                let n = self.dim();
                factorize_symbolic_lu(SymbolicSparseColMatRef::new_checked(n, n, &s.col_ptr, None, &s.row_idx), Default::default()).ok()
            })
            .as_ref()
    }

    /// A right (`left = false`) or left vector of eq. 29 as a vector of the DAE's pencil.
    pub fn to_dae(&self, x: &Col<c64>, lambda: c64) -> Col<c64> {
        let mut out = x.clone();
        for (o, &m) in crate::linear::contiguous_mut(out.as_mut()).iter_mut().zip(&self.moved) {
            if m {
                *o = *o / lambda;
            }
        }
        out
    }
}

impl Shifted {
    /// The values of `K + σ E` on the pattern, into `out` (resized).
    pub fn values_into<T: Copy>(&self, out: &mut Vec<T>, value: impl Fn(f64, f64) -> T) {
        out.clear();
        out.extend(self.k.iter().zip(&self.e).map(|(&k, &e)| value(k, e)));
    }

    /// `K + σ E` with the values `values` (from [`Self::values_into`]).
    pub fn matrix<'a, T>(&'a self, values: &'a [T]) -> SparseColMatRef<'a, usize, T> {
        let n = self.col_ptr.len() - 1;
        SparseColMatRef::new(SymbolicSparseColMatRef::new_checked(n, n, &self.col_ptr, None, &self.row_idx), values)
    }
}

/// Decoupled undamped oscillators `ẋ = v, v̇ = −ωₖ² x` as a first-order pencil `λ E + K`,
/// E = I, K = [[0, −1], [ωₖ², 0]] blocks: eigenvalues ±jωₖ (closed form). For the tests
/// of the count and the clusters.
#[cfg(test)]
pub(super) fn oscillators(omegas: &[f64]) -> Pencil {
    let n = 2 * omegas.len();
    let e = SparseMatrix::from_triplets(n, n, (0..n).map(|i| (i, i, 1.0))).unwrap();
    let k = SparseMatrix::from_triplets(n, n, omegas.iter().enumerate().flat_map(|(i, w)| [(2 * i, 2 * i + 1, -1.0), (2 * i + 1, 2 * i, w * w)])).unwrap();
    let names = (0..n).map(|i| format!("y{i}")).collect();
    let dae = SparseLinearDae { fyd: e, fy: k, b: faer::Mat::zeros(n, 0), c: faer::Mat::zeros(0, n), c_rate: None, unknown_names: names, input_names: Vec::new(), output_names: Vec::new(), constraint_form: None, multipliers: Vec::new() };
    Pencil::new(&dae).unwrap()
}
