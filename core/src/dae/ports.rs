//! Ports of a linearized model (paper §7 eqs. 38–39, §8): where the inputs act and what the
//! outputs measure, at points of nodes and along directions, as the columns of `B̃`
//! (`−ΔF = B̃ u`) and the rows of `C̃` (`z = C̃ Δy + C̃_v Δẏ`) at the reference configuration.
//!
//! A point of a node is `p = x + R f` (offset `f` in the node frame); at the reference
//! (`g = 0`, so `δθ = δg`) its displacement is `δp = δx − [R f ×] δg`. A force `u d` at `p`
//! enters the node's force rows as `d` and its moment rows as `(R f) × d`: the input column
//! of a force is the transpose of the output row of the displacement along the same
//! direction (collocation). Directions are unit vectors in the global frame, or in a node's
//! frame (the first node's for actuators and relative sensors), taken at the reference.

use faer::Mat;

use super::state::NodeFrame;
use super::{DofMap, State};
use crate::kinematics::{skew, Mat3, Vec3};
use crate::model::{Label, Model, ScalarNodeId, ScalarNodeKind};

/// The frame a direction is given in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Frame {
    Global,
    /// The node's frame at the reference configuration (for a pair: the first node's).
    Node,
}

/// A direction (normalized when the port is built).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Direction {
    pub vector: Vec3,
    pub frame: Frame,
}

impl Direction {
    pub fn global(vector: Vec3) -> Self {
        Direction { vector, frame: Frame::Global }
    }
    pub fn node(vector: Vec3) -> Self {
        Direction { vector, frame: Frame::Node }
    }
}

/// Where a point of a node is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Location {
    /// Offset in the node frame [m].
    Offset(Vec3),
    /// Global position at the reference configuration [m] (the offset follows from it).
    At(Vec3),
}

/// A point attached to a structural node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    pub node: Label,
    pub location: Location,
}

impl Point {
    /// The node's own origin.
    pub fn node(node: Label) -> Self {
        Point { node, location: Location::Offset(Vec3::zeros()) }
    }
    pub fn offset(node: Label, offset: Vec3) -> Self {
        Point { node, location: Location::Offset(offset) }
    }
    pub fn at(node: Label, position: Vec3) -> Self {
        Point { node, location: Location::At(position) }
    }
}

/// What an input applies.
#[derive(Clone, Debug, PartialEq)]
pub enum Excitation {
    /// A force `u d` at a point [N].
    Force { point: Point, direction: Direction },
    /// A moment `u d` on a node [N m].
    Moment { node: Label, direction: Direction },
    /// An actuator between two bodies: `+u d` at `to`, `−u d` at `from` [N].
    Actuator { from: Point, to: Point, direction: Direction },
    /// `u` added to a scalar node's equation, as an abstract force (`force: …, abstract`):
    /// a force on an abstract node, a current into an electric node [A], a mass flow into a
    /// hydraulic node [kg/s].
    Scalar { node: ScalarNodeId },
}

/// What an output measures.
#[derive(Clone, Debug, PartialEq)]
pub enum Measurement {
    /// Displacement of a point along a direction [m].
    Displacement { point: Point, direction: Direction },
    /// Rotation of a node about a direction [rad].
    Rotation { node: Label, direction: Direction },
    /// `d · (p_to − p_from)`, change from the reference (an LVDT) [m].
    Relative { from: Point, to: Point, direction: Direction },
    /// Velocity of a point along a direction (a geophone) [m/s].
    Velocity { point: Point, direction: Direction },
    /// Angular velocity of a node about a direction [rad/s].
    AngularVelocity { node: Label, direction: Direction },
    /// The value of a scalar node (an abstract node's, a voltage [V], a pressure [Pa]).
    ScalarValue { node: ScalarNodeId },
    /// The time derivative of a differential scalar node.
    ScalarRate { node: ScalarNodeId },
    /// A modal joint's coordinate `q` of one mode (MBDyn's `.mod` column; `mode` is the
    /// mode's number in the FEM file) [-: the unit of the FEM file's mode shapes, metres of
    /// displacement per unit `q`].
    ModalCoordinate { joint: Label, mode: usize },
    /// Its rate `q̇` [1/s].
    ModalRate { joint: Label, mode: usize },
    /// Displacement of a modal joint's FEM node along a direction (a sensor on the flexible
    /// body): `p = x + R (f₀ + Σₖ Φₖ qₖ)` linearized, the floating frame's motion and the
    /// modes' [m]. `Frame::Node` directions are in the floating frame.
    FemDisplacement { joint: Label, fem_node: String, direction: Direction },
    /// Its velocity `ṗ = ẋ + ω × R (f₀ + Φ q) + R Φ q̇` [m/s].
    FemVelocity { joint: Label, fem_node: String, direction: Direction },
    /// Rotation of a modal joint's FEM node about a direction [rad]: its orientation
    /// `R exp([ψ×])`, `ψ = Σₖ Φrₖ qₖ` the modes' rotations (the FEM file's 6-DOF shapes;
    /// MBDyn's `R (I + [ψ×])` to first order), linearized: `δθ + R J(ψ) Σₖ Φrₖ δqₖ`, `δθ`
    /// the floating frame's rotation and `J` the exponential's left Jacobian (`I` at `q = 0`).
    FemRotation { joint: Label, fem_node: String, direction: Direction },
}

/// A named input.
#[derive(Clone, Debug, PartialEq)]
pub struct InputPort {
    pub name: String,
    pub excitation: Excitation,
}

/// A named output.
#[derive(Clone, Debug, PartialEq)]
pub struct OutputPort {
    pub name: String,
    pub measurement: Measurement,
}

impl InputPort {
    /// SI unit of the input.
    pub fn unit(&self) -> &'static str {
        match self.excitation {
            Excitation::Moment { .. } => "N m",
            Excitation::Scalar { node } => match node.kind {
                ScalarNodeKind::Abstract => "-",
                ScalarNodeKind::Electric => "A",
                ScalarNodeKind::Hydraulic => "kg/s",
            },
            _ => "N",
        }
    }
    /// "NAME [UNIT]", as the ROM's input names carry it.
    pub fn label(&self) -> String {
        format!("{} [{}]", self.name, self.unit())
    }
}

impl OutputPort {
    /// SI unit of the output.
    pub fn unit(&self) -> &'static str {
        match self.measurement {
            Measurement::Displacement { .. } | Measurement::Relative { .. } | Measurement::FemDisplacement { .. } => "m",
            Measurement::Rotation { .. } | Measurement::FemRotation { .. } => "rad",
            Measurement::Velocity { .. } | Measurement::FemVelocity { .. } => "m/s",
            Measurement::AngularVelocity { .. } => "rad/s",
            Measurement::ScalarValue { node } => match node.kind {
                ScalarNodeKind::Abstract => "-",
                ScalarNodeKind::Electric => "V",
                ScalarNodeKind::Hydraulic => "Pa",
            },
            Measurement::ScalarRate { node } => match node.kind {
                ScalarNodeKind::Abstract => "1/s",
                ScalarNodeKind::Electric => "V/s",
                ScalarNodeKind::Hydraulic => "Pa/s",
            },
            Measurement::ModalCoordinate { .. } => "-",
            Measurement::ModalRate { .. } => "1/s",
        }
    }
    pub fn label(&self) -> String {
        format!("{} [{}]", self.name, self.unit())
    }
    /// Whether the output is a rate (it has a row in `C̃_v`).
    pub fn is_rate(&self) -> bool {
        matches!(self.measurement, Measurement::Velocity { .. } | Measurement::AngularVelocity { .. } | Measurement::ScalarRate { .. } | Measurement::ModalRate { .. } | Measurement::FemVelocity { .. })
    }
}

/// A malformed or dangling port.
#[derive(Debug, thiserror::Error)]
pub enum PortError {
    #[error("'{0}': expected NODE:COMPONENT with COMPONENT one of {1}")]
    Syntax(String, String),
    #[error("'{0}': structural node {1} is not defined")]
    UnknownNode(String, Label),
    #[error("'{0}': {1} is not defined")]
    UnknownScalarNode(String, ScalarNodeId),
    #[error("'{0}': the direction is zero or not finite")]
    BadDirection(String),
    #[error("'{0}': {1}")]
    Invalid(String, String),
}

/// The model's nodes at the reference configuration ([`State::linearization_base`]: `g = 0`, `ġ = 0`, ω in `W_ref`), to build `B̃`
/// columns and `C̃` rows from.
pub struct PortMap<'m> {
    model: &'m Model,
    dofs: DofMap,
    frames: Vec<NodeFrame>,
    /// The unknowns and their rates at the reference (modal coordinates for FEM nodes).
    y: Vec<f64>,
    yp: Vec<f64>,
}

/// A FEM node at the reference, in global axes: `r = R (f₀ + Φ q)` from the floating frame's
/// origin, `v = R Φ q̇`, and `R Φₖ` per own unknown `qₖ`.
struct FlexibleAt {
    /// The modal node's index (`None`: a clamped body's fixed frame).
    node: Option<usize>,
    orientation: Mat3,
    r: Vec3,
    deformation_rate: Vec3,
    shapes: Vec<(usize, Vec3)>,
    /// `R J(ψ) Φrₖ` per own unknown `qₖ` (the rotation's, [`Measurement::FemRotation`]).
    rotation_shapes: Vec<(usize, Vec3)>,
}

/// The left Jacobian `J(ψ) = I + (1 − cos θ)/θ² [ψ×] + (θ − sin θ)/θ³ [ψ×]²` (`θ = |ψ|`) of
/// the exponential map: `δ(exp[ψ×]) exp[ψ×]ᵀ = [J(ψ) δψ ×]`.
fn exponential_left_jacobian(psi: &Vec3) -> Mat3 {
    let t = psi.norm();
    let s = skew(psi);
    // Series below 1e-4 rad (the closed forms cancel there): 1/2 − θ²/24, 1/6 − θ²/120.
    let (a, b) = if t < 1e-4 { (0.5 - t * t / 24.0, 1.0 / 6.0 - t * t / 120.0) } else { ((1.0 - t.cos()) / (t * t), (t - t.sin()) / (t * t * t)) };
    Mat3::identity() + s * a + s * s * b
}

/// One output row: `C̃` and, for rates, `C̃_v`.
pub struct OutputRow {
    pub c: Vec<f64>,
    pub c_rate: Option<Vec<f64>>,
}

impl<'m> PortMap<'m> {
    /// `state` is put in the linearization form here (a copy), so rotations are measured by `g` from `R_ref`.
    pub fn new(model: &'m Model, state: &State) -> Self {
        let dofs = DofMap::new(model);
        let mut st = state.clone();
        st.linearization_base(&dofs);
        let frames = (0..model.nodes.len()).map(|i| st.node_frame(&dofs, i)).collect();
        PortMap { model, dofs, frames, y: st.y, yp: st.yp }
    }

    /// Number of unknowns (= equations).
    pub fn dim(&self) -> usize {
        self.dofs.len
    }

    fn node(&self, name: &str, label: Label) -> Result<usize, PortError> {
        self.model.node_index(label).ok_or_else(|| PortError::UnknownNode(name.to_string(), label))
    }

    /// The unknown (= equation) of a scalar node.
    fn scalar(&self, name: &str, id: ScalarNodeId) -> Result<usize, PortError> {
        self.model.scalar_index(id).map(|i| self.dofs.scalar_first + i).ok_or_else(|| PortError::UnknownScalarNode(name.to_string(), id))
    }

    /// The unknown of modal joint `joint`'s coordinate of mode `mode` (its number in the FEM
    /// file).
    fn modal(&self, name: &str, joint: Label, mode: usize) -> Result<usize, PortError> {
        let invalid = |m: String| PortError::Invalid(name.to_string(), m);
        let e = self.model.elements.iter().position(|e| e.type_name() == "modal" && e.label() == joint).ok_or_else(|| invalid(format!("modal joint {joint} is not defined")))?;
        let modes = self.model.elements[e].outputs().map(|o| o.modal_coordinates()).unwrap_or_default();
        let k = modes.iter().find(|(_, m)| *m == mode).map(|(k, _)| *k);
        let listed: Vec<String> = modes.iter().map(|(_, m)| m.to_string()).collect();
        k.map(|k| self.dofs.element_first[e] + k).ok_or_else(|| invalid(format!("modal joint {joint} has no mode {mode} (its modes: {}; numbers in the FEM file)", listed.join(", "))))
    }

    /// Modal joint `joint`'s FEM node `fem_node` at the reference.
    fn flexible(&self, name: &str, joint: Label, fem_node: &str) -> Result<FlexibleAt, PortError> {
        let invalid = |m: String| PortError::Invalid(name.to_string(), m);
        let e = self.model.elements.iter().position(|e| e.type_name() == "modal" && e.label() == joint).ok_or_else(|| invalid(format!("modal joint {joint} is not defined")))?;
        let el = &self.model.elements[e];
        let point = el.outputs().ok_or_else(|| invalid(format!("modal joint {joint} has no FEM nodes")))?.flexible_point(fem_node).map_err(invalid)?;
        let first = self.dofs.element_first[e];
        let (node, orientation) = match point.clamped {
            Some((_, orientation)) => (None, orientation),
            None => {
                let i = self.node(name, el.nodes()[0])?;
                (Some(i), self.frames[i].kin.r)
            }
        };
        let mut local = point.position;
        let mut rate = Vec3::zeros();
        for &(k, phi) in &point.shapes {
            local += phi * self.y[first + k];
            rate += phi * self.yp[first + k];
        }
        let shapes = point.shapes.iter().map(|&(k, phi)| (first + k, orientation * phi)).collect();
        let psi: Vec3 = point.rotation_shapes.iter().map(|&(k, phi)| phi * self.y[first + k]).sum();
        let turn = orientation * exponential_left_jacobian(&psi);
        let rotation_shapes = point.rotation_shapes.iter().map(|&(k, phi)| (first + k, turn * phi)).collect();
        Ok(FlexibleAt { node, orientation, r: orientation * local, deformation_rate: orientation * rate, shapes, rotation_shapes })
    }

    /// The global unit vector of a direction on a flexible body (node frames: its floating frame).
    fn flexible_direction(&self, name: &str, d: &Direction, at: &FlexibleAt) -> Result<Vec3, PortError> {
        let n = d.vector.norm();
        if !(n > 0.0 && n.is_finite()) {
            return Err(PortError::BadDirection(name.to_string()));
        }
        Ok(match d.frame {
            Frame::Global => d.vector / n,
            Frame::Node => at.orientation * (d.vector / n),
        })
    }

    /// Node index and the point's offset in global axes `R f` [m].
    fn point(&self, name: &str, p: &Point) -> Result<(usize, Vec3), PortError> {
        let i = self.node(name, p.node)?;
        let fr = &self.frames[i];
        let r = match p.location {
            Location::Offset(f) => fr.kin.r * f,
            Location::At(x) => x - fr.kin.x,
        };
        if !r.iter().all(|v| v.is_finite()) {
            return Err(PortError::Invalid(name.to_string(), "the point is not finite".into()));
        }
        Ok((i, r))
    }

    /// The global unit vector of a direction (node frames: of node `i`).
    fn direction(&self, name: &str, d: &Direction, i: usize) -> Result<Vec3, PortError> {
        let n = d.vector.norm();
        if !(n > 0.0 && n.is_finite()) {
            return Err(PortError::BadDirection(name.to_string()));
        }
        let v = d.vector / n;
        Ok(match d.frame {
            Frame::Global => v,
            Frame::Node => self.frames[i].kin.r * v,
        })
    }

    /// Global position of a point at the reference [m].
    pub fn position(&self, name: &str, p: &Point) -> Result<Vec3, PortError> {
        let (i, r) = self.point(name, p)?;
        Ok(self.frames[i].kin.x + r)
    }

    /// The column of `B̃` of an input.
    pub fn input_column(&self, port: &InputPort) -> Result<Vec<f64>, PortError> {
        let name = &port.name;
        let mut col = vec![0.0; self.dofs.len];
        let force = |col: &mut Vec<f64>, i: usize, r: Vec3, f: Vec3| {
            let row = self.dofs.equilibrium_row(i);
            let m = r.cross(&f);
            for k in 0..3 {
                col[row + k] += f[k];
                col[row + 3 + k] += m[k];
            }
        };
        match &port.excitation {
            Excitation::Force { point, direction } => {
                let (i, r) = self.point(name, point)?;
                force(&mut col, i, r, self.direction(name, direction, i)?);
            }
            Excitation::Moment { node, direction } => {
                let i = self.node(name, *node)?;
                let d = self.direction(name, direction, i)?;
                let row = self.dofs.equilibrium_row(i) + 3;
                (0..3).for_each(|k| col[row + k] += d[k]);
            }
            Excitation::Actuator { from, to, direction } => {
                let (a, ra) = self.point(name, from)?;
                let (b, rb) = self.point(name, to)?;
                let d = self.direction(name, direction, a)?;
                force(&mut col, b, rb, d);
                force(&mut col, a, ra, -d);
            }
            Excitation::Scalar { node } => col[self.scalar(name, *node)?] += 1.0,
        }
        Ok(col)
    }

    /// Adds `s d · δp` of a point (offset `r`) of node `i` to a row of `C̃`.
    fn add_motion(&self, row: &mut [f64], i: usize, r: Vec3, d: Vec3, s: f64) {
        let first = self.dofs.node_first[i];
        let m = r.cross(&d);
        for k in 0..3 {
            row[first + k] += s * d[k];
            row[first + 3 + k] += s * m[k];
        }
    }

    /// The rows of `C̃` (and `C̃_v`) of an output.
    pub fn output_row(&self, port: &OutputPort) -> Result<OutputRow, PortError> {
        let name = &port.name;
        let n = self.dofs.len;
        let mut c = vec![0.0; n];
        let mut rate = None;
        match &port.measurement {
            Measurement::Displacement { point, direction } => {
                let (i, r) = self.point(name, point)?;
                self.add_motion(&mut c, i, r, self.direction(name, direction, i)?, 1.0);
            }
            Measurement::Rotation { node, direction } => {
                let i = self.node(name, *node)?;
                let d = self.direction(name, direction, i)?;
                (0..3).for_each(|k| c[self.dofs.node_first[i] + 3 + k] += d[k]);
            }
            Measurement::Relative { from, to, direction } => {
                let (a, ra) = self.point(name, from)?;
                let (b, rb) = self.point(name, to)?;
                let d = self.direction(name, direction, a)?;
                self.add_motion(&mut c, b, rb, d, 1.0);
                self.add_motion(&mut c, a, ra, d, -1.0);
                if direction.frame == Frame::Node {
                    // δ(d · Δ) with d turning with node `from`: δθ_a · (d × Δ).
                    let gap = (self.frames[b].kin.x + rb) - (self.frames[a].kin.x + ra);
                    let t = d.cross(&gap);
                    (0..3).for_each(|k| c[self.dofs.node_first[a] + 3 + k] += t[k]);
                }
            }
            Measurement::Velocity { point, direction } => {
                // ṗ = ẋ + ω × r, δω = δġ + ∂(Gġ)/∂g δg at g = 0, δr = δθ × r.
                let (i, r) = self.point(name, point)?;
                let d = self.direction(name, direction, i)?;
                let fr = &self.frames[i];
                let mut cv = vec![0.0; n];
                self.add_motion(&mut cv, i, r, d, 1.0);
                let pdot = fr.kin.xdot + fr.kin.omega.cross(&r);
                let mut t = (r.cross(&d)).transpose() * fr.rate_derivative - d.transpose() * skew(&fr.kin.omega) * skew(&r);
                if direction.frame == Frame::Node {
                    t += d.cross(&pdot).transpose();
                }
                (0..3).for_each(|k| c[self.dofs.node_first[i] + 3 + k] += t[k]);
                rate = Some(cv);
            }
            Measurement::AngularVelocity { node, direction } => {
                let i = self.node(name, *node)?;
                let d = self.direction(name, direction, i)?;
                let fr = &self.frames[i];
                let mut cv = vec![0.0; n];
                (0..3).for_each(|k| cv[self.dofs.node_first[i] + 3 + k] += d[k]);
                let mut t = d.transpose() * fr.rate_derivative;
                if direction.frame == Frame::Node {
                    t += d.cross(&fr.kin.omega).transpose();
                }
                (0..3).for_each(|k| c[self.dofs.node_first[i] + 3 + k] += t[k]);
                rate = Some(cv);
            }
            Measurement::ScalarValue { node } => c[self.scalar(name, *node)?] += 1.0,
            Measurement::ScalarRate { node } => {
                let mut cv = vec![0.0; n];
                cv[self.scalar(name, *node)?] = 1.0;
                rate = Some(cv);
            }
            Measurement::ModalCoordinate { joint, mode } => c[self.modal(name, *joint, *mode)?] += 1.0,
            Measurement::FemDisplacement { joint, fem_node, direction } => {
                // δp = δx + δθ × r + Σₖ R Φₖ δqₖ.
                let at = self.flexible(name, *joint, fem_node)?;
                let d = self.flexible_direction(name, direction, &at)?;
                if let Some(i) = at.node {
                    self.add_motion(&mut c, i, at.r, d, 1.0);
                }
                at.shapes.iter().for_each(|&(k, phi)| c[k] += d.dot(&phi));
            }
            Measurement::FemVelocity { joint, fem_node, direction } => {
                // δṗ = δẋ + δω × r + ω × (δθ × r + Σₖ R Φₖ δqₖ) + δθ × v + Σₖ R Φₖ δq̇ₖ, with
                // v = R Φ q̇ (the rigid point's terms as `Velocity`'s).
                let at = self.flexible(name, *joint, fem_node)?;
                let d = self.flexible_direction(name, direction, &at)?;
                let mut cv = vec![0.0; n];
                at.shapes.iter().for_each(|&(k, phi)| cv[k] += d.dot(&phi));
                if let Some(i) = at.node {
                    let fr = &self.frames[i];
                    self.add_motion(&mut cv, i, at.r, d, 1.0);
                    let pdot = fr.kin.xdot + fr.kin.omega.cross(&at.r) + at.deformation_rate;
                    let mut t = (at.r.cross(&d)).transpose() * fr.rate_derivative - d.transpose() * skew(&fr.kin.omega) * skew(&at.r) + at.deformation_rate.cross(&d).transpose();
                    if direction.frame == Frame::Node {
                        t += d.cross(&pdot).transpose();
                    }
                    (0..3).for_each(|k| c[self.dofs.node_first[i] + 3 + k] += t[k]);
                    at.shapes.iter().for_each(|&(k, phi)| c[k] += d.dot(&fr.kin.omega.cross(&phi)));
                }
                rate = Some(cv);
            }
            Measurement::FemRotation { joint, fem_node, direction } => {
                // δθₙ = δθ + Σₖ R J(ψ) Φrₖ δqₖ (a clamped body's frame does not turn).
                let at = self.flexible(name, *joint, fem_node)?;
                let d = self.flexible_direction(name, direction, &at)?;
                if let Some(i) = at.node {
                    (0..3).for_each(|k| c[self.dofs.node_first[i] + 3 + k] += d[k]);
                }
                at.rotation_shapes.iter().for_each(|&(k, phi)| c[k] += d.dot(&phi));
            }
            Measurement::ModalRate { joint, mode } => {
                let mut cv = vec![0.0; n];
                cv[self.modal(name, *joint, *mode)?] = 1.0;
                rate = Some(cv);
            }
        }
        Ok(OutputRow { c, c_rate: rate })
    }

    /// `B̃` (equations × inputs).
    pub fn input_matrix(&self, inputs: &[InputPort]) -> Result<Mat<f64>, PortError> {
        let cols = inputs.iter().map(|p| self.input_column(p)).collect::<Result<Vec<_>, _>>()?;
        Ok(Mat::from_fn(self.dofs.len, cols.len(), |i, j| cols[j][i]))
    }

    /// `C̃` and `C̃_v` (outputs × unknowns); `C̃_v` is `None` when no output is a rate.
    pub fn output_matrices(&self, outputs: &[OutputPort]) -> Result<(Mat<f64>, Option<Mat<f64>>), PortError> {
        let rows = outputs.iter().map(|p| self.output_row(p)).collect::<Result<Vec<_>, _>>()?;
        let n = self.dofs.len;
        let c = Mat::from_fn(rows.len(), n, |i, j| rows[i].c[j]);
        let any_rate = rows.iter().any(|r| r.c_rate.is_some());
        let c_rate = any_rate.then(|| Mat::from_fn(rows.len(), n, |i, j| rows[i].c_rate.as_ref().map_or(0.0, |v| v[j])));
        Ok((c, c_rate))
    }
}

/// A FEM node's displacement, velocity or rotation component in global axes, as the command
/// line writes it: `JOINT:FEM_NODE:x|y|z` [m], `JOINT:FEM_NODE:vx|vy|vz` [m/s] or
/// `JOINT:FEM_NODE:rx|ry|rz` [rad] (modal joint `JOINT`, its FEM file's node label
/// `FEM_NODE`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FemOutput {
    pub joint: Label,
    pub fem_node: String,
    /// 0..3 displacement x, y, z; 3..6 velocity x, y, z; 6..9 rotation about x, y, z.
    pub component: usize,
}

const FEM_COMPONENTS: [&str; 9] = ["x", "y", "z", "vx", "vy", "vz", "rx", "ry", "rz"];

impl std::str::FromStr for FemOutput {
    type Err = PortError;
    fn from_str(s: &str) -> Result<Self, PortError> {
        let bad = || PortError::Invalid(s.to_string(), format!("expected JOINT:FEM_NODE:COMPONENT with COMPONENT one of {} (JOINT a modal joint's label, FEM_NODE a node label of its FEM file)", FEM_COMPONENTS.join("|")));
        let (joint, rest) = s.split_once(':').ok_or_else(bad)?;
        let (fem_node, comp) = rest.rsplit_once(':').ok_or_else(bad)?;
        let joint = joint.trim().parse().map_err(|_| bad())?;
        let component = FEM_COMPONENTS.iter().position(|c| c.eq_ignore_ascii_case(comp.trim())).ok_or_else(bad)?;
        let fem_node = fem_node.trim();
        if fem_node.is_empty() {
            return Err(bad());
        }
        Ok(FemOutput { joint, fem_node: fem_node.to_string(), component })
    }
}

impl FemOutput {
    /// The same output as a port, global axes.
    pub fn port(&self) -> OutputPort {
        let direction = Direction::global(Vec3::from_fn(|i, _| if i == self.component % 3 { 1.0 } else { 0.0 }));
        let (joint, fem_node) = (self.joint, self.fem_node.clone());
        let name = format!("modal {joint} FEM node {fem_node} {}", FEM_COMPONENTS[self.component]);
        let measurement = match self.component {
            0..3 => Measurement::FemDisplacement { joint, fem_node, direction },
            3..6 => Measurement::FemVelocity { joint, fem_node, direction },
            _ => Measurement::FemRotation { joint, fem_node, direction },
        };
        OutputPort { name, measurement }
    }
}
