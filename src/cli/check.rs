//! `romdyn check`: every element's analytic Jacobian against finite differences of its
//! residual at the model's reference solution.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use romdyn::analysis::{check_model_jacobians, JACOBIAN_CHECK_TOLERANCE};
use romdyn::input::mbdyn::read_model;

/// Compares each element's J(c) = F/y' + c F/y (c = b0 of the file's method and step [s]) with central finite differences of its residual, perturbing y' by h and y by c h (multipliers as Newton moves them), h = 1e-6 (1 + max(|y_j|, |y'_j|)). An element fails when max |analytic - fd| / max(max |J_element|, 1) exceeds the tolerance; exit status 1 if any fails.
#[derive(Args, Debug)]
pub struct CheckArgs {
    /// MBDyn input file
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// Check at the solution at TIME [s] (default: the initial time, after the initial derivatives)
    #[arg(long, value_name = "TIME")]
    pub at: Option<f64>,
    /// Largest relative disagreement accepted
    #[arg(long, default_value_t = JACOBIAN_CHECK_TOLERANCE)]
    pub tolerance: f64,
}

pub fn run(a: CheckArgs) -> Result<()> {
    let m = read_model(&a.file)?;
    let check = check_model_jacobians(&m.model, &m.problem, a.at, a.tolerance).with_context(|| format!("{}: reference solution", a.file.display()))?;
    print!("{}", check.to_text());
    let failed = check.failures().count();
    if failed > 0 {
        anyhow::bail!("{}: {failed} of {} elements have Jacobians that disagree with their residuals", a.file.display(), check.elements.len());
    }
    Ok(())
}
