//! The cogging (ripple) torque of MBDyn's `motor` (elec/motor.cc; input manual §Motor:
//! `M0, DRIVE, M1, DRIVE, terminal pairs, P` after `orientation, R`): the torque becomes
//! `M = M0(Φₑ) + (G + M1(Φₑ)) i`, the drives evaluated at the electrical angle `Φₑ = p Φₘ`
//! wrapped to [0, 2π), `Φₘ = atan2(a₂·r, a₁·r)` the mechanical angle of node 2 about the
//! motor's axis (`aₖ = R₁ Rₙ eₖ` the motor frame's axes on node 1, `r = R₂ e₁` node 2's
//! first axis). The back-EMF stays `G ω`, as in MBDyn.

use super::contract::ElementState;
use super::drive::Drive;
use crate::kinematics::{Mat3, Vec3};

/// `M0`, `M1` and the frame they turn in.
pub struct Cogging {
    /// `Rₙ`, the motor's frame in node 1's (axis 3 is the motor's).
    pub frame: Mat3,
    /// The number of terminal pairs `p`.
    pub pairs: f64,
    /// `M0(Φₑ)` [N m], `M1(Φₑ)` [N m/A]: drive callers of the electrical angle [rad].
    pub m0: Drive,
    pub m1: Drive,
}

/// The cogging terms at a state.
pub struct CoggingState {
    /// `M0(Φₑ)`, `M1(Φₑ)`.
    pub m0: f64,
    pub m1: f64,
    /// `∂M0/∂Φₑ · p`, `∂M1/∂Φₑ · p`: slopes in the mechanical angle.
    pub m0_slope: f64,
    pub m1_slope: f64,
    /// `∂Φₘ/∂δθ₁`, `∂Φₘ/∂δθ₂` (virtual rotations in the global frame).
    pub angle_theta: [Vec3; 2],
}

impl Cogging {
    /// The drives whose slope in their argument romdyn computes (MBDyn's `dGetP`): the
    /// reader refuses the others.
    pub fn differentiable(drive: &Drive) -> bool {
        drive.time_derivative(0.0).is_some()
    }

    /// `Φₘ` [rad] and its derivatives at `st` (nodes in slots 0 and 1).
    pub fn mechanical_angle(&self, st: &dyn ElementState) -> (f64, [Vec3; 2]) {
        let (r1, r2) = (st.node(0).r, st.node(1).r);
        let (a1, a2) = (r1 * self.frame.column(0), r1 * self.frame.column(1));
        let r: Vec3 = r2.column(0).into_owned();
        let (x, y) = (a1.dot(&r), a2.dot(&r));
        let q = x * x + y * y;
        // δy = δθ₁·(a₂ × r) + δθ₂·(r × a₂), likewise δx with a₁.
        let d1 = (a2.cross(&r) * x - a1.cross(&r) * y) / q;
        let d2 = (r.cross(&a2) * x - r.cross(&a1) * y) / q;
        (y.atan2(x), [d1, d2])
    }

    /// The electrical angle `Φₑ = p Φₘ` wrapped to [0, 2π) (motor.cc `dGetPhiElectric`).
    pub fn electrical_angle(&self, mechanical: f64) -> f64 {
        let two_pi = 2.0 * std::f64::consts::PI;
        let e = (self.pairs * mechanical) % two_pi;
        if e < 0.0 {
            e + two_pi
        } else {
            e
        }
    }

    pub fn at(&self, st: &dyn ElementState) -> CoggingState {
        let (mechanical, angle_theta) = self.mechanical_angle(st);
        let e = self.electrical_angle(mechanical);
        let slope = |d: &Drive| d.time_derivative(e).unwrap_or(0.0) * self.pairs;
        CoggingState { m0: self.m0.value(e), m1: self.m1.value(e), m0_slope: slope(&self.m0), m1_slope: slope(&self.m1), angle_theta }
    }
}
