//! Building a model from Rust: nodes, elements and gravity, checked for consistency.

use super::{ConstraintForm, Label, Model, NodeKind, ScalarNode, ScalarNodeId, StructuralNode};
use crate::element::Element;
use crate::kinematics::{Mat3, Vec3};

/// An inconsistent model.
#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    #[error("structural node {0} is defined twice")]
    DuplicateNode(Label),
    #[error("element {0} is defined twice")]
    DuplicateElement(Label),
    #[error("{kind} {element} refers to structural node {node}, which is not defined")]
    UnknownNode { kind: &'static str, element: Label, node: Label },
    #[error("{0} is defined twice")]
    DuplicateScalarNode(ScalarNodeId),
    #[error("{kind} {element} refers to {node}, which is not defined")]
    UnknownScalarNode { kind: &'static str, element: Label, node: ScalarNodeId },
    #[error("the orientation of node {0} is not a rotation matrix")]
    BadOrientation(Label),
}

/// Collects nodes and elements; `build` checks labels and references.
pub struct ModelBuilder {
    nodes: Vec<StructuralNode>,
    scalar_nodes: Vec<ScalarNode>,
    elements: Vec<Box<dyn Element>>,
    /// Where each element is written ("file:line:col"), when it comes from a file.
    element_origins: Vec<Option<String>>,
    element_functions: Vec<Vec<String>>,
    gravity: Option<Vec3>,
    form: ConstraintForm,
    node_names: std::collections::BTreeMap<Label, String>,
    step_drives: Vec<crate::element::drive::StepDrive>,
    displacement_nodes: std::collections::BTreeSet<Label>,
    frame_motion: Option<std::sync::Arc<crate::element::FrameMotion>>,
}

impl Default for ModelBuilder {
    fn default() -> Self {
        ModelBuilder { nodes: Vec::new(), scalar_nodes: Vec::new(), elements: Vec::new(), element_origins: Vec::new(), element_functions: Vec::new(), gravity: None, form: ConstraintForm::Scaled, node_names: Default::default(), step_drives: Vec::new(), displacement_nodes: Default::default(), frame_motion: None }
    }
}

impl ModelBuilder {
    pub fn new() -> Self {
        Self::default()
    }

    /// A static node (6 unknowns) at `position` with `orientation`.
    pub fn static_node(&mut self, label: Label, position: Vec3, orientation: Mat3) -> &mut Self {
        self.node(StructuralNode { label, kind: NodeKind::Static, position, orientation, velocity: Vec3::zeros(), angular_velocity: Vec3::zeros() })
    }

    /// A dynamic node (12 unknowns) with initial velocity and angular velocity.
    pub fn dynamic_node(&mut self, label: Label, position: Vec3, orientation: Mat3, velocity: Vec3, angular_velocity: Vec3) -> &mut Self {
        self.node(StructuralNode { label, kind: NodeKind::Dynamic, position, orientation, velocity, angular_velocity })
    }

    pub fn node(&mut self, node: StructuralNode) -> &mut Self {
        self.nodes.push(node);
        self
    }

    /// The nodes added so far (elements such as beams take their reference configuration
    /// from them).
    pub fn nodes(&self) -> &[StructuralNode] {
        &self.nodes
    }

    /// Drives with memory the elements use: their memory advances at every step.
    pub fn step_drives(&mut self, drives: Vec<crate::element::drive::StepDrive>) -> &mut Self {
        self.step_drives.extend(drives);
        self
    }

    pub fn element(&mut self, element: impl Element + 'static) -> &mut Self {
        self.boxed_element(Box::new(element))
    }

    pub fn boxed_element(&mut self, element: Box<dyn Element>) -> &mut Self {
        self.elements.push(element);
        self.element_origins.push(None);
        self.element_functions.push(Vec::new());
        self
    }

    /// An element read from a file, with where it is written (`file:line:col`), which
    /// messages about it at run time name.
    pub fn element_from(&mut self, element: Box<dyn Element>, origin: String) -> &mut Self {
        self.elements.push(element);
        self.element_origins.push(Some(origin));
        self.element_functions.push(Vec::new());
        self
    }

    /// The scalar functions the last element's card uses, each as `scalar function "NAME"
    /// (file:line:col)`, which a message about a residual that is not finite names.
    pub fn element_uses(&mut self, functions: Vec<String>) -> &mut Self {
        if let Some(last) = self.element_functions.last_mut() {
            *last = functions;
        }
        self
    }

    /// A human name for node `label` (MBDyn's `name, "…"`), used in mode labels.
    pub fn node_name(&mut self, label: Label, name: impl Into<String>) -> &mut Self {
        self.node_names.insert(label, name.into());
        self
    }

    /// Uniform gravity [m/s²].
    pub fn gravity(&mut self, g: Vec3) -> &mut Self {
        self.gravity = Some(g);
        self
    }

    /// Constraint layout for dynamics and linearization (default: eq. 30, MBDyn's).
    pub fn constraint_form(&mut self, form: ConstraintForm) -> &mut Self {
        self.form = form;
        self
    }

    /// Marks node `label` as displacement-only ([`Model::displacement_nodes`]).
    pub fn displacement_node(&mut self, label: Label) -> &mut Self {
        self.displacement_nodes.insert(label);
        self
    }

    /// The moving reference frame ([`Model::frame_motion`]).
    pub fn frame_motion(&mut self, f: std::sync::Arc<crate::element::FrameMotion>) -> &mut Self {
        self.frame_motion = Some(f);
        self
    }

    /// A scalar node ([`ScalarNode`]: abstract, electric, hydraulic).
    pub fn scalar_node(&mut self, node: ScalarNode) -> &mut Self {
        self.scalar_nodes.push(node);
        self
    }

    pub fn build(self) -> Result<Model, ModelError> {
        let mut seen = std::collections::HashSet::new();
        for n in &self.nodes {
            if !seen.insert(n.label) {
                return Err(ModelError::DuplicateNode(n.label));
            }
            let r = &n.orientation;
            if ((r.transpose() * r) - Mat3::identity()).norm() > 1e-9 || r.determinant() < 0.0 {
                return Err(ModelError::BadOrientation(n.label));
            }
        }
        let mut scalar_indices = std::collections::HashMap::new();
        for (i, n) in self.scalar_nodes.iter().enumerate() {
            if scalar_indices.insert(n.id, i).is_some() {
                return Err(ModelError::DuplicateScalarNode(n.id));
            }
        }
        let mut seen_el = std::collections::HashSet::new();
        for e in &self.elements {
            if !seen_el.insert((e.type_name(), e.label())) {
                return Err(ModelError::DuplicateElement(e.label()));
            }
            for node in e.nodes() {
                if !seen.contains(&node) {
                    return Err(ModelError::UnknownNode { kind: e.type_name(), element: e.label(), node });
                }
            }
            if let Some(node) = e.scalar_nodes().into_iter().find(|id| !scalar_indices.contains_key(id)) {
                return Err(ModelError::UnknownScalarNode { kind: e.type_name(), element: e.label(), node });
            }
        }
        let node_indices = self.nodes.iter().enumerate().map(|(i, n)| (n.label, i)).collect();
        Ok(Model {
            node_indices,
            nodes: self.nodes,
            scalar_nodes: self.scalar_nodes,
            scalar_indices,
            elements: self.elements,
            element_origins: self.element_origins,
            element_functions: self.element_functions,
            gravity: self.gravity.unwrap_or_else(Vec3::zeros),
            has_gravity: self.gravity.is_some(),
            constraint_form: self.form,
            node_names: self.node_names,
            step_drives: self.step_drives,
            displacement_nodes: self.displacement_nodes,
            frame_motion: self.frame_motion,
        })
    }
}
