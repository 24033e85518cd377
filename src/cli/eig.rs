//! `romdyn eig`: the modal table.

use anyhow::Result;
use clap::Args;
use romdyn::input::pencil::read_pencil;
use romdyn::linear::ModalAnalysis;
use romdyn::output::modal::ModalReport;

use super::args::PencilArgs;

#[derive(Args, Debug)]
pub struct EigArgs {
    #[command(flatten)]
    pub pencil: PencilArgs,
    /// Print JSON (equations, dcoef, eigenvalues: [{re, im, kind, freq_hz, damping, error}])
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: EigArgs) -> Result<()> {
    let file = read_pencil(&a.pencil.pencil)?;
    let modal = ModalAnalysis::compute_with_dcoef(&file.dae.jacobians, a.pencil.route.into(), a.pencil.dcoef.or(file.dcoef))?;
    let report = ModalReport::new(&modal, file.dae.dim());
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", report.to_text());
    }
    Ok(())
}
