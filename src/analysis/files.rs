//! The files of a run, named after a prefix as MBDyn names them: `PREFIX.out` (step log),
//! `PREFIX.mov` (node motion), `PREFIX.log` (model log), for models with scalar nodes
//! `PREFIX.abs`, `PREFIX.ele`, `PREFIX.prs` (abstract, electric, hydraulic nodes' values),
//! for models with written hydraulic elements `PREFIX.hyd` (their own flows, volumes, …),
//! for models with beams `PREFIX.act`
//! (internal forces) and `PREFIX.bst` (strains and curvatures), for models with modal
//! joints `PREFIX.mod` (modal coordinates and their derivatives), and for each eigenanalysis
//! `PREFIX_K.m` (Octave script) and `PREFIX_K.json` (romdyn's JSON), K its 0-based number
//! as MBDyn 1.7.3 writes it for one analysis or several (`_0` unless the file's `suffix
//! width` or `suffix format` says otherwise; [`EigenFileSuffix`]).
//!
//! Every file is written under a temporary name; [`RunFiles::finish`] puts them all in
//! place after a successful run, as one set ([`commit_set`]: while the journal
//! `.NAME.romdyn-commit` exists beside them, the set is incomplete; the next run with the
//! same prefix completes it). A run that stops on a failure (a step whose Newton iteration
//! did not converge, say) puts in place what it wrote up to its last converged step, with
//! the failure as the `.out` file's last line ([`RunFiles::finish_failed`]), as MBDyn leaves
//! its files for the user to see where the motion went; an interrupted run drops them.

use std::path::{Path, PathBuf};

use super::observer::{Derivatives, EigenDone, ObserverError, RunObserver, StepDone};
use super::run::RunReport;
use crate::model::{EigenFileSuffix, InitialValueProblem, Model, MotionOutput};
use crate::output::atomic::{commit_set, recover_set, AtomicFile, OutputError};
use crate::output::beam_sections::BeamSectionWriter;
use crate::output::hydraulic_elements::HydraulicWriter;
use crate::output::plates::PlateWriter;
use crate::output::modal_coordinates::ModalCoordinateWriter;
use crate::output::eigen_json::write_eigen_json;
use crate::output::eigen_m::write_eigen_m;
use crate::output::model_log::write_model_log;
use crate::output::motion::{motion_rows, MotionWriter, OrientationOutput};
use crate::output::prefixed_path;
use crate::output::scalar_nodes::ScalarNodeWriter;
use crate::output::step_log::{StepLine, StepLog};

/// `PREFIX_K` for analysis K of `count`, K written as `suffix` says.
pub fn eigen_file_stem(prefix: &Path, suffix: &EigenFileSuffix, index: usize, count: usize) -> PathBuf {
    let mut s = prefix.as_os_str().to_owned();
    s.push(suffix.suffix(index, count));
    PathBuf::from(s)
}

/// The journal of the set of files under `prefix` (`.NAME.romdyn-commit` beside them):
/// while it exists, the set is incomplete.
pub fn journal_path(prefix: &Path) -> PathBuf {
    let name = prefix.file_name().map_or_else(|| "romdyn".into(), |n| n.to_string_lossy().into_owned());
    prefix.with_file_name(format!(".{name}.romdyn-commit"))
}

/// Writes a run's files as the run goes (an observer).
pub struct RunFiles {
    prefix: PathBuf,
    input: String,
    eigen_count: usize,
    eigen_suffix: EigenFileSuffix,
    out: StepLog,
    mov: MotionWriter,
    /// `.abs`, `.ele`, `.prs` of the written scalar nodes.
    scalars: ScalarNodeWriter,
    /// The nodes and steps the file asks for (`None`: every node, every step).
    motion: Option<MotionOutput>,
    /// `.act` and `.bst`, opened at step 0 when the model has beams.
    beams: Option<BeamSectionWriter>,
    /// `.pla`, when the model has shells.
    plates: Option<PlateWriter>,
    /// `.mod`, when the model has modal joints.
    modal: Option<ModalCoordinateWriter>,
    /// `.hyd`, when the model has written hydraulic elements.
    hydraulic: Option<HydraulicWriter>,
    /// Whether step 0 showed elements with evaluation points (then every step is written).
    has_beams: Option<bool>,
    staged: Vec<AtomicFile>,
    /// The last converged step written: number, time [s]; Newton iterations so far.
    last_step: Option<(usize, f64)>,
    iterations: usize,
}

impl RunFiles {
    /// Starts the files of a run of `model` (read from `input`) under `prefix`.
    pub fn create(prefix: &Path, input: &str, model: &Model, problem: &InitialValueProblem) -> Result<Self, OutputError> {
        recover_set(&journal_path(prefix))?;
        let eigen_count = problem.eigenanalysis.as_ref().map_or(0, |r| r.times.len());
        let eigen_suffix = problem.eigenanalysis.as_ref().map_or_else(EigenFileSuffix::default, |r| r.file_suffix.clone());
        // A directory in the way of any file of the set is found before the run.
        let stems = (0..eigen_count).map(|k| eigen_file_stem(prefix, &eigen_suffix, k, eigen_count));
        let eigen_files = stems.flat_map(|s| [prefixed_path(&s, "m"), prefixed_path(&s, "json")]);
        for path in ["out", "mov", "log", "act", "bst", "pla", "mod", "abs", "ele", "prs", "hyd"].map(|e| prefixed_path(prefix, e)).into_iter().chain(eigen_files) {
            if path.is_dir() {
                return Err(OutputError::Invalid { path, message: "is a directory: the run could not write its file there".into() });
            }
        }
        let out = StepLog::create(&prefixed_path(prefix, "out"), input)?;
        let digits = problem.output.as_ref().map_or(MotionOutput::DEFAULT_DIGITS, MotionOutput::digits);
        let mov = MotionWriter::create(&prefixed_path(prefix, "mov"), OrientationOutput::Euler123Degrees, digits)?;
        let scalars = ScalarNodeWriter::create(prefix, model, digits)?;
        let mut log = AtomicFile::create(&prefixed_path(prefix, "log"))?;
        log.write_with(|w| write_model_log(w, input, model))?;
        let has_modes = model.elements.iter().any(|e| e.outputs().is_some_and(|o| !o.modal_coordinates().is_empty()));
        let digits = problem.output.as_ref().map_or(MotionOutput::DEFAULT_DIGITS, MotionOutput::digits);
        let modal = if has_modes { Some(ModalCoordinateWriter::create(&prefixed_path(prefix, "mod"), digits)?) } else { None };
        let has_plates = model.elements.iter().any(|e| matches!(e.type_name(), "shell4eas" | "shell4easans" | "membrane4eas"));
        let plates = if has_plates { Some(PlateWriter::create(&prefixed_path(prefix, "pla"))?) } else { None };
        let has_hydraulic = model.elements.iter().any(|e| e.outputs().is_some_and(|o| o.writes_hydraulic_row()));
        let hydraulic = if has_hydraulic { Some(HydraulicWriter::create(&prefixed_path(prefix, "hyd"), digits)?) } else { None };
        Ok(RunFiles { prefix: prefix.to_path_buf(), input: input.to_string(), eigen_count, eigen_suffix, out, mov, scalars, motion: problem.output.clone(), beams: None, plates, modal, hydraulic, has_beams: None, staged: vec![log], last_step: None, iterations: 0 })
    }

    /// Ends the step log and puts every file in place; returns their paths.
    pub fn finish(mut self, report: &RunReport) -> Result<Vec<PathBuf>, OutputError> {
        self.out.end(report.final_state.t, report.steps, report.newton_iterations)?;
        self.commit()
    }

    /// After a run that stopped on `why`: the `.out` file's last line says so, and the files
    /// written up to the last converged step are put in place (nothing when no step
    /// converged, the initial derivatives' step 0 included). Returns their paths and the
    /// last converged step's number and time [s].
    pub fn finish_failed(mut self, why: &str) -> Result<Option<(Vec<PathBuf>, usize, f64)>, OutputError> {
        let Some((step, time)) = self.last_step else { return Ok(None) };
        self.out.failed(time, step, self.iterations, why)?;
        Ok(Some((self.commit()?, step, time)))
    }

    fn commit(self) -> Result<Vec<PathBuf>, OutputError> {
        let mut files = vec![self.out.into_file(), self.mov.into_file()];
        files.extend(self.modal.map(ModalCoordinateWriter::into_file));
        files.extend(self.plates.map(PlateWriter::into_file));
        files.extend(self.hydraulic.map(HydraulicWriter::into_file));
        files.extend(self.scalars.into_files());
        if let Some(b) = self.beams {
            files.extend(b.into_files());
        }
        files.extend(self.staged);
        let paths = files.iter().map(|f| f.path().to_path_buf()).collect();
        commit_set(files, &journal_path(&self.prefix))?;
        Ok(paths)
    }
}

impl RunObserver for RunFiles {
    fn derivatives(&mut self, e: &Derivatives) -> Result<(), ObserverError> {
        Ok(self.out.derivatives(e.time, e.iterations, e.residual_norm)?)
    }

    fn step(&mut self, e: &StepDone) -> Result<(), ObserverError> {
        self.last_step = Some((e.step, e.time));
        self.iterations += e.iterations;
        let written = self.motion.as_ref().is_none_or(|m| m.meter.as_ref().map_or(e.step % m.every.max(1) == 0, |d| d.value(e.time) != 0.0));
        self.out.step(&StepLine { step: e.step, time: e.time, time_step: e.time_step, iterations: e.iterations, residual_norm: e.residual_norm, written })?;
        match &self.motion {
            None => self.mov.write_step(&e.node_kinematics())?,
            Some(m) if written => self.mov.write_rows(&motion_rows(m, &e.node_kinematics(), &e.node_accelerations(m)))?,
            Some(_) => {}
        }
        if let (Some(w), true) = (self.modal.as_mut(), written) {
            w.write_step(&e.modal_coordinates())?;
        }
        if written {
            self.scalars.write_step(e.model, &e.state.y, &e.state.yp, e.assembler.dofs.scalar_first)?;
            if let Some(p) = self.plates.as_mut() {
                p.write_step(&e.plate_resultants())?;
            }
            if let Some(h) = self.hydraulic.as_mut() {
                h.write_step(&e.hydraulic_rows())?;
            }
        }
        if self.has_beams == Some(false) {
            return Ok(());
        }
        let sections = e.beam_sections();
        if self.has_beams.is_none() {
            self.has_beams = Some(!sections.is_empty());
            if !sections.is_empty() {
                self.beams = Some(BeamSectionWriter::create(&prefixed_path(&self.prefix, "act"), &prefixed_path(&self.prefix, "bst"))?);
            }
        }
        if let Some(b) = self.beams.as_mut() {
            b.write_step(&sections)?;
        }
        Ok(())
    }

    fn eigenanalysis(&mut self, e: &EigenDone) -> Result<(), ObserverError> {
        let a = e.analysis;
        let file = a.file();
        let rows: Vec<_> = a.written.iter().map(|&k| (k + 1, a.modal.modes[k].lambda)).collect();
        let title = format!(
            "Eigenanalysis {} at time {} s: dCoef {} s, {} equations, eigenvalues λ in rad/s (Λ form, paper eq. 18); {}",
            a.index,
            a.time,
            a.dcoef,
            a.pencil.dim(),
            a.solver
        );
        self.out.eigenvalues(&title, &rows)?;
        let stem = eigen_file_stem(&self.prefix, &self.eigen_suffix, a.index, self.eigen_count);
        let mut m = AtomicFile::create(&prefixed_path(&stem, "m"))?;
        m.write_with(|w| write_eigen_m(w, &self.input, &file))?;
        let mut json = AtomicFile::create(&prefixed_path(&stem, "json"))?;
        json.write_with(|w| write_eigen_json(w, &self.input, &file).map_err(std::io::Error::from))?;
        self.staged.extend([m, json]);
        Ok(())
    }
}
