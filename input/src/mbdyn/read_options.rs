//! How the reader builds a file's model: the `set:` variables given other values (a design
//! point) and the rotation update its beams take (the CLI's `--beam-update`, the Python
//! package's `beam_update`). The beam update is chosen here, card by card, so that a beam
//! that cannot take the update asked for is named at its card: MBDyn's incremental update
//! where a result comes from a time integration, so that an MBDyn file gives MBDyn's
//! numbers, and the path-independent one where it is a static equilibrium, which must not
//! depend on load steps (the book's Beams chapter, docs/src/mbdyn/beams.md: "beam.cc is
//! incremental").

use super::syntax::expr::SetOverrides;
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
    /// The rule the reader applies to each beam card, for a result of a time integration
    /// (`time_integration`: a run, a reference at a time) or not (a static equilibrium or
    /// the initial configuration: it must not depend on load steps).
    pub fn rule(self, time_integration: bool) -> BeamUpdateRule {
        match self {
            BeamUpdateChoice::Auto if time_integration => BeamUpdateRule::IncrementalWherePossible,
            BeamUpdateChoice::Auto => BeamUpdateRule::Every(BeamUpdate::PathIndependent),
            BeamUpdateChoice::Every(update) => BeamUpdateRule::Every(update),
        }
    }
}

/// The rotation update the reader gives each `beam3` and `beam2` card.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BeamUpdateRule {
    /// This update on every beam; a beam that cannot take it is an error at its card.
    Every(BeamUpdate),
    /// MBDyn's incremental update on every beam that can take it; the others (a viscous
    /// section law, a driven beam) keep the path-independent one, each with a note
    /// ([`super::MbdynModel::beam_notes`]).
    IncrementalWherePossible,
}

impl Default for BeamUpdateRule {
    /// Path independent: the library's default, whatever the analysis.
    fn default() -> Self {
        BeamUpdateRule::Every(BeamUpdate::PathIndependent)
    }
}

static NO_OVERRIDES: SetOverrides = SetOverrides::new();

/// How [`super::read_model_with`] and [`super::read_model_text`] read a file. A bare
/// `&SetOverrides` converts into options with the default (path-independent) beam update.
#[derive(Clone, Copy, Debug)]
pub struct ReadOptions<'a> {
    /// `set:` variables given other values (a variable the file does not declare is an
    /// error).
    pub overrides: &'a SetOverrides,
    /// The beams' rotation update.
    pub beam_update: BeamUpdateRule,
}

impl Default for ReadOptions<'_> {
    fn default() -> Self {
        ReadOptions { overrides: &NO_OVERRIDES, beam_update: BeamUpdateRule::default() }
    }
}

impl<'a> From<&'a SetOverrides> for ReadOptions<'a> {
    fn from(overrides: &'a SetOverrides) -> Self {
        ReadOptions { overrides, ..ReadOptions::default() }
    }
}

impl<'a> ReadOptions<'a> {
    /// The file read with `overrides` and its beams' update chosen by `choice` for a result
    /// of a time integration (`time_integration`) or not.
    pub fn new(overrides: &'a SetOverrides, choice: BeamUpdateChoice, time_integration: bool) -> Self {
        ReadOptions { overrides, beam_update: choice.rule(time_integration) }
    }
}
