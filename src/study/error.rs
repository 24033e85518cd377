//! Why a study could not be set up or a ROM built.

use std::path::{Path, PathBuf};

use crate::analysis::RunError;
use crate::dae::PortError;
use crate::input::mbdyn::MbdynError;
use crate::input::pencil::PencilError;
use crate::eigen::EigenError;
use crate::rom::RomError;

/// A failure of [`super::Study`], with the file or option it concerns.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// The MBDyn input file: `FILE:LINE:COLUMN: error: …` with the line and a caret.
    #[error(transparent)]
    Model(#[from] Box<MbdynError>),
    #[error(transparent)]
    Pencil(#[from] PencilError),
    #[error("{}reference solution: {cause}", file.as_ref().map(|f| format!("{}: ", f.display())).unwrap_or_default())]
    Reference { file: Option<PathBuf>, cause: RunError },
    #[error("static equilibrium: unrestrained {motion} (the model needs more supports or joints); {cause}")]
    Unrestrained { motion: String, cause: RunError },
    #[error("{option}: {message}")]
    Option { option: super::Setting, message: String },
    #[error(transparent)]
    Port(#[from] PortError),
    #[error(transparent)]
    Eigen(#[from] EigenError),
    #[error(transparent)]
    Rom(#[from] RomError),
    /// (Its message, not its source: printed once.)
    #[error("sparse eigenanalysis: {0}")]
    Krylov(crate::eigen::krylov::KrylovError),
    #[error("full model: {0}")]
    SparseSolve(crate::linear::SparseSolveError),
    #[error("mode selection: the sparse route computed {target} and found {found} mode(s), fewer than the selection needs{note}; --solver dense computes every mode")]
    SparseModes { found: usize, target: String, note: String },
    #[error("a ROM needs inputs and outputs: give --input NODE:COMP and --output NODE:COMP for a model, --input-row I and --output-col J for an .m pencil")]
    NoPorts,
    #[error("give a MODEL file or --pencil FILE")]
    NoSource,
    #[error("a pencil file or a linear DAE has no reference solution nor problem to run (give the model)")]
    NoReference,
    #[error(transparent)]
    ElementPart(#[from] crate::dae::ElementPartError),
    #[error(transparent)]
    PortsFile(#[from] crate::input::ports_file::PortsFileError),
    #[error("no imposed motion was given (--imposed NODE[:COMPONENTS] or \"imposed\" in the ports file)")]
    NoImposedMotion,
    #[error("the imposed motion cannot be produced at {0} Hz (C_e (jω E − A)⁻¹ B_e is singular there, eq. 99)")]
    SingularImposedMotion(f64),
    #[error("{0}")]
    Application(String),
    /// The ROM's projection is singular and kept modes could not be scaled (a repeated root
    /// with one vector: a modal ROM cannot represent it).
    #[error("{cause}: kept mode(s) {} have left and right vectors orthogonal through F_yd (a repeated eigenvalue with a single vector, such as a critically damped mode with ζ = 1 exactly): a modal ROM cannot represent them; change that damping by a part in a million, or leave those modes out", modes.iter().map(|k| k.to_string()).collect::<Vec<_>>().join(", "))]
    UnscaledModes { modes: Vec<usize>, cause: RomError },
    #[error("mode(s) {} lie below the frequencies of interest (up to {top_hz:.4} Hz): static residualization is valid only above them (--below-band keep|drop)", modes.iter().map(|(k, f)| format!("{k} ({f:.4} Hz)")).collect::<Vec<_>>().join(", "))]
    ResidualizedBelowBand { modes: Vec<(usize, f64)>, top_hz: f64 },
    #[error("modal damping for mode {0}, which the ROM does not keep")]
    DampingOfDroppedMode(usize),
    #[error("mode {0} is both kept and residualized")]
    KeptAndResidualized(usize),
}

impl From<crate::eigen::krylov::KrylovError> for StudyError {
    fn from(e: crate::eigen::krylov::KrylovError) -> Self {
        StudyError::Krylov(e)
    }
}

impl From<crate::linear::SparseSolveError> for StudyError {
    fn from(e: crate::linear::SparseSolveError) -> Self {
        StudyError::SparseSolve(e)
    }
}

/// A cut that cannot be made is an error of the `cut` setting (`--cut`, `cut=`).
impl From<crate::dae::CutError> for StudyError {
    fn from(e: crate::dae::CutError) -> Self {
        StudyError::Option { option: super::Setting::Cut, message: e.to_string() }
    }
}

impl From<MbdynError> for StudyError {
    fn from(e: MbdynError) -> Self {
        StudyError::Model(Box::new(e))
    }
}

impl StudyError {
    /// Names the model file in a reference-solution failure.
    pub fn in_file(self, path: &Path) -> Self {
        match self {
            StudyError::Reference { file: None, cause } => StudyError::Reference { file: Some(path.to_path_buf()), cause },
            e => e,
        }
    }
}
