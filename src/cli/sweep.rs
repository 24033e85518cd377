//! `romdyn sweep`: ROMs of an MBDyn file over design points of its `set:` variables.

use std::io::IsTerminal;
use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use romdyn::input::text_file::read_text_file;
use romdyn::output::atomic::{check_output_paths, check_prefix, write_set};
use romdyn::output::prefixed_path;
use romdyn::sweep::{check_lowest, check_parameters, grid, interpolation_point, run_point, sweep, worker_threads, SweepOptions};

use super::args::PencilArgs;
use super::rom::{ControlArgs, RomChoiceArgs};

#[derive(Args, Debug)]
pub struct SweepArgs {
    #[command(flatten)]
    pub pencil: PencilArgs,
    #[command(flatten)]
    pub rom: RomChoiceArgs,
    // Discrete-time ROMs at every point (--sample-rate, --discretize, --prewarp, as `romdyn rom`:
    // the states stay the modal ones, so the stacked arrays interpolate); --balanced and
    // --minimal are refused by the library (each point has its own basis).
    #[command(flatten)]
    pub control: ControlArgs,
    /// Number of lowest dynamic modes of the full model at the first design point, followed through the others by their shapes (MAC), in the table, plot and arrays (a pair counts once)
    #[arg(long, value_name = "N", default_value_t = 4)]
    pub lowest: usize,
    /// Start each static equilibrium (--static) from the previous design point's (the points then run one after the other)
    #[arg(long, requires = "static_equilibrium")]
    pub continuation: bool,
    /// Stacked arrays of every design point (.mat or .npz): E A B C D (n x n x K, point k is A(:,:,k)) in the tracked modes' consistent basis with state_tracks, parameters (K x P), point_ok, point_errors, mode_* (K x N, tracked modes) with mode_labels, mode_mac, mode_crossing, mode_flags, names and units
    #[arg(short = 'o', long = "out", value_name = "FILE")]
    pub file: Option<PathBuf>,
    /// Write the table of the lowest modes against the parameters as CSV here (default: stdout)
    #[arg(long, value_name = "FILE.csv")]
    pub table: Option<PathBuf>,
    /// Also write PREFIX.svg and PREFIX.png: frequency [Hz] and damping ratio of the tracked modes against one parameter (Campbell diagram; crosses mark ambiguous matches)
    #[arg(long, value_name = "PREFIX")]
    pub plot: Option<PathBuf>,
    /// The parameter on the plot's horizontal axis (default: the first --set)
    #[arg(long, value_name = "NAME", requires = "plot")]
    pub against: Option<String>,
    /// A ROM between the design points: NAME=VALUE for each swept parameter (repeatable), interpolated from the stacked ROMs in the tracked modes' basis (linearly between the grid values around it) and checked against the ROM computed there (relative differences printed)
    #[arg(long, value_name = "NAME=VALUE")]
    pub interpolate: Vec<romdyn::sweep::Parameter>,
    /// Write the interpolated ROM (--interpolate) here (.json, .mat or .npz; the layout of romdyn rom -o)
    #[arg(long, value_name = "FILE", requires = "interpolate")]
    pub interpolated: Option<PathBuf>,
    /// Design points computed at once, 1 to the number of cores (default: the number of cores; more are reduced to it with a warning)
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,
}

pub fn run(a: SweepArgs) -> Result<()> {
    let Some(path) = a.pencil.model.clone().filter(|_| a.pencil.pencil.is_none()) else { bail!("romdyn sweep needs a MODEL file (MBDyn input), not --pencil") };
    let (jobs, reduced) = worker_threads(a.jobs).map_err(|e| anyhow::anyhow!("--jobs {e}"))?;
    if let Some(w) = reduced {
        eprintln!("warning: --jobs {w}");
    }
    if let Some(name) = &a.against
        && !a.pencil.set.iter().any(|p| &p.name == name)
    {
        bail!("--against {name}: not a swept parameter (--set gives {})", a.pencil.set.iter().map(|p| p.name.as_str()).collect::<Vec<_>>().join(", "));
    }
    // Every output path checked before any work; written as one set at the end.
    let mut outputs: Vec<(&str, PathBuf)> = Vec::new();
    outputs.extend(a.file.iter().map(|p| ("-o", p.clone())));
    outputs.extend(a.table.iter().map(|p| ("--table", p.clone())));
    if let Some(p) = &a.interpolated {
        romdyn::output::rom_file::RomExport::check_path(p).map_err(|e| anyhow::anyhow!("--interpolated {e}"))?;
        outputs.push(("--interpolated", p.clone()));
    }
    if let Some(prefix) = &a.plot {
        check_prefix("--plot", prefix)?;
        outputs.extend(["svg", "png"].map(|e| ("--plot", prefixed_path(prefix, e))));
    }
    check_output_paths(&outputs)?;
    let points = grid(&a.pencil.set)?;
    // The mode arrays hold points x lowest values of each kind: checked before allocating.
    check_lowest(a.lowest, points.len()).map_err(|e| anyhow::anyhow!("--lowest {e}"))?;
    let text = read_text_file(&path).map_err(|e| anyhow::anyhow!("{}: {}", path.display(), e.message))?;
    let names: Vec<String> = a.pencil.set.iter().map(|p| p.name.clone()).collect();
    check_parameters(&text, &path, &names)?;
    let at = if a.interpolate.is_empty() { None } else { Some(interpolation_point(&a.pencil.set, &a.interpolate).map_err(|e| anyhow::anyhow!("--interpolate {e}"))?) };
    let options = SweepOptions {
        reference: a.pencil.reference.reference(),
        ports: a.pencil.ports()?,
        eigen: a.pencil.eigen(),
        rom: a.control.apply(a.rom.request())?,
        form: a.rom.form(),
        modes: a.lowest,
        continuation: a.continuation,
        beam_update: a.pencil.beam_update,
    };
    options.check()?;
    let bar = if std::io::stderr().is_terminal() { ProgressBar::new(points.len() as u64) } else { ProgressBar::hidden() };
    bar.set_style(ProgressStyle::with_template("{bar:30} {pos}/{len} design points eta {eta}").unwrap_or_else(|_| ProgressStyle::default_bar()));
    let pool = rayon::ThreadPoolBuilder::new().num_threads(jobs).build().context("starting the worker threads")?;
    let results = pool.install(|| sweep(&text, &path, &names, points, &options, &|| bar.inc(1)));
    bar.finish_and_clear();
    let failed: Vec<_> = results.failures().map(|(k, _, e)| (k, e.to_string())).collect();
    for (k, e) in &failed {
        eprintln!("design point {} ({}) failed: {e}", k + 1, results.describe_point(*k));
    }
    for (k, r) in results.results.iter().enumerate() {
        for w in r.as_ref().map_or(&[][..], |r| r.warnings.as_slice()) {
            eprintln!("warning: design point {} ({}): {w}", k + 1, results.describe_point(k));
        }
    }
    if a.table.is_none() {
        print!("{}", results.modes_csv());
    }
    let interpolated = match &at {
        Some(values) => {
            let exact = run_point(&text, &path, &names, values, &options, None).map_err(|e| anyhow::anyhow!("--interpolate: the ROM at the point itself failed: {e}"))?;
            let (rom, _, check) = results.check_interpolation(values, &exact)?;
            let point: Vec<String> = names.iter().zip(values).map(|(n, v)| format!("{n} = {v}")).collect();
            eprintln!("interpolated ROM at {} ({} states) against the ROM computed there: {}", point.join(", "), rom.a.nrows(), check.describe());
            Some(rom)
        }
        None => None,
    };
    if let Some((_, first)) = outputs.first() {
        let journal = romdyn::analysis::journal_path(first);
        let ((), written) = write_set(&journal, || -> Result<()> {
            if let Some(p) = &a.table {
                results.write_modes_csv(p).with_context(|| format!("writing {}", p.display()))?;
            }
            if let Some(p) = &a.file {
                results.write_arrays(p).with_context(|| format!("writing {}", p.display()))?;
            }
            if let (Some(p), Some(rom)) = (&a.interpolated, &interpolated) {
                rom.write(p).with_context(|| format!("writing {}", p.display()))?;
            }
            if let Some(prefix) = &a.plot {
                results.write_plot(prefix, a.against.as_deref()).with_context(|| format!("writing {}.{{svg,png}}", prefix.display()))?;
            }
            Ok(())
        })?;
        let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        eprintln!("wrote {} ({} design points; in the arrays point_ok marks the failed ones)", names.join(", "), results.points.len());
    }
    if !failed.is_empty() {
        bail!("{} of {} design points failed (listed above); the outputs hold the others, point_ok = 0 and point_errors mark the failed ones", failed.len(), results.points.len());
    }
    Ok(())
}
