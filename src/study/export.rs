//! A ROM of a study in exportable form ([`RomExport`]).

use faer::{c64, Mat};

use crate::output::rom_file::{unit_of_name, RomExport};

use super::{ReducedModel, Study};
use crate::linear::hz;

/// Which ROM form to export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RomForm {
    /// `ẋ = A x + B u`, `z = C x + D u` (E = I).
    Ordinary,
    /// `E ẋ = A x + B u`, `z = C x` (states of residualized modes have zero rows of E).
    Descriptor,
}

fn sorted(mut v: Vec<c64>) -> Vec<c64> {
    v.sort_by(|a, b| a.norm().total_cmp(&b.norm()).then(b.im.total_cmp(&a.im)));
    v
}

impl ReducedModel {
    /// The ROM's own eigenvalues: those of the ordinary `A` [rad/s] (the finite
    /// eigenvalues of the descriptor pencil `(A, E)` are the same), by increasing |λ|.
    pub fn eigenvalues(&self) -> Vec<c64> {
        if self.ordinary.a.nrows() == 0 {
            return Vec::new();
        }
        sorted(self.ordinary.a.as_ref().eigenvalues().unwrap_or_default())
    }

    /// The export of this ROM in `form`.
    pub fn export(&self, study: &Study, form: RomForm) -> RomExport {
        let modal = study.modal();
        let d = &self.descriptor;
        let (kind, e, a, b, c, dd, states, state_modes): (_, _, _, _, _, _, Vec<String>, Vec<usize>) = match form {
            RomForm::Ordinary => {
                // A discrete ROM's matrices; states: the kept modes' (SVD of E = I on them),
                // or the balanced, minimal or canonical states that replaced them.
                let o = self.discrete.as_ref().map_or(&self.ordinary, |dr| &dr.rom);
                let n = o.a.nrows();
                let renamed = self.discrete.as_ref().and_then(|dr| dr.state_names.clone()).or_else(|| self.order.as_ref().and_then(|r| r.states.clone()));
                let (names, modes) = match renamed {
                    Some(names) => (names, vec![0; n]),
                    None => (d.state_names.iter().take(n).cloned().collect(), d.state_modes.iter().take(n).map(|m| m + 1).collect()),
                };
                ("ordinary", Mat::identity(n, n), o.a.clone(), o.b.clone(), o.c.clone(), o.d.clone(), names, modes)
            }
            RomForm::Descriptor => {
                let kept = d.state_modes.len() - d.static_states;
                let modes = d.state_modes.iter().enumerate().map(|(k, m)| if k < kept { m + 1 } else { 0 }).collect();
                let names = d.state_names.iter().enumerate().map(|(k, s)| if k < kept { s.clone() } else { format!("{s} (static)") }).collect();
                ("descriptor", d.e.clone(), d.a.clone(), d.b.clone(), d.c.clone(), Mat::zeros(d.c.nrows(), d.b.ncols()), names, modes)
            }
        };
        let state_freq_hz = state_modes.iter().map(|&m| if m == 0 { f64::NAN } else { hz(modal.modes[m - 1].lambda.im.abs()) }).collect();
        RomExport {
            kind,
            e,
            a,
            b,
            c,
            d: dd,
            eigenvalues: match &self.discrete {
                Some(dr) => sorted(dr.rom.eigenvalues.clone()),
                None => self.eigenvalues(),
            },
            full_eigenvalues: self.selection.kept.iter().map(|&i| modal.modes[i].lambda).collect(),
            inputs: d.input_names.clone(),
            outputs: d.output_names.clone(),
            state_units: states.iter().map(|s| if s.starts_with("mode ") { "modal coordinate (scaled by u^T F_yd v = 1)" } else { "combination of modal coordinates" }.to_string()).collect(),
            states,
            input_units: d.input_names.iter().map(|n| unit_of_name(n)).collect(),
            output_units: d.output_names.iter().map(|n| unit_of_name(n)).collect(),
            state_modes,
            state_freq_hz,
            reference_time: study.reference_time(),
            dcoef: modal.dcoef,
            full_static_gain: self.static_gains.full.clone().ok(),
            rom_static_gain: self.static_gains.rom.clone().ok(),
            sample_time: self.discrete.as_ref().map(|dr| dr.sample_time()),
            discretization: self.discrete.as_ref().map_or("continuous".into(), |dr| dr.sampling.method.name()),
            hankel_singular_values: self.order.as_ref().and_then(|o| o.balanced.as_ref()).map_or(Vec::new(), |b| b.hankel.clone()),
            error_bound: self.order.as_ref().and_then(|o| o.balanced.as_ref()).map(|b| b.error_bound),
        }
    }
}
