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
//!
//! Hints (input manual, §Driven Element, "hint"; driven.cc, `DrivenElem::AfterPredict`):
//! when the element switches on (its drive non-zero at a step, zero at the step before), each
//! hint's drive is built from the model's state and replaces the wrapped element's (MBDyn
//! parses the hint's text then, so its `model::` calls take their values at that instant:
//! the predicted state at the step's time, `model::…_prev` the previous step's). That is an
//! event ([`Element::latch`]): the re-set element is kept in the state, and Newton's
//! Jacobian and a linearization see its drives as functions of time alone. An element
//! switched on at the initial time keeps its own drives, as MBDyn's (its constructor sets
//! the element active without hints).

use std::sync::Arc;

use super::contract::{Col, Element, ElementState, JacobianSink, Latched, PrivateDatum, ResidualSink, Row, SectionState};
use super::wrapper::ElementWrapper;
use super::VectorDrive;
use super::drive::Drive;
use super::UnknownKind;
use crate::element::Events;
use crate::element::NonSmooth;
use crate::element::Outputs;

/// A hint's drive, built when the element switches on.
#[derive(Clone, Debug, PartialEq)]
pub enum HintValue {
    /// `drive{…}`: a scalar drive (a distance joint's distance).
    Drive(Drive),
    /// `drive3{…}`: a 3-vector drive (a drive hinge's rotation).
    Drive3(VectorDrive),
    /// `position-drive3{…}`: a total joint's imposed position.
    PositionDrive3(VectorDrive),
    /// `orientation-drive3{…}`: a total joint's imposed rotation.
    OrientationDrive3(VectorDrive),
}

/// A hint: its drive from the predicted state at the step's time (`now`) and the previous
/// step's (`before`), or why it cannot be built.
pub type Hint = Arc<dyn Fn(&dyn ElementState, &dyn ElementState) -> Result<HintValue, String> + Send + Sync>;

pub struct DrivenElement {
    /// The element's switch: on where `drive(t) ≠ 0`.
    pub drive: Drive,
    pub inner: Box<dyn Element>,
    /// Hints applied, in order, when it switches on.
    pub hints: Vec<Hint>,
}

/// A driven element's data after its last event.
struct Switched {
    active: bool,
    /// The element its hints re-set (`None`: the element as read), or why they failed (its
    /// residual is then NaN, and Newton stops on it).
    element: Result<Option<Arc<dyn Element>>, String>,
}

impl DrivenElement {
    fn active(&self, s: &dyn ElementState) -> bool {
        self.drive.value_in(s) != 0.0
    }

    fn switched<'s>(s: &'s dyn ElementState) -> Option<&'s Switched> {
        s.latched().and_then(|l| l.downcast_ref::<Switched>())
    }

    /// The wrapped element as its last switch-on's hints left it.
    fn element<'s>(&'s self, s: &'s dyn ElementState) -> Result<&'s dyn Element, &'s str> {
        match Self::switched(s).map(|w| &w.element) {
            Some(Ok(Some(e))) => Ok(e.as_ref()),
            Some(Err(m)) => Err(m.as_str()),
            _ => Ok(self.inner.as_ref()),
        }
    }

    /// The element acting now (as its hints left it), `None` while switched off or when its
    /// hints failed.
    fn acting<'s>(&'s self, s: &'s dyn ElementState) -> Option<&'s dyn Element> {
        if self.active(s) {
            self.element(s).ok()
        } else {
            None
        }
    }

    /// The wrapped element re-set by each hint in turn.
    fn apply_hints(&self, now: &dyn ElementState, before: &dyn ElementState) -> Result<Option<Arc<dyn Element>>, String> {
        let mut element: Option<Box<dyn Element>> = None;
        for (k, hint) in self.hints.iter().enumerate() {
            let value = hint(now, before).map_err(|m| format!("{} {}: hint {}: {m}", self.inner.type_name(), self.inner.label(), k + 1))?;
            let base: &dyn Element = element.as_deref().unwrap_or(self.inner.as_ref());
            element = Some(base.hinted(&value).ok_or_else(|| format!("{} {}: hint {} does not apply to it", self.inner.type_name(), self.inner.label(), k + 1))?);
        }
        Ok(element.map(Arc::from))
    }
}

/// A sink that records where entries go, with value zero.
struct Zeros<'a>(&'a mut dyn JacobianSink);

impl JacobianSink for Zeros<'_> {
    fn add(&mut self, row: Row, col: Col, _value: f64) {
        self.0.add(row, col, 0.0);
    }
}

/// The wrapped element's contract ([`ElementWrapper`]) but for what switching changes: the
/// residual, Jacobian and sections (nothing while off), the events (its hints), and what
/// depends on the element acting (non-smoothness, reaction dependence, failures).
impl ElementWrapper for DrivenElement {
    fn inner(&self) -> &dyn Element {
        self.inner.as_ref()
    }
    /// A driven element is not hinted itself (its hints re-set the element it wraps).
    fn hinted(&self, _hint: &HintValue) -> Option<Box<dyn Element>> {
        None
    }
    fn reads_state(&self) -> bool {
        self.drive.reads_state() || self.inner.reads_state()
    }
    /// The initial assembly sees the driven element itself (switched as at the initial time).
    fn assembly_form(&self) -> Option<&dyn Element> {
        None
    }
    fn events(&self) -> Option<&dyn Events> {
        if !self.hints.is_empty() { Some(self) } else { None }
    }
    fn non_smoothness(&self) -> Option<&dyn NonSmooth> {
        Some(self)
    }
    fn failure(&self, s: &dyn ElementState) -> Option<String> {
        match self.element(s) {
            Err(why) if self.active(s) => Some(why.to_string()),
            Ok(e) if self.active(s) => e.failure(s),
            _ => None,
        }
    }
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink) {
        if self.active(s) {
            match self.element(s) {
                Ok(e) => e.residual(s, out),
                Err(_) => out.add(Row::Constraint(0), f64::NAN),
            }
        } else {
            for k in 0..self.inner.multipliers().len() {
                out.add(Row::Constraint(k), -s.multiplier(k));
            }
        }
    }
    fn jacobian(&self, s: &dyn ElementState, out: &mut dyn JacobianSink) {
        let active = self.active(s);
        let inner = self.element(s).unwrap_or(self.inner.as_ref());
        if active {
            inner.jacobian(s, out);
        } else {
            inner.jacobian(s, &mut Zeros(out));
        }
        for k in 0..self.inner.multipliers().len() {
            // ∂(−λ_k)/∂λ_k = −1 on a row the assembler scales as a constraint row (velocity
            // constraints' rows are never scaled).
            let scale = if matches!(self.inner.unknown_kind(k), UnknownKind::VelocityConstraint | UnknownKind::Coordinate) { 1.0 } else { s.constraint_row_scale() };
            out.add(Row::Constraint(k), Col::Multiplier(k), if active { 0.0 } else { -scale });
        }
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        Some(self)
    }
}

impl Outputs for DrivenElement {
    /// MBDyn's `DrivenElem` reads the wrapped element's private data whether on or off.
    fn private_data(&self, name: &str) -> Option<PrivateDatum> {
        self.inner.outputs()?.private_data(name)
    }
    fn sections(&self, s: &dyn ElementState) -> Vec<SectionState> {
        self.acting(s).and_then(|e| e.outputs()).map(|o| o.sections(s)).unwrap_or_default()
    }
}

impl NonSmooth for DrivenElement {
    fn non_smooth(&self, s: &dyn ElementState) -> Option<String> {
        self.acting(s).and_then(|e| e.non_smoothness()?.non_smooth(s))
    }
    fn kink_crossed(&self, from: &dyn ElementState, to: &dyn ElementState) -> Option<String> {
        self.acting(to).and_then(|e| e.non_smoothness()?.kink_crossed(from, to))
    }
    fn reaction_dependence(&self, s: &dyn ElementState) -> Option<String> {
        self.acting(s).and_then(|e| e.non_smoothness()?.reaction_dependence(s))
    }
}

impl Events for DrivenElement {
    fn latch(&self, now: &dyn ElementState, before: &dyn ElementState) -> Option<Latched> {
        let was = Self::switched(now).map_or_else(|| self.active(before), |w| w.active);
        let is = self.active(now);
        if is == was {
            return None;
        }
        let element = if is {
            self.apply_hints(now, before)
        } else {
            Self::switched(now).map_or(Ok(None), |w| w.element.clone())
        };
        Some(Arc::new(Switched { active: is, element }))
    }
}
