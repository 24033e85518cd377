//! `romdyn.cms(...)`: the CLI's `romdyn cms` ([`romdyn::cms`]) on a `Model`.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use romdyn::cms::{craig_bampton, CmsError, CmsRequest};

use super::convert::mat;
use super::{options, py_err, warnings, Model, RomdynError};

/// Reduces the substructure `model` (nodes, bodies, beams, deformable springs; no joints) to
/// MBDyn's modal-joint FEM file `PREFIX.fem` with Craig–Bampton modes (the CLI's `romdyn
/// cms`): `modes` fixed-interface normal modes (unit modal mass) and six constraint modes per
/// node of `interface` (structural node labels; unit displacement [m] or rotation [rad]).
/// `reference`, `load_steps` as for `Model.study()`. Returns {"path", "nodes" (FEM node
/// labels), "fixed_interface_omega" [rad/s], "mass", "stiffness" (the modal matrices),
/// "card" (the MBDyn modal joint that attaches the file), "summary" (what the CLI prints)};
/// what the FEM file leaves out (damping, off-diagonal nodal masses in record 11) is raised
/// as `AccuracyWarning`s, the FEM reader's as `InputWarning`s.
#[pyfunction]
#[pyo3(signature = (model, interface, modes, output, reference = None, load_steps = 10))]
pub fn cms<'py>(py: Python<'py>, model: &Model, interface: Vec<u32>, modes: usize, output: PathBuf, reference: Option<&Bound<'_, PyAny>>, load_steps: usize) -> PyResult<Bound<'py, PyDict>> {
    let reference = options::reference(reference, load_steps)?;
    let request = CmsRequest { interfaces: interface, modes, reference };
    let path = romdyn::output::prefixed_path(&output, "fem");
    let (cb, input, kept) = py
        .detach(|| -> Result<_, CmsError> {
            let (m, kept) = model.read(reference.integrates())?;
            let cb = craig_bampton(&m.model, &m.problem, &request)?;
            Ok((cb, m.model.input_warnings(), kept))
        })
        .map_err(|e| match e {
            CmsError::Study(e) => py_err(e),
            CmsError::Option { option, message } => crate::options::bad(option, message),
            e => RomdynError::new_err(format!("{}: {e}", model.name.display())),
        })?;
    warnings::warn_input(py, &input)?;
    warnings::warn_beam_notes(py, &kept)?;
    for w in &cb.warnings {
        warnings::warn_accuracy(py, w)?;
    }
    cb.write(&path, &model.name.display().to_string()).map_err(|e| RomdynError::new_err(e.to_string()))?;
    let name = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    let d = PyDict::new(py);
    d.set_item("path", &path)?;
    d.set_item("nodes", cb.fem.node_labels.clone())?;
    d.set_item("fixed_interface_omega", cb.fixed_interface_omega.clone())?;
    d.set_item("mass", mat(py, &cb.fem.mass))?;
    d.set_item("stiffness", mat(py, &cb.fem.stiffness))?;
    d.set_item("card", cb.modal_joint_card(1000, &name))?;
    d.set_item("summary", cb.summary(&path))?;
    Ok(d)
}
