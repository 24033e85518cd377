//! The initial assembly's numbering and the sinks that collect its rows: the layout of
//! positions, velocities and multipliers, the element state the elements read, and the
//! residual and Jacobian sinks in the position or the velocity unknowns (see the parent
//! module for the equations).

use crate::dae::Triplets;
use crate::element::{Col, Element, ElementState, JacobianSink, NodeKinematics, ResidualSink, Row};
use crate::kinematics::{Mat3, Vec3};
use crate::model::Model;

/// Whether MBDyn uses an element in its initial assembly: joints (deformable ones too) and
/// beams, not bodies (variable-mass ones too), forces and couples (elman.cc:
/// `ToBeUsedInAssembly`), nor any other element on scalar nodes (genels, abstract forces:
/// MBDyn's initial assembly has structural nodes only). A beam with a piezoelectric
/// actuator stays, its voltages held at the scalar nodes' initial values (pzbeam.cc's
/// residual reads them; its columns have no place here).
fn in_assembly(e: &dyn Element) -> bool {
    let t = e.type_name();
    if !e.scalar_nodes().is_empty() && t != "beam3" && t != "beam2" {
        return false;
    }
    // A viscous body holds nothing: its force −C v on the written velocity would only be
    // balanced by the assembly's position springs (1 N/m), moving the node by C v. A brake
    // adds nothing there either (brake.cc has no initial assembly rows).
    !(t == "body" || t == "variable body" || t.ends_with("force") || t.ends_with("couple") || t.contains("gravity") || t == "viscous body" || t == "brake")
}

/// The assembly problem's numbering: 6 rows per node, then each element's multipliers.
pub(super) struct Layout<'m> {
    pub(super) model: &'m Model,
    /// Indices in `model.elements` of the elements in the assembly.
    pub(super) elements: Vec<usize>,
    /// Node index of each slot, per element in `elements`.
    pub(super) slots: Vec<Vec<usize>>,
    /// The initial values of each element's scalar nodes, in its scalar slots (held).
    pub(super) scalars: Vec<Vec<f64>>,
    /// First multiplier row of each element in `elements`.
    pub(super) first: Vec<usize>,
    pub(super) len: usize,
}

impl<'m> Layout<'m> {
    pub(super) fn new(model: &'m Model) -> Self {
        let mut len = 6 * model.nodes.len();
        let (mut elements, mut slots, mut first, mut scalars) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (i, e) in model.elements.iter().enumerate().filter(|(_, e)| in_assembly(e.as_ref())) {
            let e = e.assembly_form().unwrap_or(e.as_ref());
            elements.push(i);
            slots.push(e.nodes().iter().map(|l| model.node_index(*l).unwrap_or(usize::MAX)).collect());
            scalars.push(e.scalar_nodes().iter().map(|id| model.scalar_index(*id).map_or(0.0, |i| model.scalar_nodes[i].value)).collect());
            first.push(len);
            len += e.multipliers().len();
        }
        Layout { model, elements, slots, scalars, first, len }
    }
    pub(super) fn nodes(&self) -> usize {
        self.model.nodes.len()
    }
    /// The `k`-th element of the assembly, in its assembly form ([`Element::assembly_form`]).
    pub(super) fn element(&self, k: usize) -> &dyn Element {
        let e = self.model.elements[self.elements[k]].as_ref();
        e.assembly_form().unwrap_or(e)
    }
    /// The name of row `i` of the position (`derivative = false`) or velocity rows.
    pub(super) fn row_name(&self, i: usize, derivative: bool) -> String {
        const POS: [&str; 6] = ["position x", "position y", "position z", "orientation gx", "orientation gy", "orientation gz"];
        const VEL: [&str; 6] = ["velocity x", "velocity y", "velocity z", "angular velocity x", "angular velocity y", "angular velocity z"];
        if i < 6 * self.nodes() {
            return format!("node {} {}", self.model.nodes[i / 6].label, if derivative { VEL[i % 6] } else { POS[i % 6] });
        }
        let k = self.first.iter().rposition(|&f| f <= i).unwrap_or(0);
        let e = self.element(k);
        let name = e.multipliers().get(i - self.first[k]).cloned().unwrap_or_default();
        format!("{} {} constraint {name}{}", e.type_name(), e.label(), if derivative { " (its time derivative)" } else { "" })
    }
}

/// The unknowns of the assembly.
#[derive(Clone)]
pub(super) struct Unknowns {
    pub(super) x: Vec<Vec3>,
    pub(super) g: Vec<Vec3>,
    pub(super) v: Vec<Vec3>,
    pub(super) w: Vec<Vec3>,
    pub(super) lambda: Vec<f64>,
    pub(super) lambda_dot: Vec<f64>,
}

pub(super) struct Ctx<'a> {
    pub(super) model: &'a Model,
    pub(super) kin: &'a [NodeKinematics],
    pub(super) slots: &'a [usize],
    pub(super) scalars: &'a [f64],
    pub(super) multipliers: &'a [f64],
    pub(super) t: f64,
}

impl ElementState for Ctx<'_> {
    fn node(&self, slot: usize) -> &NodeKinematics {
        &self.kin[self.slots[slot]]
    }
    fn multiplier(&self, k: usize) -> f64 {
        self.multipliers[k]
    }
    fn time(&self) -> f64 {
        self.t
    }
    fn scalar_value(&self, slot: usize) -> f64 {
        self.scalars[slot]
    }
    fn gravity(&self) -> Vec3 {
        Vec3::zeros()
    }
    fn load_factor(&self) -> f64 {
        1.0
    }
    fn structural_node(&self, label: crate::element::Label) -> Option<&NodeKinematics> {
        self.model.node_index(label).map(|i| &self.kin[i])
    }
}

/// The row of an element's local row (momentum rows have none here).
pub(super) fn row_of(slots: &[usize], first: usize, row: Row) -> Option<usize> {
    match row {
        Row::Equilibrium { slot, comp } => Some(6 * slots[slot] + comp),
        Row::Momentum { .. } | Row::Scalar { .. } => None,
        Row::Constraint(k) => Some(first + k),
    }
}

pub(super) struct Residual<'a> {
    pub(super) slots: &'a [usize],
    pub(super) first: usize,
    pub(super) f: &'a mut [f64],
}

impl ResidualSink for Residual<'_> {
    fn add(&mut self, row: Row, value: f64) {
        if let Some(i) = row_of(self.slots, self.first, row) {
            self.f[i] += value;
        }
    }
}

/// Jacobian entries in the position unknowns `(x, g, λ)` (`g_matrix`: `δθ = G δg`), or,
/// with `g_matrix = None`, in the velocity unknowns `(v, ω, λ̇)`: `ḟ = f_/x v + f_/θ ω +
/// f_/λ λ̇`.
/// Rows of velocity-level constraints (`velocity_rows`) have no position row: in the
/// position unknowns they are skipped (their multiplier is held at zero), in the velocity
/// unknowns they are the constraint itself, `Φ_/u u + Φ(q, 0, t)` (drvj.cc,
/// `LinearVelocityJoint::InitialAssRes`).
pub(super) struct Jacobian<'a> {
    pub(super) slots: &'a [usize],
    pub(super) first: usize,
    pub(super) g_matrix: Option<&'a [Mat3]>,
    pub(super) velocity_rows: &'a [bool],
    pub(super) out: &'a mut Triplets,
}

impl JacobianSink for Jacobian<'_> {
    fn add(&mut self, row: Row, col: Col, v: f64) {
        let Some(r) = row_of(self.slots, self.first, row) else { return };
        let velocity_row = self.velocity_rows[r];
        if velocity_row && self.g_matrix.is_some() {
            return;
        }
        match col {
            Col::Position { slot, comp } | Col::Velocity { slot, comp } if matches!(col, Col::Velocity { .. }) == velocity_row => self.out.push(r, 6 * self.slots[slot] + comp, v),
            Col::Rotation { slot, comp } | Col::AngularVelocity { slot, comp } if matches!(col, Col::AngularVelocity { .. }) == velocity_row => {
                let n = self.slots[slot];
                match self.g_matrix {
                    Some(g) => (0..3).for_each(|k| self.out.push(r, 6 * n + 3 + k, v * g[n][(comp, k)])),
                    None => self.out.push(r, 6 * n + 3 + comp, v),
                }
            }
            Col::Multiplier(k) => self.out.push(r, self.first + k, v),
            _ => {}
        }
    }
}

/// Marks the constraint rows whose Jacobian has velocity entries (velocity-level
/// constraints).
pub(super) struct VelocityProbe<'a> {
    pub(super) first: usize,
    pub(super) rows: &'a mut [bool],
}

impl JacobianSink for VelocityProbe<'_> {
    fn add(&mut self, row: Row, col: Col, _v: f64) {
        if let (Row::Constraint(k), Col::Velocity { .. } | Col::AngularVelocity { .. }) = (row, col) {
            self.rows[self.first + k] = true;
        }
    }
}
