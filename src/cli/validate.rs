//! `romdyn validate`: a ROM against the nonlinear model and measurements (library:
//! [`romdyn::validate`]); this file maps the arguments onto [`ValidateOptions`] and prints.

use std::io::IsTerminal;
use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use romdyn::output::atomic::{check_output_paths, check_prefix, write_set};
use romdyn::validate::{files, validate, SignalKind, ValidateOptions};

use super::args::{parse_band, PencilArgs};
use super::rom::RomChoiceArgs;

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum SignalArg {
    /// Gaussian noise low-pass (band-pass) filtered to the band (the paper's Fig. 7)
    Random,
    /// Sum of sines at the Welch bins in the band, Schroeder phases
    Multisine,
    /// Linear sweep across the band, once per Welch segment
    Chirp,
}

#[derive(Args, Debug)]
pub struct ValidateArgs {
    #[command(flatten)]
    pub pencil: PencilArgs,
    #[command(flatten)]
    pub rom: RomChoiceArgs,
    /// Writes PREFIX.csv (frequency [Hz]; per channel H1 estimate re/im, coherence, full model re/im, ROM re/im, in the channel's unit), PREFIX.time.csv (time [s], input [N or N m], nonlinear and ROM outputs [m, rad, m/s or rad/s] from the reference), PREFIX.svg and PREFIX.png (Bode overlay with coherence)
    #[arg(short = 'o', long = "out", value_name = "PREFIX")]
    pub prefix: PathBuf,
    /// Excitation
    #[arg(long, value_enum, default_value = "random")]
    pub signal: SignalArg,
    /// RMS of each input [N or N m], one validation per value (the linearity range; default: one, a static response of 1e-4 of the model's size or 1e-4 rad)
    #[arg(long, value_name = "A1,A2,...", value_delimiter = ',')]
    pub amplitudes: Vec<f64>,
    /// Excited and compared band [Hz] (default: 0 to twice the ROM's highest frequency of interest)
    #[arg(long, value_name = "FMIN:FMAX", value_parser = parse_band)]
    pub validation_band: Option<(f64, f64)>,
    /// Frequency resolution of the estimate [Hz] (default, from the kept modes the ports see: the lowest one's frequency / 20, or 1/8 of the narrowest damped one's half-power bandwidth if finer, at most 8 times finer)
    #[arg(long, value_name = "HZ")]
    pub resolution: Option<f64>,
    /// Welch segments (half overlap) the run lasts (N + 2)/2 of; the random input's estimate averages Hann segments overlapping by three quarters (about N independent ones)
    #[arg(long, value_name = "N", default_value_t = 8)]
    pub averages: usize,
    /// Integration step = sampling period [s] (default: 1/(80 x the band's top), smaller where the integrator's period error would exceed 0.5 % at a damped kept mode's peak or turn an undamped one's phase by 0.3 rad over the record)
    #[arg(long, value_name = "S")]
    pub time_step: Option<f64>,
    /// Seed of the random signal
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Bins with coherence at or above this are compared
    #[arg(long, value_name = "GAMMA2", default_value_t = 0.95)]
    pub coherence: f64,
    /// Largest relative error |H_ROM - H1|/|H1| the verdict accepts
    #[arg(long, value_name = "E", default_value_t = 0.1)]
    pub tolerance: f64,
    /// Smallest time-domain fit (NRMSE as MATLAB's compare, 1 = perfect) the verdict accepts
    #[arg(long, value_name = "FIT", default_value_t = 0.5)]
    pub fit: f64,
    /// A measured frequency response, CSV: 'frequency [Hz]', then per channel 'O/I re [UNIT]','O/I im [UNIT]' or 'O/I mag [UNIT]','O/I phase [deg]' (O, I: 1-based ROM output and input); overlaid and compared
    #[arg(long, value_name = "FILE.csv")]
    pub measured: Option<PathBuf>,
    /// Also write DIR/index.html: the report of `romdyn rom --report` with this validation in it (DIR/validation.{csv,time.csv,svg,png})
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
}

impl ValidateArgs {
    fn options(&self) -> ValidateOptions {
        let signal = match self.signal {
            SignalArg::Random => SignalKind::Random,
            SignalArg::Multisine => SignalKind::Multisine,
            SignalArg::Chirp => SignalKind::Chirp,
        };
        ValidateOptions { signal, amplitudes: self.amplitudes.clone(), band_hz: self.validation_band, resolution_hz: self.resolution, averages: self.averages, time_step: self.time_step, seed: self.seed, coherence: self.coherence, tolerance: self.tolerance, fit: self.fit, measured: self.measured.clone() }
    }
}

pub fn run(a: ValidateArgs) -> Result<()> {
    check_prefix("-o", &a.prefix)?;
    let paths = files::output_paths(&a.prefix);
    let mut outputs: Vec<(&str, PathBuf)> = paths.iter().map(|p| ("-o", p.clone())).collect();
    if let Some(dir) = &a.report {
        if dir.is_file() {
            bail!("--report: {} is a file; give a folder for index.html and its plots", dir.display());
        }
        outputs.extend(romdyn::output::report::Report::files(dir).map(|f| ("--report", f)));
        outputs.extend(files::output_paths(&dir.join("validation")).map(|f| ("--report", f)));
    }
    check_output_paths(&outputs)?;
    let options = a.options();
    options.check()?;
    let Some(path) = &a.pencil.model else { bail!("--pencil: validate runs the multibody model in time; give its MBDyn file") };
    let request = a.rom.request();
    let mut study = a.pencil.study(Some(&request))?;
    let (state, problem) = study.reference_and_problem()?;
    let rom = study.reduce(&request)?;
    for w in study.warnings().iter().chain(&rom.warnings) {
        eprintln!("warning: {w}");
    }
    let bar = if std::io::stderr().is_terminal() { ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr()) } else { ProgressBar::hidden() };
    bar.set_style(ProgressStyle::with_template("nonlinear run {bar:30} {pos}/{len} steps {elapsed} (eta {eta})").unwrap_or_else(|_| ProgressStyle::default_bar()));
    let result = validate(&mut study, &problem, &state, &a.pencil.ports()?, &rom, &options, &mut |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    let v = result.with_context(|| format!("validating the ROM of {}", path.display()))?;
    eprint!("{}", v.summary());
    if let Some(w) = v.warning() {
        eprintln!("warning: {w}");
    }
    // The report's Bode plot on the default grid, as `romdyn rom --report` draws it.
    let check = match &a.report {
        Some(_) => Some(study.check_rom(&rom, &romdyn::study::FrequencyGrid::default())?),
        None => None,
    };
    let (written, _) = write_set(&romdyn::analysis::journal_path(&paths[0]), || -> Result<Vec<PathBuf>, romdyn::output::atomic::OutputError> {
        let mut written = files::write_files(&v, &a.prefix, state.t)?.to_vec();
        if let (Some(dir), Some(check)) = (&a.report, &check) {
            std::fs::create_dir_all(dir).map_err(|cause| romdyn::output::atomic::OutputError::Io { path: dir.clone(), operation: "create the folder", cause })?;
            written.extend(files::write_files(&v, &dir.join("validation"), state.t)?);
            let mut report = study.report(&rom, check, &format!("ROM of {} validated against its nonlinear model", path.display()));
            report.figures.push(romdyn::output::report::Figure { heading: "Validation against the nonlinear model".into(), text: v.summary(), image: "validation.svg".into(), data: "validation.csv".into() });
            written.extend(report.write(dir, &check.comparison)?);
        }
        Ok(written)
    })?;
    eprintln!("wrote {}", written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "));
    Ok(())
}
