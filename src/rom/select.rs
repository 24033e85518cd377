//! Choosing the modes a ROM keeps: by frequency band, by count, or by index.

use crate::linear::{ModalAnalysis, ModeKind};

use super::RomError;

/// How modes are selected. A complex-conjugate pair counts as one mode and is always kept
/// or dropped whole.
#[derive(Clone, Debug, PartialEq)]
pub enum ModeSelection {
    /// Dynamic modes whose natural frequency `|λ|/2π` lies in `[fmin, fmax]` Hz.
    Band { fmin_hz: f64, fmax_hz: f64 },
    /// The `n` dynamic modes of lowest natural frequency.
    Lowest(usize),
    /// Modes by their 1-based index in the modal table (either member of a pair selects it).
    Indices(Vec<usize>),
}

/// Result of a selection: indices (0-based, into `ModalAnalysis::modes`) of the kept modes
/// and of the dynamic modes left out (candidates for static residualization).
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    pub kept: Vec<usize>,
    pub dropped: Vec<usize>,
}

/// The first member of each mode unit (pairs counted once), among dynamic modes.
fn dynamic_units(modal: &ModalAnalysis) -> Vec<usize> {
    modal.of_kind(ModeKind::Dynamic).filter(|&i| modal.modes[i].partner.is_none_or(|p| p > i)).collect()
}

fn with_partners(modal: &ModalAnalysis, units: &[usize]) -> Vec<usize> {
    let mut out: Vec<usize> = units.iter().flat_map(|&i| std::iter::once(i).chain(modal.modes[i].partner)).collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Applies a selection to a modal analysis.
pub fn select_modes(modal: &ModalAnalysis, sel: &ModeSelection) -> Result<Selection, RomError> {
    let units = dynamic_units(modal);
    let kept_units: Vec<usize> = match sel {
        ModeSelection::Band { fmin_hz, fmax_hz } => {
            if !(fmin_hz <= fmax_hz) || *fmin_hz < 0.0 {
                return Err(RomError::Selection(format!("band {fmin_hz}:{fmax_hz} Hz is empty or negative")));
            }
            units.iter().copied().filter(|&i| (*fmin_hz..=*fmax_hz).contains(&modal.modes[i].freq_hz())).collect()
        }
        ModeSelection::Lowest(n) => {
            if *n > units.len() {
                return Err(RomError::Selection(format!("{n} modes requested, the model has {} dynamic modes", units.len())));
            }
            units[..*n].to_vec()
        }
        ModeSelection::Indices(list) => {
            let mut v = Vec::new();
            for &k in list {
                let m = k.checked_sub(1).and_then(|i| modal.modes.get(i)).ok_or_else(|| {
                    RomError::Selection(format!("mode index {k} is out of range 1..={}", modal.modes.len()))
                })?;
                if m.kind == ModeKind::Infinite || m.right.is_none() {
                    return Err(RomError::Selection(format!("mode {k} is infinite and has no eigenvector to project on")));
                }
                v.push(k - 1);
            }
            v
        }
    };
    if kept_units.is_empty() {
        return Err(RomError::Selection("the selection keeps no mode".into()));
    }
    let kept = with_partners(modal, &kept_units);
    let dropped = with_partners(modal, &units).into_iter().filter(|i| !kept.contains(i)).collect();
    Ok(Selection { kept, dropped })
}
