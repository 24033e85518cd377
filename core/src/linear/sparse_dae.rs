//! A linear DAE kept sparse as assembled (issue 13 point 1): `F_yd`, `F_y` with their
//! non-zeros only, thin `B̃` and `C̃`. Memory grows with the non-zeros, not with n²; the
//! dense route converts on demand ([`SparseLinearDae::to_dense`]).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::{SparseColMat, Triplet};
use faer::{c64, Mat};

use crate::lu::PatternLu;

use super::dae::{Jacobians, LinearDae};
use crate::model::ConstraintForm;
use super::sparse::SparseMatrix;
use super::rad_per_s;

/// `F_yd Δẏ + F_y Δy = B̃ u`, `z = C̃ Δy` (eqs. 38–40), sparse.
#[derive(Clone, Debug)]
pub struct SparseLinearDae {
    pub fyd: SparseMatrix,
    pub fy: SparseMatrix,
    /// `B̃` (equations x inputs).
    pub b: Mat<f64>,
    /// `C̃` (outputs x unknowns).
    pub c: Mat<f64>,
    /// `C̃_v` of rate outputs (`z = C̃ Δy + C̃_v Δẏ`), as in [`LinearDae::c_rate`].
    pub c_rate: Option<Mat<f64>>,
    pub unknown_names: Vec<String>,
    pub input_names: Vec<String>,
    pub output_names: Vec<String>,
    pub constraint_form: Option<ConstraintForm>,
    /// Indices of the Lagrange multipliers (each also its constraint equation's index).
    pub multipliers: Vec<usize>,
}

/// A sparse solve that failed or whose true residual is not at rounding level.
#[derive(Debug, thiserror::Error)]
pub enum SparseSolveError {
    #[error("{0} is singular (sparse LU failed)")]
    Singular(&'static str),
    #[error("{what}: the sparse solve's relative residual is {residual:e} (the matrix is numerically singular)")]
    Inaccurate { what: &'static str, residual: f64 },
}

/// Largest relative residual of a solve accepted as correct.
const SOLVE_TOLERANCE: f64 = 1e-10;

impl SparseLinearDae {
    /// The sparse copy of a dense linear DAE (exact zeros dropped).
    pub fn from_dense(dae: &LinearDae) -> Self {
        let (fyd, fy) = dae.jacobians.derivatives();
        SparseLinearDae {
            fyd: SparseMatrix::from_dense(&fyd),
            fy: SparseMatrix::from_dense(&fy),
            b: dae.b.clone(),
            c: dae.c.clone(),
            c_rate: dae.c_rate.clone(),
            unknown_names: dae.unknown_names.clone(),
            input_names: dae.input_names.clone(),
            output_names: dae.output_names.clone(),
            constraint_form: dae.constraint_form,
            multipliers: dae.multipliers.clone(),
        }
    }

    /// The dense linear DAE (`F_yd`, `F_y` given directly) for the dense route.
    pub fn to_dense(&self) -> LinearDae {
        LinearDae {
            jacobians: Jacobians::Derivatives { fyd: self.fyd.to_dense(), fy: self.fy.to_dense() },
            b: self.b.clone(),
            c: self.c.clone(),
            unknown_names: self.unknown_names.clone(),
            input_names: self.input_names.clone(),
            output_names: self.output_names.clone(),
            constraint_form: self.constraint_form,
            multipliers: self.multipliers.clone(),
            c_rate: self.c_rate.clone(),
        }
    }

    /// Number of equations (= unknowns).
    pub fn dim(&self) -> usize {
        self.fy.nrows()
    }

    /// Stored non-zeros of `F_yd` and `F_y`.
    pub fn nnz(&self) -> usize {
        self.fyd.nnz() + self.fy.nnz()
    }

    /// The static matrix `S` of [`LinearDae::static_matrix`], as triplets: `F_y`, with the
    /// constraint rows and multiplier columns taken from `F_yd` in the form of eq. 30.
    fn static_triplets(&self) -> Vec<(usize, usize, f64)> {
        let special = self.eq30_rows_and_columns();
        let mut t: Vec<(usize, usize, f64)> = self.fy.triplets().filter(|&(i, j, _)| !(special[i] || special[j])).collect();
        t.extend(self.fyd.triplets().filter(|&(i, j, _)| special[i] || special[j]));
        t
    }

    /// Which unknowns' rows and columns sit in `F_yd` in the form of eq. 30 (constraint rows,
    /// multipliers), [`LinearDae::plain_derivatives`]: none in eq. 29's.
    fn eq30_rows_and_columns(&self) -> Vec<bool> {
        let mut special = vec![false; self.dim()];
        if self.constraint_form == Some(ConstraintForm::Scaled) {
            for &k in &self.multipliers {
                special[k] = true;
            }
        }
        special
    }

    /// Static gain `C̃ S⁻¹ B̃` (rate outputs read zero) by one sparse LU of the static matrix (eq. 30 rows and
    /// columns restored), checked by its true residual.
    pub fn static_gain(&self) -> Result<Mat<f64>, SparseSolveError> {
        let x = self.static_solve(&self.b)?;
        Ok(&self.c * &x)
    }

    /// `S⁻¹ R` for the static matrix `S` (one sparse LU), checked by its true residual.
    pub fn static_solve(&self, r: &Mat<f64>) -> Result<Mat<f64>, SparseSolveError> {
        let what = "the static matrix of the full model";
        let n = self.dim();
        let t = self.static_triplets();
        let entries: Vec<Triplet<usize, usize, f64>> = t.iter().map(|&(i, j, v)| Triplet::new(i, j, v)).collect();
        let s = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &entries).map_err(|_| SparseSolveError::Singular(what))?;
        let mut lu = PatternLu::<f64>::analyze(s.symbolic(), faer::get_global_parallelism()).map_err(|_| SparseSolveError::Singular(what))?;
        let mut scratch = MemBuffer::try_new(lu.factor_scratch().or(lu.solve_scratch(r.ncols()))).map_err(|_| SparseSolveError::Singular(what))?;
        lu.factor(s.as_ref(), MemStack::new(&mut scratch)).map_err(|_| SparseSolveError::Singular(what))?;
        let mut x = r.clone();
        lu.solve_in_place(x.as_mut(), false, MemStack::new(&mut scratch));
        // ‖S x − R‖ / (‖S‖ ‖x‖ + ‖R‖), column by column.
        let norm_s = t.iter().map(|e| e.2 * e.2).sum::<f64>().sqrt();
        let mut sx = Mat::<f64>::zeros(n, r.ncols());
        for &(i, j, v) in &t {
            for k in 0..r.ncols() {
                sx[(i, k)] += v * x[(j, k)];
            }
        }
        for k in 0..r.ncols() {
            let res = (0..n).map(|i| (sx[(i, k)] - r[(i, k)]).powi(2)).sum::<f64>().sqrt();
            let scale = norm_s * x.col(k).norm_l2() + r.col(k).norm_l2();
            let rel = if scale > 0.0 { res / scale } else { 0.0 };
            if !(rel <= SOLVE_TOLERANCE) {
                return Err(SparseSolveError::Inaccurate { what, residual: rel });
            }
        }
        Ok(x)
    }

    /// `z/u = (C̃ + jω C̃_v)(jω F_yd + F_y)⁻¹ B̃` at each frequency [Hz] by sparse LU (the symbolic
    /// factorization computed once), each solve checked by its true residual; `F_yd`, `F_y` in
    /// the form of eq. 29 ([`LinearDae::plain_derivatives`]: f = 0 gives the static gain).
    pub fn frequency_response(&self, freq_hz: &[f64]) -> Result<Vec<Mat<c64>>, SparseSolveError> {
        let what = "jω F_yd + F_y";
        let n = self.dim();
        let special = self.eq30_rows_and_columns();
        let pattern: Vec<(usize, usize)> = {
            let mut p: Vec<(usize, usize)> = self.fy.triplets().map(|(i, j, _)| (i, j)).chain(self.fyd.triplets().map(|(i, j, _)| (i, j))).collect();
            p.sort_unstable();
            p.dedup();
            p
        };
        let rhs = Mat::from_fn(n, self.b.ncols(), |i, j| c64::new(self.b[(i, j)], 0.0));
        let rate = |i: usize, j: usize| self.c_rate.as_ref().map_or(0.0, |cv| cv[(i, j)]);
        let norm_p = |w: f64| (self.fy.norm_l2().powi(2) + (w * self.fyd.norm_l2()).powi(2)).sqrt();
        let mut factors: Option<(PatternLu<c64>, MemBuffer)> = None;
        let mut out = Vec::with_capacity(freq_hz.len());
        for &f in freq_hz {
            let w = rad_per_s(f);
            let mut entries: Vec<Triplet<usize, usize, c64>> = pattern.iter().map(|&(i, j)| Triplet::new(i, j, c64::new(0.0, 0.0))).collect();
            let index = |i: usize, j: usize| pattern.binary_search(&(i, j)).unwrap_or_else(|_| unreachable!("pattern holds every entry"));
            for (i, j, v) in self.fy.triplets().filter(|&(i, j, _)| !(special[i] || special[j])) {
                entries[index(i, j)].val += c64::new(v, 0.0);
            }
            for (i, j, v) in self.fyd.triplets() {
                entries[index(i, j)].val += if special[i] || special[j] { c64::new(v, 0.0) } else { c64::new(0.0, w * v) };
            }
            let p = SparseColMat::<usize, c64>::try_new_from_triplets(n, n, &entries).map_err(|_| SparseSolveError::Singular(what))?;
            if factors.is_none() {
                let lu = PatternLu::<c64>::analyze(p.symbolic(), faer::get_global_parallelism()).map_err(|_| SparseSolveError::Singular(what))?;
                let scratch = MemBuffer::try_new(lu.factor_scratch().or(lu.solve_scratch(rhs.ncols()))).map_err(|_| SparseSolveError::Singular(what))?;
                factors = Some((lu, scratch));
            }
            let Some((lu, scratch)) = factors.as_mut() else { unreachable!("set above") };
            lu.factor(p.as_ref(), MemStack::new(scratch)).map_err(|_| SparseSolveError::Singular(what))?;
            let mut x = rhs.clone();
            lu.solve_in_place(x.as_mut(), false, MemStack::new(scratch));
            let px = &p * &x;
            for k in 0..rhs.ncols() {
                let res = (0..n).map(|i| (px[(i, k)] - rhs[(i, k)]).norm_sqr()).sum::<f64>().sqrt();
                let scale = norm_p(w) * x.col(k).norm_l2() + rhs.col(k).norm_l2();
                let rel = if scale > 0.0 { res / scale } else { 0.0 };
                if !(rel <= SOLVE_TOLERANCE) {
                    return Err(SparseSolveError::Inaccurate { what, residual: rel });
                }
            }
            let c = Mat::from_fn(self.c.nrows(), n, |i, j| c64::new(self.c[(i, j)], w * rate(i, j)));
            out.push(&c * &x);
        }
        Ok(out)
    }
}
