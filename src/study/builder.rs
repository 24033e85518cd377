//! The one way into a [`Study`]: where the linear DAE comes from ([`StudySource`]) and the
//! study's options, each checked once here whatever the front end (the CLI, the Python
//! package, a sweep's point, `romdyn validate`, the Rust API).
//!
//! ```no_run
//! use romdyn::analysis::Reference;
//! use romdyn::study::{Study, StudySource};
//!
//! let study = Study::builder(StudySource::model_file("examples/simply_supported_beam.mbd"))
//!     .reference(Reference::Static { load_steps: 10 })
//!     .node_ports(vec!["5:Fy".parse()?], vec!["5:y".parse()?])
//!     .build()?;
//! println!("{} equations", study.equations());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::{Path, PathBuf};

use crate::analysis::Reference;
use crate::dae::{NodeInput, NodeOutput, State};
use crate::input::eigen_pencil::PencilPorts;
use crate::input::mbdyn::{read_model_with, BeamUpdateChoice, MbdynModel, ReadOptions, SetOverrides};
use crate::input::pencil::read_pencil_file;
use crate::linear::LinearDae;
use crate::model::{InitialValueProblem, Model};

use super::setup::quiet;
use super::{Application, EigenSettings, Ports, RomRequest, Setting, Study, StudyError, Warning};

/// Where a study's linear DAE comes from.
pub enum StudySource {
    /// An MBDyn input file, its `set:` variables given the values of `overrides`.
    ModelFile { path: PathBuf, overrides: SetOverrides },
    /// A model read or built already, with its problem; `file` (when it was read from one)
    /// names it in errors; `beam_notes` are the reader's notes of beams that keep the
    /// path-independent update ([`MbdynModel::beam_notes`]), each a study warning.
    Model { model: Box<Model>, problem: Box<InitialValueProblem>, file: Option<PathBuf>, beam_notes: Vec<String> },
    /// A pencil file: an MBDyn eigenanalysis `.m` file (ports by equation row and unknown
    /// column in `ports`) or a JSON pencil (ports in the file, `ports` empty).
    PencilFile { path: PathBuf, ports: PencilPorts },
    /// A linear DAE; `model` (when it is that model's linearization) gives the modes'
    /// kinetic-energy shares.
    Dae { dae: Box<LinearDae>, model: Option<Box<Model>> },
}

impl StudySource {
    /// An MBDyn input file as written.
    pub fn model_file(path: impl Into<PathBuf>) -> Self {
        StudySource::ModelFile { path: path.into(), overrides: SetOverrides::new() }
    }

    /// A model built in Rust (`model::ModelBuilder`) or read already.
    pub fn model(model: Model, problem: InitialValueProblem) -> Self {
        StudySource::Model { model: Box::new(model), problem: Box::new(problem), file: None, beam_notes: Vec::new() }
    }

    /// A model read from `file` (errors name the file), its beams' update as the reader gave
    /// it ([`ReadOptions`]).
    pub fn read(m: MbdynModel, file: &Path) -> Self {
        StudySource::Model { model: Box::new(m.model), problem: Box::new(m.problem), file: Some(file.to_path_buf()), beam_notes: m.beam_notes }
    }

    /// A pencil file.
    pub fn pencil_file(path: impl Into<PathBuf>, ports: PencilPorts) -> Self {
        StudySource::PencilFile { path: path.into(), ports }
    }

    /// A linear DAE, without a model.
    pub fn dae(dae: LinearDae) -> Self {
        StudySource::Dae { dae: Box::new(dae), model: None }
    }
}

/// A study's options before it is built ([`Study::builder`]); [`StudyBuilder::build`] checks
/// them and runs the linearization and the eigenanalysis.
pub struct StudyBuilder<'p> {
    source: StudySource,
    reference: Reference,
    ports: Ports,
    eigen: EigenSettings,
    beam_update: Option<BeamUpdateChoice>,
    start: Option<State>,
    state: Option<State>,
    linearization: Option<LinearDae>,
    progress: &'p dyn Fn(&str),
}

impl Study {
    /// The study of `source`, its options at their defaults: the initial reference, no
    /// ports, [`EigenSettings::default`], the beams as the model has them.
    pub fn builder(source: StudySource) -> StudyBuilder<'static> {
        StudyBuilder { source, reference: Reference::Initial, ports: Ports::Nodes { inputs: Vec::new(), outputs: Vec::new() }, eigen: EigenSettings::default(), beam_update: None, start: None, state: None, linearization: None, progress: &quiet }
    }
}

impl<'p> StudyBuilder<'p> {
    /// Where a model is linearized (default: its initial time).
    pub fn reference(mut self, reference: Reference) -> Self {
        self.reference = reference;
        self
    }

    /// The ports: node ports or a whole [`Application`] ([`Ports::from_parts`]).
    pub fn ports(mut self, ports: Ports) -> Self {
        self.ports = ports;
        self
    }

    /// Forces and moments at nodes as inputs, their displacements and rotations as outputs.
    pub fn node_ports(self, inputs: Vec<NodeInput>, outputs: Vec<NodeOutput>) -> Self {
        self.ports(Ports::Nodes { inputs, outputs })
    }

    /// The paper's application (§8): ports at points of bodies, names, dummy springs
    /// removed, imposed motion.
    pub fn application(self, app: Application) -> Self {
        self.ports(Ports::Application(app))
    }

    /// How the eigenanalysis is done.
    pub fn eigen(mut self, eigen: EigenSettings) -> Self {
        self.eigen = eigen;
        self
    }

    /// The modes the sparse route computes, those `request` keeps
    /// ([`EigenSettings::for_request`]).
    pub fn for_request(mut self, request: &RomRequest) -> Self {
        self.eigen = self.eigen.for_request(request);
        self
    }

    /// The beams' rotation update (`--beam-update`, `beam_update=`) with which a model file
    /// is read, for the reference (a time integration or not); beams the `auto` update leaves
    /// path independent are warned about ([`Warning::BeamKeptPathIndependent`]). A model
    /// read already took its update from the reader ([`ReadOptions`]): asking for one here is
    /// refused.
    pub fn beam_update(mut self, choice: BeamUpdateChoice) -> Self {
        self.beam_update = Some(choice);
        self
    }

    /// A static reference starts from `start` (a neighbouring design point's solution, same
    /// unknowns) at full load ([`super::checked_reference_state`]).
    pub fn start(mut self, start: State) -> Self {
        self.start = Some(start);
        self
    }

    /// Linearizes at this reference solution instead of finding it (the reference then only
    /// says how it was found).
    pub fn at_state(mut self, state: State) -> Self {
        self.state = Some(state);
        self
    }

    /// With [`StudyBuilder::at_state`] and an application: its dense linearization, done
    /// already ([`Study::linearize_application`]; `benches/ham_sas.rs` times the rest).
    pub fn linearized(mut self, dae: LinearDae) -> Self {
        self.linearization = Some(dae);
        self
    }

    /// The sparse eigensolver's progress reports (a line per Krylov–Schur restart).
    pub fn progress<'q>(self, progress: &'q dyn Fn(&str)) -> StudyBuilder<'q> {
        let StudyBuilder { source, reference, ports, eigen, beam_update, start, state, linearization, .. } = self;
        StudyBuilder { source, reference, ports, eigen, beam_update, start, state, linearization, progress }
    }

    /// Checks every option, then linearizes and runs the eigenanalysis.
    pub fn build(self) -> Result<Study, StudyError> {
        self.eigen.validate()?;
        match self.source {
            StudySource::PencilFile { .. } => self.no_model_options("a pencil file")?,
            StudySource::Dae { .. } => self.no_model_options("a linear DAE")?,
            _ => {}
        }
        let (model, problem, file, notes) = match self.source {
            StudySource::ModelFile { ref path, ref overrides } => {
                let options = ReadOptions::new(overrides, self.beam_update.unwrap_or_default(), self.reference.integrates());
                // A beam that cannot take the update asked for is an error at its card.
                let m = read_model_with(path, options)?;
                (Box::new(m.model), Box::new(m.problem), Some(path.clone()), m.beam_notes)
            }
            StudySource::Model { .. } if self.beam_update.is_some() => {
                return Err(StudyError::Option { option: Setting::BeamUpdate, message: "the beams' update is chosen when the file is read (input::mbdyn::ReadOptions): a model read or built already keeps its beams' update".into() });
            }
            StudySource::Model { model, problem, file, beam_notes } => (model, problem, file, beam_notes),
            StudySource::PencilFile { path, ports } => {
                let file = read_pencil_file(&path, &ports)?;
                return Study::from_dae(file.dae, None, EigenSettings { dcoef: self.eigen.dcoef.or(file.dcoef), ..self.eigen });
            }
            StudySource::Dae { dae, model } => {
                return Study::from_dae(*dae, model.map(|m| *m), self.eigen);
            }
        };
        let in_file = |e: StudyError| match &file {
            Some(path) => e.in_file(path),
            None => e,
        };
        let model = *model;
        let mut study = match (self.state, self.linearization) {
            (None, Some(_)) => return Err(StudyError::Option { option: Setting::ReferenceTime, message: "a linearization needs the reference solution it was done at".into() }),
            (None, None) => {
                let (mut study, state) = Study::of_model_with_progress(model, &problem, self.reference, &self.ports, self.eigen, self.start.as_ref(), self.progress).map_err(in_file)?;
                study.reference_state = Some(state);
                study
            }
            (Some(state), dae) => Study::at_state(model, &problem, state, &self.ports, dae, self.eigen, self.progress).map_err(in_file)?,
        };
        study.warnings.splice(0..0, notes.into_iter().map(|why| Warning::BeamKeptPathIndependent { why }));
        study.problem = Some(*problem);
        Ok(study)
    }

    /// A pencil file or a linear DAE has no reference, model ports nor beams to choose.
    fn no_model_options(&self, what: &str) -> Result<(), StudyError> {
        let refuse = |option, name: &str| Err(StudyError::Option { option, message: format!("{what} has no {name} (it is linear already)") });
        if !matches!(self.reference, Reference::Initial) {
            return refuse(Setting::ReferenceTime, "reference solution");
        }
        if !matches!(&self.ports, Ports::Nodes { inputs, outputs } if inputs.is_empty() && outputs.is_empty()) {
            return refuse(Setting::Inputs, "model ports: its ports are its rows and columns");
        }
        if self.beam_update.is_some() {
            return refuse(Setting::BeamUpdate, "beams");
        }
        if self.state.is_some() || self.start.is_some() || self.linearization.is_some() {
            return refuse(Setting::ReferenceTime, "reference solution");
        }
        Ok(())
    }
}
