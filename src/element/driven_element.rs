//! MBDyn's `driven` element wrapper (driven.cc, `DrivenElem`; input manual, §Driven
//! Element): the wrapped element acts while its drive is non-zero and is switched off
//! otherwise. Switched off it adds nothing to its nodes' equations, and each of its own
//! equations becomes `−λ_k = 0` (its multipliers are held at zero), as `DrivenElem::AssRes`
//! writes `−X` on the element's own unknowns. The drive is evaluated at the time the
//! residual is evaluated at, as MBDyn's `AfterPredict` does at the step's time.
//!
//! The assembler scales a holonomic constraint row by `1/c` in the form of eq. 30 and
//! steps its multiplier as an algebraic unknown: the `−λ_k` row's derivative carries that
//! scale ([`ElementState::constraint_row_scale`]).
//!
//! The Jacobian keeps one sparsity pattern in both states: switched off, the wrapped
//! element's entries are written as zeros; switched on, the `(λ_k, λ_k)` diagonal is
//! written as a zero.

use super::contract::{Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row, SectionState};
use super::Drive;

pub struct DrivenElement {
    /// The element's switch: on where `drive(t) ≠ 0`.
    pub drive: Drive,
    pub inner: Box<dyn Element>,
}

impl DrivenElement {
    fn active(&self, s: &dyn ElementState) -> bool {
        self.drive.value_in(s) != 0.0
    }
}

/// A sink that records where entries go, with value zero.
struct Zeros<'a>(&'a mut dyn JacobianSink);

impl JacobianSink for Zeros<'_> {
    fn add(&mut self, row: Row, col: Col, _value: f64) {
        self.0.add(row, col, 0.0);
    }
}

impl Element for DrivenElement {
    fn reads_state(&self) -> bool {
        self.drive.reads_state() || self.inner.reads_state()
    }
    fn label(&self) -> Label {
        self.inner.label()
    }
    fn type_name(&self) -> &'static str {
        self.inner.type_name()
    }
    fn nodes(&self) -> Vec<Label> {
        self.inner.nodes()
    }
    fn multipliers(&self) -> Vec<String> {
        self.inner.multipliers()
    }
    fn is_velocity_constraint(&self, k: usize) -> bool {
        self.inner.is_velocity_constraint(k)
    }
    fn is_coordinate(&self, k: usize) -> bool {
        self.inner.is_coordinate(k)
    }
    fn constraint_rows_read_multipliers(&self) -> bool {
        self.inner.constraint_rows_read_multipliers()
    }
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink) {
        if self.active(s) {
            self.inner.residual(s, out);
        } else {
            for k in 0..self.inner.multipliers().len() {
                out.add(Row::Constraint(k), -s.multiplier(k));
            }
        }
    }
    fn jacobian(&self, s: &dyn ElementState, out: &mut dyn JacobianSink) {
        let active = self.active(s);
        if active {
            self.inner.jacobian(s, out);
        } else {
            self.inner.jacobian(s, &mut Zeros(out));
        }
        for k in 0..self.inner.multipliers().len() {
            // ∂(−λ_k)/∂λ_k = −1 on a row the assembler scales as a constraint row (velocity
            // constraints' rows are never scaled).
            let scale = if self.inner.is_velocity_constraint(k) || self.inner.is_coordinate(k) { 1.0 } else { s.constraint_row_scale() };
            out.add(Row::Constraint(k), Col::Multiplier(k), if active { 0.0 } else { -scale });
        }
    }
    fn sections(&self, s: &dyn ElementState) -> Vec<SectionState> {
        if self.active(s) { self.inner.sections(s) } else { Vec::new() }
    }
}
