//! One eigenanalysis of a run, as MBDyn does it (manual, "Eigenanalysis"): `J(+c)` and
//! `J(−c)` at the current solution (eqs. 13–14), eigenvalues in the Λ form (eq. 18) mapped
//! back with eq. 23 and labelled (eqs. 32–35), by the solver the file asks for:
//!
//! - `use lapack` (or none): every eigenvalue by the dense route, QZ after the deflation
//!   ([`crate::eigen::dense_modes`]), refused before anything is allocated when its n x n
//!   matrices exceed the dense budget ([`crate::limits::check_dense`]);
//! - `use arpack, NEV, …` / `use jdqz, NEV, …`: the NEV lowest dynamic modes by the sparse
//!   shift-invert route ([`crate::eigen::krylov`], `ModeTarget::Lowest`, certified by its
//!   count), the counterpart of MBDyn's ARPACK on `Aplus⁻¹ Aminus − I` (Λ nearest 1, λ
//!   nearest 0); `J(±c)` stay sparse as assembled, no n x n matrix is formed.
//!
//! The modes' kinetic-energy shares are taken by the same function as `romdyn eig`'s
//! ([`crate::eigen::energy_shares`]).

use faer::c64;

use super::error::RunError;
use crate::dae::{linearize, linearize_sparse, sparse_jacobian_pair, DofMap, State};
use crate::eigen::krylov::{sparse_modes, ModeTarget, SparseEigenSettings};
use crate::eigen::{dense_modes, energy_shares, EnergyShare, ModalEnergy};
use crate::kinematics::rotation_vector;
use crate::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use crate::limits::check_dense;
use crate::linear::{Jacobians, LinearDae};
use crate::model::{EigenOutput, EigenRequest, EigenSolverRequest, Model};
use crate::output::eigen_file::{EigenFile, Geometry, MatrixLayout, PencilMatrices};
use crate::linear::hz;

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
    /// `J(+c)` and `J(−c)`, MBDyn's `Aplus` and `Aminus`: dense on the dense route, sparse on
    /// the sparse one.
    pub pencil: PencilMatrices,
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
    /// How the modes were computed, in words (the `.out`, `.m` and JSON files say it).
    pub solver: String,
    /// On the sparse route, why its modes are not certified (then a warning), if they are not.
    pub not_certified: Option<String>,
}

/// The dense route's refusal: its n x n matrices do not fit the dense budget.
fn dense_refusal(n: usize, what: &str, instead: &str) -> Option<String> {
    check_dense(n, n, || format!("{what} of this model ({n} equations)")).err().map(|e| format!("{e}; {instead}"))
}

/// Whether `request` can be done on `model` by the route it asks for, checked before the run
/// starts: a dense eigenanalysis (or a full-matrix output of a sparse one) whose n x n
/// matrices exceed the dense budget is refused with its size and the sparse request to
/// make instead.
pub fn check_request(model: &Model, request: &EigenRequest) -> Result<(), String> {
    let n = DofMap::new(model).len;
    let refusal = match request.solver {
        EigenSolverRequest::Dense => dense_refusal(n, "the dense eigenanalysis's J(±c)", "ask for the sparse route in the eigenanalysis card instead ('use arpack, NEV, NCV, TOL': the NEV lowest modes, memory proportional to the non-zeros)"),
        EigenSolverRequest::Lowest { .. } if request.output.full_matrices => dense_refusal(n, "'output full matrices'", "write them with 'output sparse matrices' instead"),
        EigenSolverRequest::Lowest { .. } => None,
    };
    refusal.map_or(Ok(()), Err)
}

/// Modes whose frequency `|Im λ|/2π` lies inside the limits (MBDyn writes only those).
fn within_limits(modal: &ModalAnalysis, r: &EigenRequest) -> Vec<usize> {
    let (lo, hi) = (r.lower_frequency_hz.unwrap_or(f64::NEG_INFINITY), r.upper_frequency_hz.unwrap_or(f64::INFINITY));
    let freq = |l: c64| if l.re.is_finite() && l.im.is_finite() { hz(l.im.abs()) } else { f64::INFINITY };
    (0..modal.modes.len()).filter(|&k| (lo..=hi).contains(&freq(modal.modes[k].lambda))).collect()
}

impl Eigenanalysis {
    /// Eigenanalysis `index` of `request` at `state`, by the solver it asks for.
    pub fn at(model: &Model, state: &State, index: usize, request: &EigenRequest) -> Result<Self, RunError> {
        let fail = |message: String| RunError::Eigen { index, time: state.t, message };
        check_request(model, request).map_err(fail)?;
        let dcoef = request.dcoef.unwrap_or(DEFAULT_DCOEF);
        let solved = match request.solver {
            EigenSolverRequest::Dense => dense(model, state, dcoef),
            EigenSolverRequest::Lowest { modes, card } => sparse(model, state, dcoef, modes, card, request.output.full_matrices || request.output.sparse_matrices),
        };
        let Solved { pencil, unknown_names, modal, energy_of, solver, not_certified } = solved.map_err(fail)?;
        let written = within_limits(&modal, request);
        // The shares `romdyn eig` prints (a degenerate cluster's members sharing theirs),
        // written for the written dynamic modes.
        let mut energy = energy_shares(&energy_of, &modal.modes);
        for (k, shares) in energy.iter_mut().enumerate() {
            if modal.modes[k].kind != ModeKind::Dynamic || !written.contains(&k) {
                shares.clear();
            }
        }
        let dofs = DofMap::new(model);
        let frames: Vec<_> = (0..model.nodes.len()).map(|i| state.node_frame(&dofs, i).kin).collect();
        let geometry = Geometry {
            labels: model.nodes.iter().map(|n| n.label).collect(),
            first_index: dofs.node_first.clone(),
            position: frames.iter().map(|k| k.x).collect(),
            rotation_vector: frames.iter().map(|k| rotation_vector(&k.r)).collect(),
        };
        Ok(Eigenanalysis { index, time: state.t, dcoef, pencil, unknown_names, modal, written, geometry, energy, output: request.output, solver, not_certified })
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
            pencil: &self.pencil,
            matrices,
            solver: &self.solver,
            modal: &self.modal,
            written: &self.written,
            eigenvectors: self.output.eigenvectors,
            geometry: self.output.geometry.then_some(&self.geometry),
            unknown_names: &self.unknown_names,
            energy: &self.energy,
        }
    }
}

/// What either route returns.
struct Solved {
    pencil: PencilMatrices,
    unknown_names: Vec<String>,
    modal: ModalAnalysis,
    energy_of: ModalEnergy,
    solver: String,
    not_certified: Option<String>,
}

/// Every eigenvalue by QZ on the dense `J(±c)` (MBDyn's `use lapack`).
fn dense(model: &Model, state: &State, dcoef: f64) -> Result<Solved, String> {
    let dae = linearize(model, state, &[], &[], Some(dcoef)).map_err(|e| e.to_string())?;
    let modal = dense_modes(&dae, EigenRoute::Lambda, None).map_err(|e| e.to_string())?;
    let energy_of = ModalEnergy::new(model, &dae).at_state(model, state);
    let LinearDae { jacobians: Jacobians::Coefficient { j: aplus, jstar: aminus, .. }, unknown_names, .. } = dae else {
        return Err("linearization did not return J(±c)".into());
    };
    let solver = "every eigenvalue, dense route (QZ after deflation, use lapack)".to_string();
    Ok(Solved { pencil: PencilMatrices::Dense { aplus, aminus }, unknown_names, modal, energy_of, solver, not_certified: None })
}

/// The `modes` lowest dynamic modes by the sparse shift-invert route on the sparse
/// linearization (MBDyn's `use arpack` / `use jdqz`, named `card`), labelled in the Λ form
/// of this `dcoef`. `J(±c)` are assembled only when the file writes them (`with_matrices`):
/// the route solves on `F_/ẏ`, `F_/y` (eq. 29), and assembling the pair again took about a
/// twentieth of a 96,024-equation run (issue 36 point 3).
fn sparse(model: &Model, state: &State, dcoef: f64, modes: usize, card: &str, with_matrices: bool) -> Result<Solved, String> {
    let dae = linearize_sparse(model, state, &[], &[]).map_err(|e| e.to_string())?;
    let settings = SparseEigenSettings { route: EigenRoute::Lambda, dcoef: Some(dcoef), ..SparseEigenSettings::default() };
    let found = sparse_modes(&dae, ModeTarget::Lowest(modes), &settings).map_err(|e| format!("{card}, {modes}: {e}"))?;
    let mut diagonal = vec![0.0; dae.dim()];
    dae.fyd.triplets().filter(|&(i, j, _)| i == j).for_each(|(i, _, v)| diagonal[i] += v);
    let energy_of = ModalEnergy::from_fyd_diagonal(model, &diagonal).at_state(model, state);
    let pencil = if with_matrices {
        let (aplus, aminus) = sparse_jacobian_pair(model, state, dcoef).map_err(|e| e.to_string())?;
        PencilMatrices::Sparse { aplus, aminus }
    } else {
        PencilMatrices::Unassembled { dim: dae.dim() }
    };
    let certified = match &found.certificate {
        Some(c) if found.certified => format!("certified ({c})"),
        _ => format!("NOT certified: {}", found.note.as_deref().unwrap_or("see the warning")),
    };
    let solver = format!(
        "the {modes} lowest dynamic modes ({card}), sparse shift-invert Krylov-Schur route: {certified}; largest true residual {:.1e} (tolerance {:.0e}); the zero and infinite eigenvalues are not computed",
        found.max_residual, settings.tolerance
    );
    let not_certified = (!found.certified).then(|| found.note.clone().unwrap_or_else(|| "the count of the modes was not confirmed".into()));
    Ok(Solved { pencil, unknown_names: dae.unknown_names, modal: found.modal, energy_of, solver, not_certified })
}
