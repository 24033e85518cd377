//! The linear DAE a command works on: from a pencil file (JSON or MBDyn `.m`), or from an
//! MBDyn model linearized at its reference solution (initial time after consistent initial
//! derivatives, as MBDyn does, or `--at TIME`).

use anyhow::{Context, Result};
use romdyn::analysis::reference_state;
use romdyn::dae::{linearize, EnergyShare, ModalEnergy};
use romdyn::input::eigen_pencil::PencilPorts;
use romdyn::input::mbdyn::read_model;
use romdyn::input::pencil::read_pencil_file;
use romdyn::linear::{LinearDae, ModalAnalysis};
use romdyn::model::Model;

use super::args::PencilArgs;

pub struct Loaded {
    pub dae: LinearDae,
    pub modal: ModalAnalysis,
    pub model: Option<Model>,
}

impl Loaded {
    /// Kinetic-energy shares of every mode (empty lists for pencil files).
    pub fn energy(&self) -> Vec<Vec<EnergyShare>> {
        match &self.model {
            Some(model) => {
                let energy = ModalEnergy::new(model, &self.dae);
                self.modal.modes.iter().map(|m| energy.shares(m)).collect()
            }
            None => vec![Vec::new(); self.modal.modes.len()],
        }
    }
}

pub fn load(a: &PencilArgs) -> Result<Loaded> {
    let (dae, dcoef, model) = match (&a.pencil, &a.model) {
        (Some(path), _) => {
            let ports = PencilPorts { input_rows: a.input_rows.clone(), output_cols: a.output_cols.clone() };
            let file = read_pencil_file(path, &ports)?;
            (file.dae, file.dcoef, None)
        }
        (None, Some(path)) => {
            let m = read_model(path)?;
            let st = reference_state(&m.model, &m.problem, a.reference.reference()).with_context(|| format!("{}: reference solution", path.display()))?;
            let dae = linearize(&m.model, &st, &a.inputs, &a.outputs, None)?;
            // The Λ form's dCoef: the file's eigenanalysis parameter (h/2) when it gives one.
            let dcoef = m.problem.eigenanalysis.as_ref().and_then(|e| e.dcoef);
            (dae, dcoef, Some(m.model))
        }
        (None, None) => anyhow::bail!("give a MODEL file or --pencil FILE"),
    };
    let modal = ModalAnalysis::compute_with_dcoef(&dae.jacobians, a.route.into(), a.dcoef.or(dcoef)).map_err(|e| anyhow::anyhow!(e.describe(&dae.unknown_names)))?;
    Ok(Loaded { dae, modal, model })
}
