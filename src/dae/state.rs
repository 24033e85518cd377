//! The state `(t, y, ẏ)` plus each node's reference orientation `R_ref`.

use super::DofMap;
use crate::element::NodeKinematics;
use crate::kinematics::{gibbs_g, gibbs_rate_derivative, gibbs_rotation, Mat3, Vec3};
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
    /// `ẋ` and `ġ = ω` from the initial velocities; momenta and multipliers zero.
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
        State { t: 0.0, load: 1.0, y, yp, r_ref: model.nodes.iter().map(|n| n.orientation).collect(), latched: vec![None; model.elements.len()] }
    }

    /// Kinematics of node `i`.
    pub fn node_frame(&self, dofs: &DofMap, i: usize) -> NodeFrame {
        let f = dofs.node_first[i];
        let (g, gdot) = (vec3(&self.y, f + 3), vec3(&self.yp, f + 3));
        let g_matrix = gibbs_g(&g);
        NodeFrame {
            kin: NodeKinematics { x: vec3(&self.y, f), r: gibbs_rotation(&g) * self.r_ref[i], xdot: vec3(&self.yp, f), omega: g_matrix * gdot },
            g_matrix,
            rate_derivative: gibbs_rate_derivative(&g, &gdot),
        }
    }

    /// Momenta `(β, γ)` of a dynamic node (zero for static nodes).
    pub fn momenta(&self, dofs: &DofMap, i: usize) -> (Vec3, Vec3) {
        match dofs.node_kind[i] {
            NodeKind::Dynamic => (vec3(&self.y, dofs.node_first[i] + 6), vec3(&self.y, dofs.node_first[i] + 9)),
            NodeKind::Static => (Vec3::zeros(), Vec3::zeros()),
        }
    }

    /// Re-bases every node's orientation: `R_ref ← R(g) R_ref`, `g ← 0`, `ġ ← ω`
    /// (since `G(0) = I`).
    pub fn rebase(&mut self, dofs: &DofMap) {
        for i in 0..self.r_ref.len() {
            let fr = self.node_frame(dofs, i);
            self.r_ref[i] = fr.kin.r;
            let f = dofs.node_first[i] + 3;
            for k in 0..3 {
                self.y[f + k] = 0.0;
                self.yp[f + k] = fr.kin.omega[k];
            }
        }
    }
}
