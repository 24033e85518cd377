//! MBDyn's `distance` joint (genj.cc, `DistanceJoint`): two points kept at a distance `L(t)`
//! with the direction between them an unknown of its own.
//!
//! Unknowns: the unit direction `v = v₀ + w` from A's point to B's (`w` the change from the
//! written direction `v₀`, three coordinates, [`UnknownKind::Coordinate`]) and the tension `α`.
//! Equations, none divided by dCoef (MBDyn writes them unscaled):
//!
//! ```text
//! p_a − p_b + L v = 0      (3 rows, the unknowns w)
//! 1 − |v| = 0              (1 row, the unknown α)
//! ```
//!
//! and the reaction `α v` pulls A's point towards B's (and B's towards A's) for `α > 0`.
//! The direction absorbs the rounding of the written positions: with one multiplier and the
//! row `(|p_b − p_a| − L)/dCoef` (romdyn's earlier form), MBDyn's `tests/stiff/Swing4`
//! (dCoef = 2e-13 s in its derivatives phase, where positions are held) read its 1.1e-16 m
//! of rounding as a residual of 5.6e-4, above the tolerance, in every iteration.
//!
//! `α` is an algebraic unknown that is not a holonomic multiplier
//! ([`UnknownKind::VelocityConstraint`]: its equation is never divided by dCoef, and the
//! unknown moves as `y += c δ`, the same Newton iterates as MBDyn's `α += δ` with MBDyn's
//! Jacobian entries divided by c). The coordinates `w` move with the configuration (set by
//! the initial assembly, with their rates `ẇ` on its velocity rows, as MBDyn's
//! `InitialAssRes` carries `v̇`).

use super::anchor::{node_labels, Anchor, Pair};
use super::contract::{Col, Element, ElementState, JacobianSink, Label, ResidualSink, Row};
use super::deformable::{add_pair_force, add_pair_force_jacobian};
use crate::kinematics::{Mat3, Vec3};
use super::UnknownKind;

/// Distance `L(t)` between two points, MBDyn's four-unknown form (module documentation).
#[derive(Clone, Debug)]
pub struct Distance {
    pub label: Label,
    pub a: Anchor,
    pub b: Anchor,
    /// Imposed distance L(t) [m].
    pub length: super::drive::Drive,
    /// The unit direction from A's point to B's as written, `v₀` (MBDyn's `SetInitialValue`).
    pub direction: Vec3,
}

impl Distance {
    /// The joint with a hint's `drive{…}` as its distance (MBDyn's `DistanceJoint::SetValue`).
    pub fn with_hint(&self, hint: &super::HintValue) -> Option<Self> {
        match hint {
            super::HintValue::Drive(d) => Some(Distance { length: d.clone(), ..self.clone() }),
            _ => None,
        }
    }

    /// The direction unknown `v = v₀ + w`.
    fn direction_at(&self, st: &dyn ElementState) -> Vec3 {
        self.direction + Vec3::new(st.multiplier(0), st.multiplier(1), st.multiplier(2))
    }
}

impl Element for Distance {
    fn reads_state(&self) -> bool {
        self.length.reads_state()
    }
    fn label(&self) -> Label {
        self.label
    }
    fn hinted(&self, hint: &super::HintValue) -> Option<Box<dyn Element>> {
        self.with_hint(hint).map(|j| Box::new(j) as Box<dyn Element>)
    }
    fn type_name(&self) -> &'static str {
        "distance"
    }
    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.a, &self.b)
    }
    fn multipliers(&self) -> Vec<String> {
        vec!["direction x".into(), "direction y".into(), "direction z".into(), "f".into()]
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        match k {
            0..3 => UnknownKind::Coordinate,
            3 => UnknownKind::VelocityConstraint,
            _ => UnknownKind::Multiplier,
        }
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let v = self.direction_at(st);
        let gap = self.length.value_in(st) * v - p.d;
        for k in 0..3 {
            out.add(Row::Constraint(k), gap[k]);
        }
        out.add(Row::Constraint(3), 1.0 - v.norm());
        add_pair_force(out, &p, &(st.multiplier(3) * v));
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let p = Pair::new(&self.a, &self.b, st);
        let (v, alpha, l) = (self.direction_at(st), st.multiplier(3), self.length.value_in(st));
        // Geometric terms of the reaction at fixed (v, α); the gap rows are −δd.
        for (cols, m) in add_pair_force_jacobian(out, &p, &(alpha * v), &Mat3::zeros()) {
            for (j, col) in cols.iter().enumerate() {
                for k in 0..3 {
                    out.add(Row::Constraint(k), *col, -m[(k, j)]);
                }
            }
        }
        let norm = v.norm();
        for j in 0..3 {
            out.add(Row::Constraint(j), Col::Multiplier(j), l);
            if norm > 0.0 {
                out.add(Row::Constraint(3), Col::Multiplier(j), -v[j] / norm);
            }
        }
        // The reaction's unknowns: ∂(α v)/∂w_j = α e_j, ∂(α v)/∂α = v.
        let column = |out: &mut dyn JacobianSink, col: Col, df: &Vec3| {
            let (mb, ma) = (p.f_b.cross(df), p.f_a.cross(df));
            for i in 0..3 {
                out.add(Row::Equilibrium { slot: p.slot_b, comp: i }, col, df[i]);
                out.add(Row::Equilibrium { slot: p.slot_b, comp: 3 + i }, col, mb[i]);
                if let Some(a) = p.slot_a {
                    out.add(Row::Equilibrium { slot: a, comp: i }, col, -df[i]);
                    out.add(Row::Equilibrium { slot: a, comp: 3 + i }, col, -ma[i]);
                }
            }
        };
        for j in 0..3 {
            let mut df = Vec3::zeros();
            df[j] = alpha;
            column(out, Col::Multiplier(j), &df);
        }
        column(out, Col::Multiplier(3), &v);
    }
}
