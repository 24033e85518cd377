//! `romdyn cms`: a substructure in MBDyn's input language reduced to the FEM file of MBDyn's
//! modal joint with Craig–Bampton modes ([`romdyn::cms`]); prints the fixed-interface
//! frequencies and the card that attaches the file.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use romdyn::cms::{craig_bampton, CmsRequest};
use romdyn::model::Label;

use super::args::ReferenceArgs;

#[derive(Args, Debug)]
pub struct CmsArgs {
    /// MBDyn input file of the substructure: structural nodes, bodies, beams, deformable springs (no joints: it is free)
    #[arg(value_name = "MODEL")]
    pub file: PathBuf,
    /// Interface nodes (structural node labels, comma-separated): six constraint modes each (unit displacement [m], unit rotation [rad])
    #[arg(long, value_name = "NODE[,NODE…]", value_delimiter = ',', required = true)]
    pub interface: Vec<Label>,
    /// Fixed-interface normal modes kept (the lowest, unit modal mass)
    #[arg(long, value_name = "N")]
    pub modes: usize,
    /// Output prefix: writes PREFIX.fem (MBDyn's FEM file format, SI units)
    #[arg(short = 'o', long = "output", value_name = "PREFIX")]
    pub prefix: PathBuf,
    #[command(flatten)]
    pub reference: ReferenceArgs,
    /// A `set:` variable of the file given another value, NAME=VALUE in the file's (SI) units; repeatable
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<romdyn::sweep::Parameter>,
}

pub fn run(a: CmsArgs) -> Result<()> {
    // The output is checked before any work (a special file, a folder, a prefix naming no file).
    let path = romdyn::output::prefixed_path(&a.prefix, "fem");
    romdyn::output::atomic::check_prefix("-o", &a.prefix)?;
    romdyn::output::atomic::check_output_paths(&[("-o", path.clone())])?;
    let reference = a.reference.reference();
    let m = super::args::read_model_with_beams(&a.file, &a.set, romdyn::input::mbdyn::BeamUpdateChoice::Auto, reference.integrates())?;
    let request = CmsRequest { interfaces: a.interface.clone(), modes: a.modes, reference };
    let cb = match craig_bampton(&m.model, &m.problem, &request) {
        // The request's option named by its flag.
        Err(romdyn::cms::CmsError::Option { option, message }) => anyhow::bail!("{}: --{option}: {message}", a.file.display()),
        r => r.with_context(|| a.file.display().to_string())?,
    };
    for w in &cb.warnings {
        eprintln!("warning: {w}");
    }
    cb.write(&path, &a.file.display().to_string())?;
    print!("{}", cb.summary(&path));
    Ok(())
}
