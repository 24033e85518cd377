//! `romdyn rom` and `romdyn freq`: reduced-order models and their frequency responses.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use romdyn::output::frequency_plot::FrequencyResponses;
use romdyn::output::rom_file::RomExport;
use romdyn::rom::ModeSelection;
use romdyn::output::mimo_plot::MimoPlot;
use romdyn::rom::full_frequency_response;
use romdyn::study::{ReducedModel, Residualization, RomRequest, StaticGains, Study};

use super::args::{parse_band, FrequencyArgs, PencilArgs, SelectionArgs};

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Form {
    /// x' = A x + B u, z = C x + D u (E = I), after SVD residualization (eqs. 51–63)
    Ordinary,
    /// E x' = A x + B u, z = C x (eqs. 47–50)
    Descriptor,
}

#[derive(Args, Debug)]
pub struct RomArgs {
    #[command(flatten)]
    pub pencil: PencilArgs,
    #[command(flatten)]
    pub select: SelectionArgs,
    /// Statically residualize the dynamic modes that were not selected (paper Fig. 7)
    #[arg(long, conflicts_with = "residualize_modes")]
    pub residualize: bool,
    /// Statically residualize only these modes (1-based indices of the modal table; a pair counts once), e.g. the third bending mode of a beam
    #[arg(long, value_name = "I,J,...", value_delimiter = ',')]
    pub residualize_modes: Option<Vec<usize>>,
    /// Which form to export
    #[arg(long, value_enum, default_value = "ordinary")]
    pub form: Form,
    /// ROM file: .json, .mat (MATLAB v5) or .npz (NumPy); JSON to stdout if absent
    #[arg(short = 'o', long = "out", value_name = "FILE")]
    pub file: Option<PathBuf>,
    /// Also write PREFIX.csv, PREFIX.svg and PREFIX.png: Bode plot of the full model and the ROM
    #[arg(long, value_name = "PREFIX")]
    pub bode: Option<PathBuf>,
    /// Also write PREFIX.{csv,svg,png}: the transfer matrix as a grid of Bode-magnitude panels, full model and ROM (paper Figs. 9, 10)
    #[arg(long, value_name = "PREFIX")]
    pub grid: Option<PathBuf>,
    /// Only the diagonal panels of --grid and --transmissibility
    #[arg(long)]
    pub diagonal: bool,
    /// With an imposed motion (--imposed or the ports file): write PREFIX.{csv,svg,png}, the transmissibility z/z_e of eq. 100, full model and ROM, log-log (paper Fig. 11)
    #[arg(long, value_name = "PREFIX")]
    pub transmissibility: Option<PathBuf>,
    /// With an imposed motion: write the proper state-space model from the imposed displacements to the other outputs (.json/.mat/.npz)
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
    /// Statically residualize the modes the overlaid ROM drops
    #[arg(long)]
    pub residualize: bool,
    /// Writes PREFIX.csv, PREFIX.svg, PREFIX.png
    #[arg(short = 'o', long = "out", value_name = "PREFIX")]
    pub prefix: PathBuf,
    #[command(flatten)]
    pub freq: FrequencyArgs,
}

/// Static gains of the full model and of the ROM, side by side, on stderr.
fn report_static_gain(g: &StaticGains) {
    let entries = g.input_names.len() * g.output_names.len();
    if entries > 16 {
        let worst = match (&g.full, &g.rom) {
            (Ok(full), Ok(rom)) => format!("largest difference |ROM - full| / max |full| {:.1e}", (rom - full).norm_max() / full.norm_max().max(f64::MIN_POSITIVE)),
            (Err(e), Ok(_)) => format!("full model: not available ({e})"),
            (_, Err(e)) => format!("not available ({e})"),
        };
        eprintln!("static gains ({} outputs x {} inputs, in the exported files): {worst}", g.output_names.len(), g.input_names.len());
        return;
    }
    match (&g.full, &g.rom) {
        (Ok(full), Ok(rom)) => {
            for i in 0..full.nrows() {
                for j in 0..full.ncols() {
                    let (f, r) = (full[(i, j)], rom[(i, j)]);
                    let rel = if f != 0.0 { (r - f).abs() / f.abs() } else { (r - f).abs() };
                    eprintln!("static gain {} / {}: full {f:.6e}, ROM {r:.6e} (relative difference {rel:.1e})", g.output_names[i], g.input_names[j]);
                }
            }
        }
        (Err(full), Ok(rom)) => {
            eprintln!("static gain of the full model: not available ({full})");
            for i in 0..rom.nrows() {
                for j in 0..rom.ncols() {
                    eprintln!("static gain {} / {}: ROM {:.6e}", g.output_names[i], g.input_names[j], rom[(i, j)]);
                }
            }
        }
        (_, Err(e)) => eprintln!("static gain: not available ({e})"),
    }
}

fn print_summary(r: &ReducedModel) {
    let kept: Vec<String> = r.descriptor.eigenvalues.iter().map(|l| format!("{:.6}{:+.6}j", l.re, l.im)).collect();
    eprintln!("ROM: {} states ({} kept eigenvalues: {}), {} statically residualized states", r.ordinary.a.nrows(), kept.len(), kept.join(", "), r.descriptor.static_states);
    report_static_gain(&r.static_gains);
}

/// Writes PREFIX.csv, PREFIX.svg and PREFIX.png.
fn write_bode_files(r: &FrequencyResponses, prefix: &Path) -> Result<()> {
    let [csv, svg, png] = r.write_files(prefix, "Frequency response").with_context(|| format!("writing {}.{{csv,svg,png}}", prefix.display()))?;
    eprintln!("wrote {}, {}, {}", csv.display(), svg.display(), png.display());
    Ok(())
}

pub fn run(a: RomArgs) -> Result<()> {
    let residualization = match (&a.residualize_modes, a.residualize) {
        (Some(list), _) => Residualization::Modes(list.clone()),
        (None, true) => Residualization::Dropped,
        (None, false) => Residualization::None,
    };
    let study = a.pencil.study()?;
    let rom = study.reduce(&RomRequest::new(a.select.selection()).residualize(residualization))?;
    eprint!("{}", study.modal_report().to_text_dynamic(12));
    print_summary(&rom);
    let removed = study.removed_springs();
    if !removed.is_empty() {
        eprintln!("removed from the full model and the ROM (their force fed back, A + B_e K C_e): {}", removed.join(", "));
    }
    let export = match a.form {
        Form::Ordinary => RomExport::from(&rom.ordinary),
        Form::Descriptor if rom.descriptor.c_rate.is_some() => anyhow::bail!("--form descriptor: velocity outputs need z = C x + C_v x', which the descriptor export has no place for; use --form ordinary (its C and D carry them)"),
        Form::Descriptor => RomExport::from(&rom.descriptor),
    };
    match &a.file {
        Some(path) => {
            export.write(path).with_context(|| format!("writing {}", path.display()))?;
            eprintln!("wrote {}", path.display());
        }
        None => println!("{}", serde_json::to_string_pretty(&export.to_json())?),
    }
    if let Some(prefix) = &a.bode {
        let freq = study.frequencies(&a.freq.grid(), &rom.descriptor.eigenvalues)?;
        write_bode_files(&study.full_responses(freq).with_rom("ROM", &rom.ordinary), prefix)?;
    }
    write_application_files(&a, &study, &rom)
}

/// --grid, --transmissibility, --imposed-out.
fn write_application_files(a: &RomArgs, study: &Study, rom: &ReducedModel) -> Result<()> {
    let wrote = |p: [PathBuf; 3]| eprintln!("wrote {}, {}, {}", p[0].display(), p[1].display(), p[2].display());
    if let Some(prefix) = &a.grid {
        let freq = study.frequencies(&a.freq.grid(), &rom.descriptor.eigenvalues)?;
        let dae = study.dae();
        // The imposed displacements (last outputs) are inputs of the transmissibility, not
        // responses: the grid shows the other outputs.
        let no = dae.num_outputs() - study.imposed_len();
        let rows = |h: Vec<faer::Mat<faer::c64>>| h.into_iter().map(|m| m.get(..no, ..).to_owned()).collect::<Vec<_>>();
        let plot = MimoPlot {
            title: "Transfer matrix |z/u|".into(),
            full: rows(full_frequency_response(dae, &freq)),
            rom: Some(rows(rom.ordinary.frequency_response(&freq))),
            freq_hz: freq,
            inputs: dae.input_names.clone(),
            outputs: dae.output_names[..no].to_vec(),
            diagonal: a.diagonal,
        };
        wrote(plot.write_files(prefix).with_context(|| format!("writing {}.{{csv,svg,png}}", prefix.display()))?);
    }
    if let Some(prefix) = &a.transmissibility {
        let freq = study.frequencies(&a.freq.grid(), &rom.descriptor.eigenvalues)?;
        let t = study.transmissibility(rom, &freq)?;
        let mut plot = MimoPlot { title: "Transmissibility |z/z_e| (eq. 100)".into(), freq_hz: t.freq_hz, inputs: t.imposed, outputs: t.outputs, full: t.full, rom: Some(t.rom), diagonal: a.diagonal };
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
        RomExport::from(&m.rom).write(path).with_context(|| format!("writing {}", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

pub fn run_freq(a: FreqArgs) -> Result<()> {
    let selection = match (&a.count, &a.band) {
        (Some(n), _) => Some(ModeSelection::Lowest(*n)),
        (None, Some((fmin_hz, fmax_hz))) => Some(ModeSelection::Band { fmin_hz: *fmin_hz, fmax_hz: *fmax_hz }),
        (None, None) => None,
    };
    let study = a.pencil.study()?;
    let curves = match selection {
        Some(sel) => {
            let residualization = if a.residualize { Residualization::Dropped } else { Residualization::None };
            let rom = study.reduce(&RomRequest::new(sel).residualize(residualization))?;
            let freq = study.frequencies(&a.freq.grid(), &rom.descriptor.eigenvalues)?;
            study.full_responses(freq).with_rom("ROM", &rom.ordinary)
        }
        None => study.full_responses(study.frequencies(&a.freq.grid(), &[])?),
    };
    write_bode_files(&curves, &a.prefix)
}
