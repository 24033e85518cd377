//! Projection onto selected right and adjoint eigenvectors: the descriptor ROM
//! `E ẋ = A x + B u`, `z = C x` (eqs. 41–50; eqs. 64–67 when J and J* were given).

use faer::{c64, Mat};

use super::dense::transfer_with_rates;
use super::select::Selection;
use super::RomError;
use crate::eigen::{ModalAnalysis, Mode};
use crate::linear::{Jacobians, LinearDae, SparseLinearDae};
use crate::linear::rad_per_s;

/// The input and output maps of the full model, dense or sparse alike.
struct Ports<'a> {
    b: &'a Mat<f64>,
    c: &'a Mat<f64>,
    c_rate: Option<&'a Mat<f64>>,
    input_names: &'a [String],
    output_names: &'a [String],
}

/// Descriptor reduced-order model. States of statically residualized modes have zero rows
/// and columns in `E`.
#[derive(Clone, Debug)]
pub struct DescriptorRom {
    pub e: Mat<f64>,
    pub a: Mat<f64>,
    pub b: Mat<f64>,
    pub c: Mat<f64>,
    /// Rate rows of velocity outputs: `z = C x + C_v ẋ` (`None` without rate outputs).
    pub c_rate: Option<Mat<f64>>,
    /// Eigenvalues of the kept (dynamic) part [rad/s].
    pub eigenvalues: Vec<c64>,
    pub state_names: Vec<String>,
    /// The mode (0-based index into the modal analysis) each state comes from: both states
    /// `[Re v, Im v]` of a complex pair name its member with positive imaginary part.
    pub state_modes: Vec<usize>,
    pub input_names: Vec<String>,
    pub output_names: Vec<String>,
    /// Number of statically residualized states.
    pub static_states: usize,
}

/// Real bases `V = Ỹ T`, `W` (eq. 42): a complex pair gives `[Re v, Im v]` and
/// `[2 Re u, −2 Im u]`, so that with `uᵀ F_yd v = 1` the pair's block of `E` is the identity.
fn real_bases(modal: &ModalAnalysis, modes: &[usize], n: usize) -> Result<(Mat<f64>, Mat<f64>, Vec<String>, Vec<usize>), RomError> {
    let mut cols_v: Vec<Vec<f64>> = Vec::new();
    let mut cols_w: Vec<Vec<f64>> = Vec::new();
    let mut names = Vec::new();
    let mut state_modes = Vec::new();
    for &i in modes {
        let m: &Mode = &modal.modes[i];
        let (v, u) = match (&m.right, &m.left) {
            (Some(v), Some(u)) => (v, u),
            _ => return Err(RomError::MissingVectors(i + 1)),
        };
        match m.partner {
            Some(p) if p < i => continue,
            Some(_) => {
                cols_v.push((0..n).map(|k| v[k].re).collect());
                cols_v.push((0..n).map(|k| v[k].im).collect());
                cols_w.push((0..n).map(|k| 2.0 * u[k].re).collect());
                cols_w.push((0..n).map(|k| -2.0 * u[k].im).collect());
                names.push(format!("mode {} re", i + 1));
                names.push(format!("mode {} im", i + 1));
                state_modes.extend([i, i]);
            }
            None => {
                cols_v.push((0..n).map(|k| v[k].re).collect());
                cols_w.push((0..n).map(|k| u[k].re).collect());
                names.push(format!("mode {}", i + 1));
                state_modes.push(i);
            }
        }
    }
    let to_mat = |cols: &Vec<Vec<f64>>| Mat::from_fn(n, cols.len(), |r, c| cols[c][r]);
    Ok((to_mat(&cols_v), to_mat(&cols_w), names, state_modes))
}

/// The bases of the kept modes (followed, with `residualize`, by the dropped ones) and the
/// number of states of the kept ones.
#[allow(clippy::type_complexity)]
fn projection_bases(modal: &ModalAnalysis, sel: &Selection, residualize: bool, n: usize) -> Result<(Mat<f64>, Mat<f64>, Vec<String>, Vec<usize>, usize), RomError> {
    let mut modes = sel.kept.clone();
    if residualize {
        modes.extend(sel.dropped.iter().copied());
    }
    let (v, w, state_names, state_modes) = real_bases(modal, &modes, n)?;
    let kept_states = real_bases(modal, &sel.kept, n)?.0.ncols();
    Ok((v, w, state_names, state_modes, kept_states))
}

impl DescriptorRom {
    /// Projects the linear DAE onto the kept modes; with `residualize`, the dropped dynamic
    /// modes are projected too but with their rows and columns of `E` set to zero, so that
    /// they contribute only their static response (paper Fig. 7).
    pub fn project(dae: &LinearDae, modal: &ModalAnalysis, sel: &Selection, residualize: bool) -> Result<Self, RomError> {
        let n = dae.dim();
        let (v, w, state_names, state_modes, kept_states) = projection_bases(modal, sel, residualize, n)?;
        let wt = w.transpose();
        let (mut e, a) = match &dae.jacobians {
            Jacobians::Derivatives { fyd, fy } => (wt * fyd * &v, -(wt * fy * &v)),
            Jacobians::Coefficient { j, jstar, dcoef } => {
                // Eqs. 66–67: E = ½ (WᵀJV + WᵀJ*V), A = −(WᵀJV − WᵀJ*V)/(2c).
                let (wjv, wjsv) = (wt * j * &v, wt * jstar * &v);
                (&wjv + &wjsv, (&wjv - &wjsv) * faer::Scale(-0.5 / dcoef))
            }
        };
        if let Jacobians::Coefficient { .. } = &dae.jacobians {
            e = e * faer::Scale(0.5);
        }
        let ports = Ports { b: &dae.b, c: &dae.c, c_rate: dae.c_rate.as_ref(), input_names: &dae.input_names, output_names: &dae.output_names };
        Ok(Self::assemble(e, a, &v, &w, ports, modal, sel, kept_states, state_names, state_modes))
    }

    /// [`DescriptorRom::project`] for a sparse linear DAE: `E = Wᵀ (F_yd V)`,
    /// `A = −Wᵀ (F_y V)` by sparse products (issue 13 point 3), nothing n x n formed.
    pub fn project_sparse(dae: &SparseLinearDae, modal: &ModalAnalysis, sel: &Selection, residualize: bool) -> Result<Self, RomError> {
        let n = dae.dim();
        let (v, w, state_names, state_modes, kept_states) = projection_bases(modal, sel, residualize, n)?;
        let wt = w.transpose();
        let e = wt * dae.fyd.mul_dense(&v);
        let a = -(wt * dae.fy.mul_dense(&v));
        let ports = Ports { b: &dae.b, c: &dae.c, c_rate: dae.c_rate.as_ref(), input_names: &dae.input_names, output_names: &dae.output_names };
        Ok(Self::assemble(e, a, &v, &w, ports, modal, sel, kept_states, state_names, state_modes))
    }

    /// The ROM from its projected `E`, `A` (residualized states' rows and columns of `E`
    /// zeroed) and the ports projected on the bases.
    #[allow(clippy::too_many_arguments)]
    fn assemble(mut e: Mat<f64>, a: Mat<f64>, v: &Mat<f64>, w: &Mat<f64>, ports: Ports<'_>, modal: &ModalAnalysis, sel: &Selection, kept_states: usize, state_names: Vec<String>, state_modes: Vec<usize>) -> Self {
        let s = v.ncols();
        for i in kept_states..s {
            for k in 0..s {
                e[(i, k)] = 0.0;
                e[(k, i)] = 0.0;
            }
        }
        DescriptorRom {
            e,
            a,
            b: w.transpose() * ports.b,
            c: ports.c * v,
            c_rate: ports.c_rate.map(|cv| cv * v),
            eigenvalues: sel.kept.iter().map(|&i| modal.modes[i].lambda).collect(),
            state_names,
            state_modes,
            input_names: ports.input_names.to_vec(),
            output_names: ports.output_names.to_vec(),
            static_states: s - kept_states,
        }
    }

    /// `(C + jω C_v) (jω E − A)⁻¹ B` at each frequency [Hz].
    pub fn frequency_response(&self, freq_hz: &[f64]) -> Vec<Mat<c64>> {
        let minus_a = -&self.a;
        freq_hz.iter().map(|f| transfer_with_rates(rad_per_s(*f), &self.e, &minus_a, &self.b, &self.c, self.c_rate.as_ref(), None)).collect()
    }
}
