//! `romdyn check`: every element's analytic Jacobian against finite differences of its
//! residual at the model's reference solution, then the whole model's assembled `F_/ẏ`,
//! `F_/y` against differences of the whole residual.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use romdyn::analysis::{check_model_jacobians, JACOBIAN_CHECK_TOLERANCE};

use super::args::ReferenceArgs;

#[derive(Args, Debug)]
pub struct CheckArgs {
    /// MBDyn input file
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    #[command(flatten)]
    pub reference: ReferenceArgs,
    /// Largest accepted max |analytic - fd| / max(max |J_element|, 1)
    #[arg(long, default_value_t = JACOBIAN_CHECK_TOLERANCE)]
    pub tolerance: f64,
    /// Rotation update of beam3 and beam2: auto (default: MBDyn 1.7.3's incremental one for a reference at a time, --at, path independent otherwise), path-independent, or incremental
    #[arg(long = "beam-update", value_parser = super::args::named::<romdyn::input::mbdyn::BeamUpdateChoice>(), default_value = "auto")]
    pub beam_update: romdyn::input::mbdyn::BeamUpdateChoice,
    /// A `set:` variable of the file given another value, NAME=VALUE in the file's (SI) units, replacing what its `set:` gives NAME; repeatable
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<romdyn::sweep::Parameter>,
}

pub fn run(a: CheckArgs) -> Result<()> {
    let integrates = a.reference.reference().integrates();
    let m = super::args::read_model_with_beams(&a.file, &a.set, a.beam_update, integrates)?;
    let check = check_model_jacobians(&m.model, &m.problem, a.reference.reference(), a.tolerance).with_context(|| format!("{}: reference solution", a.file.display()))?;
    print!("{}", check.to_text());
    let failed = check.failures().count();
    if failed > 0 {
        anyhow::bail!("{}: {failed} of {} elements have Jacobians that disagree with their residuals", a.file.display(), check.elements.len());
    }
    if !check.passed() {
        anyhow::bail!("{}: the whole model's assembled Jacobians disagree with the differences of its residual", a.file.display());
    }
    Ok(())
}
