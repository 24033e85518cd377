//! `romdyn rom` and `romdyn freq`: reduced-order models and their frequency responses.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use romdyn::output::frequency_plot::FrequencyResponses;
use romdyn::output::rom_file::RomExport;
use romdyn::rom::ModeSelection;
use romdyn::study::{ReducedModel, Residualization, RomRequest, StaticGains};

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
    let export = match a.form {
        Form::Ordinary => RomExport::from(&rom.ordinary),
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
