//! Building a ROM from a [`Study`]: selection, residualization, projection, SVD
//! residualization to the ordinary form, static gains against the full model.

use faer::Mat;

use crate::rom::{full_static_gain, select_modes, DescriptorRom, ModeSelection, OrdinaryRom, RomError, Selection};

use super::{Study, StudyError};

/// Which dropped dynamic modes a ROM keeps as static states (paper Fig. 7).
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Residualization {
    /// None: the ROM is the projection on the kept modes only.
    #[default]
    None,
    /// Every dynamic mode that the selection drops.
    Dropped,
    /// These modes (1-based modal-table indices; either member of a pair).
    Modes(Vec<usize>),
}

/// What ROM to build.
#[derive(Clone, Debug, PartialEq)]
pub struct RomRequest {
    pub selection: ModeSelection,
    pub residualization: Residualization,
}

impl RomRequest {
    /// The projection on `selection`, nothing residualized.
    pub fn new(selection: ModeSelection) -> Self {
        RomRequest { selection, residualization: Residualization::None }
    }

    /// The same request with `r` as residualization.
    pub fn residualize(mut self, r: Residualization) -> Self {
        self.residualization = r;
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

/// A ROM with what a user must know to trust it.
#[derive(Clone, Debug)]
pub struct ReducedModel {
    /// Kept and residualized modes (0-based indices into the modal analysis).
    pub selection: Selection,
    /// `E ẋ = A x + B u`, `z = C x` (eqs. 47–50).
    pub descriptor: DescriptorRom,
    /// `ẋ = A x + B u`, `z = C x + D u` (eqs. 51–63).
    pub ordinary: OrdinaryRom,
    pub static_gains: StaticGains,
}

impl Study {
    /// Builds the ROM that `request` describes.
    pub fn reduce(&self, request: &RomRequest) -> Result<ReducedModel, StudyError> {
        let (dae, modal) = (&self.dae, &self.modal);
        if dae.num_inputs() == 0 || dae.num_outputs() == 0 {
            return Err(StudyError::NoPorts);
        }
        let mut sel = select_modes(modal, &request.selection)?;
        if let Residualization::Modes(list) = &request.residualization {
            let chosen = select_modes(modal, &ModeSelection::Indices(list.clone()))?.kept;
            if let Some(k) = chosen.iter().find(|k| sel.kept.contains(k)) {
                return Err(StudyError::KeptAndResidualized(k + 1));
            }
            sel.dropped = chosen;
        }
        let residualize = request.residualization != Residualization::None;
        // Dummy springs (paper eqs. 92–95): projected with the springs present, then their
        // force fed back with a plus sign (`A + B_e K C_e`, see `rom::springs`).
        let applied = self.application.as_ref();
        let projected = applied.and_then(|a| a.projected.as_ref()).unwrap_or(dae);
        let mut descriptor = DescriptorRom::project(projected, modal, &sel, residualize)?;
        if let Some(fb) = applied.and_then(|a| a.feedback.as_ref()) {
            descriptor = descriptor.without_springs(fb)?;
        }
        let ordinary = descriptor.to_ordinary()?;
        let static_gains = StaticGains {
            input_names: dae.input_names.clone(),
            output_names: dae.output_names.clone(),
            full: full_static_gain(dae).map_err(|e: RomError| e.to_string()),
            rom: rigid_body_modes(&ordinary.eigenvalues).map_or_else(|| ordinary.static_gain().map_err(|e| e.to_string()), Err),
        };
        Ok(ReducedModel { selection: sel, descriptor, ordinary, static_gains })
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
