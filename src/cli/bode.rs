//! The frequency grid of `--bode` / `romdyn freq` from the command line.

use std::path::Path;

use anyhow::{Context, Result};
use faer::c64;
use romdyn::linear::{LinearDae, ModalAnalysis};
use romdyn::output::frequency_plot::{default_band, FrequencyResponses};
use romdyn::rom::frequency_grid;

use super::args::FrequencyArgs;

/// The full model's response on the requested grid (default: around `focus`).
pub fn full_responses(dae: &LinearDae, modal: &ModalAnalysis, f: &FrequencyArgs, focus: &[c64]) -> Result<FrequencyResponses> {
    let (lo, hi) = default_band(modal, focus);
    Ok(FrequencyResponses::full(dae, frequency_grid(f.fmin.unwrap_or(lo), f.fmax.unwrap_or(hi), f.points.max(2))?))
}

/// Writes PREFIX.csv, PREFIX.svg and PREFIX.png.
pub fn write_bode_files(r: &FrequencyResponses, prefix: &Path) -> Result<()> {
    let [csv, svg, png] = r.write_files(prefix, "Frequency response").with_context(|| format!("writing {}.{{csv,svg,png}}", prefix.display()))?;
    eprintln!("wrote {}, {}, {}", csv.display(), svg.display(), png.display());
    Ok(())
}
