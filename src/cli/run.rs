//! `romdyn run`: the initial-value problem of an MBDyn input file with its eigenanalyses,
//! MBDyn-compatible files, a progress bar on a terminal and a summary.

use std::io::IsTerminal;
use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use romdyn::analysis::{run as run_problem, EigenDone, ObserverError, RunFiles, RunObserver, RunReport, RunStart, StepDone};
use romdyn::linear::hz;

#[derive(Args, Debug)]
pub struct RunArgs {
    /// MBDyn input file (its 'initial value' block sets times [s], method, step, tolerance, max iterations and eigenanalyses)
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// Output prefix: writes PREFIX.out, .mov, .log and PREFIX_K.m/.json for eigenanalysis K (0, 1, …; as MBDyn names them); an existing directory DIR means DIR/NAME with NAME the file's stem [default: NAME in the current directory, NAME the file's stem]
    #[arg(short = 'o', long = "out", value_name = "PREFIX")]
    pub prefix: Option<PathBuf>,
    /// Rotation update of beam3 and beam2: auto (default: MBDyn 1.7.3's incremental one, MBDyn's numbers, where a beam can take it), incremental (every beam, or an error), or path-independent (the beam a function of the state)
    #[arg(long = "beam-update", value_parser = super::args::named::<romdyn::input::mbdyn::BeamUpdateChoice>(), default_value = "auto")]
    pub beam_update: romdyn::input::mbdyn::BeamUpdateChoice,
    /// A `set:` variable of the file given another value, NAME=VALUE in the file's (SI) units, replacing what its `set:` gives NAME; repeatable
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<romdyn::sweep::Parameter>,
}

/// A progress bar on stderr (hidden when stderr is not a terminal).
struct Progress {
    bar: ProgressBar,
}

impl Progress {
    fn new() -> Self {
        let bar = if std::io::stderr().is_terminal() { ProgressBar::new(0) } else { ProgressBar::hidden() };
        let style = ProgressStyle::with_template("{bar:30} {pos}/{len} steps {msg} eta {eta}").unwrap_or_else(|_| ProgressStyle::default_bar());
        bar.set_style(style);
        Progress { bar }
    }
}

impl RunObserver for Progress {
    fn started(&mut self, e: &RunStart) -> Result<(), ObserverError> {
        self.bar.set_length(e.steps as u64);
        Ok(())
    }
    fn step(&mut self, e: &StepDone) -> Result<(), ObserverError> {
        self.bar.set_position(e.step as u64);
        self.bar.set_message(format!("t = {:.4} s", e.time));
        Ok(())
    }
    fn eigenanalysis(&mut self, e: &EigenDone) -> Result<(), ObserverError> {
        self.bar.set_message(format!("eigenanalysis {}", e.analysis.index));
        Ok(())
    }
}

/// A time [s] to 9 decimals, trailing zeros dropped (steps accumulate rounding in t).
fn seconds(t: f64) -> String {
    let s = format!("{t:.9}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}

fn print_summary(file: &str, r: &RunReport, written: &[PathBuf]) {
    println!(
        "romdyn run {file}: {} steps to t = {} s, {} Newton iterations (+{} for the initial derivatives; {} of all with a new Jacobian factorization), wall time {:.3} s",
        r.steps,
        seconds(r.final_state.t),
        r.newton_iterations,
        r.derivatives_iterations,
        r.factorizations,
        r.wall_time.as_secs_f64()
    );
    let a = &r.assembly;
    if a.iterations > 0 {
        println!(
            "initial assembly: {} iteration(s) (test {:.1e}); positions moved by up to {:.3e} m and {:.3e} rad, velocities by up to {:.3e} m/s and {:.3e} rad/s",
            a.iterations, a.test, a.moved_position, a.moved_rotation, a.moved_velocity, a.moved_angular_velocity
        );
    }
    for e in &r.eigenanalyses {
        if e.every_eigenvalue {
            println!("eigenanalysis {} at t = {} s (dCoef = {} s): {} dynamic, {} zero, {} infinite eigenvalues", e.index, seconds(e.time), e.dcoef, e.dynamic.len(), e.zero, e.infinite);
        } else {
            println!("eigenanalysis {} at t = {} s (dCoef = {} s): {} dynamic eigenvalues, {}", e.index, seconds(e.time), e.dcoef, e.dynamic.len(), e.solver);
        }
        const SHOWN: usize = 10;
        for l in e.dynamic.iter().take(SHOWN) {
            let (f, zeta) = (hz(l.norm()), if l.norm() > 0.0 { -l.re / l.norm() } else { 0.0 });
            // freq = |Im λ|/2π as `eig` and MBDyn's .out print it; undamped = |λ|/2π.
            println!("  λ = {:.6}{:+.6}j rad/s  (freq = {:.6} Hz, undamped = {f:.6} Hz, ζ = {:.4})", l.re, l.im, hz(l.im.abs()), if zeta.abs() < 5e-5 { 0.0 } else { zeta });
        }
        if e.dynamic.len() > SHOWN {
            println!("  … {} more (all of them in the .m and .json files)", e.dynamic.len() - SHOWN);
        }
    }
    if !r.eigen_times_not_reached.is_empty() {
        let times: Vec<String> = r.eigen_times_not_reached.iter().map(|t| seconds(*t)).collect();
        println!("eigenanalyses not done (the run ended first): t = {} s", times.join(", "));
    }
    let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    println!("wrote {}", names.join(", "));
}

pub fn run(a: RunArgs) -> Result<()> {
    let m = super::args::read_model_with_beams(&a.file, &a.set, a.beam_update, true)?;
    let input = a.file.display().to_string();
    if m.model.nodes.is_empty() && m.model.scalar_nodes.is_empty() {
        anyhow::bail!("{input}: the model has no structural or scalar nodes: nothing to run, no file written");
    }
    let stem = a.file.file_stem().map(PathBuf::from).unwrap_or_else(|| PathBuf::from("romdyn"));
    let prefix = match &a.prefix {
        Some(dir) if dir.is_dir() => dir.join(stem),
        Some(p) => p.clone(),
        None => stem,
    };
    romdyn::output::atomic::check_prefix("-o", &prefix)?;
    romdyn::output::atomic::check_output_paths(&[("-o", romdyn::output::prefixed_path(&prefix, "out"))])?;
    let files = RunFiles::create(&prefix, &input, &m.model, &m.problem).with_context(|| format!("starting the output files {}.*", prefix.display()))?;
    let mut observers = (Progress::new(), files);
    let result = run_problem(&m.model, &m.problem, &mut observers);
    let (progress, files) = observers;
    progress.bar.finish_and_clear();
    let report = match result {
        Ok(report) => report,
        Err(error) => {
            // What converged is kept for the user to see where the motion went (as MBDyn
            // leaves its files); the exit status says the run failed.
            let why = error.to_string();
            return match files.finish_failed(&why).with_context(|| format!("{input}: the run failed ({why}), and its output files could not be put in place"))? {
                Some((written, step, time)) => {
                    let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
                    Err(anyhow::Error::new(error).context(format!(
                        "{input}: the run failed; the files hold the solution up to the last converged step {step} (t = {} s), with the failure as the .out file's last line: {}",
                        seconds(time),
                        names.join(", ")
                    )))
                }
                None => Err(anyhow::Error::new(error).context(format!("{input}: the run failed before any step converged; no output file was written"))),
            };
        }
    };
    let written = files.finish(&report)?;
    print_summary(&input, &report, &written);
    for w in report.warnings() {
        eprintln!("warning: {w}");
    }
    Ok(())
}
