//! A rod whose prestrain is a drive (MBDyn's `rod` with `prestrain, DRIVE` on its 1-D linear
//! law: rodj.cc with constltp's `N = EA (ε − ε_p(t)) + C ε̇`): the [`Rod`] of the law's
//! constant part plus the force `−EA ε_p(t) e` along the rod, `e = d/l`, whose derivative
//! with `ε_p` held is `−EA ε_p (I − e eᵀ)/l`. Written so, a prestrain that balances a load
//! exactly (MBDyn's `tests/joints/rod/rodprestrain`) does so in floating point too.

use super::anchor::{node_labels, Pair};
use super::contract::{Element, ElementState, JacobianSink, Label, ResidualSink};
use super::deformable::{add_pair_force, add_pair_force_jacobian};
use super::Rod;
use super::drive::Drive;
use crate::kinematics::Mat3;

#[derive(Clone, Debug)]
pub struct PrestrainedRod {
    /// The rod at zero prestrain drive.
    pub rod: Rod,
    /// `ε_p(t)`, evaluated in each residual at the state being assembled (a drive that reads
    /// the model's state is held in the Jacobian, as MBDyn's).
    pub prestrain: Drive,
    /// The length `l₀` the strain is measured against [m].
    pub strain_length: f64,
}

impl PrestrainedRod {
    /// `EA ε_p` of the state [N].
    fn prestrain_force(&self, st: &dyn ElementState) -> f64 {
        self.rod.axial_stiffness / self.rod.length * self.strain_length * self.prestrain.value_in(st)
    }
}

impl Element for PrestrainedRod {
    fn label(&self) -> Label {
        self.rod.label
    }
    fn type_name(&self) -> &'static str {
        "rod"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.rod.a, &self.rod.b)
    }
    fn reads_state(&self) -> bool {
        self.prestrain.reads_state()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        self.rod.residual(st, out);
        let p = Pair::new(&self.rod.a, &self.rod.b, st);
        add_pair_force(out, &p, &(-self.prestrain_force(st) / p.d.norm() * p.d));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        self.rod.jacobian(st, out);
        let p = Pair::new(&self.rod.a, &self.rod.b, st);
        let (n, l) = (self.prestrain_force(st), p.d.norm());
        let e = p.d / l;
        add_pair_force_jacobian(out, &p, &(-n * e), &(-n / l * (Mat3::identity() - e * e.transpose())));
    }
}
