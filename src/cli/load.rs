//! The linear DAE a command works on: from a pencil file, or from an MBDyn model linearized
//! at its initial time (after consistent initial derivatives, as MBDyn does).

use anyhow::{Context, Result};
use romdyn::dae::{kinetic_energy_shares, linearize, Assembler, EnergyShare, State};
use romdyn::input::mbdyn::read_model;
use romdyn::input::pencil::read_pencil;
use romdyn::linear::{LinearDae, ModalAnalysis};
use romdyn::model::Model;
use romdyn::solve::{initial_derivatives, NewtonSettings};

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
            Some(model) => self.modal.modes.iter().map(|m| kinetic_energy_shares(model, &self.dae, m)).collect(),
            None => vec![Vec::new(); self.modal.modes.len()],
        }
    }
}

pub fn load(a: &PencilArgs) -> Result<Loaded> {
    let (dae, dcoef, model) = match (&a.pencil, &a.model) {
        (Some(path), _) => {
            let file = read_pencil(path)?;
            (file.dae, file.dcoef, None)
        }
        (None, Some(path)) => {
            let m = read_model(path)?;
            let asm = Assembler::new(&m.model);
            let mut st = State::initial(&m.model, &asm.dofs);
            st.t = m.problem.initial_time;
            let settings = NewtonSettings { tolerance: m.problem.tolerance, max_iterations: m.problem.max_iterations.max(20), ..Default::default() };
            initial_derivatives(&asm, &mut st, &settings).with_context(|| format!("{}: initial derivatives", path.display()))?;
            let dae = linearize(&m.model, &st, &a.inputs, &a.outputs, None)?;
            drop(asm);
            (dae, None, Some(m.model))
        }
        (None, None) => anyhow::bail!("give a MODEL file or --pencil FILE"),
    };
    let modal = ModalAnalysis::compute_with_dcoef(&dae.jacobians, a.route.into(), a.dcoef.or(dcoef))?;
    Ok(Loaded { dae, modal, model })
}
