//! Which rotation update the beams take (the CLI's `--beam-update`, the Python package's
//! `beam_update`): MBDyn's incremental one where a result comes from a time integration,
//! so that an MBDyn file gives MBDyn's numbers, and the path-independent one where it is a
//! static equilibrium, which must not depend on load steps (the book's Beams
//! chapter, docs/src/mbdyn/beams.md: "beam.cc is incremental").

use super::Model;
use crate::element::BeamUpdate;

/// The beams' rotation update asked for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BeamUpdateChoice {
    /// MBDyn's incremental update for a result of a time integration, on every beam that can
    /// take it (the others keep the path-independent one, and say why); path independent
    /// otherwise.
    #[default]
    Auto,
    /// This update on every beam (an error names a beam that cannot take it).
    Every(BeamUpdate),
}

impl BeamUpdateChoice {
    /// The update a study that is not a time integration uses (a static equilibrium or the
    /// initial configuration: it must not depend on load steps).
    pub fn without_time_integration(self) -> BeamUpdate {
        match self {
            BeamUpdateChoice::Auto => BeamUpdate::PathIndependent,
            BeamUpdateChoice::Every(update) => update,
        }
    }
}

impl Model {
    /// Sets the beams' update as `choice` asks, for a result of a time integration
    /// (`integrates`: a run, a reference at a time) or not. `Ok`: why beams that `Auto`
    /// could not give MBDyn's update keep the path-independent one (empty if none).
    pub fn choose_beam_update(&mut self, choice: BeamUpdateChoice, integrates: bool) -> Result<Vec<String>, String> {
        if choice != BeamUpdateChoice::Auto || !integrates {
            self.set_beam_update(choice.without_time_integration())?;
            return Ok(Vec::new());
        }
        let mut kept = Vec::new();
        for e in self.elements.iter_mut() {
            match e.beam_update(BeamUpdate::Incremental) {
                Some(Ok(changed)) => *e = changed,
                Some(Err(why)) => kept.push(format!("{why}; this beam keeps the path-independent update, so its numbers can differ from MBDyn's (MBDyn's beam.cc is incremental)")),
                None => {}
            }
        }
        Ok(kept)
    }
}
