//! `romdyn rom` and `romdyn freq`: reduced-order models and their frequency responses.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use romdyn::linear::{LinearDae, ModalAnalysis};
use romdyn::output::modal::ModalReport;
use romdyn::output::rom_file::RomExport;
use romdyn::rom::{full_static_gain, select_modes, DescriptorRom, OrdinaryRom};

use super::args::{parse_band, FrequencyArgs, PencilArgs, SelectionArgs};
use super::bode::{full_responses, write_bode_files};
use super::load::{load, Loaded};

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

struct Built {
    dae: LinearDae,
    modal: ModalAnalysis,
    /// The lowest dynamic modes of the modal table, as text.
    table: String,
    descriptor: DescriptorRom,
    ordinary: OrdinaryRom,
}

/// Which dropped modes a ROM keeps as static states.
enum Residualize {
    None,
    AllDropped,
    /// 1-based modal-table indices.
    Modes(Vec<usize>),
}

fn build(pencil: &PencilArgs, selection: &romdyn::rom::ModeSelection, residualize: Residualize) -> Result<Built> {
    let loaded = load(pencil)?;
    let table = ModalReport::new(&loaded.modal, loaded.dae.dim()).with_energy(loaded.energy()).to_text_dynamic(12);
    let Loaded { dae, modal, .. } = loaded;
    if dae.num_inputs() == 0 || dae.num_outputs() == 0 {
        anyhow::bail!("a ROM needs inputs and outputs: give --input NODE:COMP and --output NODE:COMP for a model, --input-row I and --output-col J for an .m pencil");
    }
    let mut sel = select_modes(&modal, selection)?;
    if let Residualize::Modes(list) = &residualize {
        let chosen = select_modes(&modal, &romdyn::rom::ModeSelection::Indices(list.clone()))?.kept;
        if let Some(k) = chosen.iter().find(|k| sel.kept.contains(k)) {
            anyhow::bail!("mode {} is both kept and residualized", k + 1);
        }
        sel.dropped = chosen;
    }
    let descriptor = DescriptorRom::project(&dae, &modal, &sel, !matches!(residualize, Residualize::None))?;
    let ordinary = descriptor.to_ordinary()?;
    Ok(Built { dae, modal, table, descriptor, ordinary })
}

/// Static gains of the full model and of the ROM, side by side, on stderr.
fn report_static_gain(b: &Built) {
    let rom = b.ordinary.static_gain();
    match (full_static_gain(&b.dae), rom) {
        (Ok(full), Ok(rom)) => {
            for i in 0..full.nrows() {
                for j in 0..full.ncols() {
                    let (f, r) = (full[(i, j)], rom[(i, j)]);
                    let rel = if f != 0.0 { (r - f).abs() / f.abs() } else { (r - f).abs() };
                    eprintln!("static gain {} / {}: full {f:.6e}, ROM {r:.6e} (relative difference {rel:.1e})", b.dae.output_names[i], b.dae.input_names[j]);
                }
            }
        }
        (Err(full), Ok(rom)) => {
            eprintln!("static gain of the full model: not available ({full})");
            for i in 0..rom.nrows() {
                for j in 0..rom.ncols() {
                    eprintln!("static gain {} / {}: ROM {:.6e}", b.dae.output_names[i], b.dae.input_names[j], rom[(i, j)]);
                }
            }
        }
        (_, Err(e)) => eprintln!("static gain: not available ({e})"),
    }
}

pub fn run(a: RomArgs) -> Result<()> {
    let residualize = match (&a.residualize_modes, a.residualize) {
        (Some(list), _) => Residualize::Modes(list.clone()),
        (None, true) => Residualize::AllDropped,
        (None, false) => Residualize::None,
    };
    let b = build(&a.pencil, &a.select.selection(), residualize)?;
    eprint!("{}", b.table);
    let kept: Vec<String> = b.descriptor.eigenvalues.iter().map(|l| format!("{:.6}{:+.6}j", l.re, l.im)).collect();
    eprintln!(
        "ROM: {} states ({} kept eigenvalues: {}), {} statically residualized states",
        b.ordinary.a.nrows(),
        kept.len(),
        kept.join(", "),
        b.descriptor.static_states
    );
    report_static_gain(&b);
    let export = match a.form {
        Form::Ordinary => RomExport::from(&b.ordinary),
        Form::Descriptor => RomExport::from(&b.descriptor),
    };
    match &a.file {
        Some(path) => {
            export.write(path).with_context(|| format!("writing {}", path.display()))?;
            eprintln!("wrote {}", path.display());
        }
        None => println!("{}", serde_json::to_string_pretty(&export.to_json())?),
    }
    if let Some(prefix) = &a.bode {
        let curves = full_responses(&b.dae, &b.modal, &a.freq, &b.descriptor.eigenvalues)?;
        let curves = curves.with_rom("ROM", &b.ordinary);
        write_bode_files(&curves, prefix)?;
    }
    Ok(())
}

pub fn run_freq(a: FreqArgs) -> Result<()> {
    let selection = match (&a.count, &a.band) {
        (Some(n), _) => Some(romdyn::rom::ModeSelection::Lowest(*n)),
        (None, Some((fmin_hz, fmax_hz))) => Some(romdyn::rom::ModeSelection::Band { fmin_hz: *fmin_hz, fmax_hz: *fmax_hz }),
        (None, None) => None,
    };
    let curves = match selection {
        Some(sel) => {
            let b = build(&a.pencil, &sel, if a.residualize { Residualize::AllDropped } else { Residualize::None })?;
            full_responses(&b.dae, &b.modal, &a.freq, &b.descriptor.eigenvalues)?.with_rom("ROM", &b.ordinary)
        }
        None => {
            let Loaded { dae, modal, .. } = load(&a.pencil)?;
            full_responses(&dae, &modal, &a.freq, &[])?
        }
    };
    write_bode_files(&curves, &a.prefix)
}
