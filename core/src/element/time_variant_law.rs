//! MBDyn's `linear time variant viscoelastic generic` law (input manual, "General", §Linear
//! time variant viscoelastic generic; constltp_impl.h, `LTVViscoElasticGenericConstitutiveLaw`):
//! `f = f_p + s_K(t) K (ε − ε_p) + s_C(t) C ε̇`, the stiffness and viscosity matrices times
//! the values of two drive callers at the state being assembled. MBDyn's `Update` scales
//! `K` and `C` by the drives' current values and its Jacobian uses the scaled matrices: the
//! drives are held in the Jacobian, as a prestrain drive is (a drive reading the model's
//! state makes the element [`super::Element::reads_state`]).

use super::contract::{Col, ElementState, JacobianSink, ResidualSink, Row};
use super::drive::Drive;
use crate::kinematics::Mat3;

/// The two drives of a time-variant law: `s_K(t)` on the stiffness, `s_C(t)` on the viscosity.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeVariance {
    pub stiffness: Drive,
    pub viscosity: Drive,
}

impl TimeVariance {
    /// `(s_K, s_C)` at the state `st` (its time, and the model's state for a drive reading it).
    pub fn scales(&self, st: &dyn ElementState) -> (f64, f64) {
        (self.stiffness.value_in(st), self.viscosity.value_in(st))
    }

    /// Whether a drive reads the model's state.
    pub fn reads_state(&self) -> bool {
        self.stiffness.reads_state() || self.viscosity.reads_state()
    }
}

/// `(s_K, s_C)` of an optional time variance at `st`: `(1, 1)` for a law that does not vary.
pub fn scales_of(variance: Option<&TimeVariance>, st: &dyn ElementState) -> (f64, f64) {
    variance.map_or((1.0, 1.0), |v| v.scales(st))
}

/// A sink that multiplies every entry by `factor` before passing it on: an element whose
/// residual is linear in its law's matrices evaluates a part of the law (the elastic one,
/// the viscous one) into it to scale that part.
pub struct Scaled<'a, S: ?Sized> {
    pub inner: &'a mut S,
    pub factor: f64,
}

impl<S: ResidualSink + ?Sized> ResidualSink for Scaled<'_, S> {
    fn add(&mut self, row: Row, value: f64) {
        self.inner.add(row, self.factor * value);
    }
}

impl<S: JacobianSink + ?Sized> JacobianSink for Scaled<'_, S> {
    fn add(&mut self, row: Row, col: Col, value: f64) {
        self.inner.add(row, col, self.factor * value);
    }
    fn add_block(&mut self, rows: [Row; 3], cols: [Col; 3], m: &Mat3) {
        self.inner.add_block(rows, cols, &(self.factor * m));
    }
}
