//! Building a ROM from a [`Study`]: selection, residualization (valid only above the
//! frequencies of interest), projection, modal damping, SVD residualization to the
//! ordinary form, static gains against the full model, warnings.

use faer::{c64, Mat};

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
    /// Remove uncontrollable and unobservable states with this tolerance ([`super::minimal_tolerance`]).
    pub minimal: Option<f64>,
    /// Balanced reduction of the stable part ([`super::balancing`]).
    pub balanced: Option<super::Balancing>,
    /// A discrete-time ROM at this sampling ([`super::sampling`]).
    pub sampling: Option<crate::rom::Sampling>,
}

impl RomRequest {
    /// The projection on `selection` ranked by frequency, nothing residualized, no damping.
    pub fn new(selection: ModeSelection) -> Self {
        RomRequest { selection, ranking: Ranking::Frequency, residualization: Residualization::None, below_band: BelowBand::Drop, damping: None, minimal: None, balanced: None, sampling: None }
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
    /// Channels (outputs × inputs) whose every full-model response is zero to rounding
    /// ([`super::zero_channels`]: a force on a clamped node reads 1e-22 m/N): their static
    /// gains, full and ROM, are rounding and are neither compared nor reported as differences.
    pub zero: Vec<Vec<bool>>,
    /// The relative difference that rounding alone gives on this model
    /// ([`StaticGains::rounding_of`]), for a channel whose modal terms do not cancel.
    pub rounding: f64,
    /// Per channel, `max(1, s / |G_full|)` with `s` the larger of the modal terms' size
    /// `Σ_k |static contribution of mode k|` (their cancellation) and, on the dense route, the
    /// static solution's ([`crate::rom::full_static_gain_and_scale`]: an LU's rounding is
    /// relative to the whole solution): it multiplies the rounding; empty without a full
    /// static gain.
    pub cancellation: Vec<Vec<f64>>,
}

impl StaticGains {
    /// Entries of the full gain below this fraction of its largest are zero to rounding:
    /// their relative differences are not reported.
    pub const ZERO: f64 = 1e-12;

    /// The largest relative difference ROM vs full over the entries that are not zero to
    /// rounding, with its channel "output / input".
    pub fn largest_relative_difference(&self) -> Option<(f64, String)> {
        let (Ok(full), Ok(rom)) = (&self.full, &self.rom) else { return None };
        let pairs = || (0..full.nrows()).flat_map(|i| (0..full.ncols()).map(move |j| (i, j))).filter(|&(i, j)| !self.is_zero(i, j));
        let big = pairs().map(|(i, j)| full[(i, j)].abs()).fold(0.0, f64::max);
        let mut worst: Option<(f64, String)> = None;
        for (i, j) in pairs() {
            let f = full[(i, j)];
            let rel = if f.abs() > Self::ZERO * big { (rom[(i, j)] - f).abs() / f.abs() } else { (rom[(i, j)] - f).abs() / big.max(f64::MIN_POSITIVE) };
            if worst.as_ref().is_none_or(|w| rel > w.0) {
                worst = Some((rel, format!("{} / {}", self.output_names[i], self.input_names[j])));
            }
        }
        worst
    }

    /// The relative rounding of static gains on a model whose dynamic modes span
    /// `|λ|_max / |λ|_min = spread`: both the full model's LU and the ROM's residualization
    /// lose about `ε κ` of relative accuracy, and the static matrix's condition number `κ` is
    /// at least the stiffness-to-mass spread `spread²` the modes show (ω² = k/m); ten times
    /// `ε spread²`, never below 1e-9 (the threshold on well-conditioned models). Measured:
    /// examples/cantilever.mbd (beam3, EA/EJ = 1e5 m⁻², modes 119 to 1.03e6 rad/s:
    /// `ε spread²` = 1.7e-8) differs by 3.2e-8 with every dropped mode residualized, and by
    /// the same with every mode kept.
    pub fn rounding_of(spread: f64) -> f64 {
        (10.0 * f64::EPSILON * spread * spread).max(1e-9)
    }

    /// The relative difference channel (`i`, `j`) may show from rounding alone:
    /// `rounding × cancellation` (measured on examples/cantilever.mbd with every mode
    /// residualized: tip 3.2e-8; node 2 beside the clamp 2.8e-6, the same with every dynamic
    /// mode kept, so rounding: the same 1e-11 m/N absolute as the tip's, where the
    /// solution's scale is the tip's 3e-4 m/N against node 2's 1e-6).
    pub fn tolerance(&self, i: usize, j: usize) -> f64 {
        self.rounding * self.cancellation.get(i).and_then(|r| r.get(j)).copied().unwrap_or(1.0)
    }

    /// The channel whose relative difference exceeds its [`StaticGains::tolerance`] the most
    /// (over the channels not zero to rounding): its relative difference and "output / input".
    pub fn beyond_rounding(&self) -> Option<(f64, String)> {
        let (Ok(full), Ok(rom)) = (&self.full, &self.rom) else { return None };
        let pairs = (0..full.nrows()).flat_map(|i| (0..full.ncols()).map(move |j| (i, j))).filter(|&(i, j)| !self.is_zero(i, j));
        let big = pairs.clone().map(|(i, j)| full[(i, j)].abs()).fold(0.0, f64::max);
        let mut worst: Option<(f64, f64, String)> = None;
        for (i, j) in pairs {
            let f = full[(i, j)];
            let rel = (rom[(i, j)] - f).abs() / if f.abs() > Self::ZERO * big { f.abs() } else { big.max(f64::MIN_POSITIVE) };
            let excess = rel / self.tolerance(i, j);
            if excess > 1.0 && worst.as_ref().is_none_or(|w| excess > w.0) {
                worst = Some((excess, rel, format!("{} / {}", self.output_names[i], self.input_names[j])));
            }
        }
        worst.map(|(_, rel, channel)| (rel, channel))
    }

    /// Whether channel (output `i`, input `j`) is zero to rounding in the full model.
    pub fn is_zero(&self, i: usize, j: usize) -> bool {
        self.zero.get(i).and_then(|r| r.get(j)).copied().unwrap_or(false)
    }

    /// `‖G_rom‖_F / ‖G_full‖_F` over the channels not zero to rounding: how much of the full
    /// model's static gain the ROM keeps.
    pub fn kept_share(&self) -> Option<f64> {
        let (Ok(full), Ok(rom)) = (&self.full, &self.rom) else { return None };
        let norm = |g: &Mat<f64>| (0..g.nrows()).flat_map(|i| (0..g.ncols()).map(move |j| (i, j))).filter(|&(i, j)| !self.is_zero(i, j)).map(|(i, j)| g[(i, j)].powi(2)).sum::<f64>().sqrt();
        let f = norm(full);
        (f > 0.0).then(|| norm(rom) / f)
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
    /// The residualization asked for (what a warning may advise depends on it).
    pub residualization: Residualization,
    /// The top of the frequencies of interest [Hz]: the band's upper end, or the highest kept
    /// mode; static residualization holds only above it, and the response check warns only
    /// at or below it.
    pub interest_top_hz: f64,
    pub warnings: Vec<Warning>,
    /// The minimal realization and balanced reduction that made `ordinary` (`None`: its
    /// states are the kept modes').
    pub order: Option<super::OrderReduction>,
    /// The discrete-time form of `ordinary` (`--sample-rate`).
    pub discrete: Option<crate::rom::DiscreteRom>,
    /// `ordinary` without the modal damping the request added to the ROM only: the full model
    /// has none, so the accuracy check compares this one (the reduction's error, not the
    /// damping's: a 2 %-damped ROM of an undamped beam is 96 % off at its resonance).
    pub undamped: Option<UndampedTwin>,
}

/// The ROM of a damped request built without its damping ([`ReducedModel::undamped`]).
#[derive(Clone, Debug)]
pub struct UndampedTwin {
    pub ordinary: OrdinaryRom,
    /// The request's balanced reduction needs the damping (an undamped ROM has no stable
    /// mode): the twin is the modal ROM before it, whose own error the Hankel bound states.
    pub before_order_reduction: bool,
}

impl ReducedModel {
    /// Refuses a form that cannot hold this ROM: the descriptor form has no place for rate
    /// outputs' `C_v` nor for a static correction's `D`.
    pub fn check_form(&self, form: super::RomForm) -> Result<(), StudyError> {
        if form != super::RomForm::Descriptor {
            return Ok(());
        }
        let message = if self.order.is_some() || self.discrete.is_some() {
            "descriptor: a balanced, minimal or discrete-time ROM is an ordinary state-space model (x' = A x + B u, or x[k+1] = A x[k] + B u[k]); use the ordinary form"
        } else if self.descriptor.c_rate.is_some() {
            "descriptor: velocity outputs need z = C x + C_v x', which the descriptor export has no place for; use the ordinary form (its C and D carry them)"
        } else if self.static_correction {
            "descriptor: the sparse route's --residualize is a static correction of the ordinary ROM's D, which the descriptor form has no place for; use the ordinary form, or --solver dense"
        } else {
            return Ok(());
        };
        Err(StudyError::Option { option: super::Setting::Form, message: message.into() })
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
        // A count or modes ranked by dominance among modes not computed for that ranking
        // (a band ranks the band's modes, as asked).
        if let (Ranking::Dominance, Some(run)) = (request.ranking, &self.sparse) {
            if !run.dominance_pool && !matches!(request.selection, ModeSelection::Band { .. }) {
                warnings.push(Warning::DominanceAmongComputed { target: run.describe_target() });
            }
        }
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
        // A left vector that could not be scaled to uᵀ F_yd v = 1 (that product was rounding:
        // a repeated root with one vector, a critically damped mode): the mode adds nothing,
        // whatever the ports, and says why (issue 30).
        let once = |i: usize| modal.modes[i].partner.is_none_or(|p| p > i);
        let with_vectors: Vec<(usize, (&faer::Col<c64>, &faer::Col<c64>))> = sel.kept.iter().copied().filter(|&i| once(i)).filter_map(|i| Some((i, (modal.modes[i].left.as_ref()?, modal.modes[i].right.as_ref()?)))).collect();
        let products = self.linear.fyd_bilinear(&with_vectors.iter().map(|w| w.1).collect::<Vec<_>>());
        let unscaled: Vec<(usize, f64)> = with_vectors.iter().zip(products).filter(|(_, p)| (p - c64::new(1.0, 0.0)).norm() > 1e-6).map(|(w, _)| (w.0 + 1, modal.modes[w.0].freq_hz())).collect();
        let invisible: Vec<(usize, f64)> = sel.kept.iter().copied().filter(|&i| dominance.is_negligible(i) && once(i) && !unscaled.iter().any(|m| m.0 == i + 1)).map(|i| (i + 1, modal.modes[i].freq_hz())).collect();
        if !unscaled.is_empty() {
            warnings.push(Warning::Unscaled { modes: unscaled.clone() });
        }
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
        let mut ordinary = match descriptor.to_ordinary() {
            Ok(o) => o,
            Err(cause @ crate::rom::RomError::SingularStatic(_)) if !unscaled.is_empty() => return Err(StudyError::UnscaledModes { modes: unscaled.iter().map(|m| m.0).collect(), cause }),
            Err(e) => return Err(e.into()),
        };
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
        let (ordinary, order) = super::control::reduce_order(ordinary, request)?;
        let (discrete, aliased) = super::control::discretize(&ordinary, request)?;
        warnings.extend(aliased);
        let (zero, sums) = self.channel_sums();
        let rounding = StaticGains::rounding_of(self.modal_spread());
        // The LU's scale (dense route: the whole static solution) and the modal terms'.
        let solution = if self.sparse.is_none() { self.linear.dense_static_gain_scale() } else { None };
        let cancellation = match &full {
            Ok(g) => (0..g.nrows())
                .map(|i| {
                    (0..g.ncols())
                        .map(|j| {
                            let of_solution = solution.map_or(0.0, |s| s[(i, j)]);
                            (sums.absolute[(i, j)].max(of_solution) / g[(i, j)].abs()).max(1.0)
                        })
                        .collect()
                })
                .collect(),
            Err(_) => Vec::new(),
        };
        let rom_gain = rigid_body_modes(&ordinary.eigenvalues).map_or_else(|| ordinary.static_gain().map_err(|e| e.to_string()), Err);
        let static_gains = StaticGains { input_names: self.linear.input_names().to_vec(), output_names: self.linear.output_names().to_vec(), full, rom: rom_gain, zero, rounding, cancellation };
        if let Some((rel, channel)) = static_gains.largest_relative_difference() {
            let all_residualized = request.residualization == Residualization::Dropped && relevant.is_empty();
            // Where the ROM should match exactly, only a difference beyond rounding is one.
            let beyond = static_gains.beyond_rounding();
            let (reason, shown) = if corrected && let Some(b) = beyond {
                (Some(if below_dropped.is_empty() { "the static correction did not reach the full model's static gain (an ill-conditioned static matrix?)".to_string() } else { "modes below the frequencies of interest were not residualized (see above)".to_string() }), b)
            } else if all_residualized && let Some(b) = beyond {
                (Some("every dropped dynamic mode is residualized: the rest of the static response comes from the full model's infinite eigenvalues (algebraic or massless unknowns, not representable by modes) or is lost to rounding in an ill-conditioned static matrix".to_string()), b)
            } else if request.residualization == Residualization::Dropped && let Some(b) = beyond {
                (Some("modes below the frequencies of interest were not residualized (see above)".to_string()), b)
            } else if rel > 0.1 {
                (Some("the dropped modes carry it: keep more modes, --residualize, or --by dominance".to_string()), (rel, channel))
            } else {
                (None, (rel, channel))
            };
            if let Some(reason) = reason {
                warnings.push(Warning::StaticGain { relative: shown.0, channel: shown.1, reason });
            }
        }
        let kept_modes = crate::rom::mode_units(modal)
            .into_iter()
            .filter(|u| sel.kept.contains(&u[0]))
            .map(|u| KeptMode { indices: u.iter().map(|i| i + 1).collect(), lambda: modal.modes[u[0]].lambda, dominance: dominance.relative(u[0]) })
            .collect();
        // The ROM's own eigenvalues (those of the exported A) must be the kept modes' that the
        // summary reports (issue 30: a summary at 25.27 Hz next to an A with ±1.414e6j).
        // Removed springs and modal damping move them on purpose.
        let springs_removed = self.application.as_ref().is_some_and(|a| a.feedback.is_some());
        if !springs_removed && request.damping.is_none() && order.is_none() {
            let exported: Vec<faer::c64> = if ordinary.a.nrows() == 0 { Vec::new() } else { ordinary.a.as_ref().eigenvalues().unwrap_or_default() };
            warnings.extend(rom_eigenvalue_mismatch(modal, &sel.kept, &exported));
        }
        let undamped = if damping.is_empty() {
            None
        } else {
            let twin = RomRequest { damping: None, sampling: None, ..request.clone() };
            match self.reduce(&twin) {
                Ok(r) => Some(UndampedTwin { ordinary: r.ordinary, before_order_reduction: false }),
                Err(_) if twin.balanced.is_some() => Some(UndampedTwin { ordinary: self.reduce(&RomRequest { balanced: None, ..twin })?.ordinary, before_order_reduction: true }),
                Err(e) => return Err(e),
            }
        };
        Ok(ReducedModel { selection: sel, kept_modes, descriptor, ordinary, static_gains, damping, static_correction: corrected && full_ok, residualization: request.residualization.clone(), interest_top_hz: top, warnings, order, discrete, undamped })
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

    /// `|λ|_max / |λ|_min` over the dynamic modes found (1 without two of them).
    pub fn modal_spread(&self) -> f64 {
        let sizes = self.modal.of_kind(crate::eigen::ModeKind::Dynamic).map(|i| self.modal.modes[i].lambda.norm()).filter(|l| *l > 0.0 && l.is_finite());
        let (lo, hi) = sizes.fold((f64::INFINITY, 0.0f64), |(lo, hi), l| (lo.min(l), hi.max(l)));
        if hi > 0.0 && lo.is_finite() { hi / lo } else { 1.0 }
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

/// The kept modes whose reported λ has no eigenvalue of the ROM's ordinary `A` within
/// `max(10 × its error estimate, 1e-8 |λ|)`: a [`Warning::RomEigenvalues`] naming the worst.
fn rom_eigenvalue_mismatch(modal: &crate::eigen::ModalAnalysis, kept: &[usize], exported: &[faer::c64]) -> Option<Warning> {
    let mut worst: Option<(f64, usize, faer::c64, faer::c64)> = None;
    let mut count = 0;
    for &i in kept {
        let m = &modal.modes[i];
        let Some(near) = exported.iter().copied().min_by(|a, b| (a - m.lambda).norm().total_cmp(&(b - m.lambda).norm())) else { continue };
        let off = (near - m.lambda).norm();
        let allowed = (10.0 * m.error).max(1e-8 * m.lambda.norm());
        if !(off <= allowed) {
            count += 1;
            let rel = off / m.lambda.norm().max(near.norm());
            if worst.is_none_or(|w| rel > w.0) {
                worst = Some((rel, i + 1, m.lambda, near));
            }
        }
    }
    worst.map(|(relative, mode, reported, exported)| Warning::RomEigenvalues { modes: count, mode, reported, exported, relative })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eigen::{Classification, EigenRoute, ModalAnalysis, Mode, ModeKind};
    use faer::c64;

    fn mode(lambda: c64, error: f64) -> Mode {
        let classification = Classification { kind: ModeKind::Dynamic, alpha: lambda, beta: 1.0, to_zero: 1.0, to_infinity: 1.0, uncertainty: 0.0 };
        Mode { lambda, kind: ModeKind::Dynamic, error, classification, right: None, left: None, partner: None }
    }

    #[test]
    fn rom_eigenvalues_that_differ_from_the_reported_ones_are_named() {
        // Issue 30: a mode reported at 158.75 rad/s (25.27 Hz, error 1.3e2) whose exported A
        // has ±1.414e6j must be flagged; one within 10x its error estimate must not.
        let modal = ModalAnalysis { route: EigenRoute::Lambda, dcoef: 1.0, modes: vec![mode(c64::new(0.0, 158.75), 1.3e2), mode(c64::new(0.0, 10.0), 1e-9)] };
        let exported = [c64::new(0.0, 1.414e6), c64::new(0.0, -1.414e6)];
        match rom_eigenvalue_mismatch(&modal, &[0], &exported) {
            Some(Warning::RomEigenvalues { modes, mode, relative, .. }) => {
                assert_eq!((modes, mode), (1, 1));
                // |1.414e6 − 158.75| / 1.414e6.
                assert!((relative - (1.414e6 - 158.75) / 1.414e6).abs() < 1e-12, "{relative}");
            }
            other => panic!("{other:?}"),
        }
        assert!(rom_eigenvalue_mismatch(&modal, &[1], &[c64::new(0.0, 10.0 + 5e-9), c64::new(0.0, -10.0 - 5e-9)]).is_none());
    }
}
