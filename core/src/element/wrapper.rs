//! Elements that wrap another element and change part of its behaviour (a driven element,
//! a joint regularization). [`ElementWrapper`] forwards every method of the [`Element`]
//! contract to the wrapped element unless the wrapper overrides it, so a wrapper states
//! only what it changes and cannot silently drop the rest: a regularized driven joint that
//! lost its events and hints (MBDyn's tests/joints/total/totalhint ran 0.79 m off) was
//! exactly such a missing forward.
//!
//! A method added to [`Element`] must be added here too, with its forward in the trait
//! and in the blanket `impl Element`; otherwise wrappers fall back to its default.

use super::contract::{Element, ElementState, Events, JacobianSink, Label, NonSmooth, Outputs, ResidualSink, ScalarNodeId};
use super::HintValue;
use super::UnknownKind;

/// An element built around another one. Each method forwards to [`ElementWrapper::inner`]
/// by default; `hinted` has no default because a hinted element must be wrapped again
/// (forwarding would return the bare inner element, without the wrapper).
pub trait ElementWrapper: Send + Sync {
    /// The wrapped element.
    fn inner(&self) -> &dyn Element;
    /// As [`Element::hinted`]: the wrapper around the hinted inner element, or `None`.
    fn hinted(&self, hint: &HintValue) -> Option<Box<dyn Element>>;

    fn label(&self) -> Label {
        self.inner().label()
    }
    fn type_name(&self) -> &'static str {
        self.inner().type_name()
    }
    fn nodes(&self) -> Vec<Label> {
        self.inner().nodes()
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        self.inner().scalar_nodes()
    }
    fn multipliers(&self) -> Vec<String> {
        self.inner().multipliers()
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        self.inner().unknown_kind(k)
    }
    fn momentum_unknowns(&self) -> std::ops::Range<usize> {
        self.inner().momentum_unknowns()
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        self.inner().initial_unknowns()
    }
    fn reads_state(&self) -> bool {
        self.inner().reads_state()
    }
    fn assembly_form(&self) -> Option<&dyn Element> {
        self.inner().assembly_form()
    }
    fn events(&self) -> Option<&dyn Events> {
        self.inner().events()
    }
    fn non_smoothness(&self) -> Option<&dyn NonSmooth> {
        self.inner().non_smoothness()
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        self.inner().outputs()
    }
    fn constraint_rows_read_multipliers(&self) -> bool {
        self.inner().constraint_rows_read_multipliers()
    }
    fn failure(&self, s: &dyn ElementState) -> Option<String> {
        self.inner().failure(s)
    }
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink) {
        self.inner().residual(s, out)
    }
    fn jacobian(&self, s: &dyn ElementState, out: &mut dyn JacobianSink) {
        self.inner().jacobian(s, out)
    }
}

impl<W: ElementWrapper> Element for W {
    fn label(&self) -> Label {
        ElementWrapper::label(self)
    }
    fn type_name(&self) -> &'static str {
        ElementWrapper::type_name(self)
    }
    fn nodes(&self) -> Vec<Label> {
        ElementWrapper::nodes(self)
    }
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        ElementWrapper::scalar_nodes(self)
    }
    fn multipliers(&self) -> Vec<String> {
        ElementWrapper::multipliers(self)
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        ElementWrapper::unknown_kind(self, k)
    }
    fn momentum_unknowns(&self) -> std::ops::Range<usize> {
        ElementWrapper::momentum_unknowns(self)
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        ElementWrapper::initial_unknowns(self)
    }
    fn reads_state(&self) -> bool {
        ElementWrapper::reads_state(self)
    }
    fn assembly_form(&self) -> Option<&dyn Element> {
        ElementWrapper::assembly_form(self)
    }
    fn events(&self) -> Option<&dyn Events> {
        ElementWrapper::events(self)
    }
    fn non_smoothness(&self) -> Option<&dyn NonSmooth> {
        ElementWrapper::non_smoothness(self)
    }
    fn outputs(&self) -> Option<&dyn Outputs> {
        ElementWrapper::outputs(self)
    }
    fn hinted(&self, hint: &HintValue) -> Option<Box<dyn Element>> {
        ElementWrapper::hinted(self, hint)
    }
    fn constraint_rows_read_multipliers(&self) -> bool {
        ElementWrapper::constraint_rows_read_multipliers(self)
    }
    fn failure(&self, s: &dyn ElementState) -> Option<String> {
        ElementWrapper::failure(self, s)
    }
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink) {
        ElementWrapper::residual(self, s, out)
    }
    fn jacobian(&self, s: &dyn ElementState, out: &mut dyn JacobianSink) {
        ElementWrapper::jacobian(self, s, out)
    }
}
