//! `romdyn eig`: the modal table.

use anyhow::Result;
use clap::Args;
use romdyn::output::modal::ModalReport;

use super::args::PencilArgs;
use super::load::load;

#[derive(Args, Debug)]
pub struct EigArgs {
    #[command(flatten)]
    pub pencil: PencilArgs,
    /// Print JSON (equations, dcoef, eigenvalues: [{re, im, kind, freq_hz, damping, error}])
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: EigArgs) -> Result<()> {
    let loaded = load(&a.pencil)?;
    let report = ModalReport::new(&loaded.modal, loaded.dae.dim()).with_energy(loaded.energy());
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", report.to_text());
    }
    Ok(())
}
