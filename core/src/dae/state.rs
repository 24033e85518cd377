//! The state `(t, y, ẏ)` plus each node's reference orientation `R_ref`, and inside a time
//! step its predicted rotation `g_ref` and angular velocity `W_ref` (as MBDyn's strnode.cc:
//! after the prediction the orientation parameters measure Newton's correction from the
//! predicted orientation, [`State::after_predict`]).

use super::DofMap;
use crate::element::NodeKinematics;
use crate::kinematics::{gibbs_compose, gibbs_g, gibbs_rate_derivative, gibbs_rotation, skew, Mat3, Vec3};
use crate::model::{Model, NodeKind};

/// A point on the solution: time, unknowns, their derivatives, reference orientations.
#[derive(Clone, Debug)]
pub struct State {
    pub t: f64,
    /// Factor on applied loads and gravity (1 except while static analysis ramps them).
    pub load: f64,
    pub y: Vec<f64>,
    pub yp: Vec<f64>,
    pub r_ref: Vec<Mat3>,
    /// Per node, the predicted rotation's parameters `g_ref`, `R = R(g) R(g_ref) R_ref`,
    /// during a time step's Newton iteration ([`State::after_predict`]), zero elsewhere
    /// ([`State::rebase`]).
    pub g_ref: Vec<Vec3>,
    /// Per node, the angular velocity `W_ref` [rad/s] that `ω = G(g) ġ + R(g) W_ref` adds to
    /// the parameters' rate: the predicted one during a time step's Newton iteration, zero
    /// elsewhere.
    pub w_ref: Vec<Vec3>,
    /// Per element, the data of its last event ([`crate::element::Element::latch`]); `None`
    /// before any.
    pub latched: Vec<Option<crate::element::Latched>>,
}

/// A node's kinematics with the maps of its orientation parameters.
#[derive(Clone, Debug)]
pub struct NodeFrame {
    pub kin: NodeKinematics,
    /// `G(g)`: `δθ = G δg`, `ω = G ġ`.
    pub g_matrix: Mat3,
    /// `∂(G ġ)/∂g`.
    pub rate_derivative: Mat3,
}

fn vec3(v: &[f64], i: usize) -> Vec3 {
    Vec3::new(v[i], v[i + 1], v[i + 2])
}

impl State {
    /// The initial state of a model: positions, `g = 0`, `R_ref` = initial orientation,
    /// `ẋ` and `ġ = ω` from the initial velocities; scalar nodes' values and derivatives as
    /// written; elements' own initial values
    /// ([`crate::element::Element::initial_unknowns`]); momenta and multipliers zero.
    pub fn initial(model: &Model, dofs: &DofMap) -> Self {
        let mut y = vec![0.0; dofs.len];
        let mut yp = vec![0.0; dofs.len];
        for (i, n) in model.nodes.iter().enumerate() {
            let f = dofs.node_first[i];
            for k in 0..3 {
                y[f + k] = n.position[k];
                yp[f + k] = n.velocity[k];
                yp[f + 3 + k] = n.angular_velocity[k];
            }
        }
        for (e, element) in model.elements.iter().enumerate() {
            for (k, value, rate) in element.initial_unknowns() {
                y[dofs.element_first[e] + k] = value;
                yp[dofs.element_first[e] + k] = rate;
            }
        }
        for (i, n) in model.scalar_nodes.iter().enumerate() {
            y[dofs.scalar_first + i] = n.value;
            yp[dofs.scalar_first + i] = n.derivative;
        }
        State { t: 0.0, load: 1.0, y, yp, r_ref: model.nodes.iter().map(|n| n.orientation).collect(), g_ref: vec![Vec3::zeros(); model.nodes.len()], w_ref: vec![Vec3::zeros(); model.nodes.len()], latched: vec![None; model.elements.len()] }
    }

    /// Kinematics of node `i`: `R = R(g) R(g_ref) R_ref`, `ω = G(g) ġ + R(g) W_ref`
    /// (strnode.cc, `StructNode::Update`), and `∂ω/∂g = ∂(G ġ)/∂g − [R(g) W_ref]× G(g)`.
    /// `R(g) R(g_ref)` is computed as `R(g ∘ g_ref)` ([`gibbs_compose`]): Newton's correction
    /// of a node held still cancels the predicted round-off exactly, where the product of
    /// the matrices would leave an ulp in the orientation every step, which a stiff element
    /// turns into a residual floor.
    pub fn node_frame(&self, dofs: &DofMap, i: usize) -> NodeFrame {
        let f = dofs.node_first[i];
        let (g, gdot) = (vec3(&self.y, f + 3), vec3(&self.yp, f + 3));
        let g_matrix = gibbs_g(&g);
        let rotation = gibbs_rotation(&g);
        let total = if self.g_ref[i] == Vec3::zeros() { rotation } else { gibbs_rotation(&gibbs_compose(&g, &self.g_ref[i])) };
        let mut omega = g_matrix * gdot;
        let mut rate_derivative = gibbs_rate_derivative(&g, &gdot);
        if self.w_ref[i] != Vec3::zeros() {
            let carried = rotation * self.w_ref[i];
            omega += carried;
            rate_derivative -= skew(&carried) * g_matrix;
        }
        NodeFrame { kin: NodeKinematics { x: vec3(&self.y, f), r: total * self.r_ref[i], xdot: vec3(&self.yp, f), omega }, g_matrix, rate_derivative }
    }

    /// Momenta `(β, γ)` of a dynamic node (zero for static nodes).
    pub fn momenta(&self, dofs: &DofMap, i: usize) -> (Vec3, Vec3) {
        match dofs.node_kind[i] {
            NodeKind::Dynamic => (vec3(&self.y, dofs.node_first[i] + 6), vec3(&self.y, dofs.node_first[i] + 9)),
            NodeKind::Static => (Vec3::zeros(), Vec3::zeros()),
        }
    }

    /// Re-bases every node's orientation: `R_ref ← R(g) R(g_ref) R_ref`, `g ← 0`, `ġ ← ω`
    /// (since `G(0) = I`), `g_ref ← 0`, `W_ref ← 0`; the kinematics are unchanged.
    pub fn rebase(&mut self, dofs: &DofMap) {
        let frames: Vec<NodeFrame> = (0..self.r_ref.len()).map(|i| self.node_frame(dofs, i)).collect();
        self.rebase_with(dofs, &frames);
    }

    /// [`State::rebase`] with this state's node frames given ([`State::node_frame`] of every
    /// node): a time step computes them once for its snapshot and the re-basing.
    pub fn rebase_with(&mut self, dofs: &DofMap, frames: &[NodeFrame]) {
        for (i, fr) in frames.iter().enumerate() {
            self.r_ref[i] = fr.kin.r;
            self.g_ref[i] = Vec3::zeros();
            self.w_ref[i] = Vec3::zeros();
            let f = dofs.node_first[i] + 3;
            for k in 0..3 {
                self.y[f + k] = 0.0;
                self.yp[f + k] = fr.kin.omega[k];
            }
        }
    }

    /// The form the model is linearized in: re-based ([`State::rebase`]), then every node's
    /// angular velocity carried in `W_ref` with `ġ = 0`, as the integrator carries it after a
    /// prediction ([`State::after_predict`]; MBDyn's eigenanalysis assembles its Jacobians in
    /// that form). A perturbation `δg` then turns the moving reference,
    /// `R = R(δg) R₀(t)`, so `ω = G(δg) δġ + R(δg) ω₀` and `∂ω/∂g = −[ω₀]×`: the small
    /// motion relative to a steady spin or a uniform rotation. In the re-based form
    /// (`ġ = ω₀`, `W_ref = 0`) the same perturbation gives `∂(G ġ)/∂g = −½[ω₀]×` (the
    /// parameters' rate read as a fixed rate), which halves the gyroscopic coupling `δg × ω₀`
    /// of a spinning body. The kinematics are unchanged.
    pub fn linearization_base(&mut self, dofs: &DofMap) {
        self.rebase(dofs);
        for i in 0..self.r_ref.len() {
            let f = dofs.node_first[i] + 3;
            self.w_ref[i] = vec3(&self.yp, f);
            for k in 0..3 {
                self.yp[f + k] = 0.0;
            }
        }
    }

    /// After a time step's prediction, as MBDyn's `StructNode::AfterPredict` (strnode.cc):
    /// every node's predicted rotation and angular velocity become the references,
    /// `g_ref ← g ∘ g_ref`, `W_ref ← ω` (from a re-based state `g_ref = 0`, `W_ref = 0`:
    /// `R_ref` stays the last step's), and `g ← 0`, `ġ ← 0`, so that Newton's increments compose with the predicted
    /// orientation (`R = R(δg) R_pred`) instead of adding to its parameters; the kinematics
    /// are unchanged.
    pub fn after_predict(&mut self, dofs: &DofMap) {
        for i in 0..self.r_ref.len() {
            let fr = self.node_frame(dofs, i);
            let f = dofs.node_first[i] + 3;
            self.g_ref[i] = gibbs_compose(&vec3(&self.y, f), &self.g_ref[i]);
            self.w_ref[i] = fr.kin.omega;
            for k in 0..3 {
                self.y[f + k] = 0.0;
                self.yp[f + k] = 0.0;
            }
        }
    }
}
