//! MBDyn's `modal` joint: a flexible body from a reduced finite-element model (component
//! mode synthesis), in the floating-frame formulation (input manual §Modal; MBDyn's
//! modal.cc and its technical manual, "Modal element").
//!
//! The body's points sit at `x + R (f₀ₙ + Φtₙ q)` with `x`, `R` the frame of the modal node
//! (or a fixed frame, `clamped`), `f₀ₙ` the FEM node positions, `Φtₙ`, `Φrₙ` the mode
//! shapes' translations and rotations and `q` the modal coordinates. The element owns `q`
//! and the modal momenta `p = ∂T/∂q̇` as differential states ([`UnknownKind::State`]), and
//! six multipliers per interface node (a clamp of the multibody node to its FEM node).
//!
//! Kinetic energy, with `v = Rᵀẋ`, `w = Rᵀω` in the floating frame and the inertia
//! invariants of the lumped FEM masses ([`invariants`]):
//!
//! ```text
//! T = ½ m v·v + v·(w × s(q)) + v·I₃ q̇ + ½ wᵀ J(q) w + wᵀ B(q) q̇ + ½ q̇ᵀ M q̇
//! s(q) = I₂ + I₃ q,   B(q) = I₄ + Σⱼ qⱼ I₅ⱼ,   J(q) = I₇ + Σⱼ qⱼ dJⱼ + ½ Σⱼₖ qⱼ qₖ Hⱼₖ
//! ```
//!
//! (`Hⱼₖ` only with `use invariant 9`, as in MBDyn). The modal node's momentum definitions
//! receive `∂T/∂ẋ` and `∂T/∂ω` (the node's own rows then hold Newton–Euler's equations for
//! the whole flexible body, as for a rigid body, METHOD §5), and the element's own rows are
//! Lagrange's equations for `q` in first-order form:
//!
//! ```text
//! p − ∂T/∂q̇ = 0,      ṗ − ∂T/∂q + K q + C q̇ − Q = 0,
//! ```
//!
//! `Q` the generalized forces of gravity and of the interface reactions. Being derived from
//! one kinetic energy, the equations conserve the body's momentum and angular momentum; at
//! rest (`ω = 0`) they coincide with modal.cc's (whose gyroscopic terms are written
//! directly in accelerations, not from one `T`).

mod equations;
mod interface;
pub mod invariants;

use super::contract::{Element, ElementState, EnergyStore, FlexiblePoint, JacobianSink, Label, Outputs, ResidualSink};
use super::UnknownKind;
use crate::kinematics::{Mat3, Vec3};
use nalgebra::DMatrix;
pub use invariants::{Component, Invariants};

/// Where the body's floating frame is.
#[derive(Clone, Debug)]
pub enum ModalFrame {
    /// The frame of a modal node (slot 0).
    Node(Label),
    /// A fixed frame (`clamped`): origin [m] and orientation.
    Clamped { position: Vec3, orientation: Mat3 },
}

/// An interface node: a multibody node clamped to a FEM node.
#[derive(Clone, Debug)]
pub struct Interface {
    /// The multibody node.
    pub node: Label,
    /// The FEM node's label (for messages) and its position in the floating frame [m].
    pub fem_node: String,
    pub position: Vec3,
    /// The FEM node's mode shapes: translation [m] and rotation [rad] per unit modal
    /// coordinate, one per mode.
    pub translation: Vec<Vec3>,
    pub rotation: Vec<Vec3>,
    /// Offset of the FEM node from the multibody node, in the multibody node's frame [m].
    pub offset: Vec3,
}

/// A FEM node of the body, kept for outputs at points (sensors on the flexible body).
#[derive(Clone, Debug)]
pub struct FemNode {
    pub label: String,
    /// Its undeformed position in the floating frame [m].
    pub position: Vec3,
    /// Its translation per unit coordinate of each mode the joint uses [m].
    pub translation: Vec<Vec3>,
    /// Its rotation per unit coordinate of each mode [rad] (the FEM file's 6-DOF shapes).
    pub rotation: Vec<Vec3>,
}

/// The flexible body.
#[derive(Clone, Debug)]
pub struct ModalBody {
    pub label: Label,
    pub frame: ModalFrame,
    /// Modal mass, stiffness and damping matrices (`modes × modes`).
    pub mass: DMatrix<f64>,
    pub stiffness: DMatrix<f64>,
    pub damping: DMatrix<f64>,
    pub invariants: Invariants,
    pub interfaces: Vec<Interface>,
    /// The modes' ordinals in the FEM file (1-based), for names and output.
    pub mode_numbers: Vec<usize>,
    /// Initial modal coordinates and their rates (`initial value`, FEM records 3 and 4).
    pub initial: Vec<(f64, f64)>,
    /// The FEM file reader's warnings (`romdyn::input::fem::FemFile::warnings`).
    pub input_warnings: Vec<String>,
    /// Every FEM node of the file, for outputs at points ([`Outputs::flexible_point`]).
    pub fem_nodes: Vec<FemNode>,
    /// The element the initial assembly uses ([`ModalBody::for_initial_assembly`]).
    assembly: Option<Box<ModalBody>>,
    /// Whether this is that element: the interface constraints alone, `q` held at its
    /// initial values.
    assembling: bool,
}

impl ModalBody {
    /// The body; `initial` empty means every mode starts at rest at zero.
    #[allow(clippy::too_many_arguments)]
    pub fn new(label: Label, frame: ModalFrame, mass: DMatrix<f64>, stiffness: DMatrix<f64>, damping: DMatrix<f64>, invariants: Invariants, interfaces: Vec<Interface>, mode_numbers: Vec<usize>, initial: Vec<(f64, f64)>) -> Self {
        let initial = if initial.is_empty() { vec![(0.0, 0.0); mass.nrows()] } else { initial };
        let mut body = ModalBody { label, frame, mass, stiffness, damping, invariants, interfaces, mode_numbers, initial, input_warnings: Vec::new(), fem_nodes: Vec::new(), assembly: None, assembling: false };
        let twin = ModalBody { assembling: true, ..body.clone() };
        body.assembly = Some(Box::new(twin));
        body
    }

    pub fn modes(&self) -> usize {
        self.mass.nrows()
    }

    /// Own unknowns: the interfaces' six multipliers each, then `q`, then `p` (the
    /// interfaces first, so that the initial assembly's element, which has them alone, has
    /// this one's first unknowns).
    pub fn q_index(&self, k: usize) -> usize {
        6 * self.interfaces.len() + k
    }
    pub fn p_index(&self, k: usize) -> usize {
        6 * self.interfaces.len() + self.modes() + k
    }

    /// The slot of interface `i`'s node.
    fn interface_slot(&self, i: usize) -> usize {
        i + usize::from(matches!(self.frame, ModalFrame::Node(_)))
    }

    /// The floating frame: `(x, R, ẋ, ω)` of the modal node, or the clamped frame at rest.
    fn floating_frame(&self, s: &dyn ElementState) -> (Vec3, Mat3, Vec3, Vec3) {
        match &self.frame {
            ModalFrame::Node(_) => {
                let n = s.node(0);
                (n.x, n.r, n.xdot, n.omega)
            }
            ModalFrame::Clamped { position, orientation } => (*position, *orientation, Vec3::zeros(), Vec3::zeros()),
        }
    }

    /// The modal coordinates `q` and their rates `q̇` (the initial ones while assembling).
    pub fn coordinates(&self, s: &dyn ElementState) -> (Vec<f64>, Vec<f64>) {
        if self.assembling {
            return self.initial.iter().copied().unzip();
        }
        let n = self.modes();
        ((0..n).map(|k| s.multiplier(self.q_index(k))).collect(), (0..n).map(|k| s.rate(self.q_index(k))).collect())
    }
}

impl Element for ModalBody {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "modal"
    }
    fn input_warnings(&self) -> Vec<String> {
        self.input_warnings.clone()
    }
    fn nodes(&self) -> Vec<Label> {
        let mut v = match self.frame {
            ModalFrame::Node(l) => vec![l],
            ModalFrame::Clamped { .. } => Vec::new(),
        };
        v.extend(self.interfaces.iter().map(|i| i.node));
        v
    }
    fn multipliers(&self) -> Vec<String> {
        let mut names = Vec::new();
        for i in &self.interfaces {
            for c in ["Fx", "Fy", "Fz", "Mx", "My", "Mz"] {
                names.push(format!("interface FEM node {} / node {} reaction {c}", i.fem_node, i.node));
            }
        }
        if !self.assembling {
            names.extend(self.mode_numbers.iter().map(|m| format!("modal coordinate q{m}")));
            names.extend(self.mode_numbers.iter().map(|m| format!("modal momentum p{m}")));
        }
        names
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        if k < 6 * self.interfaces.len() { UnknownKind::Multiplier } else { UnknownKind::State }
    }
    fn momentum_unknowns(&self) -> std::ops::Range<usize> {
        if self.assembling { 0..0 } else { self.p_index(0)..self.p_index(self.modes()) }
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        if self.assembling {
            return Vec::new();
        }
        self.initial.iter().enumerate().filter(|(_, v)| **v != (0.0, 0.0)).map(|(k, (q, qdot))| (self.q_index(k), *q, *qdot)).collect()
    }
    /// MBDyn's modal joint assembles its interfaces with the modal coordinates held at
    /// their initial values (modal.cc, `InitialAssRes`): the modes are not part of the
    /// initial assembly, as an element's differential states are not.
    fn assembly_form(&self) -> Option<&dyn Element> {
        self.assembly.as_deref().map(|a| a as &dyn Element)
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink) {
        if !self.assembling {
            equations::residual(self, s, out);
        }
        interface::residual(self, s, out);
    }
    fn jacobian(&self, s: &dyn ElementState, out: &mut dyn JacobianSink) {
        if !self.assembling {
            equations::jacobian(self, s, out);
        }
        interface::jacobian(self, s, out);
    }
}

impl Outputs for ModalBody {
    /// MBDyn's `q[N]`, `qP[N]` (mode number N in the FEM file) and `q[#I]`, `qP[#I]` (the
    /// I-th mode the joint uses), modal.cc's `iGetPrivDataIdx`; `qPP` and the FEM nodes'
    /// `x[…]`, `w[…]` are not computed (`None`: the reader names them).
    fn private_data(&self, name: &str) -> Option<crate::element::contract::PrivateDatum> {
        let (rate, inside) = if let Some(r) = name.strip_prefix("qP[") { (true, r) } else { (false, name.strip_prefix("q[")?) };
        let inside = inside.strip_suffix(']')?.trim();
        let k = match inside.strip_prefix('#') {
            Some(i) => i.trim().parse::<usize>().ok().filter(|i| (1..=self.modes()).contains(i))? - 1,
            None => self.mode_numbers.iter().position(|m| Some(*m) == inside.parse::<usize>().ok())?,
        };
        let (index, initial, label) = (self.q_index(k), self.initial[k], self.label);
        // Read through the state by the joint's label (the datum is evaluated in the reading
        // element's state); the initial assembly, where the modes are not unknowns, reads
        // their initial values, as the joint holds them there.
        Some(crate::element::contract::PrivateDatum::new(move |st| {
            let (q, qdot) = st.element_unknown("modal", label, index).unwrap_or(initial);
            Some(if rate { qdot } else { q })
        }))
    }

    fn modal_coordinates(&self) -> Vec<(usize, usize)> {
        if self.assembling {
            return Vec::new();
        }
        self.mode_numbers.iter().enumerate().map(|(k, m)| (self.q_index(k), *m)).collect()
    }

    /// Each mode's own kinetic energy `½ Mₖₖ q̇ₖ²` [J] (the diagonal of the `½ q̇ᵀ M q̇` term
    /// of `T`; the floating frame's share is its node's), so that the modal table names the
    /// flexible body's modes ("modal joint 10 mode 3 64 %").
    fn energy_stores(&self, _s: &dyn ElementState) -> Vec<EnergyStore> {
        if self.assembling {
            return Vec::new();
        }
        self.mode_numbers.iter().enumerate().map(|(k, &m)| EnergyStore { unknown: self.q_index(k), weight: self.mass[(k, k)], rate: true, name: format!("mode {m}"), mode: Some(m) }).collect()
    }

    /// FEM node `fem_node`: `x + R (f₀ + Σₖ Φₖ qₖ)` (the module's kinematics).
    fn flexible_point(&self, fem_node: &str) -> Result<FlexiblePoint, String> {
        let Some(n) = self.fem_nodes.iter().find(|n| n.label == fem_node) else {
            let listed: Vec<&str> = self.fem_nodes.iter().take(12).map(|n| n.label.as_str()).collect();
            let more = if self.fem_nodes.len() > 12 { ", …" } else { "" };
            return Err(format!("modal joint {} has no FEM node \"{fem_node}\" (its FEM nodes: {}{more})", self.label, listed.join(", ")));
        };
        let clamped = match &self.frame {
            ModalFrame::Node(_) => None,
            ModalFrame::Clamped { position, orientation } => Some((*position, *orientation)),
        };
        let per_mode = |shapes: &[Vec3]| shapes.iter().enumerate().map(|(k, t)| (self.q_index(k), *t)).collect();
        Ok(FlexiblePoint { position: n.position, shapes: per_mode(&n.translation), rotation_shapes: per_mode(&n.rotation), clamped })
    }
}
