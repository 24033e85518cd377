//! A ROM of a study in exportable form ([`RomExport`]).

use faer::{c64, Mat};

use crate::output::rom_file::{unit_of_name, RomExport};

use super::{ReducedModel, Study};

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
                let n = self.ordinary.a.nrows();
                // The ordinary form's states are the kept modes' (SVD of E = I on them).
                let modes: Vec<usize> = d.state_modes.iter().take(n).map(|m| m + 1).collect();
                let names = d.state_names.iter().take(n).cloned().collect();
                ("ordinary", Mat::identity(n, n), self.ordinary.a.clone(), self.ordinary.b.clone(), self.ordinary.c.clone(), self.ordinary.d.clone(), names, modes)
            }
            RomForm::Descriptor => {
                let kept = d.state_modes.len() - d.static_states;
                let modes = d.state_modes.iter().enumerate().map(|(k, m)| if k < kept { m + 1 } else { 0 }).collect();
                let names = d.state_names.iter().enumerate().map(|(k, s)| if k < kept { s.clone() } else { format!("{s} (static)") }).collect();
                ("descriptor", d.e.clone(), d.a.clone(), d.b.clone(), d.c.clone(), Mat::zeros(d.c.nrows(), d.b.ncols()), names, modes)
            }
        };
        let state_freq_hz = state_modes.iter().map(|&m| if m == 0 { f64::NAN } else { modal.modes[m - 1].lambda.im.abs() / (2.0 * std::f64::consts::PI) }).collect();
        RomExport {
            kind,
            e,
            a,
            b,
            c,
            d: dd,
            eigenvalues: self.eigenvalues(),
            full_eigenvalues: self.selection.kept.iter().map(|&i| modal.modes[i].lambda).collect(),
            inputs: d.input_names.clone(),
            outputs: d.output_names.clone(),
            state_units: states.iter().map(|_| "modal coordinate (scaled by u^T F_yd v = 1)".to_string()).collect(),
            states,
            input_units: d.input_names.iter().map(|n| unit_of_name(n)).collect(),
            output_units: d.output_names.iter().map(|n| unit_of_name(n)).collect(),
            state_modes,
            state_freq_hz,
            reference_time: study.reference_time(),
            dcoef: modal.dcoef,
            full_static_gain: self.static_gains.full.clone().ok(),
            rom_static_gain: self.static_gains.rom.clone().ok(),
        }
    }
}
