//! A moving reference frame (MBDyn's `rigid body kinematics` in control data; input manual,
//! "Rigid Body Kinematics"; tecman, "Dynamics in a Relative Reference Frame").
//!
//! The model's unknowns are relative to a frame with angular velocity `W`, angular
//! acceleration `Ẇ` and origin acceleration `A` (global components, functions of time). As
//! in MBDyn 1.7.3 (body.cc `AssVecRBK_int`, autostr.cc), a dynamic node's equilibrium gets
//! `2 W × β` and `W × γ`, and a body of mass `m`, static moment `S` and inertia `J` about
//! its node (at `x`, moving with `v`, `ω`) the transport terms
//!
//! ```text
//! f = m A + Ẇ × s₀ + W × (W × s₀),   s₀ = m x + S
//! M = S × a + W × (J W) + J Ẇ + ω × (J W) − J (ω × W) + v × (W × S),
//! a = A + Ẇ × x + W × (W × x) + W × v
//! ```
//!
//! on its force and moment equilibrium (with the `ω × J W` terms and `2 W × β`, `W × γ`
//! they make the inertia of the absolute motion). The frame's position, orientation and
//! velocity enter no equation; with a `drive` form's orientation `R(θ)`, the vectors given
//! are turned by `Rᵀ` (rbk_impl.cc, `DriveRigidBodyKinematics::Update`).

use super::contract::{add_block, add_vec, Col, ElementState, JacobianSink, ResidualSink, Row};
use super::VectorDrive;
use crate::kinematics::{skew, Mat3, Vec3};

/// The frame's motion as functions of time.
#[derive(Clone, Debug)]
pub struct FrameMotion {
    /// `drive` form's orientation vector θ(t) (rotation vector, global); `None`: identity.
    pub orientation: Option<VectorDrive>,
    pub angular_velocity: VectorDrive,
    pub acceleration: VectorDrive,
    pub angular_acceleration: VectorDrive,
}

/// `(W, Ẇ, A)` at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameState {
    pub w: Vec3,
    pub wp: Vec3,
    pub a: Vec3,
}

/// `exp([θ×])`.
fn rotation(theta: &Vec3) -> Mat3 {
    let phi = theta.norm();
    let k = skew(theta);
    if phi < 1e-8 {
        return Mat3::identity() + k + 0.5 * k * k;
    }
    Mat3::identity() + phi.sin() / phi * k + (1.0 - phi.cos()) / (phi * phi) * k * k
}

impl FrameMotion {
    pub fn at(&self, t: f64) -> FrameState {
        let rt = self.orientation.as_ref().map_or_else(Mat3::identity, |o| rotation(&o.value(t)).transpose());
        FrameState { w: rt * self.angular_velocity.value(t), wp: rt * self.angular_acceleration.value(t), a: rt * self.acceleration.value(t) }
    }
}

/// A body's transport terms on its node (slot 0): force and moment rows.
pub fn body_residual(f: &FrameState, m: f64, s: &Vec3, j: &Mat3, st: &dyn ElementState, out: &mut dyn ResidualSink) {
    let n = st.node(0);
    let (w, wp) = (f.w, f.wp);
    let s0 = m * n.x + s;
    add_vec(out, Row::force(0), &(m * f.a + wp.cross(&s0) + w.cross(&w.cross(&s0))));
    let a = f.a + wp.cross(&n.x) + w.cross(&w.cross(&n.x)) + w.cross(&n.xdot);
    let moment = s.cross(&a) + w.cross(&(j * w)) + j * wp + n.omega.cross(&(j * w)) - j * n.omega.cross(&w) + n.xdot.cross(&w.cross(s));
    add_vec(out, Row::moment(0), &moment);
}

/// The derivatives of [`body_residual`] by the node's position, rotation, velocity and
/// angular velocity (`δS = −[S×] δθ`, `δJ u = (J [u×] − [(J u)×]) δθ`).
pub fn body_jacobian(f: &FrameState, m: f64, s: &Vec3, j: &Mat3, st: &dyn ElementState, out: &mut dyn JacobianSink) {
    let n = st.node(0);
    let (w, wp) = (f.w, f.wp);
    let (sx, wx) = (skew(s), skew(&w));
    let k = skew(&wp) + wx * wx;
    let (force, moment) = (Row::force(0), Row::moment(0));
    add_block(out, force, Col::position(0), &(m * k));
    add_block(out, force, Col::rotation(0), &(-k * sx));
    let a = f.a + wp.cross(&n.x) + w.cross(&w.cross(&n.x)) + w.cross(&n.xdot);
    add_block(out, moment, Col::position(0), &(sx * k));
    add_block(out, moment, Col::velocity(0), &(sx * wx - skew(&w.cross(s))));
    add_block(out, moment, Col::angular_velocity(0), &(j * wx - skew(&(j * w))));
    // δ(J u) for a fixed u.
    let dj = |u: &Vec3| j * skew(u) - skew(&(j * u));
    let rot = skew(&a) * sx + wx * dj(&w) + dj(&wp) + skew(&n.omega) * dj(&w) - dj(&n.omega.cross(&w)) - skew(&n.xdot) * wx * sx;
    add_block(out, moment, Col::rotation(0), &rot);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::drive::Drive;

    fn constant(v: Vec3) -> VectorDrive {
        VectorDrive(vec![(v, Drive::Const(1.0))])
    }

    /// A `drive` form's orientation turns the given vectors by `Rᵀ`: 90° about z takes a
    /// global x angular velocity to −y.
    #[test]
    fn the_orientation_turns_the_vectors() {
        let f = FrameMotion { orientation: Some(constant(Vec3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2))), angular_velocity: constant(Vec3::x()), acceleration: constant(Vec3::zeros()), angular_acceleration: constant(Vec3::zeros()) };
        assert!((f.at(0.0).w - Vec3::new(0.0, -1.0, 0.0)).norm() < 1e-15);
    }
}
