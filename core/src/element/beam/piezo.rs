//! MBDyn's `piezoelectric actuator` on a finite-volume beam (input manual, "Three-node beam
//! element" and "Two-node beam element"; MBDyn 1.7.3 pzbeam.cc, pzbeam2.cc): `N`
//! electrodes whose voltages `V` are the values of abstract nodes, and at each evaluation
//! point `s` a 6×N actuation matrix `T_s` [N/V; N m/V] whose product with the voltages is
//! added to the section law's local generalized forces,
//!
//! `[F; M]_s = K ([ε; κ] − e_p) + V [ε̇; κ̇] + f_p + T_s V`,
//!
//! before they are turned to the global frame and applied to the finite volumes
//! ([`super::finite_volume`]). The voltage term therefore also enters the geometric
//! stiffness `−[F×] δθ` of the section frame's rotation, and its own derivative is the
//! voltage columns: `∂F/∂V_j = R_s T_s[0..3, j]`, `∂M/∂V_j = R_s T_s[3..6, j]`, applied
//! with the arms `p_s − x_i` of the point's two nodes. A voltage node's value is a `y`
//! unknown like a position, so the ports of a linearized model see the actuator through
//! these columns (an input on the abstract node's equation moves the beam through them).

use nalgebra::{DMatrix, Vector6};

use super::finite_volume::stack;
use crate::element::contract::{Col, ElementState, JacobianSink, Label, Row, ScalarNodeId};
use crate::kinematics::{Mat3, Vec3};

/// The electrodes of a beam's piezoelectric actuator and its actuation matrix at each
/// evaluation point.
#[derive(Clone, Debug, PartialEq)]
pub struct PiezoActuator {
    /// The abstract nodes whose values are the electrodes' voltages [V], in the order of
    /// the matrices' columns (the element's scalar slots).
    electrodes: Vec<ScalarNodeId>,
    /// `T_s`, 6 × N per evaluation point: local force per volt (rows 0..3, [N/V]) and
    /// moment per volt (rows 3..6, [N m/V]) in the section frame.
    matrices: Vec<DMatrix<f64>>,
}

/// An actuator that does not fit its beam.
#[derive(Debug, thiserror::Error)]
pub enum PiezoError {
    #[error("beam {0}: a piezoelectric actuator needs at least one electrode")]
    NoElectrode(Label),
    #[error("beam {0}: the piezoelectric actuator has {1} actuation matrices, the beam {2} evaluation points")]
    Points(Label, usize, usize),
    #[error("beam {0}: actuation matrix {1} is {2}x{3}, expected 6x{4} (one column per electrode)")]
    Shape(Label, usize, usize, usize, usize),
    #[error("beam {0}: actuation matrix {1} has a value that is not finite")]
    NotFinite(Label, usize),
}

impl PiezoActuator {
    /// An actuator of beam `label` with `electrodes` and one 6 × N matrix per evaluation
    /// point (the beam's `with_piezo` checks their number).
    pub fn new(label: Label, electrodes: Vec<ScalarNodeId>, matrices: Vec<DMatrix<f64>>) -> Result<Self, PiezoError> {
        if electrodes.is_empty() {
            return Err(PiezoError::NoElectrode(label));
        }
        for (s, t) in matrices.iter().enumerate() {
            if t.nrows() != 6 || t.ncols() != electrodes.len() {
                return Err(PiezoError::Shape(label, s + 1, t.nrows(), t.ncols(), electrodes.len()));
            }
            if t.iter().any(|v| !v.is_finite()) {
                return Err(PiezoError::NotFinite(label, s + 1));
            }
        }
        Ok(PiezoActuator { electrodes, matrices })
    }

    /// Whether the actuator fits beam `label` with `points` evaluation points (one matrix
    /// each).
    pub fn check_points(&self, label: Label, points: usize) -> Result<(), PiezoError> {
        if self.matrices.len() == points { Ok(()) } else { Err(PiezoError::Points(label, self.matrices.len(), points)) }
    }

    /// The electrodes' nodes, in scalar-slot order.
    pub fn electrodes(&self) -> &[ScalarNodeId] {
        &self.electrodes
    }

    /// `T_s V`: the local generalized force of the voltages at point `s` [N; N m].
    pub fn local_forces(&self, s: usize, st: &dyn ElementState) -> Vector6<f64> {
        let t = &self.matrices[s];
        let mut f = Vector6::zeros();
        for j in 0..self.electrodes.len() {
            let v = st.scalar_value(j);
            for i in 0..6 {
                f[i] += t[(i, j)] * v;
            }
        }
        f
    }

    /// The voltage columns of the point `s` between nodes `s` and `s + 1` at `p` with frame
    /// `r` (nodes at `x`), with the residual's signs of
    /// [`super::finite_volume::add_point_residual`]: node `s` receives `−(F, M + (p − x_s) ×
    /// F)`, node `s + 1` the opposite with its own arm.
    pub fn add_voltage_jacobian(&self, out: &mut dyn JacobianSink, s: usize, p: &Vec3, r: &Mat3, x: &[Vec3]) {
        let t = &self.matrices[s];
        for j in 0..self.electrodes.len() {
            let (df, dm) = (r * Vec3::new(t[(0, j)], t[(1, j)], t[(2, j)]), r * Vec3::new(t[(3, j)], t[(4, j)], t[(5, j)]));
            for (node, sign) in [(s, -1.0), (s + 1, 1.0)] {
                let moment = dm + (p - x[node]).cross(&df);
                let column = stack(&df, &moment);
                for comp in 0..6 {
                    out.add(Row::Equilibrium { slot: node, comp }, Col::ScalarValue { slot: j }, sign * column[comp]);
                }
            }
        }
    }
}
