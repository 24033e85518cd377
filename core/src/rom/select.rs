//! Choosing the modes a ROM keeps: by frequency band, by count, or by index, ranked by
//! frequency or by dominance for the chosen ports.

use crate::eigen::ModalAnalysis;

use super::dominance::Dominance;
use super::units::{mode_units, unit_of};
use super::RomError;

/// How modes are selected. A mode is a unit of [`mode_units`]: a complex-conjugate pair or a
/// `±a` real pair counts as one mode and is always kept or dropped whole.
#[derive(Clone, Debug, PartialEq)]
pub enum ModeSelection {
    /// Dynamic modes whose natural frequency `|λ|/2π` lies in `[fmin, fmax]` Hz.
    Band { fmin_hz: f64, fmax_hz: f64 },
    /// The `n` dynamic modes of lowest natural frequency (or of largest dominance).
    Lowest(usize),
    /// Modes by their 1-based index in the modal table (either member of a pair selects it).
    Indices(Vec<usize>),
}

impl ModeSelection {
    /// The band `[fmin, fmax]` [Hz], checked as every front end and the sparse route need it:
    /// finite, `0 ≤ fmin < fmax` (an empty band holds no mode; the CLI took `fmin = fmax`
    /// where Python and the Krylov solver refused it, issue 31).
    pub fn band(fmin_hz: f64, fmax_hz: f64) -> Result<Self, String> {
        if !(fmin_hz.is_finite() && fmax_hz.is_finite() && 0.0 <= fmin_hz && fmin_hz < fmax_hz) {
            return Err(format!("need 0 <= FMIN < FMAX (finite, in Hz), got {fmin_hz}:{fmax_hz}"));
        }
        Ok(ModeSelection::Band { fmin_hz, fmax_hz })
    }
}

/// How [`ModeSelection::Lowest`] and [`ModeSelection::Band`] rank the modes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Ranking {
    /// By natural frequency, lowest first (every mode in a band is kept).
    #[default]
    Frequency,
    /// By [`Dominance`] for the DAE's inputs and outputs, largest first; modes that
    /// contribute nothing to the ports are never kept: "the N modes that matter".
    Dominance,
}

/// Result of a selection: indices (0-based, into `ModalAnalysis::modes`) of the kept modes
/// and of the dynamic modes left out (candidates for static residualization).
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    pub kept: Vec<usize>,
    pub dropped: Vec<usize>,
}

fn flatten(units: &[Vec<usize>], chosen: &[usize]) -> Vec<usize> {
    let mut out: Vec<usize> = chosen.iter().flat_map(|&k| units[k].iter().copied()).collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Applies a selection to a modal analysis, modes ranked by frequency.
pub fn select_modes(modal: &ModalAnalysis, sel: &ModeSelection) -> Result<Selection, RomError> {
    select(modal, sel, None)
}

/// Applies a selection with modes ranked by `dominance` (see [`Ranking::Dominance`]).
pub fn select_dominant_modes(modal: &ModalAnalysis, dominance: &Dominance, sel: &ModeSelection) -> Result<Selection, RomError> {
    select(modal, sel, Some(dominance))
}

fn select(modal: &ModalAnalysis, sel: &ModeSelection, dominance: Option<&Dominance>) -> Result<Selection, RomError> {
    let units = mode_units(modal);
    let freq = |k: usize| modal.modes[units[k][0]].freq_hz();
    let visible = |k: usize| dominance.is_none_or(|d| !d.is_negligible(units[k][0]));
    let kept_units: Vec<usize> = match sel {
        ModeSelection::Band { fmin_hz, fmax_hz } => {
            if !(fmin_hz <= fmax_hz) || *fmin_hz < 0.0 {
                return Err(RomError::Selection(format!("band {fmin_hz}:{fmax_hz} Hz is empty or negative")));
            }
            (0..units.len()).filter(|&k| (*fmin_hz..=*fmax_hz).contains(&freq(k)) && visible(k)).collect()
        }
        ModeSelection::Lowest(n) => {
            let mut order: Vec<usize> = (0..units.len()).filter(|&k| visible(k)).collect();
            if let Some(d) = dominance {
                order.sort_by(|&a, &b| d.values[b].total_cmp(&d.values[a]));
            }
            if *n > order.len() {
                return Err(RomError::Selection(match dominance {
                    Some(_) => format!("{n} modes requested, {} of the model's {} dynamic modes contribute to these inputs and outputs", order.len(), units.len()),
                    None => format!("{n} modes requested, the model has {} dynamic modes", units.len()),
                }));
            }
            order[..*n].to_vec()
        }
        ModeSelection::Indices(list) => {
            let mut v = Vec::new();
            for &k in list {
                let m = k.checked_sub(1).and_then(|i| modal.modes.get(i)).ok_or_else(|| RomError::Selection(format!("mode index {k} is out of range 1..={}", modal.modes.len())))?;
                let unit = unit_of(&units, k - 1).filter(|_| m.right.is_some()).ok_or_else(|| {
                    RomError::Selection(format!("mode {k} is {} (not a dynamic mode); a ROM keeps dynamic modes: `romdyn eig` lists them", m.kind.name()))
                })?;
                v.push(unit);
            }
            v
        }
    };
    if kept_units.is_empty() {
        return Err(RomError::Selection(match (sel, dominance) {
            (ModeSelection::Band { fmin_hz, fmax_hz }, Some(_)) => format!("no mode in {fmin_hz}:{fmax_hz} Hz contributes to these inputs and outputs"),
            (ModeSelection::Band { fmin_hz, fmax_hz }, None) => format!("no dynamic mode has its natural frequency in {fmin_hz}:{fmax_hz} Hz"),
            _ => "the selection keeps no mode".into(),
        }));
    }
    let kept = flatten(&units, &kept_units);
    let dropped = flatten(&units, &(0..units.len()).collect::<Vec<_>>()).into_iter().filter(|i| !kept.contains(i)).collect();
    Ok(Selection { kept, dropped })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eigen::EigenRoute;
    use crate::linear::Jacobians;
    use faer::Mat;

    /// Issue 9 point 3: `x'' = a² x` (an inverted pendulum's linearization, a = 3.13 rad/s)
    /// has λ = ±a; `--count 1` keeps both, as it keeps both members of a complex pair.
    #[test]
    fn a_plus_minus_real_pair_counts_as_one_mode() {
        let a = 3.13f64;
        // y = (x, v): x' − v = 0, v' − a² x = 0  →  F_yd = I, F_y = [[0, −1], [−a², 0]].
        let fyd = Mat::<f64>::identity(2, 2);
        let fy = Mat::from_fn(2, 2, |i, j| match (i, j) { (0, 1) => -1.0, (1, 0) => -a * a, _ => 0.0 });
        let modal = ModalAnalysis::compute(&Jacobians::Derivatives { fyd, fy }, EigenRoute::Direct).unwrap();
        let mut l: Vec<f64> = modal.modes.iter().map(|m| m.lambda.re).collect();
        l.sort_by(f64::total_cmp);
        // λ = ±a exactly (closed form), 1e-12 relative.
        assert!((l[0] + a).abs() < 1e-12 * a && (l[1] - a).abs() < 1e-12 * a, "{l:?}");
        assert_eq!(mode_units(&modal), vec![vec![0, 1]]);
        let sel = select_modes(&modal, &ModeSelection::Lowest(1)).unwrap();
        assert_eq!(sel.kept, vec![0, 1]);
        assert!(select_modes(&modal, &ModeSelection::Lowest(2)).is_err());
    }
}
