//! `romdyn eig`: the modal table.

use anyhow::Result;
use clap::Args;

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
    let report = a.pencil.study()?.modal_report();
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{}", report.to_text());
    }
    Ok(())
}
