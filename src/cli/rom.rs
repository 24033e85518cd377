//! `romdyn rom` and `romdyn freq`: reduced-order models and their frequency responses.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::builder::{PossibleValue, PossibleValuesParser};
use clap::Args;
use romdyn::output::atomic::{check_output_paths, check_prefix, write_set};
use romdyn::linear::FrequencyResponse;
use romdyn::output::frequency_plot::write_bode_files as write_response_plot;
use romdyn::output::rom_file::RomExport;
use romdyn::output::mimo_plot::MimoPlot;
use romdyn::rom::{ModalDamping, ModeSelection, Ranking};
use romdyn::study::{BelowBand, ReducedModel, Residualization, RomCheck, RomForm, RomRequest, Study, Warning, DISCRETIZATIONS};

use super::args::{named, parse_band, parse_damping, FrequencyArgs, PencilArgs, SelectionArgs};

/// Which ROM to build: modes, residualization, ranking, damping, form (`rom` and `sweep`).
#[derive(Args, Debug)]
pub struct RomChoiceArgs {
    #[command(flatten)]
    pub select: SelectionArgs,
    /// Statically residualize the dynamic modes that were not selected (paper Fig. 7)
    #[arg(long, conflicts_with = "residualize_modes")]
    pub residualize: bool,
    /// Statically residualize only these modes (1-based indices of the modal table; a pair counts once), e.g. the third bending mode of a beam
    #[arg(long, value_name = "I,J,...", value_delimiter = ',')]
    pub residualize_modes: Option<Vec<usize>>,
    /// Rank modes for --count and --band by natural frequency or by dominance for these inputs and outputs
    #[arg(long, value_parser = named::<Ranking>(), default_value = "frequency")]
    pub by: Ranking,
    /// What --residualize does with a dropped mode below the frequencies of interest (the band's top, or the highest kept mode): static residualization is valid only above them
    #[arg(long, value_parser = named::<BelowBand>(), default_value = "drop")]
    pub below_band: BelowBand,
    /// Modal damping ratio added to the ROM (never to the full model): ZETA for every kept mode, or K=ZETA,... by modal-table index; reported in the summary
    #[arg(long, value_name = "ZETA|K=ZETA,...", value_parser = parse_damping)]
    pub damping: Option<ModalDamping>,
    /// Which form to export
    #[arg(long, value_parser = named::<RomForm>(), default_value = "ordinary")]
    pub form: RomForm,
}

impl RomChoiceArgs {
    pub fn request(&self) -> RomRequest {
        let residualization = match (&self.residualize_modes, self.residualize) {
            (Some(list), _) => Residualization::Modes(list.clone()),
            (None, true) => Residualization::Dropped,
            (None, false) => Residualization::None,
        };
        let mut request = RomRequest::new(self.select.selection()).residualize(residualization).ranked_by(self.by);
        request.below_band = self.below_band;
        request.damping = self.damping.clone();
        request
    }

    pub fn form(&self) -> RomForm {
        self.form
    }
}

/// The control hand-off of `rom`: minimal realization, balanced reduction, discrete time.
#[derive(Args, Debug)]
pub struct ControlArgs {
    /// Remove uncontrollable and unobservable states: those whose Hankel singular value (of the system shifted to make every mode stable) is below TOL times the largest, e.g. 1e-10; the summary says how many
    #[arg(long, value_name = "TOL")]
    pub minimal: Option<f64>,
    /// Balanced truncation to N states in all: the stable part is reduced, rigid-body, integrator (λ = 0) and unstable modes are kept whole; Hankel singular values and the error bound 2 Σ dropped σ in the summary (undamped modes are not stable: add --damping)
    #[arg(long, value_name = "N")]
    pub balanced: Option<usize>,
    /// Balanced truncation keeping the stable states whose Hankel singular value exceeds TOL times the largest
    #[arg(long, value_name = "TOL")]
    pub hankel_tol: Option<f64>,
    /// With --balanced or --hankel-tol: singular perturbation approximation instead of truncation (the static gain is kept; same error bound)
    #[arg(long)]
    pub spa: bool,
    /// Discrete-time ROM at FS [Hz] (x[k+1] = A x[k] + B u[k], sampling time 1/FS s), e.g. 2048 for the paper's HAM-SAS controller; the export stores the sampling time and says discrete
    #[arg(long, value_name = "FS")]
    pub sample_rate: Option<f64>,
    /// Discretization: zoh (zero-order hold: exact for inputs held between samples), tustin (bilinear; DC gain kept) or matched (pole-zero mapping, one input and one output)
    #[arg(long, value_name = "METHOD", value_parser = PossibleValuesParser::new(DISCRETIZATIONS.map(|(name, what)| PossibleValue::new(name).help(what))), default_value = "zoh")]
    pub discretize: String,
    /// Tustin's prewarping frequency [Hz] (the discrete response is exact there), below FS/2
    #[arg(long, value_name = "HZ")]
    pub prewarp: Option<f64>,
}

impl ControlArgs {
    /// `request` with these options, checked by the library.
    pub fn apply(&self, mut request: RomRequest) -> Result<RomRequest, romdyn::study::StudyError> {
        request.minimal = romdyn::study::minimal_tolerance(self.minimal)?;
        request.balanced = romdyn::study::balancing(self.balanced, self.hankel_tol, self.spa)?;
        request.sampling = romdyn::study::sampling(self.sample_rate, &self.discretize, self.prewarp)?;
        Ok(request)
    }
}

#[derive(Args, Debug)]
pub struct RomArgs {
    #[command(flatten)]
    pub pencil: PencilArgs,
    #[command(flatten)]
    pub rom: RomChoiceArgs,
    #[command(flatten)]
    pub control: ControlArgs,
    /// ROM file: .json, .mat (MATLAB v5), .npz (NumPy), .m (an Octave/MATLAB script building sys with ss/dss, names and units) or .fmu (an FMI 2.0 FMU, model exchange and co-simulation, built with the C compiler $CC or cc); JSON to stdout if absent
    #[arg(short = 'o', long = "out", value_name = "FILE")]
    pub file: Option<PathBuf>,
    /// Also write PREFIX.csv, PREFIX.svg and PREFIX.png: Bode plot of the full model and the ROM
    #[arg(long, value_name = "PREFIX")]
    pub bode: Option<PathBuf>,
    /// Also write DIR/index.html: a report to open in a browser (summary, warnings, modal table, Bode plot DIR/bode.{csv,svg,png}, each kept mode's shape animated in 3-D on the model's nodes)
    #[arg(long, value_name = "DIR")]
    pub report: Option<PathBuf>,
    /// Also write PREFIX.{csv,svg,png}: the transfer matrix as a grid of Bode-magnitude panels, full model and ROM (paper Figs. 9, 10)
    #[arg(long, value_name = "PREFIX")]
    pub grid: Option<PathBuf>,
    /// Only the diagonal panels of --grid and --transmissibility
    #[arg(long)]
    pub diagonal: bool,
    /// With an imposed motion (--imposed or the ports file): write PREFIX.{csv,svg,png}, the transmissibility z/z_e of eq. 100, full model and ROM, log-log (paper Fig. 11)
    #[arg(long, value_name = "PREFIX")]
    pub transmissibility: Option<PathBuf>,
    /// With an imposed motion: write the proper state-space model from the imposed displacements to the other outputs (.json/.mat/.npz/.m)
    #[arg(long, value_name = "FILE")]
    pub imposed_out: Option<PathBuf>,
    #[command(flatten)]
    pub freq: FrequencyArgs,
}

#[derive(Args, Debug)]
pub struct FreqArgs {
    #[command(flatten)]
    pub pencil: PencilArgs,
    /// Overlay the ROM keeping the N lowest dynamic modes
    #[arg(long, value_name = "N")]
    pub count: Option<usize>,
    /// Overlay the ROM keeping the modes in FMIN:FMAX Hz
    #[arg(long, value_name = "FMIN:FMAX", value_parser = parse_band)]
    pub band: Option<(f64, f64)>,
    /// Statically residualize the modes the overlaid ROM drops (above the frequencies of interest)
    #[arg(long)]
    pub residualize: bool,
    /// Rank modes for --count and --band by natural frequency or by dominance for these inputs and outputs
    #[arg(long, value_parser = named::<Ranking>(), default_value = "frequency")]
    pub by: Ranking,
    /// Modal damping ratio added to the overlaid ROM: ZETA, or K=ZETA,...
    #[arg(long, value_name = "ZETA|K=ZETA,...", value_parser = parse_damping)]
    pub damping: Option<ModalDamping>,
    /// Writes PREFIX.csv, PREFIX.svg, PREFIX.png
    #[arg(short = 'o', long = "out", value_name = "PREFIX")]
    pub prefix: PathBuf,
    #[command(flatten)]
    pub freq: FrequencyArgs,
}

fn print_warnings(w: &[Warning]) {
    for w in w {
        eprintln!("warning: {w}");
    }
}

fn print_study(study: &Study) {
    print_warnings(study.warnings());
}

/// Writes PREFIX.csv, PREFIX.svg and PREFIX.png (into the command's set); returns the line
/// that says so.
fn write_bode_files(r: &FrequencyResponse, prefix: &Path) -> Result<String> {
    let [csv, svg, png] = write_response_plot(r, prefix, "Frequency response").with_context(|| format!("writing {}.{{csv,svg,png}}", prefix.display()))?;
    Ok(format!("wrote {}, {}, {}", csv.display(), svg.display(), png.display()))
}

/// PREFIX.csv, PREFIX.svg and PREFIX.png of option `option`, for the checks before any work.
fn plot_files(option: &'static str, prefix: &Path) -> Result<[(&'static str, PathBuf); 3]> {
    check_prefix(option, prefix)?;
    Ok(["csv", "svg", "png"].map(|e| (option, romdyn::output::prefixed_path(prefix, e))))
}

/// Runs `write` (whose lines say what it wrote) with the command's files as one set
/// ([`write_set`]): all of them in place at the end, or none; then prints the lines.
fn write_outputs(outputs: &[(&str, PathBuf)], write: impl FnOnce() -> Result<Vec<String>>) -> Result<()> {
    let Some((_, first)) = outputs.first() else {
        write()?;
        return Ok(());
    };
    let (lines, _) = write_set(&romdyn::analysis::journal_path(first), write)?;
    for l in lines {
        eprintln!("{l}");
    }
    Ok(())
}

/// Every file `rom` will write, each with its option.
fn rom_outputs(a: &RomArgs) -> Result<Vec<(&'static str, PathBuf)>> {
    let mut out = Vec::new();
    if let Some(path) = &a.file {
        RomExport::check_path(path)?;
        out.push(("-o", path.clone()));
    }
    if let Some(prefix) = &a.bode {
        out.extend(plot_files("--bode", prefix)?);
    }
    if let Some(prefix) = &a.grid {
        out.extend(plot_files("--grid", prefix)?);
    }
    if let Some(dir) = &a.report {
        if dir.is_file() {
            anyhow::bail!("--report: {} is a file; give a folder for index.html and its plots", dir.display());
        }
        out.extend(romdyn::output::report::Report::files(dir).map(|f| ("--report", f)));
    }
    if let Some(prefix) = &a.transmissibility {
        out.extend(plot_files("--transmissibility", prefix)?);
        if !a.diagonal {
            out.extend(plot_files("--transmissibility", &romdyn::output::prefixed_path(prefix, "diagonal"))?);
        }
    }
    if let Some(path) = &a.imposed_out {
        RomExport::check_path(path)?;
        out.push(("--imposed-out", path.clone()));
    }
    check_output_paths(&out)?;
    Ok(out)
}

pub fn run(a: RomArgs) -> Result<()> {
    let outputs = rom_outputs(&a)?;
    let request = a.control.apply(a.rom.request())?;
    let study = a.pencil.study(Some(&request))?;
    let rom = study.reduce(&request)?;
    rom.check_form(a.rom.form())?;
    // Every response asked for against the full model on the grid (the library's check,
    // the same Python's reduce() runs).
    let check = study.check_rom(&rom, &a.freq.grid())?;
    eprint!("{}", study.modal_report().to_text_dynamic(12));
    print_study(&study);
    eprint!("{}", rom.summary(&study, Some(&check)));
    print_warnings(&rom.new_warnings(&study, Some(&check)));
    if let Some(free) = study.free_eigenvalues(&rom) {
        eprint!("{free}");
    }
    let export = rom.export(&study, a.rom.form());
    if a.file.is_none() {
        println!("{}", serde_json::to_string_pretty(&export.to_json())?);
    }
    write_outputs(&outputs, || {
        let mut lines = Vec::new();
        if let Some(path) = &a.file {
            export.write(path).with_context(|| format!("writing {}", path.display()))?;
            lines.push(format!("wrote {}", path.display()));
        }
        if let Some(prefix) = &a.bode {
            lines.push(write_bode_files(&check.comparison, prefix)?);
        }
        if let Some(dir) = &a.report {
            let source = a.pencil.model.as_ref().or(a.pencil.pencil.as_ref()).map_or(String::new(), |p| p.display().to_string());
            let report = study.report(&rom, &check, &format!("ROM of {source}"));
            let files = report.write(dir, &check.comparison).with_context(|| format!("writing the report in {}", dir.display()))?;
            lines.push(format!("wrote {} (open it in a browser) and {}/bode.{{csv,svg,png}}", files[0].display(), dir.display()));
        }
        lines.extend(write_application_files(&a, &study, &rom, &check)?);
        Ok(lines)
    })
}

/// --grid, --transmissibility, --imposed-out; returns the lines that say what was written.
fn write_application_files(a: &RomArgs, study: &Study, rom: &ReducedModel, check: &RomCheck) -> Result<Vec<String>> {
    let mut lines = Vec::new();
    let mut wrote = |p: [PathBuf; 3]| lines.push(format!("wrote {}, {}, {}", p[0].display(), p[1].display(), p[2].display()));
    if let Some(prefix) = &a.grid {
        let plot = study.transfer_panels(check, a.diagonal);
        wrote(plot.write_files(prefix).with_context(|| format!("writing {}.{{csv,svg,png}}", prefix.display()))?);
    }
    if let Some(prefix) = &a.transmissibility {
        // The checked transmissibility, or the error that kept it from being formed.
        let t = match &check.transmissibility {
            Some((t, _)) => t.clone(),
            None => study.transmissibility(rom, &check.comparison.freq_hz)?,
        };
        let mut plot = MimoPlot { title: "Transmissibility |z/z_e| (eq. 100)".into(), response: t, diagonal: a.diagonal };
        wrote(plot.write_files(prefix).with_context(|| format!("writing {}.{{csv,svg,png}}", prefix.display()))?);
        // The diagonal alone (x/x, y/y, …: paper Fig. 11) beside the whole matrix.
        if !plot.diagonal {
            plot.diagonal = true;
            let diag = romdyn::output::prefixed_path(prefix, "diagonal");
            wrote(plot.write_files(&diag).with_context(|| format!("writing {}.{{csv,svg,png}}", diag.display()))?);
        }
    }
    if let Some(path) = &a.imposed_out {
        let m = study.imposed_model(rom)?;
        let eig: Vec<String> = m.rom.eigenvalues.iter().map(|l| format!("{:.6}{:+.6}j", l.re, l.im)).collect();
        eprintln!("imposed-motion model: {} states, eigenvalues {}", m.rom.a.nrows(), eig.join(", "));
        let discrete = study.imposed_discrete(&m, rom)?;
        study.imposed_export(&m, discrete.as_ref()).write(path).with_context(|| format!("writing {}", path.display()))?;
        lines.push(format!("wrote {}", path.display()));
    }
    Ok(lines)
}

pub fn run_freq(a: FreqArgs) -> Result<()> {
    let outputs = plot_files("-o", &a.prefix)?;
    check_output_paths(&outputs)?;
    let selection = match (&a.count, &a.band) {
        (Some(n), _) => Some(ModeSelection::Lowest(*n)),
        (None, Some((fmin_hz, fmax_hz))) => Some(ModeSelection::Band { fmin_hz: *fmin_hz, fmax_hz: *fmax_hz }),
        (None, None) => None,
    };
    let request = selection.map(|sel| {
        let residualization = if a.residualize { Residualization::Dropped } else { Residualization::None };
        let mut request = RomRequest::new(sel).residualize(residualization).ranked_by(a.by);
        request.damping = a.damping.clone();
        request
    });
    let study = a.pencil.study(request.as_ref())?;
    print_study(&study);
    let curves = match &request {
        Some(request) => {
            let rom = study.reduce(request)?;
            let check = study.check_rom(&rom, &a.freq.grid())?;
            print_warnings(&rom.new_warnings(&study, Some(&check)));
            check.comparison
        }
        None => study.full_responses(study.frequencies(&a.freq.grid(), &[])?)?,
    };
    write_outputs(&outputs, || Ok(vec![write_bode_files(&curves, &a.prefix)?]))
}
