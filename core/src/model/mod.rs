//! The model description, independent of any file format: structural nodes, elements
//! addressed by label, gravity, and the constraint form.

mod builder;
mod constraint_form;
mod problem;
mod summary;

pub use builder::{ModelBuilder, ModelError};
pub use constraint_form::ConstraintForm;
pub use problem::{AbortAfter, AutoCoefficient, EigenFileSuffix, EigenOutput, EigenRequest, EigenSolverRequest, InitialAssembly, InitialValueProblem, Method, MotionOutput, NodeAssembly, NodeSource, OrientationOutput, ResidualNorm, SuffixWidth, WrittenNode};
pub use summary::Summary;

use std::collections::HashMap;

use crate::element::Element;
use crate::kinematics::{Mat3, Vec3};

pub use crate::element::{Label, ScalarNodeId, ScalarNodeKind};

/// Static nodes carry 6 unknowns (x, g); dynamic ones 12 (x, g, β, γ).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeKind {
    Static,
    Dynamic,
}

impl NodeKind {
    pub fn unknowns(self) -> usize {
        match self {
            NodeKind::Static => 6,
            NodeKind::Dynamic => 12,
        }
    }
}

/// A structural node with its initial state (SI units: m, rad, m/s, rad/s).
#[derive(Clone, Debug)]
pub struct StructuralNode {
    pub label: Label,
    pub kind: NodeKind,
    pub position: Vec3,
    pub orientation: Mat3,
    pub velocity: Vec3,
    pub angular_velocity: Vec3,
}

/// A scalar node (MBDyn's `abstract`, `electric`, `hydraulic` nodes, input manual §Nodes;
/// `ScalarAlgebraicNode`, `ScalarDifferentialNode` of MBDyn's source): one unknown `x`, its
/// own equation, which the elements connected to it write ([`crate::element::Row::Scalar`]).
/// A differential node's derivative `ẋ` may appear in those equations (its entries go to
/// `F_/ẏ`); an algebraic node's may not (the reader refuses the `differential` order on it).
#[derive(Clone, Debug, PartialEq)]
pub struct ScalarNode {
    pub id: ScalarNodeId,
    /// MBDyn's `differential` (the default of abstract nodes; electric nodes) rather than
    /// `algebraic` (hydraulic nodes).
    pub differential: bool,
    /// Initial value (`value, …`).
    pub value: f64,
    /// Initial derivative (`derivative, …`; differential nodes).
    pub derivative: f64,
    /// Whether a run writes its rows (`.abs`, `.ele`, `.prs`: `romdyn::output::scalar_nodes`).
    pub output: bool,
}

/// A complete model. Build it with [`ModelBuilder`].
pub struct Model {
    pub nodes: Vec<StructuralNode>,
    /// The scalar nodes ([`ScalarNode`]); their unknowns follow the structural nodes'.
    pub scalar_nodes: Vec<ScalarNode>,
    pub elements: Vec<Box<dyn Element>>,
    /// Where each element of `elements` is written (`file:line:col`), when it was read from a
    /// file: run-time messages name it ([`Model::element_name`]).
    pub element_origins: Vec<Option<String>>,
    /// The scalar functions each element's card uses (`scalar function "NAME" (file:line:col)`).
    pub element_functions: Vec<Vec<String>>,
    /// Uniform gravity field [m/s²] (zero when absent).
    pub gravity: Vec3,
    pub has_gravity: bool,
    /// Layout of the constraint equations (eq. 29 or eq. 30) used by dynamics and
    /// linearization; static analysis always uses the plain form.
    pub constraint_form: ConstraintForm,
    /// Names of nodes given in the input (MBDyn's `name, "…"` after a node label), for mode
    /// labels; a ports file's `names` take precedence.
    pub node_names: std::collections::BTreeMap<Label, String>,
    /// Drives with a memory of the accepted steps, updated once at the start of every
    /// time step ([`crate::element::drive::StepDrive::begin_step`]).
    pub step_drives: Vec<crate::element::drive::StepDrive>,
    /// Nodes without rotations (MBDyn's `static displacement` and `dynamic displacement`
    /// nodes): their orientation stays the initial one, `g = 0` is their moment equation
    /// (static) or, with `γ = 0` as angular momentum, their angular equilibrium (dynamic),
    /// so they move as 3-DoF points; only elements that read positions and write forces
    /// may connect to them (the reader's check).
    pub displacement_nodes: std::collections::BTreeSet<Label>,
    /// The moving reference frame of MBDyn's `rigid body kinematics`: its `2 W × β` and
    /// `W × γ` on every dynamic node's equilibrium (the bodies carry their own terms).
    pub frame_motion: Option<std::sync::Arc<crate::element::FrameMotion>>,
    /// Index in `nodes` of each node label.
    node_indices: HashMap<Label, usize>,
    /// Index in `scalar_nodes` of each scalar node.
    scalar_indices: HashMap<ScalarNodeId, usize>,
}

impl Model {
    /// What the reader noticed in the elements' own input files (a modal joint's FEM file)
    /// and let pass, each as "TYPE LABEL: FILE:LINE:COL: …"; the front ends print them.
    pub fn input_warnings(&self) -> Vec<String> {
        self.elements.iter().flat_map(|e| e.input_warnings().into_iter().map(move |w| format!("{} {}: {w}", e.type_name(), e.label()))).collect()
    }

    /// `TYPE LABEL (file:line:col)` of element `e`, as run-time messages name it.
    pub fn element_name(&self, e: usize) -> String {
        let el = &self.elements[e];
        match self.element_origins.get(e).and_then(Option::as_ref) {
            Some(at) => format!("{} {} ({at})", el.type_name(), el.label()),
            None => format!("{} {}", el.type_name(), el.label()),
        }
    }

    /// The scalar functions element `e`'s card makes it evaluate, as " (it evaluates scalar
    /// function "NAME" (file:line:col), …)", or "": what a message about a value that is not
    /// finite adds after naming the element.
    pub fn element_functions_note(&self, e: usize) -> String {
        match self.element_functions.get(e).filter(|f| !f.is_empty()) {
            Some(functions) => format!(" (it evaluates {})", functions.join(", ")),
            None => String::new(),
        }
    }

    /// Index of the node with this label.
    pub fn node_index(&self, label: Label) -> Option<usize> {
        self.node_indices.get(&label).copied()
    }

    /// Index in [`Model::scalar_nodes`] of a scalar node.
    pub fn scalar_index(&self, id: ScalarNodeId) -> Option<usize> {
        self.scalar_indices.get(&id).copied()
    }
}
