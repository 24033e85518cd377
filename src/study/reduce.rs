//! Building a ROM from a [`Study`]: selection, residualization (valid only above the
//! frequencies of interest), projection, modal damping, SVD residualization to the
//! ordinary form, static gains against the full model, warnings.

use faer::Mat;

use crate::rom::{select_dominant_modes, select_modes, with_static_correction, DampingChange, DescriptorRom, Dominance, ModalDamping, ModeSelection, OrdinaryRom, Ranking, Selection};

use super::{Study, StudyError, Warning};

/// Which dropped dynamic modes a ROM keeps as static states (paper Fig. 7).
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Residualization {
    /// None: the ROM is the projection on the kept modes only.
    #[default]
    None,
    /// Every dynamic mode that the selection drops (above the frequencies of interest).
    Dropped,
    /// These modes (1-based modal-table indices; either member of a pair).
    Modes(Vec<usize>),
}

/// What happens to a mode to be residualized that lies below the frequencies of interest
/// (the band's upper end, or the highest kept mode): static residualization would turn it
/// into a feedthrough that is wrong at every frequency above it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum BelowBand {
    /// Keep it as a dynamic mode (warning).
    Keep,
    /// Leave it out of the ROM (warning).
    #[default]
    Drop,
    /// Stop with [`StudyError::ResidualizedBelowBand`].
    Refuse,
}

/// What ROM to build.
#[derive(Clone, Debug, PartialEq)]
pub struct RomRequest {
    pub selection: ModeSelection,
    pub ranking: Ranking,
    pub residualization: Residualization,
    pub below_band: BelowBand,
    /// Modal damping of the ROM (the full model is never changed).
    pub damping: Option<ModalDamping>,
}

impl RomRequest {
    /// The projection on `selection` ranked by frequency, nothing residualized, no damping.
    pub fn new(selection: ModeSelection) -> Self {
        RomRequest { selection, ranking: Ranking::Frequency, residualization: Residualization::None, below_band: BelowBand::Drop, damping: None }
    }

    /// The same request with `r` as residualization.
    pub fn residualize(mut self, r: Residualization) -> Self {
        self.residualization = r;
        self
    }

    /// The same request with modes ranked by `ranking`.
    pub fn ranked_by(mut self, ranking: Ranking) -> Self {
        self.ranking = ranking;
        self
    }

    /// The same request with modal damping.
    pub fn damped(mut self, damping: ModalDamping) -> Self {
        self.damping = Some(damping);
        self
    }
}

/// Static gains (outputs × inputs) of the full model and of the ROM.
#[derive(Clone, Debug)]
pub struct StaticGains {
    pub input_names: Vec<String>,
    pub output_names: Vec<String>,
    /// `C̃ S⁻¹ B̃` of the full model, or why it does not exist.
    pub full: Result<Mat<f64>, String>,
    /// `D − C A⁻¹ B` of the ordinary ROM, or why it does not exist.
    pub rom: Result<Mat<f64>, String>,
}

impl StaticGains {
    /// Entries of the full gain below this fraction of its largest are zero to rounding:
    /// their relative differences are not reported.
    pub const ZERO: f64 = 1e-12;

    /// The largest relative difference ROM vs full over the entries that are not zero to
    /// rounding, with its channel "output / input".
    pub fn largest_relative_difference(&self) -> Option<(f64, String)> {
        let (Ok(full), Ok(rom)) = (&self.full, &self.rom) else { return None };
        let big = (0..full.nrows()).flat_map(|i| (0..full.ncols()).map(move |j| (i, j))).map(|(i, j)| full[(i, j)].abs()).fold(0.0, f64::max);
        let mut worst: Option<(f64, String)> = None;
        for i in 0..full.nrows() {
            for j in 0..full.ncols() {
                let f = full[(i, j)];
                let rel = if f.abs() > Self::ZERO * big { (rom[(i, j)] - f).abs() / f.abs() } else { (rom[(i, j)] - f).abs() / big.max(f64::MIN_POSITIVE) };
                if worst.as_ref().is_none_or(|w| rel > w.0) {
                    worst = Some((rel, format!("{} / {}", self.output_names[i], self.input_names[j])));
                }
            }
        }
        worst
    }

    /// `‖G_rom‖_F / ‖G_full‖_F`: how much of the full model's static gain the ROM keeps.
    pub fn kept_share(&self) -> Option<f64> {
        let (Ok(full), Ok(rom)) = (&self.full, &self.rom) else { return None };
        let f = full.norm_l2();
        (f > 0.0).then(|| rom.norm_l2() / f)
    }
}

/// A kept mode as the summary lists it.
#[derive(Clone, Debug, PartialEq)]
pub struct KeptMode {
    /// 1-based modal-table indices of the unit's members.
    pub indices: Vec<usize>,
    /// Eigenvalue of the first member [rad/s] (in the full model).
    pub lambda: faer::c64,
    /// Dominance relative to the largest mode's (1 = the most dominant).
    pub dominance: f64,
}

/// A ROM with what a user must know to trust it.
#[derive(Clone, Debug)]
pub struct ReducedModel {
    /// Kept and residualized modes (0-based indices into the modal analysis).
    pub selection: Selection,
    /// The kept modes, one entry per unit (pair).
    pub kept_modes: Vec<KeptMode>,
    /// `E ẋ = A x + B u`, `z = C x` (eqs. 47–50).
    pub descriptor: DescriptorRom,
    /// `ẋ = A x + B u`, `z = C x + D u` (eqs. 51–63).
    pub ordinary: OrdinaryRom,
    pub static_gains: StaticGains,
    /// Modes whose ROM eigenvalues modal damping moved.
    pub damping: Vec<DampingChange>,
    /// The ordinary ROM's `D` carries the static correction of the modes it does not keep
    /// (the sparse route's `--residualize`: full model's static gain minus the kept modes'):
    /// the descriptor form, which has no `D`, cannot carry it.
    pub static_correction: bool,
    pub warnings: Vec<Warning>,
}

impl ReducedModel {
    /// Refuses a form that cannot hold this ROM: the descriptor form has no place for rate
    /// outputs' `C_v` nor for a static correction's `D`.
    pub fn check_form(&self, form: super::RomForm) -> Result<(), StudyError> {
        if form != super::RomForm::Descriptor {
            return Ok(());
        }
        let message = if self.descriptor.c_rate.is_some() {
            "descriptor: velocity outputs need z = C x + C_v x', which the descriptor export has no place for; use the ordinary form (its C and D carry them)"
        } else if self.static_correction {
            "descriptor: the sparse route's --residualize is a static correction of the ordinary ROM's D, which the descriptor form has no place for; use the ordinary form, or --solver dense"
        } else {
            return Ok(());
        };
        Err(StudyError::Option { option: "--form", message: message.into() })
    }
}

/// Static residualization must only take modes above this frequency [Hz].
fn top_of_interest(study: &Study, request: &RomRequest, sel: &Selection) -> f64 {
    let kept_top = sel.kept.iter().map(|&i| study.modal.modes[i].freq_hz()).fold(0.0, f64::max);
    match request.selection {
        ModeSelection::Band { fmax_hz, .. } => fmax_hz.max(kept_top),
        _ => kept_top,
    }
}

impl Study {
    /// Dominance of every dynamic mode for the DAE's inputs and outputs.
    pub fn dominance(&self) -> Dominance {
        Dominance::of_ports(self.linear.b(), self.linear.c(), &self.modal)
    }

    /// Builds the ROM that `request` describes.
    pub fn reduce(&self, request: &RomRequest) -> Result<ReducedModel, StudyError> {
        let modal = &self.modal;
        if self.linear.input_names().is_empty() || self.linear.output_names().is_empty() {
            return Err(StudyError::NoPorts);
        }
        let sparse = self.sparse.is_some();
        if sparse && super::solver::needs_every_mode(request) {
            return Err(StudyError::Option { option: "--by", message: "dominance of a --count ranks every mode of the model, and the sparse route computed only the modes asked for (use --solver dense or auto, or --band F1:F2 --by dominance: dominance of the modes in a band)".into() });
        }
        let dominance = self.dominance();
        let mut sel = match (request.ranking, &self.sparse) {
            (Ranking::Frequency, None) => select_modes(modal, &request.selection)?,
            // The sparse route has only the modes it found: say so, not "the model has".
            (Ranking::Frequency, Some(run)) => select_modes(modal, &request.selection).map_err(|_| StudyError::SparseModes {
                found: crate::rom::mode_units(modal).len(),
                target: run.describe_target(),
                note: run.note.clone().map_or(String::new(), |n| format!(" (not certified: {n})")),
            })?,
            (Ranking::Dominance, _) => select_dominant_modes(modal, &dominance, &request.selection)?,
        };
        // A ROM from modes that may be incomplete carries the warning itself.
        let mut warnings: Vec<Warning> = self.sparse_warning().into_iter().collect();
        let mut candidates = match &request.residualization {
            Residualization::None => Vec::new(),
            Residualization::Dropped => sel.dropped.clone(),
            Residualization::Modes(list) => {
                let chosen = select_modes(modal, &ModeSelection::Indices(list.clone()))?.kept;
                if let Some(k) = chosen.iter().find(|k| sel.kept.contains(k)) {
                    return Err(StudyError::KeptAndResidualized(k + 1));
                }
                chosen
            }
        };
        // Residualization is valid only above the frequencies of interest (issue 9, point 1).
        let top = top_of_interest(self, request, &sel);
        let below: Vec<usize> = candidates.iter().copied().filter(|&i| modal.modes[i].freq_hz() < top * (1.0 - 1e-9)).collect();
        let relevant: Vec<(usize, f64)> = below.iter().filter(|&&i| !dominance.is_negligible(i) && modal.modes[i].partner.is_none_or(|p| p > i)).map(|&i| (i + 1, modal.modes[i].freq_hz())).collect();
        candidates.retain(|i| !below.contains(i));
        if !relevant.is_empty() {
            match request.below_band {
                BelowBand::Refuse => return Err(StudyError::ResidualizedBelowBand { modes: relevant, top_hz: top }),
                BelowBand::Drop => warnings.push(Warning::BelowBandDropped { modes: relevant.clone(), top_hz: top }),
                BelowBand::Keep => {
                    sel.kept.extend(below.iter().copied().filter(|&i| !dominance.is_negligible(i)));
                    sel.kept.sort_unstable();
                    warnings.push(Warning::BelowBandKept { modes: relevant.clone(), top_hz: top });
                }
            }
        }
        sel.dropped = candidates;
        let invisible: Vec<(usize, f64)> = sel.kept.iter().filter(|&&i| dominance.is_negligible(i) && modal.modes[i].partner.is_none_or(|p| p > i)).map(|&i| (i + 1, modal.modes[i].freq_hz())).collect();
        if !invisible.is_empty() {
            warnings.push(Warning::Invisible { modes: invisible });
        }

        // The sparse route's --residualize: the kept modes' projection, its D corrected to the
        // full model's static gain less the static part of the modes below the band.
        let corrected = sparse && request.residualization == Residualization::Dropped;
        let below_dropped: Vec<usize> = if corrected && request.below_band == BelowBand::Drop { below.iter().copied().filter(|i| !sel.kept.contains(i)).collect() } else { Vec::new() };
        if corrected {
            sel.dropped.clear();
        }
        let mut descriptor = self.project(&sel)?;
        let damping = match &request.damping {
            Some(d) => {
                for &i in &sel.kept {
                    let m = &modal.modes[i];
                    let asked = match d {
                        ModalDamping::Uniform(_) => true,
                        ModalDamping::PerMode(list) => list.iter().any(|(k, _)| *k == i + 1),
                    };
                    if asked && m.partner.is_none() {
                        warnings.push(Warning::DampingNotApplied { mode: i + 1, reason: format!("λ = {:.6e} rad/s is real (not an oscillation)", m.lambda.re) });
                    }
                }
                if let ModalDamping::PerMode(list) = d {
                    if let Some((k, _)) = list.iter().find(|(k, _)| !sel.kept.iter().any(|&i| i + 1 == *k)) {
                        return Err(StudyError::DampingOfDroppedMode(*k));
                    }
                }
                descriptor.add_modal_damping(d, |i| modal.modes[i].partner)?
            }
            None => Vec::new(),
        };
        let mut ordinary = descriptor.to_ordinary()?;
        let full = self.full_static_gain();
        let full_ok = full.is_ok();
        if corrected && let Ok(full) = &full {
            let target = if below_dropped.is_empty() {
                full.clone()
            } else {
                // Their static part: G(kept ∪ below) − G(kept), both undamped projections.
                let mut with_below = Selection { kept: sel.kept.iter().chain(&below_dropped).copied().collect(), dropped: Vec::new() };
                with_below.kept.sort_unstable();
                let only_kept = Selection { kept: sel.kept.clone(), dropped: Vec::new() };
                let g = |s: &Selection| -> Result<Mat<f64>, StudyError> { Ok(self.project(s)?.to_ordinary()?.static_gain()?) };
                full - (g(&with_below)? - g(&only_kept)?)
            };
            ordinary = with_static_correction(&ordinary, &target)?;
        }
        let static_gains = StaticGains { input_names: self.linear.input_names().to_vec(), output_names: self.linear.output_names().to_vec(), full, rom: rigid_body_modes(&ordinary.eigenvalues).map_or_else(|| ordinary.static_gain().map_err(|e| e.to_string()), Err) };
        if let Some((rel, channel)) = static_gains.largest_relative_difference() {
            let all_residualized = request.residualization == Residualization::Dropped && relevant.is_empty();
            let reason = if corrected && rel > 1e-9 {
                Some(if below_dropped.is_empty() { "the static correction did not reach the full model's static gain (an ill-conditioned static matrix?)".to_string() } else { "modes below the frequencies of interest were not residualized (see above)".to_string() })
            } else if all_residualized && rel > 1e-9 {
                Some("every dropped dynamic mode is residualized: the rest of the static response comes from the full model's infinite eigenvalues (algebraic or massless unknowns, not representable by modes) or is lost to rounding in an ill-conditioned static matrix".to_string())
            } else if request.residualization == Residualization::Dropped && rel > 1e-9 {
                Some("modes below the frequencies of interest were not residualized (see above)".to_string())
            } else if rel > 0.1 {
                Some("the dropped modes carry it: keep more modes, --residualize, or --by dominance".to_string())
            } else {
                None
            };
            if let Some(reason) = reason {
                warnings.push(Warning::StaticGain { relative: rel, channel, reason });
            }
        }
        let kept_modes = crate::rom::mode_units(modal)
            .into_iter()
            .filter(|u| sel.kept.contains(&u[0]))
            .map(|u| KeptMode { indices: u.iter().map(|i| i + 1).collect(), lambda: modal.modes[u[0]].lambda, dominance: dominance.relative(u[0]) })
            .collect();
        Ok(ReducedModel { selection: sel, kept_modes, descriptor, ordinary, static_gains, damping, static_correction: corrected && full_ok, warnings })
    }

    /// The descriptor ROM of `sel` (kept and residualized modes): by sparse products on the
    /// sparse route, else dense, with the dummy springs' feedback (paper eqs. 92–95: projected
    /// with the springs present, their force fed back with a plus sign, `A + B_e K C_e`, see
    /// `rom::springs`).
    fn project(&self, sel: &Selection) -> Result<DescriptorRom, StudyError> {
        let residualize = !sel.dropped.is_empty();
        if let (Some(_), Some(sparse)) = (&self.sparse, self.linear.sparse()) {
            return Ok(DescriptorRom::project_sparse(sparse, &self.modal, sel, residualize)?);
        }
        let applied = self.application.as_ref();
        let projected = applied.and_then(|a| a.projected.as_ref()).unwrap_or(self.linear.dense());
        let mut descriptor = DescriptorRom::project(projected, &self.modal, sel, residualize)?;
        if let Some(fb) = applied.and_then(|a| a.feedback.as_ref()) {
            descriptor = descriptor.without_springs(fb)?;
        }
        Ok(descriptor)
    }

    /// The full model's static gain `C̃ S⁻¹ B̃` (by sparse LU on the sparse route), or why it
    /// does not exist (with the free direction on the dense route).
    pub fn full_static_gain(&self) -> Result<Mat<f64>, String> {
        if self.sparse.is_some()
            && let Some(g) = self.linear.sparse_static_gain()
        {
            return g.map_err(|e| format!("{e}: an unrestrained motion, or a load path the supports do not close"));
        }
        self.linear.dense_static_gain().cloned().map_err(|e| match self.linear.dense_free_direction() {
            Some(x) => match self.model.as_ref().and_then(|m| super::checks::whole_model_rigid_motion(m, x)) {
                Some(rigid) => format!("{e}: unrestrained {rigid}"),
                None => format!("{e}: unrestrained motion along {}", self.describe_direction(x)),
            },
            None => e.to_string(),
        })
    }


    /// The largest components of a direction in the unknowns, e.g. "node 2 x, node 2 y"
    /// (multipliers left out).
    pub(super) fn describe_direction(&self, x: &[f64]) -> String {
        super::checks::largest_components(x, self.linear.unknown_names(), self.linear.multipliers())
    }
}

/// With rigid-body (zero) eigenvalues, e.g. after removing the springs that ground a model,
/// a ROM has no static gain: `A` is singular up to rounding, and inverting it would print
/// numbers that mean nothing.
fn rigid_body_modes(eigenvalues: &[faer::c64]) -> Option<String> {
    let big = eigenvalues.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let zero = eigenvalues.iter().filter(|l| l.norm() <= 1e-6 * big).count();
    (zero > 0).then(|| format!("the ROM has {zero} zero (rigid-body) eigenvalues"))
}
