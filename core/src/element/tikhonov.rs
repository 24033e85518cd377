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

use super::contract::{Col, Element, ElementState, JacobianSink, ResidualSink, Row};
use super::wrapper::ElementWrapper;
use super::UnknownKind;

pub struct Tikhonov {
    pub inner: Box<dyn Element>,
    /// `C_k` of each of the joint's equations [m/N or rad/(N m)].
    pub c: Vec<f64>,
}

impl Tikhonov {
    /// Whether equation `k` is one the regularization relaxes (the holonomic ones).
    fn relaxed(&self, k: usize) -> bool {
        self.inner.unknown_kind(k) == UnknownKind::Multiplier
    }
}

/// The rest of the contract, events and hints included, is the wrapped element's
/// ([`ElementWrapper`]): a regularized driven element keeps its hints.
impl ElementWrapper for Tikhonov {
    fn inner(&self) -> &dyn Element {
        self.inner.as_ref()
    }
    fn hinted(&self, hint: &super::HintValue) -> Option<Box<dyn Element>> {
        self.inner.hinted(hint).map(|inner| Box::new(Tikhonov { inner, c: self.c.clone() }) as Box<dyn Element>)
    }
    fn constraint_rows_read_multipliers(&self) -> bool {
        true
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
}
