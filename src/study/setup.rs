//! Building a [`Study`]: where the linear DAE comes from and its eigenanalysis.

use std::path::Path;

use crate::analysis::{reference_state, static_state_from, Reference};
use crate::dae::{linearize, EnergyShare, ModalEnergy, NodeInput, NodeOutput, State};
use crate::input::eigen_pencil::PencilPorts;
use crate::input::mbdyn::read_model;
use crate::input::pencil::read_pencil_file;
use crate::linear::{EigenRoute, LinearDae, ModalAnalysis};
use crate::model::{InitialValueProblem, Model};
use crate::output::modal::ModalReport;

use super::checks::{equilibrium_warning, port_warnings, unrestrained_motion};
use super::{Application, StudyError, Warning};

/// Where a model is linearized and which inputs and outputs the linear DAE has.
#[derive(Clone, Debug)]
pub struct Linearization {
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
            Reference::At(t) if !t.is_finite() => return option("--at", format!("TIME must be a finite time [s], got {t}")),
            Reference::At(t) if t < problem.initial_time => return option("--at", format!("TIME {t} s is before the file's initial time {} s", problem.initial_time)),
            Reference::At(t) if t > problem.final_time => return option("--at", format!("TIME {t} s is after the file's final time {} s (the file's problem ends there)", problem.final_time)),
            Reference::Static { load_steps: 0 } => return option("--load-steps", "need at least 1 load increment".into()),
            _ => {}
        }
        for (k, p) in self.inputs.iter().enumerate() {
            if self.inputs[..k].contains(p) {
                return option("--input", format!("{} is given twice", p.name()));
            }
        }
        for (k, p) in self.outputs.iter().enumerate() {
            if self.outputs[..k].contains(p) {
                return option("--output", format!("{} is given twice", p.name()));
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
    /// names, springs and imposed motion), then node ports, springs to remove and an imposed
    /// motion (`NODE[:COMPONENTS]`); without a ports file, springs or imposed motion, node
    /// ports only.
    pub fn from_parts(ports_file: Option<&Path>, inputs: &[NodeInput], outputs: &[NodeOutput], remove_springs: &[crate::model::Label], imposed: Option<&str>) -> Result<Self, StudyError> {
        if ports_file.is_none() && remove_springs.is_empty() && imposed.is_none() {
            return Ok(Ports::Nodes { inputs: inputs.to_vec(), outputs: outputs.to_vec() });
        }
        let file = match ports_file {
            Some(path) => crate::input::ports_file::read_ports_file(path)?,
            None => crate::input::ports_file::PortsFile::default(),
        };
        let mut app = Application { inputs: file.inputs, outputs: file.outputs, names: file.names, remove_springs: file.remove_springs, imposed: None };
        app.inputs.extend(inputs.iter().map(|p| p.port()));
        app.outputs.extend(outputs.iter().map(|p| p.port()));
        for l in remove_springs {
            if !app.remove_springs.contains(l) {
                app.remove_springs.push(*l);
            }
        }
        if let Some(s) = imposed.or(file.imposed.as_deref()) {
            app.imposed = Some(super::parse_imposed(s).map_err(|m| StudyError::Application(format!("--imposed {m}")))?);
        }
        Ok(Ports::Application(app))
    }
}

/// The reference solution of a study, with an unrestrained model named. With `start` (a
/// neighbouring design point's solution, same unknowns) the static equilibrium starts from
/// it at full load; if Newton fails from there, it ramps the loads from the file's
/// configuration as without `start`.
pub fn checked_reference_state(model: &Model, problem: &InitialValueProblem, reference: Reference, start: Option<&State>) -> Result<State, StudyError> {
    let result = match (reference, start) {
        (Reference::Static { .. }, Some(start)) => static_state_from(model, problem, start).or_else(|_| reference_state(model, problem, reference)),
        _ => reference_state(model, problem, reference),
    };
    result.map_err(|source| {
        let motion = matches!(reference, Reference::Static { .. }).then(|| unrestrained_motion(model)).flatten();
        match motion {
            Some(motion) => StudyError::Unrestrained { motion, source },
            None => StudyError::Reference { file: None, source },
        }
    })
}

/// How the eigenanalysis is done.
#[derive(Clone, Copy, Debug)]
pub struct EigenSettings {
    pub route: EigenRoute,
    /// dCoef of the Λ form [s]; `None`: the file's (MBDyn's eigenanalysis parameter h/2), else
    /// `‖F_yd‖/‖F_y‖`.
    pub dcoef: Option<f64>,
}

impl Default for EigenSettings {
    fn default() -> Self {
        EigenSettings { route: EigenRoute::Lambda, dcoef: None }
    }
}

/// A linear DAE with its eigenanalysis: the starting point of every ROM.
pub struct Study {
    pub(super) dae: LinearDae,
    pub(super) modal: ModalAnalysis,
    pub(super) model: Option<Model>,
    pub(super) warnings: Vec<Warning>,
    pub(super) reference_time: Option<f64>,
    /// Ports, names, removed springs and imposed motion (paper §8), when given.
    pub(super) application: Option<super::application::Applied>,
}

impl Study {
    /// Reads an MBDyn input file and linearizes it at `lin.reference`.
    pub fn from_model_file(path: &Path, lin: &Linearization, eigen: EigenSettings) -> Result<Self, StudyError> {
        let m = read_model(path)?;
        Self::from_model(m.model, &m.problem, lin, eigen).map_err(|e| e.in_file(path))
    }

    /// Linearizes a model at `lin.reference` of `problem` (the Rust API's entry).
    pub fn from_model(model: Model, problem: &InitialValueProblem, lin: &Linearization, eigen: EigenSettings) -> Result<Self, StudyError> {
        lin.validate(problem)?;
        let state = checked_reference_state(&model, problem, lin.reference, None)?;
        Self::from_model_state(model, problem, state, lin, eigen)
    }

    /// Linearizes a model at a given reference solution (`lin.reference` says only how it
    /// was found).
    pub fn from_model_state(model: Model, problem: &InitialValueProblem, state: State, lin: &Linearization, eigen: EigenSettings) -> Result<Self, StudyError> {
        let dae = linearize(&model, &state, &lin.inputs, &lin.outputs, None)?;
        let equilibrium = equilibrium_warning(&model, &state, problem.tolerance);
        // The Λ form's dCoef: the file's eigenanalysis parameter (h/2) when it gives one.
        let file_dcoef = problem.eigenanalysis.as_ref().and_then(|e| e.dcoef);
        let mut study = Self::from_dae(dae, Some(model), EigenSettings { dcoef: eigen.dcoef.or(file_dcoef), ..eigen })?;
        study.warnings.splice(0..0, equilibrium);
        study.reference_time = Some(state.t);
        Ok(study)
    }

    /// The one entry every front end uses for a model: `ports` node ports only (as
    /// `romdyn rom --input/--output`) or a whole [`Application`]; the reference solution is
    /// found from `start` when given (a sweep's continuation, see [`checked_reference_state`]).
    /// Returns the study and the reference solution it was linearized at.
    pub fn of_model(model: Model, problem: &InitialValueProblem, reference: Reference, ports: &Ports, eigen: EigenSettings, start: Option<&State>) -> Result<(Self, State), StudyError> {
        let (inputs, outputs) = match ports {
            Ports::Nodes { inputs, outputs } => (inputs.clone(), outputs.clone()),
            Ports::Application(_) => (Vec::new(), Vec::new()),
        };
        let lin = Linearization { reference, inputs, outputs };
        lin.validate(problem)?;
        let state = checked_reference_state(&model, problem, reference, start)?;
        let study = match ports {
            Ports::Nodes { .. } => Self::from_model_state(model, problem, state.clone(), &lin, eigen)?,
            Ports::Application(app) => Self::from_application_state(model, problem, state.clone(), app, eigen)?,
        };
        Ok((study, state))
    }

    /// Reads a pencil file: an MBDyn eigenanalysis `.m` file (ports by equation row and
    /// unknown column) or a JSON pencil (ports in the file, `ports` empty).
    pub fn from_pencil_file(path: &Path, ports: &PencilPorts, eigen: EigenSettings) -> Result<Self, StudyError> {
        let file = read_pencil_file(path, ports)?;
        Self::from_dae(file.dae, None, EigenSettings { dcoef: eigen.dcoef.or(file.dcoef), ..eigen })
    }

    /// Eigenanalysis of a given linear DAE; `model` (when it is a model's linearization)
    /// gives the modes' kinetic-energy shares.
    pub fn from_dae(dae: LinearDae, model: Option<Model>, eigen: EigenSettings) -> Result<Self, StudyError> {
        if let Some(c) = eigen.dcoef {
            if !(c.is_finite() && c > 0.0) {
                return Err(StudyError::Option { option: "--dcoef", message: format!("dCoef must be a positive finite time step coefficient [s], got {c}") });
            }
        }
        let modal = ModalAnalysis::of_dae(&dae, eigen.route, eigen.dcoef).map_err(|e| e.with_unknown_names(&dae.unknown_names))?;
        let warnings = port_warnings(&dae, &modal);
        Ok(Study { dae, modal, model, warnings, reference_time: None, application: None })
    }

    /// What the user must know about the linear model: reference not in equilibrium, ports
    /// that move nothing.
    pub fn warnings(&self) -> &[Warning] {
        &self.warnings
    }

    /// Time of the reference solution [s] (`None` for a pencil file).
    pub fn reference_time(&self) -> Option<f64> {
        self.reference_time
    }

    /// The linear DAE `F_yd Δẏ + F_y Δy = B̃ u`, `z = C̃ Δy`.
    pub fn dae(&self) -> &LinearDae {
        &self.dae
    }

    /// All eigenvalues with right and adjoint vectors and labels.
    pub fn modal(&self) -> &ModalAnalysis {
        &self.modal
    }

    /// The multibody model, when the DAE is its linearization.
    pub fn model(&self) -> Option<&Model> {
        self.model.as_ref()
    }

    /// Kinetic-energy shares of every mode (empty lists without a model).
    pub fn energy(&self) -> Vec<Vec<EnergyShare>> {
        match &self.model {
            Some(model) => {
                let energy = ModalEnergy::new(model, &self.dae);
                self.modal.modes.iter().map(|m| energy.shares(m)).collect()
            }
            None => vec![Vec::new(); self.modal.modes.len()],
        }
    }

    /// The modal table with kinetic-energy shares, and a label column when nodes have names
    /// (in the model file or a ports file) or ports are given.
    pub fn modal_report(&self) -> ModalReport {
        let report = ModalReport::new(&self.modal, self.dae.dim()).with_energy(self.energy());
        let named = self.model.as_ref().is_some_and(|m| !m.node_names.is_empty());
        if self.application.is_some() || named { report.with_labels(self.mode_labels()) } else { report }
    }
}
