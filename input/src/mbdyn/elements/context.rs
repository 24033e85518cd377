//! What an `elements` statement reads from the rest of the file (nodes, reference frames,
//! drive callers, constitutive laws) and what it produces.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use crate::mbdyn::drives::callers::Drives;
use super::laws::Laws;
use crate::mbdyn::nodes::structural::Nodes;
use crate::mbdyn::syntax::references::{Context, Frames};
use crate::element::Element;
use crate::kinematics::Vec3;
use crate::model::StructuralNode;
use crate::mbdyn::syntax::diagnostic;

/// What an `elements` statement produced.
pub enum Parsed {
    Element(Box<dyn Element>),
    /// Gravity acceleration [m/s²].
    Gravity(Vec3),
    /// A central gravity field: its centre [m] and `G M` [m³/s²].
    CentralGravity { origin: Vec3, gm: f64 },
    /// A uniform field varying in time: `direction · drive(t)` [m/s²].
    DrivenGravity { direction: Vec3, drive: crate::element::drive::Drive },
    /// A rigid body (which a central gravity field acts on).
    Body(crate::element::RigidBody),
    /// A `total equation`, waiting for the reactions that apply its multipliers.
    TotalEquation(crate::element::DrivenJoint),
    /// A `total internal reaction` of the total equation `equation`.
    TotalReaction { reaction: crate::element::TotalReaction, equation: crate::model::Label, span: diagnostic::Span },
    /// A `joint regularization: JOINT, tikhonov, …` of a joint defined above.
    Regularization { joint: crate::model::Label, c: Compliance, span: diagnostic::Span },
    /// A card that does not change the model.
    Ignored,
}

/// The fluids of `hydraulic fluid` cards by label: the fluid, the card's place in the file
/// (an element reads the fluids defined above it) and its span.
pub type Fluids = std::collections::HashMap<crate::model::Label, (crate::element::HydraulicFluid, usize, diagnostic::Span)>;

/// Everything an element statement can refer to.
/// The node labels of each `beam3` read so far, by beam label.
pub type BeamNodes = std::collections::HashMap<crate::model::Label, [crate::model::Label; 3]>;

pub struct ElementContext<'a> {
    pub nodes: &'a Nodes,
    pub frames: &'a Frames,
    pub drives: &'a Drives,
    pub laws: &'a Laws,
    /// The `hydraulic fluid` cards.
    pub fluids: &'a Fluids,
    /// The node labels of the beams read so far (a beam slider names them).
    pub beams: &'a BeamNodes,
    /// The statement being read (cards must come before it).
    pub seq: usize,
    /// `model: static` in control data: every node is static and bodies only weigh.
    pub static_model: bool,
    /// The rotation update beam cards take.
    pub beam_update: crate::mbdyn::read_options::BeamUpdateRule,
    /// Why beams keep the path-independent update where the incremental one was wanted.
    pub beam_notes: &'a std::cell::RefCell<Vec<String>>,
    /// Whether hydraulic elements write their `.hyd` rows unless their card says otherwise
    /// (control data's `default output`).
    pub hydraulic_output: bool,
}

impl<'a> ElementContext<'a> {
    /// A structural node label that names a node with unknowns.
    /// A node with rotations: a displacement node is refused (MBDyn 1.7.3 reads the node of
    /// every element but those of [`ElementContext::point_node`] as a 6-DoF `StructNode`).
    pub fn node(&self, c: &mut Cursor, what: &str) -> Result<&'a StructuralNode, MbdynError> {
        let span = c.here();
        let (n, displacement) = self.point_node(c, what)?;
        if displacement {
            return Err(c.error_at(span, format!("structural node {} is a displacement node (no rotations): only bodies (a mass), rods and distance joints without offsets, membrane4eas and the 'absolute displacement' forces connect to it, as in MBDyn 1.7.3", n.label)));
        }
        Ok(n)
    }
    /// A structural node with unknowns, with whether it is a displacement node (for the
    /// elements MBDyn 1.7.3 reads as `StructDispNode`: body, rod and distance without
    /// offsets, the displacement forces).
    pub fn point_node(&self, c: &mut Cursor, what: &str) -> Result<(&'a StructuralNode, bool), MbdynError> {
        let span = c.here();
        let label = c.label(what)?;
        match self.nodes.find(label) {
            Some(n) if n.dummy => Err(c.error_at(span, format!("structural node {label} is a dummy node (output only): romdyn cannot connect elements to it"))),
            Some(n) => Ok((&n.node, n.displacement)),
            None => Err(c.error_at(span, format!("structural node {label} is not defined"))),
        }
    }
    /// Entities read relative to node `n`.
    pub fn on(&self, n: &StructuralNode) -> Context<'a> {
        Context::on_node(self.frames, self.seq, n)
    }
    pub fn global(&self) -> Context<'a> {
        Context::global(self.frames, self.seq)
    }
}

/// The compliances of a regularization, one a joint equation.
#[derive(Clone, Debug)]
pub enum Compliance {
    /// One value for every equation.
    All(f64),
    List(Vec<f64>),
}
