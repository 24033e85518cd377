//! One eigenanalysis of a run, as MBDyn does it (manual, "Eigenanalysis"): `J(+c)` and
//! `J(−c)` at the current solution (eqs. 13–14), QZ on the pencil in the Λ form (eq. 18),
//! eigenvalues mapped back with eq. 23 and labelled (eqs. 32–35). The pencil is solved and
//! its modes' kinetic-energy shares taken by the same functions as `romdyn eig`'s
//! ([`crate::eigen::dense_modes`], [`crate::eigen::energy_shares`]).

use faer::{c64, Mat};

use super::error::RunError;
use crate::dae::{linearize, DofMap, State};
use crate::eigen::{dense_modes, energy_shares, EnergyShare, ModalEnergy};
use crate::kinematics::rotation_vector;
use crate::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use crate::linear::{Jacobians, LinearDae};
use crate::model::{EigenOutput, EigenRequest, Model};
use crate::output::eigen_file::{EigenFile, Geometry, MatrixLayout};

/// dCoef used when the file gives no `parameter` [s]: MBDyn's default parameter is 1 and
/// its `dCoef` is half the parameter.
pub const DEFAULT_DCOEF: f64 = 0.5;

/// The result of one eigenanalysis.
pub struct Eigenanalysis {
    /// 0-based number of the analysis in the run's list of times.
    pub index: usize,
    /// Time of the solution it was done at [s].
    pub time: f64,
    /// `c` of `J(±c)` [s].
    pub dcoef: f64,
    /// `J(+c)`, MBDyn's `Aplus`.
    pub aplus: Mat<f64>,
    /// `J(−c)`, MBDyn's `Aminus`.
    pub aminus: Mat<f64>,
    /// Names of the unknowns (= equations), in order.
    pub unknown_names: Vec<String>,
    /// Eigenvalues of the Λ form with this `c`.
    pub modal: ModalAnalysis,
    /// Modes inside the request's frequency limits (all modes without limits).
    pub written: Vec<usize>,
    /// Structural nodes at the analysis.
    pub geometry: Geometry,
    /// Kinetic-energy shares of each mode (computed for the written dynamic modes).
    pub energy: Vec<Vec<EnergyShare>>,
    /// What the request asks to write.
    pub output: EigenOutput,
}

/// Modes whose frequency `|Im λ|/2π` lies inside the limits (MBDyn writes only those).
fn within_limits(modal: &ModalAnalysis, r: &EigenRequest) -> Vec<usize> {
    let (lo, hi) = (r.lower_frequency_hz.unwrap_or(f64::NEG_INFINITY), r.upper_frequency_hz.unwrap_or(f64::INFINITY));
    let freq = |l: c64| if l.re.is_finite() && l.im.is_finite() { l.im.abs() / (2.0 * std::f64::consts::PI) } else { f64::INFINITY };
    (0..modal.modes.len()).filter(|&k| (lo..=hi).contains(&freq(modal.modes[k].lambda))).collect()
}

impl Eigenanalysis {
    /// Eigenanalysis `index` of `request` at `state`.
    pub fn at(model: &Model, state: &State, index: usize, request: &EigenRequest) -> Result<Self, RunError> {
        let fail = |message: String| RunError::Eigen { index, time: state.t, message };
        let dcoef = request.dcoef.unwrap_or(DEFAULT_DCOEF);
        let dae = linearize(model, state, &[], &[], Some(dcoef)).map_err(|e| fail(e.to_string()))?;
        let modal = dense_modes(&dae, EigenRoute::Lambda, None).map_err(|e| fail(e.to_string()))?;
        let written = within_limits(&modal, request);
        // The shares `romdyn eig` prints (a degenerate cluster's members sharing theirs),
        // written for the written dynamic modes.
        let mut energy = energy_shares(&ModalEnergy::new(model, &dae), &modal.modes);
        for (k, shares) in energy.iter_mut().enumerate() {
            if modal.modes[k].kind != ModeKind::Dynamic || !written.contains(&k) {
                shares.clear();
            }
        }
        let LinearDae { jacobians: Jacobians::Coefficient { j: aplus, jstar: aminus, .. }, unknown_names, .. } = dae else {
            return Err(fail("linearization did not return J(±c)".into()));
        };
        let dofs = DofMap::new(model);
        let frames: Vec<_> = (0..model.nodes.len()).map(|i| state.node_frame(&dofs, i).kin).collect();
        let geometry = Geometry {
            labels: model.nodes.iter().map(|n| n.label).collect(),
            first_index: dofs.node_first.clone(),
            position: frames.iter().map(|k| k.x).collect(),
            rotation_vector: frames.iter().map(|k| rotation_vector(&k.r)).collect(),
        };
        Ok(Eigenanalysis { index, time: state.t, dcoef, aplus, aminus, unknown_names, modal, written, geometry, energy, output: request.output })
    }

    /// The eigenvalues labelled dynamic [rad/s], in table order.
    pub fn dynamic_eigenvalues(&self) -> Vec<c64> {
        self.modal.of_kind(ModeKind::Dynamic).map(|k| self.modal.modes[k].lambda).collect()
    }

    /// The content of its `.m` and JSON files.
    pub fn file(&self) -> EigenFile<'_> {
        let matrices = match (self.output.full_matrices, self.output.sparse_matrices) {
            (true, _) => Some(MatrixLayout::Full),
            (false, true) => Some(MatrixLayout::Sparse),
            _ => None,
        };
        EigenFile {
            index: self.index,
            time: self.time,
            dcoef: self.dcoef,
            aplus: &self.aplus,
            aminus: &self.aminus,
            matrices,
            modal: &self.modal,
            written: &self.written,
            eigenvectors: self.output.eigenvectors,
            geometry: self.output.geometry.then_some(&self.geometry),
            unknown_names: &self.unknown_names,
            energy: &self.energy,
        }
    }
}
