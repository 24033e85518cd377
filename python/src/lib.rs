//! `romdyn._romdyn`: the Python face of romdyn's library workflow. Every function maps its
//! arguments onto the same library calls as the CLI (`Study::builder`, `Study::reduce`,
//! `sweep::run_point`) and converts the results to NumPy arrays; solves run with the GIL
//! released. SI units throughout: eigenvalues in rad/s, frequencies in Hz, forces in N,
//! moments in N m, displacements in m, rotations in rad, times and dCoef in s.

mod cms;
mod convert;
mod options;
mod sweep;
mod validate;
mod warnings;

use std::path::PathBuf;

use numpy::{Complex64, IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use romdyn::analysis::{run, NodeHistories, RunReport};
use romdyn::input::mbdyn::{read_model_text, MbdynModel, ReadOptions, SetOverrides};
use romdyn::output::rom_file::RomExport;
use romdyn::study::{python_spelling, EigenSettings, FrequencyGrid, ReducedModel, Study, StudyBuilder, StudyError, StudySource};

use convert::{complex_vec, mat, responses};

pyo3::create_exception!(_romdyn, RomdynError, PyException, "A romdyn failure, with the message the CLI prints.");
pyo3::create_exception!(_romdyn, ModelError, RomdynError, "An error in an MBDyn input file: 'FILE:LINE:COLUMN: error: ...' with the line and a caret.");

/// The Python exception of a library error: input-file errors keep file:line:col, a bad
/// setting is a `ValueError` naming its keyword argument.
pub(crate) fn py_err(e: StudyError) -> PyErr {
    match e {
        StudyError::Model(m) => ModelError::new_err(m.to_string()),
        // A setting named as the caller wrote it (`dcoef`, not the CLI's `--dcoef`).
        StudyError::Option { option, message } => pyo3::exceptions::PyValueError::new_err(format!("{}: {}", option.python_name(), python_spelling(&message))),
        // Advice in the library's words ("use --solver dense") spelled as keywords.
        e => RomdynError::new_err(python_spelling(&e.to_string())),
    }
}

/// The columns of a modal table shared by `Study.modes()` and `Model.sparse_modes()`:
/// "eigenvalues" [rad/s], "kind", "freq_hz" (|Im λ|/2π), "undamped_hz" (|λ|/2π), "damping",
/// "error" [rad/s].
fn modes_dict<'py>(py: Python<'py>, modal: &romdyn::eigen::ModalAnalysis) -> PyResult<Bound<'py, PyDict>> {
    let lam: Vec<_> = modal.modes.iter().map(|m| m.lambda).collect();
    let d = PyDict::new(py);
    d.set_item("eigenvalues", complex_vec(py, &lam))?;
    d.set_item("kind", modal.modes.iter().map(|m| format!("{:?}", m.kind).to_lowercase()).collect::<Vec<_>>())?;
    d.set_item("freq_hz", lam.iter().map(|l| l.im.abs() / (2.0 * std::f64::consts::PI)).collect::<Vec<_>>().into_pyarray(py))?;
    d.set_item("undamped_hz", modal.modes.iter().map(|m| m.freq_hz()).collect::<Vec<_>>().into_pyarray(py))?;
    d.set_item("damping", modal.modes.iter().map(|m| m.damping()).collect::<Vec<_>>().into_pyarray(py))?;
    d.set_item("error", modal.modes.iter().map(|m| m.error).collect::<Vec<_>>().into_pyarray(py))?;
    Ok(d)
}

/// An MBDyn input file, its text kept (with `set:` overrides) and read again for each
/// study: `Model(path, set={"L": 2.0})`.
#[pyclass(module = "romdyn._romdyn", frozen)]
struct Model {
    text: String,
    name: PathBuf,
    overrides: SetOverrides,
    /// The beams' rotation update (the CLI's `--beam-update`).
    beam_update: romdyn::input::mbdyn::BeamUpdateChoice,
    #[pyo3(get)]
    /// Labels of the structural nodes.
    nodes: Vec<u32>,
    #[pyo3(get)]
    /// Number of equations (unknowns) of the DAE.
    equations: usize,
}

impl Model {
    /// The model read again, its beams' update set for a time integration (`integrates`) or
    /// not; with why beams the `auto` update leaves path independent do so.
    fn read(&self, integrates: bool) -> Result<(MbdynModel, Vec<String>), StudyError> {
        let mut m = read_model_text(&self.text, &self.name, ReadOptions::new(&self.overrides, self.beam_update, integrates))?;
        let kept = std::mem::take(&mut m.beam_notes);
        Ok((m, kept))
    }

    /// The study of this model ([`Study::builder`]), its beams' update set as the model was
    /// made: the road every front end takes.
    fn builder(&self, integrates: bool) -> Result<StudyBuilder<'static>, StudyError> {
        let m = read_model_text(&self.text, &self.name, ReadOptions::new(&self.overrides, self.beam_update, integrates))?;
        Ok(Study::builder(StudySource::read(m, &self.name)))
    }

    fn new_checked(text: String, name: PathBuf, overrides: SetOverrides, beam_update: Option<&str>) -> PyResult<Self> {
        let beam_update = options::beam_update(beam_update)?;
        let m = read_model_text(&text, &name, ReadOptions::new(&overrides, beam_update, false)).map_err(|e| ModelError::new_err(e.to_string()))?;
        let nodes = m.model.nodes.iter().map(|n| n.label).collect();
        let equations = romdyn::dae::Assembler::new(&m.model).dofs.len;
        Ok(Model { text, name, overrides, beam_update, nodes, equations })
    }
}

#[pymethods]
impl Model {
    /// Reads the MBDyn input file `path`; `set` maps `set:` variables of the file to the values
    /// that replace theirs (SI units of the file); `beam_update`: "auto" (default: MBDyn 1.7.3's
    /// incremental update in `run()` and at a reference time, path independent at a static or
    /// the initial reference; a beam that cannot take it warns), "path-independent" or
    /// "incremental" (the CLI's `--beam-update`). Raises ModelError with
    /// file:line:col.
    #[new]
    #[pyo3(signature = (path, set = None, beam_update = None))]
    fn new(path: PathBuf, set: Option<SetOverrides>, beam_update: Option<&str>) -> PyResult<Self> {
        let text = romdyn::input::text_file::read_text_file(&path).map_err(|e| ModelError::new_err(format!("{}: error: {}", path.display(), e.message)))?;
        Self::new_checked(text, path, set.unwrap_or_default(), beam_update)
    }

    /// A model from the text of an MBDyn input file; `name` labels messages and resolves
    /// includes.
    #[staticmethod]
    #[pyo3(signature = (text, name = "model.mbd".into(), set = None, beam_update = None))]
    fn from_text(text: String, name: PathBuf, set: Option<SetOverrides>, beam_update: Option<&str>) -> PyResult<Self> {
        Self::new_checked(text, name, set.unwrap_or_default(), beam_update)
    }

    /// The file's text (a sweep's work unit).
    #[getter]
    fn text(&self) -> &str {
        &self.text
    }

    /// The file name.
    #[getter]
    fn name(&self) -> PathBuf {
        self.name.clone()
    }

    /// The `set:` overrides.
    #[getter]
    fn set(&self) -> SetOverrides {
        self.overrides.clone()
    }

    /// Linearizes the model and runs its eigenanalysis (as `romdyn eig|rom`).
    ///
    /// reference: "initial" (the initial time after consistent derivatives), "static" (static
    /// equilibrium, loads in `load_steps` increments) or a time [s] of the file's problem.
    /// inputs/outputs: "NODE:Fx|Fy|Fz|Mx|My|Mz" (force [N], moment [N m]) and
    /// "NODE:x|y|z|rx|ry|rz" (displacement [m], rotation [rad]); on scalar nodes
    /// "NODE:abstract|electric|hydraulic" (input on the node's equation, output its value)
    /// and "NODE:abstract_rate|…" (output its derivative); fem_outputs: "JOINT:FEM_NODE:x|y|z"
    /// (displacement [m] of a modal joint's FEM node, a sensor on the flexible body) or
    /// "JOINT:FEM_NODE:vx|vy|vz" (its velocity [m/s]) or "JOINT:FEM_NODE:rx|ry|rz" (its rotation [rad]); ports: a ports file (JSON);
    /// remove_springs: labels of dummy springs; imposed: "NODE[:COMPONENTS]"; cut: control
    /// loops to cut open, ["genel:LABEL" | "force:LABEL"] (as `--cut`: the element's part of
    /// the linearization taken out, the signal across it an input "(injected)" and an output
    /// "(returned)" after the others; the loop transfer function at the cut is
    /// L(s) = −returned/injected; the reference stays the closed loop's). route:
    /// "lambda" or "direct"; dcoef [s]. solver: "dense" (QZ: every eigenvalue), "sparse"
    /// (shift-invert Krylov–Schur on the sparse linearization: only the modes `count` (the
    /// lowest N, default 10) or `band` (FMIN, FMAX) [Hz] ask for, no dense n x n matrix) or
    /// "auto" (sparse from 400 equations on, as `romdyn --solver auto`); `tolerance`: the
    /// sparse route's largest true relative residual of a mode.
    #[pyo3(signature = (reference = None, load_steps = 10, inputs = Vec::new(), outputs = Vec::new(), fem_outputs = Vec::new(), ports = None, remove_springs = Vec::new(), imposed = None, cut = Vec::new(), route = "lambda", dcoef = None, solver = "auto", count = None, band = None, tolerance = 1e-10))]
    #[allow(clippy::too_many_arguments)]
    fn study(&self, py: Python<'_>, reference: Option<&Bound<'_, PyAny>>, load_steps: usize, inputs: Vec<String>, outputs: Vec<String>, fem_outputs: Vec<String>, ports: Option<PathBuf>, remove_springs: Vec<u32>, imposed: Option<String>, cut: Vec<String>, route: &str, dcoef: Option<f64>, solver: &str, count: Option<usize>, band: Option<(f64, f64)>, tolerance: f64) -> PyResult<StudyPy> {
        let reference = options::reference(reference, load_steps)?;
        let ports = options::ports(&inputs, &outputs, &fem_outputs, ports.as_deref(), &remove_springs, imposed.as_deref(), &cut)?;
        let eigen = EigenSettings { target: options::sparse_target(count, band)?, tolerance, ..options::eigen(route, dcoef, solver)? };
        let study = py.detach(|| self.builder(reference.integrates())?.reference(reference).ports(ports).eigen(eigen).build()).map_err(py_err)?;
        // The study's warnings, as `romdyn eig|rom` prints them.
        warnings::warn_all(py, study.warnings())?;
        Ok(StudyPy { study })
    }

    /// `romdyn.validate(self, **options)`: a ROM of this model against its nonlinear run (as
    /// `romdyn validate`), with the keywords of `romdyn.validate` (reference, ports, mode
    /// selection as `study()` and `Study.reduce()`; signal, amplitudes, validation_band,
    /// resolution, averages, time_step, seed, coherence, tolerance, fit, measured).
    #[pyo3(signature = (**options))]
    fn validate<'py>(slf: &Bound<'py, Self>, options: Option<&Bound<'py, PyDict>>) -> PyResult<Bound<'py, PyAny>> {
        slf.py().import("romdyn")?.getattr("validate")?.call((slf,), options)
    }

    /// The lowest `count` dynamic modes, or those with natural frequency |λ|/2π in `band`
    /// (FMIN, FMAX) [Hz], by the sparse shift-invert Krylov–Schur solver (issue 13): the
    /// study of `study(solver="sparse", count=…|band=…)` without ports, so models too large
    /// for the dense eigenanalysis can be analysed. Every mode returned has a true relative
    /// residual below `tolerance`. Returns {"eigenvalues" [rad/s] (complex), "kind",
    /// "freq_hz" (|Im λ|/2π), "undamped_hz" (|λ|/2π), "damping", "error" [rad/s], "certified"
    /// (every shift window's right and adjoint runs agreed and the windows cover the band),
    /// "max_residual", "note" (why not certified, or None), "windows" (shifts used),
    /// "warnings"}. `reference` and `load_steps` as for `study()`.
    #[pyo3(signature = (count = None, band = None, reference = None, load_steps = 10, tolerance = 1e-10))]
    fn sparse_modes<'py>(&self, py: Python<'py>, count: Option<usize>, band: Option<(f64, f64)>, reference: Option<&Bound<'_, PyAny>>, load_steps: usize, tolerance: f64) -> PyResult<Bound<'py, PyDict>> {
        if count.is_none() == band.is_none() {
            return Err(options::bad("count", "give exactly one of count (a positive number of modes) and band (FMIN, FMAX) [Hz]"));
        }
        let study = self.study(py, reference, load_steps, Vec::new(), Vec::new(), Vec::new(), None, Vec::new(), None, Vec::new(), "lambda", None, "sparse", count, band, tolerance)?;
        let Some(run) = study.study.sparse_run() else { return Err(RomdynError::new_err("the sparse route was not taken")) };
        let d = modes_dict(py, study.study.modal())?;
        d.set_item("certified", run.certified)?;
        d.set_item("max_residual", run.max_residual)?;
        d.set_item("note", run.note.clone())?;
        d.set_item("windows", run.windows)?;
        d.set_item("warnings", study.warnings())?;
        Ok(d)
    }

    /// Runs the file's initial-value problem (as `romdyn run`, without files) and returns the
    /// node histories: {"time" [s] (steps,), "labels" (nodes,), "position" [m] (steps, nodes,
    /// 3), "orientation" (steps, nodes, 3, 3: node frame to global), "velocity" [m/s],
    /// "angular_velocity" [rad/s] (steps, nodes, 3)}; step 0 is the initial state.
    /// What `romdyn run` prints of the run comes along: "steps", "newton_iterations",
    /// "derivatives_iterations", "factorizations" (Newton iterations with a new Jacobian),
    /// "wall_time" [s], "assembly" (MBDyn's initial assembly: "iterations", "test",
    /// "moved_position" [m], "moved_rotation" [rad], "moved_velocity" [m/s],
    /// "moved_angular_velocity" [rad/s]) and "eigenanalyses", one dict per eigenanalysis
    /// of the file ("index", "time" [s], "dcoef" [s], "eigenvalues" [rad/s] (the dynamic
    /// ones, complex), "zero", "infinite", "solver", "every_eigenvalue", "certified").
    /// The run's warnings (initial velocities that violate the joints, the derivatives
    /// phase, eigenanalyses one-sided or not certified) are raised as `romdyn run` prints them
    /// (ReferenceWarning, EigenanalysisWarning).
    fn run<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (h, kept, report) = py
            .detach(|| -> Result<(NodeHistories, (Vec<String>, Vec<String>), RunReport), StudyError> {
                let (m, kept) = self.read(true)?;
                let mut h = NodeHistories::default();
                let report = run(&m.model, &m.problem, &mut h).map_err(|cause| StudyError::Reference { file: Some(self.name.clone()), cause })?;
                Ok((h, (kept, m.model.input_warnings()), report))
            })
            .map_err(py_err)?;
        let (kept, input) = kept;
        warnings::warn_input(py, &input)?;
        warnings::warn_beam_notes(py, &kept)?;
        warnings::warn_run(py, &report.warnings())?;
        let (nt, nn) = (h.time.len(), h.labels.len());
        let d = PyDict::new(py);
        d.set_item("time", h.time.into_pyarray(py))?;
        d.set_item("labels", h.labels.into_pyarray(py))?;
        d.set_item("position", h.position.into_pyarray(py).reshape([nt, nn, 3])?)?;
        d.set_item("orientation", h.orientation.into_pyarray(py).reshape([nt, nn, 3, 3])?)?;
        d.set_item("velocity", h.velocity.into_pyarray(py).reshape([nt, nn, 3])?)?;
        d.set_item("angular_velocity", h.angular_velocity.into_pyarray(py).reshape([nt, nn, 3])?)?;
        run_report_items(py, &d, &report)?;
        Ok(d)
    }
}

/// The counters and summaries `romdyn run` prints, into `d` (Model.run).
fn run_report_items<'py>(py: Python<'py>, d: &Bound<'py, PyDict>, r: &RunReport) -> PyResult<()> {
    d.set_item("steps", r.steps)?;
    d.set_item("newton_iterations", r.newton_iterations)?;
    d.set_item("derivatives_iterations", r.derivatives_iterations)?;
    d.set_item("factorizations", r.factorizations)?;
    d.set_item("wall_time", r.wall_time.as_secs_f64())?;
    let a = PyDict::new(py);
    a.set_item("iterations", r.assembly.iterations)?;
    a.set_item("test", r.assembly.test)?;
    a.set_item("moved_position", r.assembly.moved_position)?;
    a.set_item("moved_rotation", r.assembly.moved_rotation)?;
    a.set_item("moved_velocity", r.assembly.moved_velocity)?;
    a.set_item("moved_angular_velocity", r.assembly.moved_angular_velocity)?;
    d.set_item("assembly", a)?;
    let eigen = r
        .eigenanalyses
        .iter()
        .map(|e| {
            let x = PyDict::new(py);
            x.set_item("index", e.index)?;
            x.set_item("time", e.time)?;
            x.set_item("dcoef", e.dcoef)?;
            x.set_item("eigenvalues", complex_vec(py, &e.dynamic))?;
            x.set_item("zero", e.zero)?;
            x.set_item("infinite", e.infinite)?;
            x.set_item("solver", e.solver.clone())?;
            x.set_item("every_eigenvalue", e.every_eigenvalue)?;
            x.set_item("certified", e.not_certified.is_none())?;
            Ok(x)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("eigenanalyses", eigen)?;
    Ok(())
}

/// A linear DAE with its eigenanalysis (romdyn's `Study`).
#[pyclass(name = "Study", module = "romdyn._romdyn", frozen)]
struct StudyPy {
    study: Study,
}

#[pymethods]
impl StudyPy {
    /// Warnings (reference not in equilibrium, ports that move nothing, …).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.study.warnings().iter().map(|w| w.to_string()).collect()
    }

    /// Time of the reference solution [s].
    #[getter]
    fn reference_time(&self) -> Option<f64> {
        self.study.reference_time()
    }

    /// The modal table as arrays: "eigenvalues" [rad/s] (complex), "kind" ("dynamic", "zero",
    /// "infinite"), "freq_hz" (|Im λ|/2π, MBDyn's), "undamped_hz" (|λ|/2π), "damping"
    /// (−Re λ/|λ|), "error" [rad/s], "partner" (index of a conjugate, -1 if none), "dcoef" [s];
    /// "description" (the modal table's: "node 2 y 75 %, modal joint 10 mode 1 25 %") and
    /// "energy", each mode's shares as dicts {"node", "component", "share"} plus, for an
    /// element's own unknown, "element" ("motor", "actuator", "modal joint", …), "state"
    /// ("current", "chamber 1 pressure", "mode 3") and, for a modal joint's mode, "mode" (its
    /// number in the FEM file).
    fn modes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let modal = self.study.modal();
        let d = modes_dict(py, modal)?;
        let energy = self.study.energy();
        d.set_item("description", energy.iter().map(|s| romdyn::eigen::describe(s)).collect::<Vec<_>>())?;
        let shares = energy
            .iter()
            .map(|mode| {
                mode.iter()
                    .map(|s| {
                        let e = PyDict::new(py);
                        e.set_item("node", s.node)?;
                        e.set_item("component", s.component)?;
                        e.set_item("share", s.share)?;
                        if let Some(element) = &s.element {
                            e.set_item("element", element)?;
                            e.set_item("state", s.state.clone())?;
                        }
                        if let Some(m) = s.mode {
                            e.set_item("mode", m)?;
                        }
                        Ok(e)
                    })
                    .collect::<PyResult<Vec<_>>>()
            })
            .collect::<PyResult<Vec<_>>>()?;
        d.set_item("energy", shares)?;
        d.set_item("partner", modal.modes.iter().map(|m| m.partner.map_or(-1, |p| p as i64)).collect::<Vec<_>>().into_pyarray(py))?;
        d.set_item("dcoef", modal.dcoef)?;
        Ok(d)
    }

    /// The modal table as `romdyn eig` prints it (the lowest `limit` dynamic modes).
    #[pyo3(signature = (limit = 12))]
    fn modal_table(&self, limit: usize) -> String {
        self.study.modal_report().to_text_dynamic(limit)
    }

    /// The linear DAE `F_yd Δẏ + F_y Δy = B̃ u`, `z = C̃ Δy` (paper eqs. 38, 39): "Fyd", "Fy",
    /// "B", "C", "unknowns", "inputs", "outputs" (names with units). Dense n x n arrays, also
    /// on the sparse route (converted on this call).
    fn linear<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dae = self.study.dae();
        let (fyd, fy) = dae.jacobians.derivatives();
        let d = PyDict::new(py);
        d.set_item("Fyd", mat(py, &fyd))?;
        d.set_item("Fy", mat(py, &fy))?;
        d.set_item("B", mat(py, &dae.b))?;
        d.set_item("C", mat(py, &dae.c))?;
        d.set_item("unknowns", dae.unknown_names.clone())?;
        d.set_item("inputs", dae.input_names.clone())?;
        d.set_item("outputs", dae.output_names.clone())?;
        Ok(d)
    }

    /// Builds a ROM (as `romdyn rom`): count (N lowest, or with by="dominance" the N that
    /// matter), band (FMIN, FMAX) [Hz] or modes (1-based modal-table indices); residualize:
    /// True (the dropped modes) or a list of modes; below_band "drop"|"keep"|"refuse";
    /// damping: ζ for every kept mode or {mode: ζ}; form "ordinary"|"descriptor".
    ///
    /// Runs the CLI's accuracy check: every response (and with an imposed motion the
    /// transmissibility, eq. 100) against the full model on a log grid of `points`
    /// frequencies from `fmin` to `fmax` [Hz] (defaults: a decade around the ROM's modes, as
    /// `romdyn rom`). The ROM's warnings (static gain, modes below the band, responses that
    /// depart within the frequencies of interest, …) are raised with `warnings.warn` under
    /// `romdyn.RomdynWarning` (e.g. `romdyn.TransmissibilityWarning`) and kept in
    /// `Rom.warnings`; `Rom.summary` holds the accuracy lines.
    ///
    /// The control hand-off (the CLI's options of the same names): `minimal` (a tolerance:
    /// remove uncontrollable and unobservable states), `balanced` (a number of states) or
    /// `hankel_tol` (balanced truncation of the stable part, rigid-body, integrator and
    /// unstable modes kept whole; `spa=True`: singular perturbation approximation, which keeps
    /// the static gain), `sample_rate` [Hz] (a discrete-time ROM; `discretize` "zoh" (default),
    /// "tustin" (with `prewarp` [Hz]) or "matched").
    /// Writes the report of `rom` (one of this study's ROMs) as `romdyn rom --report DIR`
    /// does: `dir/index.html` (summary, warnings, modal table, each kept mode's shape
    /// animated in 3-D on the model's nodes) and the Bode plot `dir/bode.{csv,svg,png}` on
    /// the grid `fmin`, `fmax` [Hz] (default: a decade around the kept modes), `points`.
    /// Returns the page's path.
    #[pyo3(signature = (rom, dir, title = "romdyn ROM", fmin = None, fmax = None, points = 400))]
    #[allow(clippy::too_many_arguments)]
    fn report(&self, py: Python<'_>, rom: &Rom, dir: PathBuf, title: &str, fmin: Option<f64>, fmax: Option<f64>, points: usize) -> PyResult<PathBuf> {
        let grid = FrequencyGrid { fmin_hz: fmin, fmax_hz: fmax, points };
        let check = py.detach(|| self.study.check_rom(&rom.rom, &grid)).map_err(py_err)?;
        let report = self.study.report(&rom.rom, &check, title);
        let files = py.detach(|| report.write(&dir, &check.comparison)).map_err(|e| RomdynError::new_err(e.to_string()))?;
        Ok(files[0].clone())
    }

    #[pyo3(signature = (count = None, band = None, modes = None, residualize = None, by = "frequency", below_band = "drop", damping = None, form = "ordinary", fmin = None, fmax = None, points = 400, minimal = None, balanced = None, hankel_tol = None, spa = false, sample_rate = None, discretize = "zoh", prewarp = None))]
    #[allow(clippy::too_many_arguments)]
    fn reduce(&self, py: Python<'_>, count: Option<usize>, band: Option<(f64, f64)>, modes: Option<Vec<usize>>, residualize: Option<&Bound<'_, PyAny>>, by: &str, below_band: &str, damping: Option<&Bound<'_, PyAny>>, form: &str, fmin: Option<f64>, fmax: Option<f64>, points: usize, minimal: Option<f64>, balanced: Option<usize>, hankel_tol: Option<f64>, spa: bool, sample_rate: Option<f64>, discretize: &str, prewarp: Option<f64>) -> PyResult<Rom> {
        let request = options::request(count, band, modes, residualize, by, below_band, damping)?;
        let request = options::control(request, minimal, balanced, hankel_tol, spa, sample_rate, discretize, prewarp)?;
        let form = options::form(form)?;
        let grid = FrequencyGrid { fmin_hz: fmin, fmax_hz: fmax, points };
        let (mut rom, check) = py
            .detach(|| -> Result<_, StudyError> {
                let rom = self.study.reduce(&request)?;
                rom.check_form(form)?;
                let check = self.study.check_rom(&rom, &grid)?;
                Ok((rom, check))
            })
            .map_err(py_err)?;
        let export = rom.export(&self.study, form);
        let mut summary = rom.summary(&self.study, Some(&check));
        // The free ROM's eigenvalues when dummy springs were removed, as `romdyn rom` prints them.
        let free = self.study.free_eigenvalues(&rom);
        if let Some(free) = &free {
            summary += &free.to_string();
        }
        // The ROM's warnings the study did not already raise, then the check's (the CLI's order).
        let new = rom.new_warnings(&self.study, Some(&check));
        warnings::warn_all(py, &new)?;
        rom.warnings.extend(check.warnings);
        let mut rom = Rom::of(export, rom, summary);
        rom.free = free;
        Ok(rom)
    }

    /// The transmissibility `z/z_e` of eq. 100 (paper Fig. 11; the CLI's `--transmissibility`)
    /// of a study with an imposed motion (`imposed=` or a ports file), full model and `rom`, at
    /// `freq_hz` [Hz]: {"freq_hz", "outputs", "imposed" (names with units), "full", "rom"
    /// (complex arrays (frequencies, outputs, imposed components), in the outputs' units per
    /// imposed unit)}.
    fn transmissibility<'py>(&self, py: Python<'py>, rom: &Rom, freq_hz: Vec<f64>) -> PyResult<Bound<'py, PyDict>> {
        let t = py.detach(|| self.study.transmissibility(&rom.rom, &freq_hz)).map_err(py_err)?;
        let (no, ni) = (t.outputs.len(), t.inputs.len());
        let labels = |ports: &[romdyn::linear::Port]| ports.iter().map(|p| p.label()).collect::<Vec<_>>();
        let d = PyDict::new(py);
        d.set_item("freq_hz", t.freq_hz.clone().into_pyarray(py))?;
        d.set_item("outputs", labels(&t.outputs))?;
        d.set_item("imposed", labels(&t.inputs))?;
        d.set_item("full", responses(py, &t.full, no, ni)?)?;
        d.set_item("rom", responses(py, t.rom(), no, ni)?)?;
        Ok(d)
    }

    /// The proper state-space model from the imposed displacements to the other outputs
    /// (the CLI's `--imposed-out`): a `Rom` whose inputs are the imposed displacements, in
    /// discrete time at `rom`'s sampling when `rom` is discrete.
    fn imposed_model(&self, rom: &Rom) -> PyResult<Rom> {
        let m = self.study.imposed_model(&rom.rom).map_err(py_err)?;
        let discrete = self.study.imposed_discrete(&m, &rom.rom).map_err(py_err)?;
        let export = self.study.imposed_export(&m, discrete.as_ref());
        let summary = format!("imposed-motion model: {} states (dropped rate feedthrough {:.1e})\n", m.rom.a.nrows(), m.dropped_rate_feedthrough);
        Ok(Rom { export, rom: rom.rom.clone(), summary, system: m.rom, discrete, free: None })
    }

    /// Frequency response of the full model at `freq_hz` [Hz]: complex array (frequencies,
    /// outputs, inputs), in the outputs' units per input unit (on the sparse route by a sparse
    /// LU per frequency).
    fn frequency_response<'py>(&self, py: Python<'py>, freq_hz: Vec<f64>) -> PyResult<Bound<'py, PyArray3<Complex64>>> {
        let h = py.detach(|| self.study.full_frequency_response(&freq_hz)).map_err(py_err)?;
        responses(py, &h, self.study.output_names().len(), self.study.input_names().len())
    }

    /// "dense" or "sparse": the route the eigenanalysis took.
    #[getter]
    fn solver(&self) -> &'static str {
        if self.study.sparse_run().is_some() { "sparse" } else { "dense" }
    }
}

/// A reduced-order model: `E ẋ = A x + B u`, `z = C x + D u` (E = I for the ordinary form).
#[pyclass(module = "romdyn._romdyn", frozen)]
struct Rom {
    export: RomExport,
    /// The study's ROM this one is (or, for an imposed-motion model, was derived from).
    rom: ReducedModel,
    #[pyo3(get)]
    /// The summary `romdyn rom` prints (kept modes, static gains, their difference).
    summary: String,
    /// The continuous ordinary system (of a descriptor ROM: its algebraic part eliminated).
    system: romdyn::rom::OrdinaryRom,
    discrete: Option<romdyn::rom::DiscreteRom>,
    /// With dummy springs removed: the free ROM's eigenvalues.
    free: Option<romdyn::study::FreeEigenvalues>,
}

#[pymethods]
impl Rom {
    /// With dummy springs removed (`remove_springs`, a ports file): the removed elements and
    /// the free ROM's eigenvalues, as `romdyn rom` prints them: {"removed": [names], "zero":
    /// the number at zero (rigid-body motion), "eigenvalues" [rad/s] (complex, a pair once),
    /// "kind" ("real", "real, unstable", "oscillatory", "oscillatory, unstable"), "motion" (a
    /// real one's motion or None)}; None without removed springs.
    #[getter]
    fn free_eigenvalues<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(free) = &self.free else { return Ok(None) };
        let d = PyDict::new(py);
        d.set_item("removed", free.removed.clone())?;
        d.set_item("zero", free.zero)?;
        d.set_item("eigenvalues", complex_vec(py, &free.listed.iter().map(|e| e.lambda).collect::<Vec<_>>()))?;
        d.set_item("kind", free.listed.iter().map(|e| e.kind.name()).collect::<Vec<_>>())?;
        d.set_item("motion", free.listed.iter().map(|e| e.motion.clone()).collect::<Vec<_>>())?;
        Ok(Some(d))
    }

    /// "ordinary" or "descriptor".
    #[getter]
    fn kind(&self) -> &'static str {
        self.export.kind
    }
    #[getter(E)]
    fn e<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, &self.export.e)
    }
    #[getter(A)]
    fn a<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, &self.export.a)
    }
    #[getter(B)]
    fn b<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, &self.export.b)
    }
    #[getter(C)]
    fn c<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, &self.export.c)
    }
    #[getter(D)]
    fn d<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat(py, &self.export.d)
    }
    /// Input names with units ("node 2 Mz [N m]").
    #[getter]
    fn inputs(&self) -> Vec<String> {
        self.export.inputs.clone()
    }
    /// Output names with units ("node 2 rz [rad]").
    #[getter]
    fn outputs(&self) -> Vec<String> {
        self.export.outputs.clone()
    }
    #[getter]
    fn states(&self) -> Vec<String> {
        self.export.states.clone()
    }
    #[getter]
    fn input_units(&self) -> Vec<String> {
        self.export.input_units.clone()
    }
    #[getter]
    fn output_units(&self) -> Vec<String> {
        self.export.output_units.clone()
    }
    #[getter]
    fn state_units(&self) -> Vec<String> {
        self.export.state_units.clone()
    }
    /// The ROM's own eigenvalues [rad/s].
    #[getter]
    fn eigenvalues<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<Complex64>> {
        complex_vec(py, &self.export.eigenvalues)
    }
    /// The full model's eigenvalues of the kept modes [rad/s].
    #[getter]
    fn full_eigenvalues<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<Complex64>> {
        complex_vec(py, &self.export.full_eigenvalues)
    }
    /// Static gain of the full model (outputs × inputs), None if it has none.
    #[getter]
    fn full_static_gain<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.export.full_static_gain.as_ref().map(|m| mat(py, m))
    }
    /// Static gain of the ROM (outputs × inputs), None if it has none.
    #[getter]
    fn rom_static_gain<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.export.rom_static_gain.as_ref().map(|m| mat(py, m))
    }
    /// The ROM's warnings, the accuracy check's included (`reduce()` raised each with its
    /// `romdyn.RomdynWarning` category, but those the study had raised already).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.rom.warnings.iter().map(|w| w.to_string()).collect()
    }
    /// Time of the reference solution [s].
    #[getter]
    fn reference_time(&self) -> Option<f64> {
        self.export.reference_time
    }

    /// Sampling time [s] of a discrete-time ROM (`sample_rate=`), None in continuous time.
    #[getter]
    fn dt(&self) -> Option<f64> {
        self.export.sample_time
    }
    /// "continuous", or the discretization method ("zoh", "tustin", "matched").
    #[getter]
    fn discretization(&self) -> String {
        self.export.discretization.clone()
    }
    /// Hankel singular values of a balanced ROM's stable part, largest first (empty
    /// otherwise).
    #[getter]
    fn hankel_singular_values<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.export.hankel_singular_values.clone().into_pyarray(py)
    }
    /// A balanced ROM's bound `2 Σ dropped σ` on `‖G − G_r‖∞` (None otherwise).
    #[getter]
    fn error_bound(&self) -> Option<f64> {
        self.export.error_bound
    }

    /// Writes the ROM as `romdyn rom -o` does, the format by the extension: `.json`, `.mat`
    /// (MATLAB v5), `.npz`, `.m` (an Octave/MATLAB script building `sys` with `ss`/`dss`,
    /// names, units and the sampling time) or `.fmu` (an FMI 2.0 FMU: model exchange and
    /// co-simulation of an ordinary ROM, co-simulation of a discrete one; its binary built
    /// with the machine's C compiler); atomically (a failed write leaves no file).
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        py.detach(|| self.export.write(&path)).map_err(|e| RomdynError::new_err(format!("{}: {e}", path.display())))
    }

    /// Frequency response at `freq_hz` [Hz]: complex array (frequencies, outputs, inputs);
    /// of a discrete-time ROM `C (e^{jωT} I − A)⁻¹ B + D`.
    fn frequency_response<'py>(&self, py: Python<'py>, freq_hz: Vec<f64>) -> PyResult<Bound<'py, PyArray3<Complex64>>> {
        let h = py.detach(|| match &self.discrete {
            Some(d) => d.frequency_response(&freq_hz),
            None => self.system.frequency_response(&freq_hz),
        });
        responses(py, &h, self.export.outputs.len(), self.export.inputs.len())
    }

    /// The ROM as a python-control `StateSpace` with input, output and state names (`dt`: the
    /// sampling time of a discrete-time ROM). A descriptor ROM (`E` singular: its statically
    /// residualized states are algebraic) is converted by eliminating its algebraic part, the
    /// SVD residualization of eqs. 51–63: the ordinary form of the same ROM, same transfer
    /// function, states the kept modes'.
    fn to_control<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (a, b, c, d, states) = self.ordinary_matrices(py);
        let kw = PyDict::new(py);
        kw.set_item("inputs", self.export.inputs.clone())?;
        kw.set_item("outputs", self.export.outputs.clone())?;
        kw.set_item("states", states)?;
        let control = py.import("control")?.getattr("StateSpace")?;
        match self.export.sample_time {
            Some(t) => control.call((a, b, c, d, t), Some(&kw)),
            None => control.call((a, b, c, d), Some(&kw)),
        }
    }

    /// The ROM as a `scipy.signal.StateSpace` (continuous time, or with `dt` the sampling time
    /// of a discrete-time ROM); a descriptor ROM converted as by `to_control()`.
    fn to_scipy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (a, b, c, d, _) = self.ordinary_matrices(py);
        let kw = PyDict::new(py);
        if let Some(t) = self.export.sample_time {
            kw.set_item("dt", t)?;
        }
        py.import("scipy.signal")?.getattr("StateSpace")?.call((a, b, c, d), Some(&kw))
    }

    fn __repr__(&self) -> String {
        format!("<romdyn Rom {}: {} states, inputs {:?}, outputs {:?}>", self.export.kind, self.export.a.nrows(), self.export.inputs, self.export.outputs)
    }
}

impl Rom {
    fn of(export: RomExport, rom: ReducedModel, summary: String) -> Self {
        let (system, discrete) = (rom.ordinary.clone(), rom.discrete.clone());
        Rom { export, rom, summary, system, discrete, free: None }
    }

    /// `A, B, C, D` and the state names of the ordinary form: the export's, or for a
    /// descriptor ROM those of its algebraic part eliminated (eqs. 51–63).
    #[allow(clippy::type_complexity)]
    fn ordinary_matrices<'py>(&self, py: Python<'py>) -> (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>, Vec<String>) {
        if self.export.kind == "ordinary" {
            return (self.a(py), self.b(py), self.c(py), self.d(py), self.export.states.clone());
        }
        let o = &self.system;
        let states = self.export.states.iter().take(o.a.nrows()).cloned().collect();
        (mat(py, &o.a), mat(py, &o.b), mat(py, &o.c), mat(py, &o.d), states)
    }
}

/// Checks that the model text declares every swept variable with `set:`.
#[pyfunction]
fn check_parameters(text: &str, name: PathBuf, names: Vec<String>) -> PyResult<()> {
    romdyn::sweep::check_parameters(text, &name, &names).map_err(|e| ModelError::new_err(e.to_string()))
}

/// `"NAME=A:B:N"` or `"NAME=V1,V2,..."` as (name, values).
#[pyfunction]
fn parse_set(spec: &str) -> PyResult<(String, Vec<f64>)> {
    let p: romdyn::sweep::Parameter = spec.parse().map_err(RomdynError::new_err)?;
    Ok((p.name, p.values))
}

/// The full grid of (name, values) pairs, the first varying slowest.
#[pyfunction]
fn grid(parameters: Vec<(String, Vec<f64>)>) -> PyResult<Vec<Vec<f64>>> {
    let p: Vec<_> = parameters.into_iter().map(|(name, values)| romdyn::sweep::Parameter { name, values }).collect();
    romdyn::sweep::grid(&p).map_err(py_err)
}

/// One design point (a sweep's work unit: the model text, the parameter values and the
/// options dict): a dict of its ROM and modes, or {"error": message} when it fails.
#[pyfunction]
fn run_point<'py>(py: Python<'py>, text: &str, name: PathBuf, names: Vec<String>, values: Vec<f64>, options: &Bound<'py, PyDict>) -> PyResult<Bound<'py, PyDict>> {
    let options = options::sweep(options)?;
    let r = py.detach(|| romdyn::sweep::run_point(text, &name, &names, &values, &options, None));
    convert::point(py, r.map_err(|e| e.to_string()))
}

/// Every design point in this process on rayon threads, the GIL released (continuation runs
/// them in order); a list of run_point's dicts.
#[pyfunction]
#[pyo3(signature = (text, name, names, points, options, threads = None))]
fn run_points<'py>(py: Python<'py>, text: &str, name: PathBuf, names: Vec<String>, points: Vec<Vec<f64>>, options: &Bound<'py, PyDict>, threads: Option<usize>) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let options = options::sweep(options)?;
    romdyn::sweep::check_lowest(options.modes, points.len()).map_err(|e| pyo3::exceptions::PyValueError::new_err(format!("lowest: {e}")))?;
    // The CLI's --jobs bounds: 0 refused, more threads than cores reduced with a warning.
    let (threads, reduced) = romdyn::sweep::worker_threads(threads).map_err(|e| pyo3::exceptions::PyValueError::new_err(format!("threads: {e}")))?;
    if let Some(w) = reduced {
        let text = std::ffi::CString::new(format!("threads: {w}")).unwrap_or_default();
        PyErr::warn(py, &py.get_type::<warnings::RomdynWarning>(), &text, 1)?;
    }
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().map_err(|e| RomdynError::new_err(e.to_string()))?;
    let results = py.detach(|| pool.install(|| romdyn::sweep::sweep(text, &name, &names, points, &options, &|| {})));
    results.results.into_iter().map(|r| convert::point(py, r.map_err(|e| e.message))).collect()
}

/// The library's advice with its command-line flags spelled as keyword arguments, as every
/// warning and error reaches Python (`"--by dominance"` → `'by="dominance"'`); for tests
/// comparing the CLI's messages with Python's.
#[pyfunction]
fn advice_for_python(text: &str) -> String {
    python_spelling(text)
}

#[pymodule]
fn _romdyn(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Model>()?;
    m.add_class::<StudyPy>()?;
    m.add_class::<Rom>()?;
    m.add("RomdynError", m.py().get_type::<RomdynError>())?;
    m.add("ModelError", m.py().get_type::<ModelError>())?;
    warnings::register(m)?;
    m.add_function(wrap_pyfunction!(check_parameters, m)?)?;
    m.add_function(wrap_pyfunction!(advice_for_python, m)?)?;
    m.add_function(wrap_pyfunction!(parse_set, m)?)?;
    m.add_function(wrap_pyfunction!(grid, m)?)?;
    m.add_function(wrap_pyfunction!(run_point, m)?)?;
    m.add_function(wrap_pyfunction!(run_points, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::interpolate_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(validate::validate, m)?)?;
    m.add_function(wrap_pyfunction!(cms::cms, m)?)?;
    Ok(())
}
