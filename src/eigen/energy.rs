//! Which node and component a mode moves: shares of its kinetic energy (issue 3, item 7).
//!
//! A dynamic node's momentum-definition rows of `F_/ẏ` hold `−M_n`, its 6x6 mass matrix
//! (translation and rotation about the node). For a mode `v` with eigenvalue λ the nodal
//! velocities are `λ v`; the share of component `k` of node `n` is
//! `M_n,kk |v_k|² / Σ M_m,jj |v_j|²` (diagonal terms; `|λ|²` cancels).
//!
//! A mode that moves no structural node (a controller's, a filter's: it lives in scalar nodes, issue
//! 34) is described instead by the scalar nodes its vector moves (`component` "abstract",
//! "electric", "hydraulic"; shares `|v_k|² / Σ |v_j|²`, which depend on the nodes' units,
//! so [`describe`] names the nodes without them).

use super::Mode;
use crate::dae::DofMap;
use crate::linear::LinearDae;
use crate::model::{Model, NodeKind};

pub(super) const COMPONENTS: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];

/// One node component's share of a mode's kinetic energy.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct EnergyShare {
    pub node: u32,
    pub component: &'static str,
    /// Fraction in [0, 1].
    pub share: f64,
}

/// The diagonal mass terms of every dynamic node component, read once from `F_/ẏ`, to
/// share out the kinetic energy of any number of modes.
pub struct ModalEnergy {
    /// `(node label, component, unknown index, mass)`.
    pub(super) terms: Vec<(u32, &'static str, usize, f64)>,
    /// `(node label, kind, unknown index)` of every scalar node.
    pub(super) scalars: Vec<(u32, &'static str, usize)>,
    /// The unknowns in other units than the mechanical ones: scalar nodes' and the own
    /// unknowns of elements on scalar nodes (a motor's current, an actuator's pressures).
    pub(super) non_mechanical: Vec<usize>,
}

impl ModalEnergy {
    pub fn new(model: &Model, dae: &LinearDae) -> Self {
        let (fyd, _) = dae.jacobians.derivatives();
        Self::from_fyd_diagonal(model, &(0..fyd.nrows()).map(|k| fyd[(k, k)]).collect::<Vec<_>>())
    }

    /// The same from the diagonal of `F_/ẏ` alone (a sparse linearization's).
    pub fn from_fyd_diagonal(model: &Model, fyd: &[f64]) -> Self {
        let dofs = DofMap::new(model);
        let mut terms = Vec::new();
        for (i, node) in model.nodes.iter().enumerate() {
            if dofs.node_kind[i] != NodeKind::Dynamic {
                continue;
            }
            let f = dofs.node_first[i];
            for (k, component) in COMPONENTS.iter().enumerate() {
                terms.push((node.label, *component, f + k, (-fyd[f + k]).max(0.0)));
            }
        }
        let scalars: Vec<(u32, &'static str, usize)> = model.scalar_nodes.iter().enumerate().map(|(i, n)| (n.id.label, n.id.kind.keyword(), dofs.scalar_first + i)).collect();
        let own = model.elements.iter().enumerate().filter(|(_, e)| !e.scalar_nodes().is_empty()).flat_map(|(k, _)| dofs.element_first[k]..dofs.element_first[k] + dofs.element_len[k]);
        let non_mechanical = scalars.iter().map(|s| s.2).chain(own).collect();
        ModalEnergy { terms, scalars, non_mechanical }
    }

    /// Kinetic-energy shares of a mode, largest first (empty without eigenvector or mass).
    pub fn shares(&self, mode: &Mode) -> Vec<EnergyShare> {
        let Some(v) = &mode.right else { return Vec::new() };
        let mut out: Vec<EnergyShare> = self.terms.iter().map(|&(node, component, j, mass)| EnergyShare { node, component, share: mass * v[j].norm_sqr() }).collect();
        let mut total: f64 = out.iter().map(|s| s.share).sum();
        // A mode whose massive components are rounding next to its largest entry moves no
        // mass: a first-order mode of a viscous element on a static node gave "node 4 x
        // 100 %" of a kinetic energy of 1e-30 (seen on tests/mbdyn_files/time_variant_laws.mbd).
        // Reaction-dominated vectors keep their share (1e-4 of the largest entry in
        // examples/ham_sas.mbd's base modes).
        // Pressures [Pa] or voltages next to displacements [m] differ by their units, not by
        // rounding (a hydraulic actuator's mode moves 1e10 Pa per metre): the mass moves when
        // its entries pass 1e-10 of the largest mechanical entry and 1e-14 of the largest of
        // all (the same test as before in a model without scalar nodes).
        let largest = v.iter().map(|x| x.norm()).fold(0.0, f64::max);
        let mut mechanical = v.iter().map(|x| x.norm()).collect::<Vec<f64>>();
        self.non_mechanical.iter().for_each(|&k| mechanical[k] = 0.0);
        let largest_mechanical = mechanical.iter().copied().fold(0.0, f64::max);
        let moved = self.terms.iter().filter(|t| t.3 > 0.0).map(|t| v[t.2].norm()).fold(0.0, f64::max);
        if total <= 0.0 || moved <= 1e-10 * largest_mechanical || moved <= 1e-14 * largest {
            // No mass moves: the mode lives in the scalar nodes (a controller, a filter), or
            // in massless nodes (then it is described by nothing rather than by rounding).
            out = self.scalars.iter().map(|&(node, component, j)| EnergyShare { node, component, share: v[j].norm_sqr() }).collect();
            total = out.iter().map(|s| s.share).sum();
            if !(total > 0.0) {
                return Vec::new();
            }
            out.retain(|s| s.share > 1e-12 * total);
        }
        out.iter_mut().for_each(|s| s.share /= total);
        out.retain(|s| s.share > 0.0);
        out.sort_by(|a, b| b.share.total_cmp(&a.share));
        out
    }
}

/// Kinetic-energy shares of one mode (for several modes, build one [`ModalEnergy`]).
pub fn kinetic_energy_shares(model: &Model, dae: &LinearDae, mode: &Mode) -> Vec<EnergyShare> {
    ModalEnergy::new(model, dae).shares(mode)
}

/// "node 3 rz 92 %, node 2 x 6 %": the components above 5 % (at least the largest); for a
/// mode that moves no structural node, the scalar nodes it moves: "no structural node moves
/// (abstract nodes 1, 2)".
pub fn describe(shares: &[EnergyShare]) -> String {
    if shares.first().is_some_and(|s| !COMPONENTS.contains(&s.component)) {
        let mut kinds: Vec<(&str, Vec<u32>)> = Vec::new();
        for s in shares {
            match kinds.iter_mut().find(|(k, _)| *k == s.component) {
                Some((_, labels)) => labels.push(s.node),
                None => kinds.push((s.component, vec![s.node])),
            }
        }
        let parts: Vec<String> = kinds
            .into_iter()
            .map(|(kind, mut labels)| {
                labels.sort_unstable();
                let list: Vec<String> = labels.iter().map(|l| l.to_string()).collect();
                format!("{kind} node{} {}", if labels.len() > 1 { "s" } else { "" }, list.join(", "))
            })
            .collect();
        return format!("no structural node moves ({})", parts.join("; "));
    }
    shares
        .iter()
        .enumerate()
        .filter(|(i, s)| *i == 0 || s.share >= 0.05)
        .map(|(_, s)| format!("node {} {} {:.0} %", s.node, s.component, 100.0 * s.share))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A one-line label a control engineer reads, "table pitch (ry) 93 %": the node component
/// with the largest share of the mode's kinetic energy, named by its node's name (else
/// "node N") and by the direction of its motion relative to gravity (`vertical`, `yaw` about
/// the vertical, `horizontal`, and `roll`/`pitch` about the first/second horizontal axis);
/// without gravity the axis letters only. `None` without shares.
pub fn mode_label(shares: &[EnergyShare], names: &std::collections::BTreeMap<u32, String>, gravity: &crate::kinematics::Vec3) -> Option<String> {
    let top = shares.iter().max_by(|a, b| a.share.total_cmp(&b.share))?;
    let node = names.get(&top.node).cloned().unwrap_or_else(|| format!("node {}", top.node));
    Some(format!("{node} {}", motion_words(top.component, top.share, gravity)?))
}

/// "yaw (rz) 93 %" (with gravity) or "rz 93 %" (without): the direction words of
/// [`mode_label`] for node component `component` holding `share` of the energy.
pub(super) fn motion_words(component: &str, share: f64, gravity: &crate::kinematics::Vec3) -> Option<String> {
    let k = COMPONENTS.iter().position(|c| *c == component)?;
    let vertical = (gravity.norm() > 0.0).then(|| gravity.iamax());
    let word = match vertical {
        None => None,
        Some(v) => {
            let axis = k % 3;
            let horizontal: Vec<usize> = (0..3).filter(|&a| a != v).collect();
            Some(match (k < 3, axis == v) {
                (true, true) => "vertical",
                (true, false) => "horizontal",
                (false, true) => "yaw",
                (false, false) if axis == horizontal[0] => "roll",
                (false, false) => "pitch",
            })
        }
    };
    let pct = 100.0 * share;
    Some(match word {
        Some(w) => format!("{w} ({component}) {pct:.0} %"),
        None => format!("{component} {pct:.0} %"),
    })
}

/// A label for a real eigenvalue `lambda` [rad/s] (a `±a` pair of an unstable equilibrium,
/// e.g. a free structure standing on its ground point) with its mode's kinetic-energy
/// shares: "tipping (ry): base ry 48 %, spring box x 28 %, table x 23 %, unstable" when the
/// largest share is a rotation about a horizontal axis (relative to gravity; the components
/// above 5 % named), else [`mode_label`]'s words ("node 2 horizontal (x) 100 %, unstable");
/// "unstable" for λ > 0 (the motion grows as e^{λt}), "stable" for λ < 0. `None` without
/// shares.
pub fn real_mode_label(shares: &[EnergyShare], names: &std::collections::BTreeMap<u32, String>, gravity: &crate::kinematics::Vec3, lambda: f64) -> Option<String> {
    let top = shares.iter().max_by(|a, b| a.share.total_cmp(&b.share))?;
    let k = COMPONENTS.iter().position(|c| *c == top.component)?;
    let tipping = gravity.norm() > 0.0 && k >= 3 && k % 3 != gravity.iamax();
    let head = if tipping {
        let parts: Vec<String> = shares
            .iter()
            .enumerate()
            .filter(|(i, s)| *i == 0 || s.share >= 0.05)
            .map(|(_, s)| format!("{} {} {:.0} %", names.get(&s.node).cloned().unwrap_or_else(|| format!("node {}", s.node)), s.component, 100.0 * s.share))
            .collect();
        format!("tipping ({}): {}", top.component, parts.join(", "))
    } else {
        mode_label(shares, names, gravity)?
    };
    Some(format!("{head}, {}", if lambda > 0.0 { "unstable" } else { "stable" }))
}
