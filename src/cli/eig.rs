//! `romdyn eig`: the modal table.

use anyhow::Result;
use clap::Args;

use romdyn::rom::ModeSelection;
use romdyn::study::RomRequest;

use super::args::{parse_band, parse_count, PencilArgs};

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
    /// Only the N lowest dynamic modes (a complex or ± real pair is one mode); the same rows on both --solver routes
    #[arg(long, value_name = "N", value_parser = parse_count, conflicts_with = "band")]
    pub count: Option<usize>,
    /// Only the dynamic modes with natural frequency |λ|/2π in [FMIN, FMAX] Hz; the same rows on both --solver routes
    #[arg(long, value_name = "FMIN:FMAX", value_parser = parse_band)]
    pub band: Option<(f64, f64)>,
}

pub fn run(a: EigArgs) -> Result<()> {
    let selection = match (a.count, a.band) {
        (Some(n), _) => Some(ModeSelection::Lowest(n)),
        (None, Some((fmin_hz, fmax_hz))) => Some(ModeSelection::Band { fmin_hz, fmax_hz }),
        (None, None) => None,
    };
    let study = a.pencil.study(selection.clone().map(RomRequest::new).as_ref())?;
    for w in study.warnings() {
        eprintln!("warning: {w}");
    }
    let report = study.modal_report_of(selection.as_ref())?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else if a.all {
        print!("{}", report.to_text_all());
    } else {
        print!("{}", report.to_text());
    }
    Ok(())
}
