//! A rod with MBDyn's `linear elastic bistop` or `linear viscoelastic bistop` law
//! (constltp_impl.h, `BiStopCLWrapper`; input manual, "General", §Constitutive Laws,
//! bistop): the law acts while it is active, on the strain measured from the strain at the
//! instant it activated, `N = EA (ε − ε_ref) + C ε̇` (with `ε = l/L₀ − 1`, rodj.cc), and gives
//! no force while inactive.
//!
//! Its status and `ε_ref` are events ([`Element::latch`]): inactive, it activates at the
//! first step whose activating drive is non-zero, `ε_ref` the strain there; active, it
//! deactivates at the first step whose deactivating drive is non-zero (checked in the same
//! step as an activation, as MBDyn's wrapper falls through from one case to the other). An
//! initially active law has `ε_ref = 0`. MBDyn checks the drives in every `Update` of the
//! law, i.e. in each residual assembly; its first one of a step is at the predicted state,
//! where romdyn latches, so with drives of time alone both switch at the same step with the
//! same `ε_ref`. Newton's Jacobian and a linearization see the status and `ε_ref` of the
//! state as constants: active, the rod's stiffness and damping; inactive, nothing (the
//! rod's entries are written as zeros, which keeps one sparsity pattern).

use super::anchor::{node_labels, Pair};
use super::contract::{Col, Element, ElementState, JacobianSink, Label, Latched, ResidualSink, Row};
use super::deformable::{add_pair_force, add_pair_force_jacobian};
use super::Rod;
use super::drive::Drive;
use crate::kinematics::Mat3;
use crate::element::Events;

/// A rod whose law switches on and off (module documentation).
#[derive(Clone, Debug)]
pub struct BistopRod {
    /// The rod of the law's constant part (EA, viscosity, the rest length of a constant
    /// prestrain or prestress).
    pub rod: Rod,
    /// The length `L₀` the strain is measured against (the file's rod length) [m].
    pub strain_length: f64,
    pub initially_active: bool,
    pub activate: Drive,
    pub deactivate: Drive,
}

/// The law's status after its last event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BistopStatus {
    pub active: bool,
    /// The strain the law's force is measured from, `ε_ref` [-].
    pub reference_strain: f64,
}

impl BistopRod {
    /// The status the state carries (the initial one before any event).
    pub fn status(&self, st: &dyn ElementState) -> BistopStatus {
        st.latched().and_then(|l| l.downcast_ref::<BistopStatus>()).copied().unwrap_or(BistopStatus { active: self.initially_active, reference_strain: 0.0 })
    }

    /// `ε = l/L₀ − 1` of the state.
    fn strain(&self, st: &dyn ElementState) -> f64 {
        let p = Pair::new(&self.rod.a, &self.rod.b, st);
        p.d.norm() / self.strain_length - 1.0
    }

    /// `EA ε_ref` [N].
    fn reference_force(&self, s: &BistopStatus) -> f64 {
        self.rod.axial_stiffness / self.rod.length * self.strain_length * s.reference_strain
    }
}

/// A sink that records where entries go, with value zero.
struct Zeros<'a>(&'a mut dyn JacobianSink);

impl JacobianSink for Zeros<'_> {
    fn add(&mut self, row: Row, col: Col, _value: f64) {
        self.0.add(row, col, 0.0);
    }
}

impl Element for BistopRod {
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
        self.activate.reads_state() || self.deactivate.reads_state()
    }
    fn events(&self) -> Option<&dyn Events> {
        Some(self)
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let s = self.status(st);
        if !s.active {
            return;
        }
        self.rod.residual(st, out);
        let p = Pair::new(&self.rod.a, &self.rod.b, st);
        add_pair_force(out, &p, &(-self.reference_force(&s) / p.d.norm() * p.d));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let s = self.status(st);
        if s.active {
            self.active_jacobian(st, &s, out);
        } else {
            self.active_jacobian(st, &s, &mut Zeros(out));
        }
    }
}

impl Events for BistopRod {
    fn latch(&self, now: &dyn ElementState, _before: &dyn ElementState) -> Option<Latched> {
        let old = self.status(now);
        let mut new = old;
        if !new.active && self.activate.value_in(now) != 0.0 {
            new = BistopStatus { active: true, reference_strain: self.strain(now) };
        }
        if new.active && self.deactivate.value_in(now) != 0.0 {
            new.active = false;
        }
        (new != old).then(|| std::sync::Arc::new(new) as Latched)
    }
}

impl BistopRod {
    /// The Jacobian of the active law.
    fn active_jacobian(&self, st: &dyn ElementState, s: &BistopStatus, out: &mut dyn JacobianSink) {
        self.rod.jacobian(st, out);
        let p = Pair::new(&self.rod.a, &self.rod.b, st);
        let (n, l) = (self.reference_force(s), p.d.norm());
        let e = p.d / l;
        add_pair_force_jacobian(out, &p, &(-n * e), &(-n / l * (Mat3::identity() - e * e.transpose())));
    }
}
