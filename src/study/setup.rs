//! Building a [`Study`]: where the linear DAE comes from and its eigenanalysis.

use crate::analysis::{reference_state_with_warnings, static_state_from, Reference};
use crate::dae::ports::{InputPort, OutputPort};
use crate::dae::{cut_parts, linearize_sparse, Cut, FemOutput, NodeInput, NodeOutput, State};
use crate::eigen::{dense_modes, energy_shares, EnergyShare, ModalEnergy};
use crate::eigen::krylov::{sparse_modes_with_progress, ModeTarget, SparseEigenSettings};
use crate::eigen::{EigenRoute, ModalAnalysis};
use crate::linear::{LinearDae, SparseLinearDae};
use crate::model::{InitialValueProblem, Model};
use crate::output::modal::ModalReport;
use crate::rom::{select_modes, ModeSelection};

use super::checks::{equilibrium_warning, incremental_beams_warning, smoothness_warnings, unrestrained_motion};
use super::linear::LinearModel;
use super::solver::{needs_every_mode, sparse_target, SparseRun, SPARSE_DEFAULT_COUNT};
use super::{Application, RomRequest, Setting, Solver, StudyError, Warning};

/// Where a model is linearized and which inputs and outputs the linear DAE has, checked
/// against the problem once ([`Study::builder`]).
#[derive(Clone, Debug)]
pub(super) struct Linearization {
    pub reference: Reference,
    /// Generalized forces `u` (`−ΔF = B̃ u`, eq. 38).
    pub inputs: Vec<NodeInput>,
    /// Observed unknowns `z = C̃ Δy` (eq. 39).
    pub outputs: Vec<NodeOutput>,
}

impl Linearization {
    /// Checks the reference against the problem and the ports for duplicates.
    pub fn validate(&self, problem: &InitialValueProblem) -> Result<(), StudyError> {
        let option = |option, message: String| Err(StudyError::Option { option, message });
        match self.reference {
            Reference::At(t) if !t.is_finite() => return option(Setting::ReferenceTime, format!("TIME must be a finite time [s], got {t}")),
            Reference::At(t) if t < problem.initial_time => return option(Setting::ReferenceTime, format!("TIME {t} s is before the file's initial time {} s", problem.initial_time)),
            Reference::At(t) if t > problem.final_time => return option(Setting::ReferenceTime, format!("TIME {t} s is after the file's final time {} s (the file's problem ends there)", problem.final_time)),
            Reference::Static { load_steps: 0 } => return option(Setting::LoadSteps, "need at least 1 load increment".into()),
            _ => {}
        }
        for (k, p) in self.inputs.iter().enumerate() {
            if self.inputs[..k].contains(p) {
                return option(Setting::Inputs, format!("{} is given twice", p.name()));
            }
        }
        for (k, p) in self.outputs.iter().enumerate() {
            if self.outputs[..k].contains(p) {
                return option(Setting::Outputs, format!("{} is given twice", p.name()));
            }
        }
        Ok(())
    }
}

/// The inputs and outputs of a model's study.
#[derive(Clone, Debug)]
pub enum Ports {
    /// Forces and moments at nodes, their displacements and rotations (`--input`, `--output`).
    Nodes { inputs: Vec<NodeInput>, outputs: Vec<NodeOutput> },
    /// Ports at points of bodies, node names, dummy springs, imposed motion (paper §8).
    Application(Application),
}

impl Ports {
    /// The ports every front end describes the same way: `ports_file` (a ports file's ports,
    /// names, springs and imposed motion), then node ports, FEM node outputs (sensors on
    /// flexible bodies), springs to remove and an imposed
    /// motion (`NODE[:COMPONENTS]`), loops to cut open ([`Cut`]); without a ports file,
    /// springs, imposed motion or cuts, node ports only.
    pub fn from_parts(ports_file: Option<&std::path::Path>, inputs: &[NodeInput], outputs: &[NodeOutput], fem_outputs: &[FemOutput], remove_springs: &[crate::model::Label], imposed: Option<&str>, cuts: &[Cut]) -> Result<Self, StudyError> {
        if ports_file.is_none() && fem_outputs.is_empty() && remove_springs.is_empty() && imposed.is_none() && cuts.is_empty() {
            return Ok(Ports::Nodes { inputs: inputs.to_vec(), outputs: outputs.to_vec() });
        }
        let file = match ports_file {
            Some(path) => crate::input::ports_file::read_ports_file(path)?,
            None => crate::input::ports_file::PortsFile::default(),
        };
        let mut app = Application { inputs: file.inputs, outputs: file.outputs, names: file.names, remove_springs: file.remove_springs, imposed: None, cuts: file.cuts };
        app.cuts.extend_from_slice(cuts);
        app.inputs.extend(inputs.iter().map(|p| p.port()));
        app.outputs.extend(outputs.iter().map(|p| p.port()));
        app.outputs.extend(fem_outputs.iter().map(FemOutput::port));
        for l in remove_springs {
            if !app.remove_springs.contains(l) {
                app.remove_springs.push(*l);
            }
        }
        if let Some(s) = imposed.or(file.imposed.as_deref()) {
            app.imposed = Some(super::parse_imposed(s).map_err(|message| StudyError::Option { option: Setting::Imposed, message })?);
        }
        Ok(Ports::Application(app))
    }
}

/// The reference solution of a study, with an unrestrained model named. With `start` (a
/// neighbouring design point's solution, same unknowns) the static equilibrium starts from
/// it at full load; if Newton fails from there, it ramps the loads from the file's
/// configuration as without `start`.
/// The run's warnings come with it (the initial state's velocities and derivatives phase,
/// [`Warning::Run`]).
pub fn checked_reference_state(model: &Model, problem: &InitialValueProblem, reference: Reference, start: Option<&State>) -> Result<(State, Vec<Warning>), StudyError> {
    let result = match (reference, start) {
        (Reference::Static { .. }, Some(start)) => static_state_from(model, problem, start).map(|state| (state, Vec::new())).or_else(|_| reference_state_with_warnings(model, problem, reference)),
        _ => reference_state_with_warnings(model, problem, reference),
    };
    let result = result.map(|(state, warnings)| (state, warnings.into_iter().map(|warning| Warning::Run { warning }).collect()));
    result.map_err(|source| {
        let motion = matches!(reference, Reference::Static { .. }).then(|| unrestrained_motion(model)).flatten();
        match motion {
            Some(motion) => StudyError::Unrestrained { motion, cause: source },
            None => StudyError::Reference { file: None, cause: source },
        }
    })
}

/// How the eigenanalysis is done.
#[derive(Clone, Copy, Debug)]
pub struct EigenSettings {
    pub route: EigenRoute,
    /// dCoef of the Λ form [s]; `None`: the file's (MBDyn's eigenanalysis parameter h/2), else
    /// the reciprocal of the geometric mean of the dynamic part's |λ| (issue 30; the
    /// undeflated pencil: its balanced norms).
    pub dcoef: Option<f64>,
    /// Dense QZ, sparse shift-invert Krylov–Schur, or chosen by size.
    pub solver: Solver,
    /// The modes the sparse route computes (`None`: the lowest [`SPARSE_DEFAULT_COUNT`]); the
    /// dense route computes every mode.
    pub target: Option<ModeTarget>,
    /// The request ranks a count by dominance: `Auto` takes the dense route (every mode),
    /// `Sparse` computes [`super::DOMINANCE_POOL`] times as many lowest modes to rank.
    pub every_mode: bool,
    /// Largest true relative residual of a mode from the sparse route.
    pub tolerance: f64,
}

impl Default for EigenSettings {
    fn default() -> Self {
        EigenSettings { route: EigenRoute::Lambda, dcoef: None, solver: Solver::Auto, target: None, every_mode: false, tolerance: SparseEigenSettings::default().tolerance }
    }
}

impl EigenSettings {
    /// Checks dCoef, the sparse route's tolerance and band: once, for every front end.
    pub fn validate(&self) -> Result<(), StudyError> {
        if let Some(c) = self.dcoef {
            if !(c.is_finite() && c > 0.0) {
                return Err(StudyError::Option { option: Setting::Dcoef, message: format!("dCoef must be a positive finite time step coefficient [s], got {c}") });
            }
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(StudyError::Option { option: Setting::Tolerance, message: format!("the sparse route's residual tolerance must be in (0, 1), got {}", self.tolerance) });
        }
        match self.target {
            Some(ModeTarget::Band { fmin_hz, fmax_hz }) => ModeSelection::band(fmin_hz, fmax_hz).map(|_| ()).map_err(|message| StudyError::Option { option: Setting::Band, message }),
            Some(ModeTarget::Lowest(0)) => Err(StudyError::Option { option: Setting::Count, message: "a ROM keeps at least 1 mode".into() }),
            _ => Ok(()),
        }
    }

    /// The same settings with the sparse target and the every-mode flag of `request`.
    pub fn for_request(mut self, request: &RomRequest) -> Self {
        self.target = Some(sparse_target(request));
        self.every_mode = needs_every_mode(request);
        self
    }
}

/// A linear DAE with its eigenanalysis: the starting point of every ROM.
pub struct Study {
    pub(super) linear: LinearModel,
    pub(super) modal: ModalAnalysis,
    /// What the sparse eigensolver certified (`None`: the dense route).
    pub(super) sparse: Option<SparseRun>,
    pub(super) model: Option<Model>,
    pub(super) warnings: Vec<Warning>,
    pub(super) reference_time: Option<f64>,
    /// The reference solution the model was linearized at.
    pub(super) reference_state: Option<State>,
    /// The model's initial-value problem.
    pub(super) problem: Option<InitialValueProblem>,
    /// Ports, names, removed springs and imposed motion (paper §8), when given.
    pub(super) application: Option<super::application::Applied>,
}

/// No progress reports.
pub(super) fn quiet(_: &str) {}

impl Study {
    /// Linearizes at a given reference solution with `ports`; an application's dense
    /// linearization `dae` when done already.
    pub(super) fn at_state(model: Model, problem: &InitialValueProblem, state: State, ports: &Ports, dae: Option<LinearDae>, eigen: EigenSettings, progress: &dyn Fn(&str)) -> Result<Self, StudyError> {
        let mut study = match (ports, dae) {
            (Ports::Nodes { inputs, outputs }, None) => {
                let inputs: Vec<_> = inputs.iter().map(NodeInput::port).collect();
                let outputs: Vec<_> = outputs.iter().map(NodeOutput::port).collect();
                Self::from_model_ports(model, problem, state.clone(), &inputs, &outputs, &[], eigen, progress)?
            }
            (Ports::Application(app), None) => Self::application_state(model, problem, state.clone(), app, eigen, progress)?,
            (Ports::Application(app), Some(dae)) => Self::from_application_dae(model, problem, state.clone(), dae, app, eigen)?,
            (Ports::Nodes { .. }, Some(_)) => return Err(StudyError::Option { option: Setting::Inputs, message: "a linearization done already goes with an application's ports".into() }),
        };
        study.reference_state = Some(state);
        Ok(study)
    }

    /// The sparse linearization with these ports, loops cut open at `cuts` (their ports
    /// last), and its eigenanalysis; `progress` gets the sparse solver's reports.
    pub(super) fn from_model_ports(model: Model, problem: &InitialValueProblem, state: State, inputs: &[InputPort], outputs: &[OutputPort], cuts: &[Cut], eigen: EigenSettings, progress: &dyn Fn(&str)) -> Result<Self, StudyError> {
        let mut sparse = linearize_sparse(&model, &state, inputs, outputs)?;
        for part in cut_parts(&model, &state, cuts)? {
            part.cut_sparse(&mut sparse);
        }
        let equilibrium = equilibrium_warning(&model, &state, problem.tolerance);
        // The Λ form's dCoef: the file's eigenanalysis parameter (h/2) when it gives one.
        let file_dcoef = problem.eigenanalysis.as_ref().and_then(|e| e.dcoef);
        let mut study = Self::from_linear(LinearModel::from_sparse(sparse), Some(model), EigenSettings { dcoef: eigen.dcoef.or(file_dcoef), ..eigen }, progress)?;
        study.warnings.splice(0..0, equilibrium);
        study.reference_time = Some(state.t);
        Ok(study)
    }

    /// The one road of every front end into a model's study ([`Study::builder`]): `ports`
    /// node ports only (as `romdyn rom --input/--output`) or a whole [`Application`]; the
    /// reference solution is found from `start` when given (a sweep's continuation, see
    /// [`checked_reference_state`]); the sparse eigensolver's progress reports (a line per
    /// Krylov–Schur restart) go to `progress`. Returns the study and the reference solution
    /// it was linearized at.
    pub(super) fn of_model_with_progress(model: Model, problem: &InitialValueProblem, reference: Reference, ports: &Ports, eigen: EigenSettings, start: Option<&State>, progress: &dyn Fn(&str)) -> Result<(Self, State), StudyError> {
        let (inputs, outputs) = match ports {
            Ports::Nodes { inputs, outputs } => (inputs.clone(), outputs.clone()),
            Ports::Application(_) => (Vec::new(), Vec::new()),
        };
        let lin = Linearization { reference, inputs, outputs };
        lin.validate(problem)?;
        let (state, run_warnings) = checked_reference_state(&model, problem, reference, start)?;
        let mut beams: Vec<Warning> = incremental_beams_warning(&model, reference).into_iter().collect();
        beams.extend(run_warnings);
        beams.extend(smoothness_warnings(&model, &state));
        let input = model.input_warnings();
        let mut study = match ports {
            Ports::Nodes { inputs, outputs } => {
                let inputs: Vec<_> = inputs.iter().map(NodeInput::port).collect();
                let outputs: Vec<_> = outputs.iter().map(NodeOutput::port).collect();
                Self::from_model_ports(model, problem, state.clone(), &inputs, &outputs, &[], eigen, progress)?
            }
            Ports::Application(app) => Self::application_state(model, problem, state.clone(), app, eigen, progress)?,
        };
        study.warnings.splice(0..0, beams);
        study.warnings.splice(0..0, input.into_iter().map(|message| super::Warning::InputFile { message }));
        Ok((study, state))
    }

    /// Eigenanalysis of a given linear DAE; `model` (when it is a model's linearization)
    /// gives the modes' kinetic-energy shares.
    /// `Solver::Auto` keeps a DAE without its constraint structure (a pencil file) on the
    /// dense route: the sparse solver's shift at 0 would meet the zero eigenvalues of MBDyn's
    /// constrained variables (eq. 30), which it removes only where the structure is known.
    pub(super) fn from_dae(dae: LinearDae, model: Option<Model>, eigen: EigenSettings) -> Result<Self, StudyError> {
        let eigen = if eigen.solver == Solver::Auto && dae.constraint_form.is_none() { EigenSettings { solver: Solver::Dense, ..eigen } } else { eigen };
        let sparse = eigen.solver.is_sparse(dae.dim(), eigen.every_mode)?;
        Self::from_linear(LinearModel::from_dense(dae, sparse), model, eigen, &quiet)
    }

    /// Eigenanalysis of the study's linear model on the route `eigen.solver` picks.
    fn from_linear(linear: LinearModel, model: Option<Model>, eigen: EigenSettings, progress: &dyn Fn(&str)) -> Result<Self, StudyError> {
        let sparse_dae = match linear.sparse() {
            Some(s) if eigen.solver.is_sparse(s.dim(), eigen.every_mode)? => Some(s),
            _ => None,
        };
        let (modal, sparse) = match sparse_dae {
            Some(s) => {
                let target = eigen.target.unwrap_or(ModeTarget::Lowest(SPARSE_DEFAULT_COUNT));
                let settings = SparseEigenSettings { tolerance: eigen.tolerance, route: eigen.route, dcoef: eigen.dcoef, ..SparseEigenSettings::default() };
                let found = sparse_modes_with_progress(s, target, &settings, progress)?;
                let run = SparseRun { dominance_pool: eigen.every_mode, ..SparseRun::new(target, eigen.tolerance, &found) };
                (found.modal, Some(run))
            }
            None => {
                (dense_modes(linear.dense(), eigen.route, eigen.dcoef)?, None)
            }
        };
        let mut modal = modal;
        super::checks::refine_errors(&mut modal, &linear, model.as_ref());
        let mut study = Study { linear, modal, sparse, model, warnings: Vec::new(), reference_time: None, reference_state: None, problem: None, application: None };
        study.warnings = study.linear_warnings();
        Ok(study)
    }

    /// What the user must know about the linear model: reference not in equilibrium, ports
    /// that move nothing, a sparse eigenanalysis that is not certified.
    pub fn warnings(&self) -> &[Warning] {
        &self.warnings
    }

    /// The reference solution the model was linearized at (`None` for a pencil file or a
    /// linear DAE).
    pub fn reference_state(&self) -> Option<&State> {
        self.reference_state.as_ref()
    }

    /// The model's initial-value problem (`None` for a pencil file or a linear DAE).
    pub fn problem(&self) -> Option<&InitialValueProblem> {
        self.problem.as_ref()
    }

    /// The reference solution and the problem, to run the model from there (`romdyn
    /// validate`); an error for a pencil file or a linear DAE.
    pub fn reference_and_problem(&self) -> Result<(State, InitialValueProblem), StudyError> {
        match (&self.reference_state, &self.problem) {
            (Some(state), Some(problem)) => Ok((state.clone(), problem.clone())),
            _ => Err(StudyError::NoReference),
        }
    }

    /// Time of the reference solution [s] (`None` for a pencil file).
    pub fn reference_time(&self) -> Option<f64> {
        self.reference_time
    }

    /// The dense linear DAE `F_yd Δẏ + F_y Δy = B̃ u`, `z = C̃ Δy`; on the sparse route it is
    /// converted from the sparse one on this call (n x n matrices: prefer
    /// [`Study::sparse_dae`] there).
    pub fn dae(&self) -> &LinearDae {
        self.linear.dense()
    }

    /// The sparse linear DAE (`None` for a pencil file or a model with springs removed).
    pub fn sparse_dae(&self) -> Option<&SparseLinearDae> {
        self.linear.sparse()
    }

    /// Number of equations (= unknowns).
    pub fn equations(&self) -> usize {
        self.linear.dim()
    }

    /// Input names with units.
    pub fn input_names(&self) -> &[String] {
        self.linear.input_names()
    }

    /// Output names with units.
    pub fn output_names(&self) -> &[String] {
        self.linear.output_names()
    }

    /// What the sparse eigensolver certified (`None` on the dense route).
    pub fn sparse_run(&self) -> Option<&SparseRun> {
        self.sparse.as_ref()
    }

    /// The eigenanalysis: every eigenvalue with right and adjoint vectors and labels (dense
    /// route), or the modes asked for (sparse route).
    pub fn modal(&self) -> &ModalAnalysis {
        &self.modal
    }

    /// The multibody model, when the DAE is its linearization.
    pub fn model(&self) -> Option<&Model> {
        self.model.as_ref()
    }

    /// The model, to run it in time with loads added and removed again (`romdyn validate`).
    pub(crate) fn model_mut(&mut self) -> Option<&mut Model> {
        self.model.as_mut()
    }

    /// Kinetic-energy shares of every mode (empty lists without a model); a member of a
    /// cluster of degenerate modes ([`degenerate_clusters`]) has the cluster's shares
    /// ([`ModalEnergy::subspace_shares`]), which do not depend on the basis the eigensolver chose.
    pub fn energy(&self) -> Vec<Vec<EnergyShare>> {
        match self.modal_energy() {
            Some(energy) => energy_shares(&energy, &self.modal.modes),
            None => vec![Vec::new(); self.modal.modes.len()],
        }
    }

    /// The diagonal mass terms of the model's dynamic nodes, the elements' energy stores at
    /// the reference and the signals' columns of `F_yd` (`None` without a model).
    pub(super) fn modal_energy(&self) -> Option<ModalEnergy> {
        let model = self.model.as_ref()?;
        let energy = ModalEnergy::from_fyd_diagonal(model, &self.linear.fyd_diagonal());
        let energy = match &self.reference_state {
            Some(state) => energy.at_state(model, state),
            None => energy,
        };
        let columns = self.linear.fyd_columns(&energy.signal_unknowns());
        Some(energy.with_fyd_columns(columns))
    }

    /// The modal table with kinetic-energy shares, and a label column when nodes have names
    /// (in the model file or a ports file) or ports are given; on the sparse route the modes
    /// asked for.
    pub fn modal_report(&self) -> ModalReport {
        let report = ModalReport::new(&self.modal, self.linear.dim()).with_energy(self.energy());
        let named = self.model.as_ref().is_some_and(|m| !m.node_names.is_empty());
        let report = if self.application.is_some() || named { report.with_labels(self.mode_labels()) } else { report };
        report.with_note(self.sparse.as_ref().map(|r| r.header()))
    }

    /// The modal table of the modes `selection` keeps (`romdyn eig --count|--band`), the same
    /// rows on both routes; `None`: every mode of [`Study::modal_report`].
    /// On the sparse route `None` means the modes it was asked for.
    pub fn modal_report_of(&self, selection: Option<&ModeSelection>) -> Result<ModalReport, StudyError> {
        let asked = self.sparse.as_ref().map(|r| r.selection());
        let Some(selection) = selection.or(asked.as_ref()) else { return Ok(self.modal_report()) };
        let kept = match select_modes(&self.modal, selection) {
            Ok(sel) => sel.kept,
            // Fewer modes found than asked: the table shows them, the warning says why.
            Err(_) if self.sparse.as_ref().is_some_and(|r| !r.certified) => return Ok(self.modal_report()),
            Err(e) => return Err(e.into()),
        };
        Ok(self.modal_report().only(&kept))
    }
}
