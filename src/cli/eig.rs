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
    /// List every eigenvalue on its own row (by default a complex or ± real pair is one row and the zero and infinite eigenvalues are counted)
    #[arg(long)]
    pub all: bool,
}

pub fn run(a: EigArgs) -> Result<()> {
    let study = a.pencil.study()?;
    for w in study.warnings() {
        eprintln!("warning: {w}");
    }
    let report = study.modal_report();
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else if a.all {
        print!("{}", report.to_text_all());
    } else {
        print!("{}", report.to_text());
    }
    Ok(())
}
