//! `total equation` and `total internal reaction` joints (joint.cc, `TOTALEQUATION`,
//! `TOTALINTERNALREACTION`; totalequation.cc) and the `joint regularization` card
//! (jointreg.cc, `ReadJointRegularization`), read here and joined with what they refer to
//! once the elements block is read ([`Pending`]).
//!
//! - `joint: L, total equation, NODE_1, …, NODE_2, …, position constraint, …, orientation
//!   constraint, …;` reads as a `total joint` (the same sides and constraints).
//! - `joint: L, total internal reaction, NODE_1, [position, O] [, position orientation, R]
//!   [, rotation orientation, R], NODE_2, …, [position constraint, S, S, S,] [orientation
//!   constraint, S, S, S,] total equation, EQ;` with statuses `inactive`, `active` or 0/1:
//!   where the multipliers of the total equation EQ (defined above, as MBDyn requires) act.
//! - `joint regularization: L, {tikhonov | dynamic | jacobian} [, {list, C_1, …, C_n | C}];`
//!   on the joint L defined above (C defaults to 1e-6 for every equation, as MBDyn's).

use super::context::Compliance;
use std::collections::HashMap;

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Sources, Span};
use super::context::{ElementContext, Parsed};
use crate::mbdyn::syntax::references::{Frame, OtherSide};
use crate::element::{DrivenJoint, Element, Tikhonov, TotalEquation, TotalReaction};
use crate::kinematics::Mat3;
use crate::model::Label;
use crate::element::UnknownKind;
use crate::mbdyn::syntax::references;

/// The `total equation` / `total internal reaction` card of a `joint` statement, or `None`
/// for another joint type (read by `joints::joint`).
pub fn parts(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Option<Parsed>, MbdynError> {
    let span = c.here();
    match c.accept_any(&["total equation", "total internal reaction"]) {
        None => Ok(None),
        Some("total equation") => {
            let j = super::total_joint::total(false, label, c, ctx, span)?;
            if j.velocity_locked.contains(&true) || j.angular_velocity_locked.contains(&true) {
                return Err(c.error_at(span, "total equation: 'velocity' and 'angular velocity' constraints are not supported by romdyn (MBDyn 1.7.3 runs them) (position and rotation constraints are)"));
            }
            Ok(Some(Parsed::TotalEquation(j)))
        }
        Some(_) => reaction(label, c, ctx).map(Some),
    }
}

fn statuses(c: &mut Cursor, kind: &str) -> Result<[bool; 3], MbdynError> {
    let mut out = [false; 3];
    if !c.accept(kind) {
        return Ok(out);
    }
    for v in &mut out {
        *v = match c.accept_any(&["inactive", "active"]) {
            Some(w) => w == "active",
            None => c.real(&format!("{kind} status (active, inactive, or 0/1)"))? != 0.0,
        };
    }
    Ok(out)
}

fn reaction(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    let node = ctx.node(c, "node 1")?;
    let first = super::total_joint::total_side(c, &ctx.on(node), Some(node))?;
    let node_b = ctx.node(c, "node 2")?;
    let other = OtherSide { frame: Frame::of_node(node), offset: first.offset, orientation: first.position };
    let second = super::total_joint::total_side(c, &references::Context { other: Some(other), ..ctx.on(node_b) }, Some(node_b))?;
    let position_active = statuses(c, "position constraint")?;
    let rotation_active = statuses(c, "orientation constraint")?;
    let span = c.here();
    if !c.accept("total equation") {
        return Err(c.error(format!("total internal reaction {label}: expected 'total equation, LABEL' (the total equation whose multipliers it applies), found {}", c.found())));
    }
    let equation = c.label("total equation label")?;
    let reaction = TotalReaction {
        label,
        a_position: first.anchor(&first.position),
        a_rotation: first.anchor(&first.rotation),
        b: second.anchor(&Mat3::identity()),
        position_active,
        rotation_active,
    };
    Ok(Parsed::TotalReaction { reaction, equation, span })
}

/// `joint regularization: LABEL, TYPE [, …]` after its label.
pub fn regularization(joint: Label, c: &mut Cursor) -> Result<Parsed, MbdynError> {
    let span = c.here();
    match c.keyword("joint regularization type", &["tikhonov", "dynamic", "jacobian"])? {
        "tikhonov" => {}
        kind => {
            return Err(c.error_at(span, format!("joint regularization '{kind}' is not supported by romdyn (MBDyn 1.7.3 runs it) (it changes MBDyn's Newton matrix, or lags the multiplier a step: jointreg.cc); 'tikhonov' is")));
        }
    }
    let c_span = c.here();
    let compliance = if c.accept("list") {
        // The number of values is the joint's: read them all, checked against it later.
        let mut v = Vec::new();
        while c.next_is_number() {
            v.push(c.real("compliance")?);
        }
        Compliance::List(v)
    } else if c.next_is_number() {
        Compliance::All(c.real("compliance")?)
    } else {
        Compliance::All(1e-6)
    };
    Ok(Parsed::Regularization { joint, c: compliance, span: c_span })
}

/// Total equations waiting for their reactions, and regularizations waiting for the end of
/// the elements block.
#[derive(Default)]
pub struct Pending {
    equations: Vec<(DrivenJoint, Vec<TotalReaction>, Span, usize)>,
    regularizations: Vec<(Label, Compliance, Span)>,
}

impl Pending {
    pub fn equation(&mut self, j: DrivenJoint, span: Span, seq: usize) {
        self.equations.push((j, Vec::new(), span, seq));
    }

    /// A reaction of the total equation `equation`, defined above.
    pub fn reaction(&mut self, src: &Sources, reaction: TotalReaction, equation: Label, span: Span) -> Result<(), MbdynError> {
        let Some((j, reactions, ..)) = self.equations.iter_mut().find(|(j, ..)| j.label() == equation) else {
            return Err(src.error(span, format!("total internal reaction {}: total equation {equation} is not defined above (MBDyn reads it first)", reaction.label)));
        };
        let n = j.multipliers().len();
        if reaction.count() != n {
            return Err(src.error(span, format!("total internal reaction {}: {} active components, but total equation {equation} has {n} equations (each reaction component applies one of them)", reaction.label, reaction.count())));
        }
        reactions.push(reaction);
        Ok(())
    }

    pub fn regularization(&mut self, joint: Label, c: Compliance, span: Span) {
        self.regularizations.push((joint, c, span));
    }

    /// The joined elements added to `built` (label space "joint"), then the regularizations
    /// applied to the joints they name.
    pub fn finish(self, src: &Sources, built: &mut Vec<(&'static str, Span, usize, Box<dyn Element>)>) -> Result<(), MbdynError> {
        for (j, reactions, span, seq) in self.equations {
            if reactions.is_empty() {
                return Err(src.error(span, format!("total equation {}: no total internal reaction applies its multipliers (its equations would have no unknowns to solve for)", j.label())));
            }
            built.push(("joint", span, seq, Box::new(TotalEquation::new(j, reactions))));
        }
        let mut index: HashMap<Label, usize> = HashMap::new();
        for (i, (space, .., e)) in built.iter().enumerate() {
            if *space == "joint" {
                index.insert(e.label(), i);
            }
        }
        for (label, compliance, span) in self.regularizations {
            let Some(&i) = index.get(&label) else {
                return Err(src.error(span, format!("joint regularization {label}: there is no joint {label} above")));
            };
            let (space, at, seq, inner) = built.swap_remove(i);
            let n = inner.multipliers().len();
            if n == 0 {
                return Err(src.error(span, format!("joint regularization {label}: {} {label} has no equations to regularize", inner.type_name())));
            }
            if let Some(k) = (0..n).find(|&k| inner.unknown_kind(k) != UnknownKind::Multiplier) {
                return Err(src.error(span, format!("joint regularization {label}: equation {} of {} {label} is not a holonomic constraint; romdyn regularizes holonomic constraints only", k + 1, inner.type_name())));
            }
            let c = match compliance {
                Compliance::All(x) => vec![x; n],
                Compliance::List(v) if v.len() == n => v,
                Compliance::List(v) => {
                    return Err(src.error(span, format!("joint regularization {label}: 'list' gives {} values, {} {label} has {n} equations", v.len(), inner.type_name())));
                }
            };
            built.push((space, at, seq, Box::new(Tikhonov { inner, c })));
            let last = built.len() - 1;
            built.swap(i, last);
        }
        Ok(())
    }
}
