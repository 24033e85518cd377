//! A ROM checked against the full model on the response grid, the check `romdyn rom` and
//! Python's `Study.reduce()` both run: the transfer matrix from the inputs and, with an
//! imposed motion, the transmissibility `z/z_e` (eq. 100), each port pair on its own scale,
//! with a warning where the ROM departs within the frequencies of interest (up to the band's
//! top or the highest kept mode: above them a truncated ROM is not meant to follow).

use faer::c64;

use super::warning::Response;
use super::{ChannelError, FrequencyGrid, GridAccuracy, ReducedModel, Residualization, Study, StudyError, Warning};
use crate::linear::FrequencyResponse;

/// A ROM against the full model on one grid.
pub struct RomCheck {
    /// Both models' responses to the inputs (the ROM the response's first reduced model).
    pub comparison: FrequencyResponse,
    /// Their agreement on the whole grid.
    pub accuracy: GridAccuracy,
    /// With an imposed motion: both transmissibilities (inputs: the imposed components) and
    /// their agreement.
    pub transmissibility: Option<(FrequencyResponse, GridAccuracy)>,
    /// Where the ROM departs within the frequencies of interest (or why its
    /// transmissibility could not be formed).
    pub warnings: Vec<Warning>,
}

impl ReducedModel {
    /// The eigenvalues [rad/s] that set a default frequency grid: rigid-body (zero) ones of a
    /// ROM whose dummy springs were removed would stretch it down to rounding (below 1e-6 of
    /// the largest).
    pub fn grid_focus(&self) -> Vec<c64> {
        let eig = &self.descriptor.eigenvalues;
        let big = eig.iter().map(|l| l.norm()).fold(0.0, f64::max);
        eig.iter().copied().filter(|l| l.norm() > 1e-6 * big).collect()
    }
}

impl Study {
    /// [`Study::check_rom_on`] on `grid` (missing ends: a decade around the ROM's modes, as
    /// `romdyn rom` defaults).
    pub fn check_rom(&self, rom: &ReducedModel, grid: &FrequencyGrid) -> Result<RomCheck, StudyError> {
        let freq = self.frequencies(grid, &rom.grid_focus())?;
        self.check_rom_on(rom, freq)
    }

    /// Every response of `rom` against the full model's at `freq_hz` [Hz]: the transfer
    /// matrix from the inputs and, with an imposed motion, the transmissibility; a
    /// [`Warning::ResponseDeparts`] for each whose worst port pair, on its own scale, is off
    /// by more than [`ChannelError::WARN`] at or below the ROM's top frequency of interest.
    /// A ROM given modal damping the full model lacks is checked without it
    /// ([`ReducedModel::undamped`]).
    pub fn check_rom_on(&self, rom: &ReducedModel, freq_hz: Vec<f64>) -> Result<RomCheck, StudyError> {
        let undamped = rom.undamped.as_ref().map(|u| ReducedModel { ordinary: u.ordinary.clone(), undamped: None, ..rom.clone() });
        let rom = undamped.as_ref().unwrap_or(rom);
        let comparison = self.compare(rom, freq_hz)?;
        let accuracy = comparison.accuracy();
        let mut warnings = Vec::new();
        let top = rom.interest_top_hz;
        // Channels zero to rounding in the full model (a force on a clamped node) have no
        // response to follow: the port warnings said so.
        let zero = self.zero_channels();
        let zero_pair = |i: usize, j: usize| zero.get(i).and_then(|r| r.get(j)).copied().unwrap_or(false);
        if let Some(w) = self.departure(rom, Response::Inputs, &comparison, &zero_pair) {
            warnings.push(w);
        }
        let transmissibility = if self.imposed_len() == 0 {
            None
        } else {
            match self.transmissibility(rom, &comparison.freq_hz) {
                Ok(t) => {
                    warnings.extend(self.departure(rom, Response::Transmissibility, &t, &|_, _| false));
                    let accuracy = t.accuracy();
                    Some((t, accuracy))
                }
                Err(e) => {
                    warnings.push(Warning::TransmissibilityUnavailable { reason: e.to_string(), top_hz: top });
                    None
                }
            }
        };
        Ok(RomCheck { comparison, accuracy, transmissibility, warnings })
    }

    /// The warning for the worst port pair of `c` at or below the ROM's top of interest.
    fn departure(&self, rom: &ReducedModel, response: Response, c: &FrequencyResponse, skip: &dyn Fn(usize, usize) -> bool) -> Option<Warning> {
        let top = rom.interest_top_hz;
        let worst = c.worst_channel_up_to(top * (1.0 + 1e-9), skip)?;
        if !(worst.relative > ChannelError::WARN) && !worst.relative.is_nan() {
            return None;
        }
        let name = |ports: &[crate::linear::Port], k: usize| ports.get(k).map_or_else(|| (k + 1).to_string(), |p| p.label());
        let channel = format!("{} / {}", name(&c.outputs, worst.output), name(&c.inputs, worst.input));
        let k = c.freq_hz.iter().position(|&f| f == worst.at_hz).unwrap_or(0);
        let (full, reduced) = (c.full[k][(worst.output, worst.input)].norm(), c.rom()[k][(worst.output, worst.input)].norm());
        Some(Warning::ResponseDeparts { response, channel, relative: worst.relative, at_hz: worst.at_hz, full, rom: reduced, top_hz: top, advice: self.departure_advice(rom) })
    }

    /// What to do about a departure, from what the ROM left out and what the user already
    /// asked for: dynamic modes below the kept ones that are neither kept nor residualized
    /// (e.g. the base modes of an isolator's dummy springs, which carry an imposed motion),
    /// else the modes dropped above (`--residualize` folds them into D, unless given).
    fn departure_advice(&self, rom: &ReducedModel) -> String {
        let modal = self.modal();
        let lowest_kept = rom.kept_modes.iter().map(|k| k.lambda.norm() / (2.0 * std::f64::consts::PI)).fold(f64::INFINITY, f64::min);
        let left_out: Vec<(usize, f64)> = crate::rom::mode_units(modal)
            .into_iter()
            .map(|u| u[0])
            .filter(|i| !rom.selection.kept.contains(i) && !rom.selection.dropped.contains(i) && modal.modes[*i].freq_hz() < lowest_kept)
            .map(|i| (i + 1, modal.modes[i].freq_hz()))
            .collect();
        if !left_out.is_empty() {
            let list: Vec<String> = left_out.iter().take(6).map(|(k, f)| format!("{k} ({f:.4} Hz)")).collect();
            let more = if left_out.len() > 6 { format!(" and {} more", left_out.len() - 6) } else { String::new() };
            return format!(
                "mode(s) {}{more} below the kept ones are neither kept nor residualized, and carry this response at low frequency (with an imposed motion, the motion of the excitation point: e.g. the base modes of dummy springs): keep them (a band or --count that includes them)",
                list.join(", ")
            );
        }
        match (&rom.residualization, rom.static_correction) {
            (Residualization::Dropped, _) | (_, true) => "the dropped modes are already residualized (--residualize was given) and the difference remains: keep more modes as dynamic modes (a wider band or a larger --count)".to_string(),
            (Residualization::Modes(_), false) => "keep more modes, or residualize every dropped mode (--residualize instead of --residualize-modes)".to_string(),
            (Residualization::None, false) => "the modes the ROM drops carry it: keep more modes, or --residualize (folds the modes dropped above the band into D)".to_string(),
        }
    }
}
