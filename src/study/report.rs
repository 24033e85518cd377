//! The report of a study and one of its ROMs ([`crate::output::report`]): the texts
//! `romdyn rom` prints, the kept modes' shapes on the model's geometry and, with an imposed
//! motion, the transmissibility.

use faer::c64;

use crate::dae::Assembler;
use crate::output::mimo_plot::MimoPlot;
use crate::output::report::{Geometry, ModeShape, Report};

use super::{ReducedModel, RomCheck, Study};
use crate::linear::hz;

impl Study {
    /// The report of `rom` (checked by `check`) titled `title`: its summary, every warning,
    /// the modal table and, when the study has a model and a reference solution, each kept
    /// mode's right eigenvector at the structural nodes (translations, the first `3` unknowns
    /// of each node), scaled so the largest has unit length.
    pub fn report(&self, rom: &ReducedModel, check: &RomCheck, title: &str) -> Report {
        let mut warnings: Vec<String> = self.warnings().iter().map(|w| w.to_string()).collect();
        warnings.extend(rom.new_warnings(self, Some(check)).iter().map(|w| w.to_string()));
        let transmissibility = check.transmissibility.as_ref().map(|(t, _)| MimoPlot { title: "Transmissibility |z/z_e| (eq. 100)".into(), response: t.clone(), diagonal: false });
        Report { title: title.to_string(), summary: rom.summary(self, Some(check)), warnings, modal_table: self.modal_report().to_text_dynamic(12), geometry: self.geometry(rom), transmissibility, figures: Vec::new() }
    }

    fn geometry(&self, rom: &ReducedModel) -> Option<Geometry> {
        let (model, state) = (self.model()?, self.reference_state()?);
        let dofs = Assembler::new(model).dofs;
        if dofs.len != self.dae().unknown_names.len() || model.nodes.is_empty() {
            return None;
        }
        let nodes: Vec<[f64; 3]> = (0..model.nodes.len()).map(|i| state.node_frame(&dofs, i).kin.x.into()).collect();
        let mut edges: Vec<(usize, usize)> = dofs.element_nodes.iter().flat_map(|n| n.windows(2).map(|w| (w[0].min(w[1]), w[0].max(w[1])))).filter(|(a, b)| a != b).collect();
        edges.sort_unstable();
        edges.dedup();
        let modal = self.modal();
        let modes = rom
            .kept_modes
            .iter()
            .filter_map(|kept| {
                let index = *kept.indices.first()?;
                let mode = modal.modes.get(index.checked_sub(1)?)?;
                let v = mode.right.as_ref()?;
                let mut translations: Vec<[c64; 3]> = dofs.node_first.iter().map(|&f| [v[f], v[f + 1], v[f + 2]]).collect();
                let largest = translations.iter().map(|t| t.iter().map(|c| c.norm_sqr()).sum::<f64>().sqrt()).fold(0.0, f64::max);
                if largest == 0.0 || !largest.is_finite() {
                    return None;
                }
                for t in &mut translations {
                    for c in t.iter_mut() {
                        *c /= largest;
                    }
                }
                let hz = hz(mode.lambda.im.abs());
                Some(ModeShape { label: format!("mode {index}: {hz:.4} Hz"), translations })
            })
            .collect();
        Some(Geometry { nodes, node_labels: model.nodes.iter().map(|n| n.label).collect(), edges, modes })
    }
}
