//! MBDyn's Tikhonov joint regularization (jointreg.cc, `TikhonovRegularization`; input
//! manual, "Elements", §Joint regularization: `joint regularization: LABEL, tikhonov,
//! C;`): each holonomic constraint equation `Φ_k = 0` of the joint becomes
//! `Φ_k − C_k λ_k = 0` (MBDyn adds `C λ/dCoef` to its constraint rows, which it divides by
//! dCoef), so the joint's multiplier is `λ = Φ/C` and its reaction `−Φ_/qᵀ Φ/C` is a
//! penalty spring of stiffness `1/C` along each constrained direction: the joint no
//! longer holds exactly, it yields by `C λ` under its load. The multiplier stays an
//! algebraic unknown, so a linearization sees the joint as that spring (its Jacobian
//! gains `−C` on the multiplier's diagonal).
//!
//! romdyn's constraint rows and reactions are the transposes of each other (`Φ` and
//! `Φ_/qᵀ λ`, as MBDyn's with its opposite sign), so the same `C` gives MBDyn's spring.

use super::contract::{Col, Element, ElementState, JacobianSink, Label, Latched, PrivateDatum, ResidualSink, Row, SectionState};

pub struct Tikhonov {
    pub inner: Box<dyn Element>,
    /// `C_k` of each of the joint's equations [m/N or rad/(N m)].
    pub c: Vec<f64>,
}

impl Tikhonov {
    /// Whether equation `k` is one the regularization relaxes (the holonomic ones).
    fn relaxed(&self, k: usize) -> bool {
        !(self.inner.is_velocity_constraint(k) || self.inner.is_coordinate(k) || self.inner.is_state(k))
    }
}

impl Element for Tikhonov {
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
    fn is_state(&self, k: usize) -> bool {
        self.inner.is_state(k)
    }
    fn reads_state(&self) -> bool {
        self.inner.reads_state()
    }
    fn constraint_rows_read_multipliers(&self) -> bool {
        true
    }
    fn non_smooth(&self, s: &dyn ElementState) -> Option<String> {
        self.inner.non_smooth(s)
    }
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink) {
        self.inner.residual(s, out);
        for (k, c) in self.c.iter().enumerate() {
            if self.relaxed(k) {
                out.add(Row::Constraint(k), -c * s.multiplier(k));
            }
        }
    }
    fn jacobian(&self, s: &dyn ElementState, out: &mut dyn JacobianSink) {
        self.inner.jacobian(s, out);
        for (k, c) in self.c.iter().enumerate() {
            if self.relaxed(k) {
                // The assembler scales a holonomic row by `1/c` in the form of eq. 30.
                out.add(Row::Constraint(k), Col::Multiplier(k), -c * s.constraint_row_scale());
            }
        }
    }
    fn private_data(&self, name: &str) -> Option<PrivateDatum> {
        self.inner.private_data(name)
    }
    fn sections(&self, s: &dyn ElementState) -> Vec<SectionState> {
        self.inner.sections(s)
    }
    // A regularized driven element keeps its events and hints (MBDyn's
    // tests/joints/total/totalhint: without these the hint never applied and the joint,
    // switched on with its written null drive, pulled the node to the origin).
    fn has_events(&self) -> bool {
        self.inner.has_events()
    }
    fn latch(&self, now: &dyn ElementState, before: &dyn ElementState) -> Option<Latched> {
        self.inner.latch(now, before)
    }
    fn hinted(&self, hint: &super::HintValue) -> Option<Box<dyn Element>> {
        self.inner.hinted(hint).map(|inner| Box::new(Tikhonov { inner, c: self.c.clone() }) as Box<dyn Element>)
    }
    fn assembly_form(&self) -> Option<&dyn Element> {
        self.inner.assembly_form()
    }
    fn reaction_dependence(&self, s: &dyn ElementState) -> Option<String> {
        self.inner.reaction_dependence(s)
    }
    fn failure(&self, s: &dyn ElementState) -> Option<String> {
        self.inner.failure(s)
    }
}
