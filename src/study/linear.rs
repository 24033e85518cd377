//! The linear DAE of a study: kept sparse as assembled, its dense copy built only when the
//! dense route asks for it (issue 13 point 1: on the sparse route memory grows with the
//! non-zeros, not with n²).

use std::sync::OnceLock;

use faer::{c64, Mat};

use crate::linear::{LinearDae, SparseLinearDae};

/// `F_yd Δẏ + F_y Δy = B̃ u`, `z = C̃ Δy`, sparse, dense, or both.
pub(super) struct LinearModel {
    sparse: Option<SparseLinearDae>,
    dense: OnceLock<LinearDae>,
    /// [`crate::rom::full_static_gain`] of the dense DAE (its error's text and the free
    /// direction), computed once: the port warnings and every ROM's static gains need it.
    /// With the rounding scale of each channel ([`crate::rom::full_static_gain_and_scale`]).
    dense_gain: OnceLock<Result<(Mat<f64>, Mat<f64>), (String, Option<Vec<f64>>)>>,
}

impl LinearModel {
    pub fn from_sparse(sparse: SparseLinearDae) -> Self {
        LinearModel { sparse: Some(sparse), dense: OnceLock::new(), dense_gain: OnceLock::new() }
    }

    /// A dense DAE (a pencil file, a DAE with springs removed); `with_sparse` also keeps its
    /// sparse copy for the sparse route.
    pub fn from_dense(dense: LinearDae, with_sparse: bool) -> Self {
        let sparse = with_sparse.then(|| SparseLinearDae::from_dense(&dense));
        LinearModel { sparse, dense: OnceLock::from(dense), dense_gain: OnceLock::new() }
    }

    /// The sparse DAE, when the study has one.
    pub fn sparse(&self) -> Option<&SparseLinearDae> {
        self.sparse.as_ref()
    }

    /// The dense DAE, converted from the sparse one on first use (n x n: the dense route only).
    pub fn dense(&self) -> &LinearDae {
        self.dense.get_or_init(|| match &self.sparse {
            Some(s) => s.to_dense(),
            None => unreachable!("a study's linear model is built from a sparse or a dense DAE"),
        })
    }

    /// The dense DAE only if it exists already.
    fn dense_if_built(&self) -> Option<&LinearDae> {
        self.dense.get()
    }

    pub fn dim(&self) -> usize {
        self.sparse.as_ref().map_or_else(|| self.dense().dim(), |s| s.dim())
    }

    pub fn b(&self) -> &Mat<f64> {
        self.sparse.as_ref().map_or_else(|| &self.dense().b, |s| &s.b)
    }

    pub fn c(&self) -> &Mat<f64> {
        self.sparse.as_ref().map_or_else(|| &self.dense().c, |s| &s.c)
    }

    /// `C̃_v` of rate outputs (velocity sensors), if any.
    pub fn c_rate(&self) -> Option<&Mat<f64>> {
        self.sparse.as_ref().map_or_else(|| self.dense().c_rate.as_ref(), |s| s.c_rate.as_ref())
    }

    pub fn input_names(&self) -> &[String] {
        self.sparse.as_ref().map_or_else(|| &self.dense().input_names[..], |s| &s.input_names[..])
    }

    pub fn output_names(&self) -> &[String] {
        self.sparse.as_ref().map_or_else(|| &self.dense().output_names[..], |s| &s.output_names[..])
    }

    pub fn unknown_names(&self) -> &[String] {
        self.sparse.as_ref().map_or_else(|| &self.dense().unknown_names[..], |s| &s.unknown_names[..])
    }

    pub fn multipliers(&self) -> &[usize] {
        self.sparse.as_ref().map_or_else(|| &self.dense().multipliers[..], |s| &s.multipliers[..])
    }

    /// `uᵀ F_yd v` of each `(u, v)` (the product a mode's left vector is scaled by,
    /// `eigen::modes::normalize`), on the sparse DAE when there is one.
    pub fn fyd_bilinear(&self, pairs: &[(&faer::Col<c64>, &faer::Col<c64>)]) -> Vec<c64> {
        use crate::eigen::{dot_t, mul_real_complex};
        match (&self.sparse, self.dense_if_built()) {
            (Some(s), _) => pairs.iter().map(|(u, v)| dot_t(u, &s.fyd.mul_complex(v))).collect(),
            (None, Some(d)) => {
                let fyd = d.jacobians.derivatives().0;
                pairs.iter().map(|(u, v)| dot_t(u, &mul_real_complex(&fyd, v))).collect()
            }
            (None, None) => unreachable!("a study's linear model is built from a sparse or a dense DAE"),
        }
    }

    /// The columns `cols` of `F_yd`, each as (row, value) of its nonzeros.
    pub fn fyd_columns(&self, cols: &[usize]) -> Vec<Vec<(usize, f64)>> {
        let mut out = vec![Vec::new(); cols.len()];
        let at = |j: usize| cols.iter().position(|&c| c == j);
        match (self.dense_if_built(), &self.sparse) {
            (Some(d), _) => {
                let (fyd, _) = d.jacobians.derivatives();
                for (k, &j) in cols.iter().enumerate() {
                    out[k] = (0..fyd.nrows()).map(|i| (i, fyd[(i, j)])).filter(|e| e.1 != 0.0).collect();
                }
            }
            (None, Some(s)) => s.fyd.triplets().for_each(|(i, j, v)| {
                if let Some(k) = at(j).filter(|_| v != 0.0) {
                    out[k].push((i, v));
                }
            }),
            (None, None) => unreachable!("a study's linear model is built from a sparse or a dense DAE"),
        }
        out
    }

    /// `F_yd[k, k]` of every unknown (the dynamic nodes' masses sit on the momentum rows).
    pub fn fyd_diagonal(&self) -> Vec<f64> {
        match (self.dense_if_built(), &self.sparse) {
            (Some(d), _) => {
                let (fyd, _) = d.jacobians.derivatives();
                (0..fyd.nrows()).map(|k| fyd[(k, k)]).collect()
            }
            (None, Some(s)) => {
                let mut diag = vec![0.0; s.dim()];
                s.fyd.triplets().filter(|&(i, j, _)| i == j).for_each(|(i, _, v)| diag[i] += v);
                diag
            }
            (None, None) => unreachable!("a study's linear model is built from a sparse or a dense DAE"),
        }
    }

    /// The full model's static gain `C̃ S⁻¹ B̃` of the dense DAE by
    /// [`crate::rom::full_static_gain`] (the text of its error), computed on first use only.
    pub fn dense_static_gain(&self) -> Result<&Mat<f64>, &str> {
        self.dense_gain_or_free_direction().as_ref().map(|g| &g.0).map_err(|e| e.0.as_str())
    }

    /// The rounding scale of each channel of [`LinearModel::dense_static_gain`].
    pub fn dense_static_gain_scale(&self) -> Option<&Mat<f64>> {
        self.dense_gain_or_free_direction().as_ref().ok().map(|g| &g.1)
    }

    /// When the dense static matrix is singular, the direction it leaves free (largest
    /// entry 1), from the factorization [`LinearModel::dense_static_gain`] tried.
    pub fn dense_free_direction(&self) -> Option<&[f64]> {
        self.dense_gain_or_free_direction().as_ref().err().and_then(|e| e.1.as_deref())
    }

    fn dense_gain_or_free_direction(&self) -> &Result<(Mat<f64>, Mat<f64>), (String, Option<Vec<f64>>)> {
        self.dense_gain.get_or_init(|| crate::rom::full_static_gain_and_scale(self.dense()).map_err(|(e, free)| (e.to_string(), free)))
    }

    /// The full model's static gain `C̃ S⁻¹ B̃` on the sparse route, by one sparse LU
    /// checked by its residual.
    pub fn sparse_static_gain(&self) -> Option<Result<Mat<f64>, crate::linear::SparseSolveError>> {
        self.sparse.as_ref().map(|s| s.static_gain())
    }

    /// The full model's frequency response at `freq_hz` [Hz] (outputs × inputs): by sparse
    /// solves with one symbolic factorization when the study is on the sparse route.
    pub fn frequency_response(&self, freq_hz: &[f64], sparse_route: bool) -> Result<Vec<Mat<c64>>, crate::linear::SparseSolveError> {
        match (&self.sparse, sparse_route) {
            (Some(s), true) => s.frequency_response(freq_hz),
            _ => Ok(crate::rom::full_frequency_response(self.dense(), freq_hz)),
        }
    }
}
