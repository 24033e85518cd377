//! Command-line arguments shared by several subcommands.

use std::path::PathBuf;

use std::io::IsTerminal;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use romdyn::analysis::Reference;
use romdyn::input::mbdyn::BeamUpdateChoice;
use romdyn::dae::{NodeInput, NodeOutput};
use romdyn::input::eigen_pencil::PencilPorts;
use romdyn::eigen::EigenRoute;
use romdyn::rom::{ModalDamping, ModeSelection};
use romdyn::study::{EigenSettings, FrequencyGrid, Named, Ports, RomRequest, Solver, Study, StudyError, StudySource};

/// clap's parser of a library enum, from its one table of names ([`Named::NAMES`]: the same
/// words Python takes, each with its `--help` line).
pub fn named<T: Named + std::fmt::Debug>() -> impl clap::builder::TypedValueParser<Value = T> {
    PossibleValuesParser::new(T::NAMES.iter().map(|(name, _, help)| PossibleValue::new(*name).help(*help))).try_map(|word| T::from_name(&word).map_err(|e| e.to_string()))
}

/// Reads an MBDyn file with its beams' rotation update chosen for a time integration
/// (`integrates`) or not; beams that `auto` leaves path independent are warned on stderr.
pub fn read_model_with_beams(path: &std::path::Path, set: &[romdyn::sweep::Parameter], update: BeamUpdateChoice, integrates: bool) -> anyhow::Result<romdyn::input::mbdyn::MbdynModel> {
    let overrides = romdyn::sweep::single_values(set).map_err(|e| anyhow::anyhow!("--set {e}"))?;
    let m = romdyn::input::mbdyn::read_model_with(path, romdyn::input::mbdyn::ReadOptions::new(&overrides, update, integrates))?;
    for why in &m.beam_notes {
        eprintln!("warning: {}", romdyn::study::Warning::BeamKeptPathIndependent { why: why.clone() });
    }
    for w in m.model.input_warnings() {
        eprintln!("warning: {w}");
    }
    Ok(m)
}

/// Where the linear DAE comes from and how it is eigenanalysed.
#[derive(Args, Debug)]
pub struct PencilArgs {
    /// MBDyn input file of a multibody model, linearized at its initial time (or --at, --static)
    #[arg(value_name = "MODEL", required_unless_present = "pencil")]
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub reference: ReferenceArgs,
    /// Pencil file instead of a model: an MBDyn eigenanalysis .m file (Aplus = J(+c), Aminus = J(-c), dCoef; written with 'output matrices') or JSON (Fyd/Fy or J/Jstar/dcoef, B, C)
    #[arg(long, value_name = "FILE", conflicts_with_all = ["model", "at", "static_equilibrium"])]
    pub pencil: Option<PathBuf>,
    /// ROM input of a model: NODE:Fx|Fy|Fz (force [N]) or NODE:Mx|My|Mz (moment [N m]), global frame; or NODE:abstract|electric|hydraulic, added to that scalar node's equation as an abstract force (a current [A] into an electric node, a mass flow [kg/s] into a hydraulic one)
    #[arg(long = "input", value_name = "NODE:COMP", conflicts_with = "pencil")]
    pub inputs: Vec<NodeInput>,
    /// ROM output of a model: NODE:x|y|z (displacement [m]) or NODE:rx|ry|rz (rotation [rad]); or NODE:abstract|electric|hydraulic, that scalar node's value (a voltage [V], a pressure [Pa]), NODE:abstract_rate|electric_rate|hydraulic_rate its derivative
    #[arg(long = "output", value_name = "NODE:COMP", conflicts_with = "pencil")]
    pub outputs: Vec<NodeOutput>,
    /// ROM output at a FEM node of a modal joint (a sensor on the flexible body): JOINT:FEM_NODE:x|y|z, its displacement [m], JOINT:FEM_NODE:vx|vy|vz, its velocity [m/s], or JOINT:FEM_NODE:rx|ry|rz, its rotation [rad] (the FEM file's rotational mode shapes), global axes; the floating frame's motion and the modes' (x + R (f0 + Phi q), linearized). FEM_NODE is a node label of the joint's FEM file
    #[arg(long = "fem-output", value_name = "JOINT:FEM_NODE:COMP", conflicts_with = "pencil")]
    pub fem_outputs: Vec<romdyn::dae::FemOutput>,
    /// ROM input of an .m pencil: a unit generalized force entering equation I (1-based row of Aplus/Aminus) as -dF_I = u. In romdyn's numbering a dynamic node with first unknown idx (the file's 'idx' with 'output geometry') has its force equilibrium x,y,z in rows idx+7..idx+9 and moments in idx+10..idx+12 (static node: idx+1..idx+6)
    #[arg(long = "input-row", value_name = "I", requires = "pencil")]
    pub input_rows: Vec<usize>,
    /// ROM output of an .m pencil: unknown J (1-based column of Aplus/Aminus); a node's x,y,z displacements [m] are idx+1..idx+3 and its rotations [rad] idx+4..idx+6
    #[arg(long = "output-col", value_name = "J", requires = "pencil")]
    pub output_cols: Vec<usize>,
    /// A `set:` variable of the file given another value, NAME=VALUE in the file's (SI) units, replacing what its `set:` gives NAME; repeatable. romdyn sweep also takes NAME=A:B:N (N equally spaced values from A to B) or NAME=V1,V2,... and runs their full grid (the first varies slowest)
    #[arg(long = "set", value_name = "NAME=VALUE", conflicts_with = "pencil")]
    pub set: Vec<romdyn::sweep::Parameter>,
    /// Ports file (JSON): named inputs and outputs at points of nodes (forces, moments, actuators; displacements, rotations, LVDTs, velocities), node names for mode labels, dummy springs to remove, an imposed motion (the book's chapter Ports, docs/src/application/ports.md)
    #[arg(long, value_name = "FILE", conflicts_with = "pencil")]
    pub ports: Option<PathBuf>,
    /// Remove these deformable elements (dummy springs) from the full model and the ROM: their force is fed back, A + B_e K C_e (paper eqs. 92-95 with the sign of romdyn's applied-force inputs)
    #[arg(long = "remove-spring", value_name = "LABEL,...", value_delimiter = ',', conflicts_with = "pencil")]
    pub remove_spring: Vec<u32>,
    /// Imposed motion of a node (all six components, or NODE:x,y,rz): its forces and displacements become the last inputs and outputs; transmissibility by eq. 100
    #[arg(long, value_name = "NODE[:COMPONENTS]", conflicts_with = "pencil")]
    pub imposed: Option<String>,
    /// Cut a control loop open at a genel or an abstract force (repeatable): its part of the linearized model is taken out and the signal that crossed it becomes an input (injected) and an output (returned), after the other inputs and outputs (before an imposed motion's); closing injected = returned gives the model as written, and the loop transfer function at the cut is L(s) = -(returned/injected). An element without own states (spring support, cross spring support, spring, abstract force) is cut at its output, a state-space genel or scalar filter at its input. The reference solution stays the closed loop's. Units: the scalar node's (abstract -, electric A or V, hydraulic kg/s or Pa)
    #[arg(long = "cut", value_name = "genel:LABEL|force:LABEL", conflicts_with = "pencil")]
    pub cuts: Vec<romdyn::dae::Cut>,
    /// Eigenanalysis route (lambda by default: its pencil has no infinite eigenvalues, on which faer's QZ can stall)
    #[arg(long, value_parser = named::<EigenRoute>(), default_value = "lambda")]
    pub route: EigenRoute,
    /// dCoef of the Λ form [s], positive and finite (default: the file's, else 1/the geometric mean of the dynamic part's |λ|: the spectrum's logarithmic centre at |Λ| = 1)
    #[arg(long, value_name = "C", allow_negative_numbers = true)]
    pub dcoef: Option<f64>,
    /// Eigensolver: dense QZ (every eigenvalue), sparse shift-invert Krylov–Schur (only the modes asked for, no n x n matrix; a progress bar on a terminal; --count N --by dominance ranks among the 3N lowest), or auto: sparse from 400 equations on, dense below or for --count with --by dominance (--band with --by dominance stays sparse)
    #[arg(long, value_parser = named::<Solver>(), default_value = "auto")]
    pub solver: Solver,
    /// Rotation update of beam3 and beam2: auto (MBDyn's incremental one for a reference at a time, --at; path independent for --static and the initial configuration), path-independent, or incremental (per time step; a static equilibrium takes it as one step from the initial configuration)
    #[arg(long = "beam-update", value_parser = named::<BeamUpdateChoice>(), default_value = "auto")]
    pub beam_update: BeamUpdateChoice,
}

impl PencilArgs {
    /// The study these arguments describe: a model file linearized at its reference, or a
    /// pencil file.
    /// `request`: the ROM (or the modes of `eig`) the study is for, which tells the sparse
    /// route which modes to compute.
    pub fn study(&self, request: Option<&RomRequest>) -> Result<Study, StudyError> {
        let builder = match (&self.pencil, &self.model) {
            (Some(path), _) => Study::builder(StudySource::pencil_file(path, PencilPorts { input_rows: self.input_rows.clone(), output_cols: self.output_cols.clone() })),
            (None, Some(path)) => {
                let overrides = romdyn::sweep::single_values(&self.set).map_err(|message| StudyError::Option { option: romdyn::study::Setting::Set, message })?;
                Study::builder(StudySource::ModelFile { path: path.clone(), overrides }).reference(self.reference.reference()).ports(self.ports()?).beam_update(self.beam_update)
            }
            // clap requires one of them.
            (None, None) => return Err(StudyError::NoSource),
        };
        let builder = builder.eigen(self.eigen());
        let builder = match request {
            Some(r) => builder.for_request(r),
            None => builder,
        };
        let progress = SolverProgress::new();
        let result = builder.progress(&|line| progress.report(line)).build();
        progress.finish();
        result
    }

    pub fn eigen(&self) -> EigenSettings {
        EigenSettings { route: self.route, dcoef: self.dcoef, solver: self.solver, ..EigenSettings::default() }
    }

    /// The model's ports: --input/--output alone, or with a ports file, --remove-spring or
    /// --imposed the whole application.
    pub fn ports(&self) -> Result<Ports, StudyError> {
        Ports::from_parts(self.ports.as_deref(), &self.inputs, &self.outputs, &self.fem_outputs, &self.remove_spring, self.imposed.as_deref(), &self.cuts)
    }
}

/// A spinner with the sparse solver's last report, on stderr, drawn only on a terminal and
/// only once the solver reports (the dense route and short solves show nothing).
struct SolverProgress(ProgressBar);

impl SolverProgress {
    fn new() -> Self {
        let bar = if std::io::stderr().is_terminal() { ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr()) } else { ProgressBar::hidden() };
        bar.set_style(ProgressStyle::with_template("{spinner} sparse eigenanalysis {elapsed}: {msg}").unwrap_or_else(|_| ProgressStyle::default_spinner()));
        SolverProgress(bar)
    }

    fn report(&self, line: &str) {
        self.0.set_message(line.to_string());
        self.0.tick();
    }

    fn finish(&self) {
        self.0.finish_and_clear();
    }
}

/// Where a model file is linearized (default: its initial time, after consistent initial
/// derivatives).
#[derive(Args, Debug, Clone)]
pub struct ReferenceArgs {
    /// At the solution of the file's initial-value problem at TIME [s] (integrated with the file's method, step and tolerance)
    #[arg(long, value_name = "TIME", conflicts_with = "static_equilibrium", allow_negative_numbers = true)]
    pub at: Option<f64>,
    /// At the static equilibrium at the initial time (loads and gravity applied in --load-steps increments): prestressed structures
    #[arg(long = "static", id = "static_equilibrium")]
    pub static_equilibrium: bool,
    /// Load increments of --static
    #[arg(long, value_name = "N", default_value_t = 10, requires = "static_equilibrium")]
    pub load_steps: usize,
}

impl ReferenceArgs {
    pub fn reference(&self) -> Reference {
        match (self.at, self.static_equilibrium) {
            (_, true) => Reference::Static { load_steps: self.load_steps },
            (Some(t), false) => Reference::At(t),
            (None, false) => Reference::Initial,
        }
    }
}

/// Which modes a ROM keeps (a complex-conjugate pair counts as one mode).
#[derive(Args, Debug)]
#[group(required = true, multiple = false)]
pub struct SelectionArgs {
    /// Keep the dynamic modes with natural frequency in [FMIN, FMAX] Hz
    #[arg(long, value_name = "FMIN:FMAX", value_parser = parse_band)]
    pub band: Option<(f64, f64)>,
    /// Keep N dynamic modes (a complex or ± real pair is one mode): the lowest, or with --by dominance the N that matter most for these inputs and outputs
    #[arg(long, value_name = "N", value_parser = parse_count)]
    pub count: Option<usize>,
    /// Keep the modes with these 1-based indices of the modal table
    #[arg(long, value_name = "I,J,...", value_delimiter = ',')]
    pub modes: Option<Vec<usize>>,
}

impl SelectionArgs {
    pub fn selection(&self) -> ModeSelection {
        match (&self.band, self.count, &self.modes) {
            (Some((a, b)), _, _) => ModeSelection::Band { fmin_hz: *a, fmax_hz: *b },
            (_, Some(n), _) => ModeSelection::Lowest(n),
            (_, _, Some(list)) => ModeSelection::Indices(list.clone()),
            _ => ModeSelection::Lowest(1),
        }
    }
}

pub fn parse_band(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s.split_once(':').ok_or("expected FMIN:FMAX in Hz, e.g. 0.1:20")?;
    let a: f64 = a.trim().parse().map_err(|_| format!("FMIN '{a}' is not a number"))?;
    let b: f64 = b.trim().parse().map_err(|_| format!("FMAX '{b}' is not a number"))?;
    romdyn::rom::ModeSelection::band(a, b)?;
    Ok((a, b))
}

/// Frequency grid of a Bode plot.
#[derive(Args, Debug)]
pub struct FrequencyArgs {
    /// Lowest frequency [Hz], > 0 (default: a decade below the lowest kept mode)
    #[arg(long, value_name = "HZ", allow_negative_numbers = true)]
    pub fmin: Option<f64>,
    /// Highest frequency [Hz], > FMIN (default: a decade above the highest kept mode)
    #[arg(long, value_name = "HZ", allow_negative_numbers = true)]
    pub fmax: Option<f64>,
    /// Number of log-spaced frequencies (at least 2); the ROM summary's accuracy uses the same grid
    #[arg(long, default_value_t = 400)]
    pub points: usize,
}

impl FrequencyArgs {
    pub fn grid(&self) -> FrequencyGrid {
        FrequencyGrid { fmin_hz: self.fmin, fmax_hz: self.fmax, points: self.points }
    }
}

/// `ZETA` (every kept mode) or `K=ZETA,...` (modal-table indices), each ζ in [0, 1).
pub fn parse_damping(s: &str) -> Result<ModalDamping, String> {
    let zeta = |t: &str| -> Result<f64, String> {
        let z: f64 = t.trim().parse().map_err(|_| format!("'{t}' is not a damping ratio (expected a number in [0, 1), e.g. 0.02)"))?;
        if (0.0..1.0).contains(&z) { Ok(z) } else { Err(format!("damping ratio {z} is outside [0, 1)")) }
    };
    if !s.contains('=') {
        return zeta(s).map(ModalDamping::Uniform);
    }
    let mut list = Vec::new();
    for item in s.split(',') {
        let (k, z) = item.split_once('=').ok_or_else(|| format!("'{item}': expected MODE=ZETA, e.g. 1=0.02"))?;
        let k: usize = k.trim().parse().map_err(|_| format!("'{k}' is not a modal-table index"))?;
        if let Some((_, first)) = list.iter().find(|(j, _)| *j == k) {
            return Err(format!("mode {k} is given a damping ratio twice ({first} and {}): give each modal-table index once", z.trim()));
        }
        list.push((k, zeta(z)?));
    }
    Ok(ModalDamping::PerMode(list))
}

/// A mode count: a whole number of at least 1.
pub fn parse_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(0) => Err("a ROM keeps at least 1 mode".into()),
        Ok(n) => Ok(n),
        Err(_) => Err(format!("'{s}' is not a whole number of modes")),
    }
}
