//! One design point: the model text with `set:` overrides, reference solution,
//! linearization, modes and ROM through the same [`Study`] workflow as `romdyn rom`.

use std::path::Path;

use faer::c64;

use crate::analysis::Reference;
use crate::dae::State;
use crate::input::mbdyn::{read_model_text, SetOverrides};
use crate::eigen::ModalAnalysis;
use crate::rom::mode_units;
use crate::output::rom_file::RomExport;
use crate::study::{EigenSettings, Ports, RomForm, RomRequest, Study, StudyError};

/// What every design point computes (the options of `romdyn rom`).
#[derive(Clone, Debug)]
pub struct SweepOptions {
    pub reference: Reference,
    pub ports: Ports,
    pub eigen: EigenSettings,
    pub rom: RomRequest,
    pub form: RomForm,
    /// Number of lowest dynamic modes in the table and the plot (a pair counts once).
    pub modes: usize,
    /// Each static equilibrium starts from the previous design point's (the points then run
    /// one after the other).
    pub continuation: bool,
    /// The rotation update of the model's beams (beam3, beam2): `Auto` is MBDyn's incremental
    /// update at a reference reached by a time integration (`--at T`), as `romdyn eig` on
    /// the same file, and path independent at a static or initial one
    /// ([`crate::model::BeamUpdateChoice`]).
    pub beam_update: crate::model::BeamUpdateChoice,
}

/// What a design point gives.
#[derive(Clone, Debug)]
pub struct PointResult {
    /// The ROM (same form and ports at every point).
    pub rom: RomExport,
    /// The lowest dynamic eigenvalues of the full model [rad/s], one per mode (a pair by
    /// its member with `Im λ ≥ 0`), by increasing |λ|.
    pub modes: Vec<c64>,
    /// The study's and the ROM's warnings.
    pub warnings: Vec<String>,
    /// The reference solution (continuation starts the next point from it).
    pub state: State,
}

/// The overrides of one design point: parameter `names[k]` = `values[k]`.
pub fn overrides(names: &[String], values: &[f64]) -> SetOverrides {
    names.iter().cloned().zip(values.iter().copied()).collect()
}

/// Runs one design point on the text of the MBDyn file `name` (the name only labels messages
/// and resolves includes). `start`: the previous point's reference solution (continuation).
pub fn run_point(text: &str, name: &Path, names: &[String], values: &[f64], options: &SweepOptions, start: Option<&State>) -> Result<PointResult, StudyError> {
    let mut m = read_model_text(text, name, &overrides(names, values))?;
    let kept = m.model.choose_beam_update(options.beam_update, options.reference.integrates()).map_err(|message| StudyError::Option { option: crate::study::Setting::BeamUpdate, message: format!("{}: {message}", name.display()) })?;
    let eigen = options.eigen.for_request(&options.rom);
    let (study, state) = Study::of_model(m.model, &m.problem, options.reference, &options.ports, eigen, start).map_err(|e| e.in_file(name))?;
    let rom = study.reduce(&options.rom)?;
    rom.check_form(options.form)?;
    let modes = lowest_modes(study.modal(), options.modes);
    let mut warnings = kept;
    warnings.extend(study.warnings().iter().map(|w| w.to_string()));
    warnings.extend(rom.warnings.iter().map(|w| w.to_string()));
    Ok(PointResult { rom: rom.export(&study, options.form), modes, warnings, state })
}

/// The `n` lowest dynamic modes, one eigenvalue per mode (unit of [`mode_units`]): a complex
/// pair by its member with `Im λ > 0`, a `±a` real pair (an unstable equilibrium) by `+a`.
pub fn lowest_modes(modal: &ModalAnalysis, n: usize) -> Vec<c64> {
    let key = |l: c64| (l.im, l.re);
    mode_units(modal)
        .iter()
        .take(n)
        .filter_map(|unit| unit.iter().map(|&i| modal.modes[i].lambda).max_by(|a, b| key(*a).partial_cmp(&key(*b)).unwrap_or(std::cmp::Ordering::Equal)))
        .collect()
}
