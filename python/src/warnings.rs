//! romdyn's warnings as Python warnings: every study and ROM warning the CLI prints is raised
//! through `warnings.warn` with a category under `romdyn.RomdynWarning` (a `UserWarning`),
//! so that it can be filtered (`warnings.simplefilter("error", romdyn.AccuracyWarning)`) and
//! tested (`pytest.warns(romdyn.TransmissibilityWarning)`).

use pyo3::prelude::*;
use pyo3::types::PyType;
use romdyn::analysis::RunWarning;
use romdyn::study::{Response, Warning};

pyo3::create_exception!(_romdyn, RomdynWarning, pyo3::exceptions::PyUserWarning, "Base of romdyn's warnings: what a user must know about a study or a ROM that is not an error.");
pyo3::create_exception!(_romdyn, InputWarning, RomdynWarning, "What a reader noticed in an input file and let pass (a modal joint's FEM file: zeros skipped after a record, unequal lumped masses).");
pyo3::create_exception!(_romdyn, ReferenceWarning, RomdynWarning, "The reference solution or a run's initial state: not an equilibrium (the linear model is the frozen-time Jacobian), beams' update, initial velocities that violate the joints, the derivatives phase.");
pyo3::create_exception!(_romdyn, PortWarning, RomdynWarning, "An input that moves nothing or an output that sees nothing (zero to rounding).");
pyo3::create_exception!(_romdyn, EigenanalysisWarning, RomdynWarning, "The eigenanalysis: the sparse route not certified (a mode may be missing), eigenvalues not resolved in double precision, zeros the error estimate doubts, a run's eigenanalysis one-sided or dependent on reactions.");
pyo3::create_exception!(_romdyn, ModeSelectionWarning, RomdynWarning, "Modes below the band dropped or kept, kept modes that add no response, damping not applied.");
pyo3::create_exception!(_romdyn, AccuracyWarning, RomdynWarning, "The ROM departs from the full model (static gain, frequency response, transmissibility, eigenvalues of its exported A).");
pyo3::create_exception!(_romdyn, StaticGainWarning, AccuracyWarning, "The ROM's static gain differs from the full model's beyond rounding.");
pyo3::create_exception!(_romdyn, ResponseWarning, AccuracyWarning, "The ROM's frequency response departs from the full model's within the frequencies of interest.");
pyo3::create_exception!(_romdyn, TransmissibilityWarning, AccuracyWarning, "The ROM's transmissibility (eq. 100) departs from the full model's, or could not be checked.");

/// The Python category of a warning.
fn category<'py>(py: Python<'py>, w: &Warning) -> Bound<'py, PyType> {
    match w {
        Warning::InputFile { .. } => py.get_type::<InputWarning>(),
        Warning::NotInEquilibrium { .. } | Warning::IncrementalBeamsStatic { .. } | Warning::BeamKeptPathIndependent { .. } | Warning::OneSided { .. } | Warning::ReactionDependent { .. } => py.get_type::<ReferenceWarning>(),
        Warning::Run { warning } => run_category(py, warning),
        Warning::InputMovesNothing { .. } | Warning::OutputSeesNothing { .. } => py.get_type::<PortWarning>(),
        Warning::SparseNotCertified { .. } | Warning::DominanceAmongComputed { .. } | Warning::UnresolvedEigenvalues { .. } | Warning::DoubtfulZeros { .. } => py.get_type::<EigenanalysisWarning>(),
        Warning::RomEigenvalues { .. } | Warning::AboveNyquist { .. } => py.get_type::<AccuracyWarning>(),
        Warning::BelowBandDropped { .. } | Warning::BelowBandKept { .. } | Warning::Invisible { .. } | Warning::Unscaled { .. } | Warning::DampingNotApplied { .. } => py.get_type::<ModeSelectionWarning>(),
        Warning::StaticGain { .. } => py.get_type::<StaticGainWarning>(),
        Warning::ResponseDeparts { response: Response::Inputs, .. } => py.get_type::<ResponseWarning>(),
        Warning::ResponseDeparts { response: Response::Transmissibility, .. } | Warning::TransmissibilityUnavailable { .. } => py.get_type::<TransmissibilityWarning>(),
    }
}

/// The Python category of a run's warning: the eigenanalyses' or the initial state's.
fn run_category<'py>(py: Python<'py>, w: &RunWarning) -> Bound<'py, PyType> {
    if w.is_eigenanalysis() { py.get_type::<EigenanalysisWarning>() } else { py.get_type::<ReferenceWarning>() }
}

fn warn_text(py: Python<'_>, category: &Bound<'_, PyType>, text: &str) -> PyResult<()> {
    // Advice in the library's words names command-line flags: spelled as keywords here.
    let text = std::ffi::CString::new(romdyn::study::python_spelling(text).replace('\0', " ")).unwrap_or_default();
    PyErr::warn(py, category, &text, 1)
}

/// Raises each warning with its category (`warnings.warn`: an error when filtered so).
pub fn warn_all(py: Python<'_>, warnings: &[Warning]) -> PyResult<()> {
    for w in warnings {
        warn_text(py, &category(py, w), &w.to_string())?;
    }
    Ok(())
}

/// Raises each of a run's warnings (`Model.run()`, as `romdyn run` prints them).
pub fn warn_run(py: Python<'_>, warnings: &[RunWarning]) -> PyResult<()> {
    for w in warnings {
        warn_text(py, &run_category(py, w), &w.to_string())?;
    }
    Ok(())
}

/// A ROM that departs from the model in words of the library (`romdyn validate`'s verdict),
/// as an [`AccuracyWarning`].
pub fn warn_accuracy(py: Python<'_>, text: &str) -> PyResult<()> {
    warn_text(py, &py.get_type::<AccuracyWarning>(), text)
}

/// Each note on beams the `auto` update leaves path independent, as a [`ReferenceWarning`].
pub fn warn_beam_notes(py: Python<'_>, messages: &[String]) -> PyResult<()> {
    for message in messages {
        warn_text(py, &py.get_type::<ReferenceWarning>(), &format!("{message} (beam_update=\"path-independent\" silences this)"))?;
    }
    Ok(())
}

/// Each warning of a model's input files ([`romdyn::model::Model::input_warnings`]), as an
/// [`InputWarning`].
pub fn warn_input(py: Python<'_>, messages: &[String]) -> PyResult<()> {
    for message in messages {
        warn_text(py, &py.get_type::<InputWarning>(), message)?;
    }
    Ok(())
}

/// Adds the categories to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("RomdynWarning", py.get_type::<RomdynWarning>())?;
    m.add("InputWarning", py.get_type::<InputWarning>())?;
    m.add("ReferenceWarning", py.get_type::<ReferenceWarning>())?;
    m.add("PortWarning", py.get_type::<PortWarning>())?;
    m.add("EigenanalysisWarning", py.get_type::<EigenanalysisWarning>())?;
    m.add("ModeSelectionWarning", py.get_type::<ModeSelectionWarning>())?;
    m.add("AccuracyWarning", py.get_type::<AccuracyWarning>())?;
    m.add("StaticGainWarning", py.get_type::<StaticGainWarning>())?;
    m.add("ResponseWarning", py.get_type::<ResponseWarning>())?;
    m.add("TransmissibilityWarning", py.get_type::<TransmissibilityWarning>())?;
    Ok(())
}
