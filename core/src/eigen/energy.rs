//! Which node, component or element state a mode lives in: shares of the energy it
//! stores (issue 3, item 7; issues 34 and 35).
//!
//! A dynamic node's momentum-definition rows of `F_/ẏ` hold `−M_n`, its 6x6 mass matrix
//! (translation and rotation about the node). For a mode `v` with eigenvalue λ the nodal
//! velocities are `λ v`; node component `k` holds the kinetic energy `½ M_n,kk |λ v_k|²`
//! (diagonal terms). Elements add the energy their own unknowns store
//! ([`crate::element::EnergyStore`], physical energies in joules, so that the shares do not
//! depend on units): a motor's current `½ L |v_i|²`, an actuator chamber's pressure
//! `½ (V/β) |v_p|²`, a modal joint's mode `½ Mₖₖ |λ v_q|²`. Physical energy rather than a
//! per-group normalization: it compares a current with a rotor's speed the way the mode
//! trades one for the other (the DC motor's −974 rad/s mode is 97 % magnetic energy, its
//! −25.7 rad/s mode 97 % the rotor's), with no scale to choose. A structure's strain energy
//! is not counted (it needs the stiffness matrix per element, which a sparse linearization
//! does not keep): a mass on a spring is the mass's alone, a mass on a fluid column shares
//! its energy with the column's compression.
//!
//! Unknowns that store no energy (abstract nodes, electric and hydraulic node values,
//! genels' and filters' states: a controller's signals) take part by their participation
//! factor `πₖ = vₖ (F_/ẏᵀ u)ₖ` (Pérez-Arriaga, Verghese and Schweppe, 1982: with `uᵀ F_/ẏ v
//! = 1` the factors of all unknowns add up to 1, and they do not change when an unknown or
//! an equation is scaled, so they do not depend on units either). The signals hold
//! `P = |Σπ| / (|Σπ| + |1 − Σπ|)` of the mode (each `P |πₖ| / Σ|π|`), the energy stores the
//! rest in proportion to their energies: the mode of a PID loop's derivative filter says it
//! lives in the controller. Without a left vector (the sparse route's modes) the signals
//! take no part, and a mode with no energy at all is shared over the scalar nodes by
//! `|vₖ|²` (which depends on their units).

use super::Mode;
use crate::dae::{Assembler, DofMap, State};
use crate::linear::LinearDae;
use crate::model::{Model, NodeKind};
use faer::c64;

pub(super) const COMPONENTS: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];

/// One node component's, scalar node's or element state's share of a mode.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct EnergyShare {
    /// The node's label (structural or scalar), or the element's.
    pub node: u32,
    /// "x" … "rz" of a structural node; "abstract", "electric", "hydraulic" of a scalar
    /// node; "element" of an element's own unknown.
    pub component: &'static str,
    /// Fraction in [0, 1].
    pub share: f64,
    /// An element's own unknown: the element's type ("motor", "actuator", "modal joint",
    /// "genel mass"), its label in `node`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub element: Option<String>,
    /// What that unknown is ("current", "chamber 1 pressure", "mode 3").
    #[serde(skip_serializing_if = "Option::is_none")]
    pub state: Option<String>,
    /// A modal joint's mode: its number in the FEM file.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mode: Option<usize>,
}

impl EnergyShare {
    pub(super) fn of_node(node: u32, component: &'static str, share: f64) -> Self {
        EnergyShare { node, component, share, element: None, state: None, mode: None }
    }

    /// "node 3 rz", "abstract node 1", "motor 5 current", "modal joint 10 mode 3".
    pub fn who(&self) -> String {
        match &self.element {
            Some(e) => format!("{e} {} {}", self.node, self.state.as_deref().unwrap_or("")).trim_end().to_string(),
            None if COMPONENTS.contains(&self.component) => format!("node {} {}", self.node, self.component),
            None => format!("{} node {}", self.component, self.node),
        }
    }
}

/// An unknown that stores energy or takes part by participation, with what it is.
#[derive(Clone, Debug)]
pub(super) struct Part {
    who: EnergyShare,
    unknown: usize,
    /// A store's `½ weight |y|²` (or `|ẏ|²` when `rate`).
    weight: f64,
    rate: bool,
    /// A signal's column of `F_/ẏ` (row, value), when known.
    column: Vec<(usize, f64)>,
}

/// The diagonal mass terms of every dynamic node component, read once from `F_/ẏ`, the
/// elements' energy stores and the signals' columns of `F_/ẏ`, to share out any number of
/// modes.
#[derive(Default)]
pub struct ModalEnergy {
    /// `(node label, component, unknown index, mass)`.
    pub(super) terms: Vec<(u32, &'static str, usize, f64)>,
    /// `(node label, kind, unknown index)` of every scalar node.
    pub(super) scalars: Vec<(u32, &'static str, usize)>,
    /// The unknowns in other units than the mechanical ones: scalar nodes' and the own
    /// unknowns of elements on scalar nodes (a motor's current, an actuator's pressures).
    pub(super) non_mechanical: Vec<usize>,
    pub(super) stores: Vec<Part>,
    pub(super) signals: Vec<Part>,
}

impl ModalEnergy {
    /// From a dense linearization (the signals' columns of its `F_/ẏ` included), the
    /// elements' stores at the model's initial state ([`ModalEnergy::at_state`]).
    pub fn new(model: &Model, dae: &LinearDae) -> Self {
        let (fyd, _) = dae.jacobians.derivatives();
        let energy = Self::from_fyd_diagonal(model, &(0..fyd.nrows()).map(|k| fyd[(k, k)]).collect::<Vec<_>>());
        let columns = energy.signal_unknowns().iter().map(|&k| (0..fyd.nrows()).map(|i| (i, fyd[(i, k)])).filter(|e| e.1 != 0.0).collect()).collect();
        energy.with_fyd_columns(columns)
    }

    /// The same from the diagonal of `F_/ẏ` alone (a sparse linearization's): the signals'
    /// columns unknown ([`ModalEnergy::with_fyd_columns`] gives them).
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
        let non_mechanical = Self::non_mechanical_mask(model).iter().enumerate().filter(|(_, m)| **m).map(|(k, _)| k).collect();
        let state = State::initial(model, &dofs);
        ModalEnergy { terms, scalars, non_mechanical, ..Default::default() }.at_state(model, &state)
    }

    /// The elements' energy stores evaluated at `state` (an actuator's chamber volumes
    /// follow its stroke), and the signals: scalar nodes and the own unknowns of elements on
    /// scalar nodes that store nothing.
    pub fn at_state(mut self, model: &Model, state: &State) -> Self {
        let asm = Assembler::new(model);
        let element = |e: usize| {
            let el = &model.elements[e];
            (el.label(), if el.type_name() == "modal" { "modal joint".to_string() } else { el.type_name().to_string() })
        };
        self.stores = asm
            .energy_stores(state)
            .into_iter()
            .map(|(e, unknown, s)| {
                let (label, kind) = element(e);
                let who = EnergyShare { element: Some(kind), state: Some(s.name), mode: s.mode, ..EnergyShare::of_node(label, "element", 0.0) };
                Part { who, unknown, weight: s.weight.max(0.0), rate: s.rate, column: Vec::new() }
            })
            .collect();
        let stored: Vec<usize> = self.stores.iter().map(|s| s.unknown).collect();
        let mut signals: Vec<Part> = self.scalars.iter().map(|&(node, kind, unknown)| Part { who: EnergyShare::of_node(node, kind, 0.0), unknown, weight: 0.0, rate: false, column: Vec::new() }).collect();
        for (e, el) in model.elements.iter().enumerate() {
            if el.scalar_nodes().is_empty() {
                continue;
            }
            let (label, kind) = element(e);
            for (k, name) in el.multipliers().into_iter().enumerate() {
                let unknown = asm.dofs.element_first[e] + k;
                if !stored.contains(&unknown) {
                    let who = EnergyShare { element: Some(kind.clone()), state: Some(name), ..EnergyShare::of_node(label, "element", 0.0) };
                    signals.push(Part { who, unknown, weight: 0.0, rate: false, column: Vec::new() });
                }
            }
        }
        // Columns given before (a dense linearization's) stay with their unknowns.
        for s in &mut signals {
            s.column = self.signals.iter().find(|o| o.unknown == s.unknown).map(|o| o.column.clone()).unwrap_or_default();
        }
        self.signals = signals;
        self
    }

    /// Every unknown in other units than the mechanical ones (`true`, by index): scalar
    /// nodes' and the own unknowns of elements on scalar nodes.
    pub fn non_mechanical_mask(model: &Model) -> Vec<bool> {
        let dofs = DofMap::new(model);
        let mut mask = vec![false; dofs.len];
        (0..model.scalar_nodes.len()).for_each(|i| mask[dofs.scalar_first + i] = true);
        for (k, e) in model.elements.iter().enumerate() {
            if !e.scalar_nodes().is_empty() {
                mask[dofs.element_first[k]..dofs.element_first[k] + dofs.element_len[k]].fill(true);
            }
        }
        mask
    }

    /// The signals' unknowns, in the order [`ModalEnergy::with_fyd_columns`] takes their columns.
    pub fn signal_unknowns(&self) -> Vec<usize> {
        self.signals.iter().map(|s| s.unknown).collect()
    }

    /// The signals' columns of `F_/ẏ` (row, value), one per [`ModalEnergy::signal_unknowns`].
    pub fn with_fyd_columns(mut self, columns: Vec<Vec<(usize, f64)>>) -> Self {
        self.signals.iter_mut().zip(columns).for_each(|(s, c)| s.column = c);
        self
    }

    /// Shares of a mode, largest first (empty without eigenvector, energy or participation).
    pub fn shares(&self, mode: &Mode) -> Vec<EnergyShare> {
        let Some(v) = &mode.right else { return Vec::new() };
        // Stores of a value (a current) against kinetic energies `½ m |λ v|²`: only for a
        // finite nonzero λ; otherwise the kinetic energies alone, `|λ|²` cancelling.
        let lam2 = mode.lambda.norm_sqr();
        let moving = lam2.is_finite() && lam2 > 0.0;
        let speed2 = if moving { lam2 } else { 1.0 };
        let mut out: Vec<EnergyShare> = self.terms.iter().map(|&(node, component, j, mass)| EnergyShare::of_node(node, component, mass * v[j].norm_sqr() * speed2)).collect();
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
        if moved <= 1e-10 * largest_mechanical || moved <= 1e-14 * largest {
            out.clear();
        }
        for s in self.stores.iter().filter(|s| s.rate || moving) {
            out.push(EnergyShare { share: s.weight * v[s.unknown].norm_sqr() * if s.rate { speed2 } else { 1.0 }, ..s.who.clone() });
        }
        let total: f64 = out.iter().map(|s| s.share).sum();
        let has_energy = total > 0.0 && total.is_finite();
        match (self.participation(mode), has_energy) {
            (Some((p, signals)), true) => {
                out.iter_mut().for_each(|s| s.share *= (1.0 - p) / total);
                out.extend(signals);
            }
            (None, true) => out.iter_mut().for_each(|s| s.share /= total),
            (Some((p, signals)), false) if p > 0.0 => out = signals.into_iter().map(|s| EnergyShare { share: s.share / p, ..s }).collect(),
            _ => {
                // No energy and no participation: the scalar nodes the vector moves.
                out = self.scalars.iter().map(|&(node, component, j)| EnergyShare::of_node(node, component, v[j].norm_sqr())).collect();
                let total: f64 = out.iter().map(|s| s.share).sum();
                if !(total > 0.0) {
                    return Vec::new();
                }
                out.retain(|s| s.share > 1e-12 * total);
                out.iter_mut().for_each(|s| s.share /= total);
            }
        }
        out.retain(|s| s.share > 0.0);
        out.sort_by(|a, b| b.share.total_cmp(&a.share));
        out
    }

    /// The signals' part `P` of a mode and their shares (`P |πₖ| / Σ|π|`, module doc);
    /// `None` without a left vector or without a signal that has a column of `F_/ẏ`.
    fn participation(&self, mode: &Mode) -> Option<(f64, Vec<EnergyShare>)> {
        let (v, u) = (mode.right.as_ref()?, mode.left.as_ref()?);
        if self.signals.iter().all(|s| s.column.is_empty()) {
            return None;
        }
        let pi: Vec<c64> = self.signals.iter().map(|s| v[s.unknown] * s.column.iter().fold(c64::new(0.0, 0.0), |acc, &(i, x)| acc + u[i] * x)).collect();
        let sum: c64 = pi.iter().sum();
        let magnitude: f64 = pi.iter().map(|p| p.norm()).sum();
        let (inside, outside) = (sum.norm(), (c64::new(1.0, 0.0) - sum).norm());
        if !(magnitude > 0.0 && magnitude.is_finite() && inside + outside > 0.0) {
            return Some((0.0, Vec::new()));
        }
        let p = inside / (inside + outside);
        let shares = self.signals.iter().zip(&pi).filter(|(_, x)| x.norm() > 1e-12 * magnitude).map(|(s, x)| EnergyShare { share: p * x.norm() / magnitude, ..s.who.clone() }).collect();
        Some((p, shares))
    }
}

/// Kinetic-energy shares of one mode (for several modes, build one [`ModalEnergy`]).
pub fn kinetic_energy_shares(model: &Model, dae: &LinearDae, mode: &Mode) -> Vec<EnergyShare> {
    ModalEnergy::new(model, dae).shares(mode)
}

/// "node 3 rz 92 %, node 2 x 6 %", "motor 1 current 97 %, node 2 rz 3 %", "abstract node 3
/// 71 %, genel mass 1 derivative 12 %": the shares of at least 5 % (at least the largest).
pub fn describe(shares: &[EnergyShare]) -> String {
    shares
        .iter()
        .enumerate()
        .filter(|(i, s)| *i == 0 || s.share >= 0.05)
        .map(|(_, s)| format!("{} {:.0} %", s.who(), 100.0 * s.share))
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
    if !is_node_component(top) {
        return Some(format!("{} {:.0} %", top.who(), 100.0 * top.share));
    }
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
    let k = COMPONENTS.iter().position(|c| *c == top.component).filter(|_| is_node_component(top)).unwrap_or(0);
    let tipping = is_node_component(top) && gravity.norm() > 0.0 && k >= 3 && k % 3 != gravity.iamax();
    let head = if tipping {
        let parts: Vec<String> = shares
            .iter()
            .enumerate()
            .filter(|(i, s)| *i == 0 || s.share >= 0.05)
            .map(|(_, s)| match names.get(&s.node).filter(|_| is_node_component(s)) {
                Some(name) => format!("{name} {} {:.0} %", s.component, 100.0 * s.share),
                None => format!("{} {:.0} %", s.who(), 100.0 * s.share),
            })
            .collect();
        format!("tipping ({}): {}", top.component, parts.join(", "))
    } else {
        mode_label(shares, names, gravity)?
    };
    Some(format!("{head}, {}", if lambda > 0.0 { "unstable" } else { "stable" }))
}

/// Whether a share is a structural node's component (not a scalar node's or an element's).
fn is_node_component(s: &EnergyShare) -> bool {
    s.element.is_none() && COMPONENTS.contains(&s.component)
}
