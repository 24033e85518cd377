//! Deterministic noise for random states, an element with a deliberately wrong Jacobian, and
//! a friction model for Jacobian checks.

use romdyn::element::{Col, Element, ElementState, JacobianSink, ResidualSink, Row};
use romdyn::kinematics::{gibbs_rotation, Mat3, Vec3};

/// Deterministic pseudo-random numbers in [-1, 1) (xorshift64*).
pub struct Noise(pub u64);

impl Noise {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        2.0 * ((self.0.wrapping_mul(0x2545F4914F6CDD1D) >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }
    pub fn vec(&mut self) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next())
    }
    pub fn rotation(&mut self) -> Mat3 {
        gibbs_rotation(&self.vec())
    }
    pub fn matrix(&mut self) -> Mat3 {
        Mat3::from_fn(|_, _| self.next())
    }
}

/// A spring to ground along y at node 2 whose Jacobian is deliberately twice its residual's
/// derivative (label 99, type "wrong spring").
pub struct WrongSpring;

impl Element for WrongSpring {
    fn label(&self) -> u32 {
        99
    }
    fn type_name(&self) -> &'static str {
        "wrong spring"
    }
    fn nodes(&self) -> Vec<u32> {
        vec![2]
    }
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink) {
        out.add(Row::Equilibrium { slot: 0, comp: 1 }, 10.0 * s.node(0).x.y);
    }
    fn jacobian(&self, _: &dyn ElementState, out: &mut dyn JacobianSink) {
        out.add(Row::Equilibrium { slot: 0, comp: 1 }, Col::Position { slot: 0, comp: 1 }, 20.0);
    }
}

/// A modlugre friction model whose transition band `(1 − κ) μ/σ₀` (about 0.06 m) is wide
/// against a Jacobian check's steps (1e-6 m), so that central differences resolve its half
/// sine wave, with a speed-dependent static coefficient (so that `μ'` enters) and viscous
/// friction (tests/multibody/joint_friction.rs, hinge_friction.rs, screw_friction.rs, brake.rs).
pub fn smooth_model() -> romdyn::element::ModLugre {
    romdyn::element::ModLugre { sigma0: 3.0, sigma1: 0.4, sigma2: 0.2, kappa: 0.6, static_friction: romdyn::element::drive::ScalarFunction::Multilinear { points: vec![(0.0, 0.6), (2.0, 0.3)], extrapolate: true } }
}
