//! The eigenanalysis of a model's linearization as every front end runs it (`romdyn run`'s
//! eigenanalyses, `romdyn::analysis`, and `romdyn eig`/`rom`, `romdyn::study::Study`): the
//! dense route solves and labels the pencil (eqs. 10–11, 29–35) and the modes' kinetic-energy
//! shares are read from `F_/ẏ`'s mass terms, the members of a degenerate cluster sharing
//! their cluster's (which do not depend on the basis the eigensolver chose). The same
//! linear DAE gives the same table on every front end.

use super::{degenerate_clusters, EigenError, EigenRoute, EnergyShare, ModalAnalysis, ModalEnergy, Mode};
use crate::linear::LinearDae;

/// Dense eigenanalysis of `dae` by `route` with the Λ form's dCoef `dcoef` (`None`: the
/// Jacobians' own, or the spectrum's, [`ModalAnalysis::of_dae`]); a failure names the
/// unknowns it is about.
pub fn dense_modes(dae: &LinearDae, route: EigenRoute, dcoef: Option<f64>) -> Result<ModalAnalysis, EigenError> {
    ModalAnalysis::of_dae(dae, route, dcoef).map_err(|e| e.with_unknown_names(&dae.unknown_names))
}

/// Kinetic-energy shares of every mode of `modes`; a member of a cluster of degenerate
/// modes ([`degenerate_clusters`]) has the cluster's shares ([`ModalEnergy::subspace_shares`]).
pub fn energy_shares(energy: &ModalEnergy, modes: &[Mode]) -> Vec<Vec<EnergyShare>> {
    // A cluster member's own shares are not computed (they were, then replaced: 32 of the
    // 40 modes of the 96,024-equation spring chain's 20 lowest, 0.2 s of its run).
    let mut of_cluster: Vec<Option<Vec<EnergyShare>>> = vec![None; modes.len()];
    for cluster in degenerate_clusters(modes) {
        let shares = energy.subspace_shares(&cluster.iter().map(|&i| &modes[i]).collect::<Vec<_>>());
        cluster.iter().for_each(|&i| of_cluster[i] = Some(shares.clone()));
    }
    modes.iter().zip(of_cluster).map(|(m, shares)| shares.unwrap_or_else(|| energy.shares(m))).collect()
}
