//! The total joint and total pin joint cards (input manual, "Elements", §Total joint,
//! §Total pin joint): each side's node, offset and position and rotation orientations, and
//! the `position constraint` / `orientation constraint` words with their template drives.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use crate::mbdyn::drives::callers::template_vec3;
use super::context::ElementContext;
use crate::mbdyn::syntax::references::{Context, Frame, OtherSide};
use crate::element::{Anchor, DrivenJoint, Joint, VectorDrive};
use crate::kinematics::{Mat3, Vec3};
use crate::model::{Label, StructuralNode};
use crate::mbdyn::syntax::diagnostic;

/// One side of a total joint: a node (or the ground, `node: None`, with an absolute
/// position), the offset and the position and rotation orientations.
pub(in crate::mbdyn) struct TotalSide<'a> {
    pub(in crate::mbdyn) node: Option<&'a StructuralNode>,
    pub(in crate::mbdyn) offset: Vec3,
    pub(in crate::mbdyn) position: Mat3,
    pub(in crate::mbdyn) rotation: Mat3,
}

impl TotalSide<'_> {
    /// The anchor with frame `q`.
    pub(in crate::mbdyn) fn anchor(&self, q: &Mat3) -> Anchor {
        match self.node {
            Some(n) => Anchor::Node { label: n.label, offset: self.offset, orientation: *q },
            None => Anchor::Ground { position: self.offset, orientation: *q },
        }
    }
}

/// `[position, OFFSET] [, position orientation, R] [, rotation orientation, R]`.
pub(in crate::mbdyn) fn total_side<'a>(c: &mut Cursor, on: &Context, node: Option<&'a StructuralNode>) -> Result<TotalSide<'a>, MbdynError> {
    let ground = node.is_none();
    let offset = match (c.accept("position"), ground) {
        (false, _) => Vec3::zeros(),
        (true, false) => on.relative_position(c, "offset [m]")?,
        (true, true) => on.position(c, "absolute position [m]")?,
    };
    let orientation = |c: &mut Cursor, kw: &str| -> Result<Mat3, MbdynError> {
        match (c.accept(kw), ground) {
            (false, _) => Ok(Mat3::identity()),
            (true, false) => on.relative_orientation(c, kw),
            (true, true) => on.orientation(c, kw),
        }
    };
    let position = orientation(c, "position orientation")?;
    let rotation = orientation(c, "rotation orientation")?;
    Ok(TotalSide { node, offset, position, rotation })
}

/// `total joint` / `total pin joint` (input manual, §Total joint, §Total pin joint): the
/// active components of relative position and rotation are locked, or their rates imposed
/// (`velocity`, `angular velocity`), in the frame of node 1 (total joint) or in the absolute
/// frame (total pin joint), each to its component of the imposed-value template drive.
/// romdyn's total joint has one frame per side: where both kinds of constraint are active
/// and side A's position and rotation orientations differ, [`one_constraint_frame`] maps one
/// onto the other when all three of one kind are constrained. Some rotations locked, not all
/// three: MBDyn's rows, with the remnant of the free ones (`DrivenJoint::rotation_remnant`).
pub(in crate::mbdyn) fn total(pin: bool, label: Label, c: &mut Cursor, ctx: &ElementContext, span: diagnostic::Span) -> Result<DrivenJoint, MbdynError> {
    let node = ctx.node(c, if pin { "the node" } else { "node 1" })?;
    let first = total_side(c, &ctx.on(node), Some(node))?;
    let second = if pin {
        // joint.cc reads the ground side with the node as the other side
        // (`GetPosRel(AbsRefFrame, RF, fn)`): `reference, other node` is the node's frame.
        let other = OtherSide { frame: Frame::of_node(node), offset: first.offset, orientation: first.position };
        let ground = Context { node: Some(Frame::of_node(node)), other: Some(other), ..ctx.global() };
        total_side(c, &ground, None)?
    } else {
        let node_b = ctx.node(c, "node 2")?;
        let other = OtherSide { frame: Frame::of_node(node), offset: first.offset, orientation: first.position };
        total_side(c, &Context { other: Some(other), ..ctx.on(node_b) }, Some(node_b))?
    };
    let position = constraint(c, ctx, "position constraint", &["position", "velocity"])?;
    let rotation = constraint(c, ctx, "orientation constraint", &["rotation", "angular velocity"])?;
    let any_pos = position.holonomic.contains(&true) || position.rate.contains(&true);
    let any_rot = rotation.holonomic.contains(&true) || rotation.rate.contains(&true);
    // A: where the constraints are written (the ground of a pin joint, node 1 otherwise).
    let (a, b) = if pin { (second, first) } else { (first, second) };
    let imposed_rotation = rotation.on(&rotation.holonomic);
    // Some rotations locked, not all three: MBDyn's rows with the remnant of the free
    // components (totalj.cc; `DrivenJoint::rotation_remnant`), whatever the imposed value.
    let rotation_remnant = rotation.holonomic.contains(&true) && rotation.holonomic != [true; 3];
    let frames = if any_pos && any_rot { one_constraint_frame(&a, &b, &position, &rotation) } else { None };
    let (qa, qb, position_turn, rotation_turn) = match frames {
        Some(f) => f,
        None if any_pos && any_rot && (a.position - a.rotation).norm() > 1e-12 => {
            return Err(c.error_at(
                span,
                "romdyn's total joint uses one constraint frame: with 'position orientation' and 'rotation orientation' different, either all three position components or all three rotation components must be constrained, all of one kind (held, or their rate imposed)",
            ));
        }
        None => (if any_pos { a.position } else { a.rotation }, if any_rot { b.rotation } else { b.position }, Mat3::identity(), Mat3::identity()),
    };
    let name = if pin { "total pin joint" } else { "total joint" };
    let mut j = DrivenJoint::new(Joint::total(label, a.anchor(&qa), b.anchor(&qb), position.holonomic, rotation.holonomic), name);
    j.position = position.on(&position.holonomic).turned(&position_turn);
    j.rotation = imposed_rotation.turned(&rotation_turn);
    j.velocity_locked = position.rate;
    j.velocity = position.on(&position.rate).turned(&position_turn);
    j.angular_velocity_locked = rotation.rate;
    j.angular_velocity = rotation.on(&rotation.rate).turned(&rotation_turn);
    (j.hint_position_held, j.hint_position_turn, j.hint_rotation_turn) = (position.holonomic, position_turn, rotation_turn);
    j.hint_rotation_held = rotation.holonomic == [true; 3];
    j.rotation_remnant = rotation_remnant;
    Ok(j)
}

/// The one constraint frame of a total joint whose side A has different position and
/// rotation orientations `H_p`, `H_r`, when the constraints allow it exactly: `(Q_a, Q_b,
/// turn of the position values, turn of the rotation values)`, `None` when they do not.
/// - All three rotations held (or all three angular-velocity components imposed): the frame
///   is `H_p` and B's rotation frame becomes `H_b H_rᵀ H_p`, so that `Q_aᵀ Q_b` is unchanged
///   and `exp(Θ)` in `H_r` reads `exp(T Θ)`, `T = H_pᵀ H_r`; imposed angular velocities turn
///   by `T` likewise (the same constraint manifold, the reaction moment in another basis).
/// - Otherwise, all three positions held (or all three velocities imposed): the frame is
///   `H_r`, and the imposed position `D` in `H_p` is `S D` in it, `S = H_rᵀ H_p` (and `V`).
fn one_constraint_frame(a: &TotalSide, b: &TotalSide, position: &Constraint, rotation: &Constraint) -> Option<(Mat3, Mat3, Mat3, Mat3)> {
    let all_of_one_kind = |k: &Constraint| (k.holonomic == [true; 3] && k.rate == [false; 3]) || (k.rate == [true; 3] && k.holonomic == [false; 3]);
    if all_of_one_kind(rotation) {
        let t = a.position.transpose() * a.rotation;
        Some((a.position, b.rotation * t.transpose(), Mat3::identity(), t))
    } else if all_of_one_kind(position) {
        Some((a.rotation, b.rotation, a.rotation.transpose() * a.position, Mat3::identity()))
    } else {
        None
    }
}

/// One `position constraint` or `orientation constraint`: components held (holonomic) or
/// whose rate is imposed, and the imposed value.
struct Constraint {
    holonomic: [bool; 3],
    rate: [bool; 3],
    value: VectorDrive,
}

impl Constraint {
    /// The imposed value on the given components only.
    fn on(&self, components: &[bool; 3]) -> VectorDrive {
        let mask = |v: &Vec3| Vec3::from_fn(|k, _| if components[k] { v[k] } else { 0.0 });
        VectorDrive(self.value.0.iter().map(|(v, d)| (mask(v), d.clone())).filter(|(v, _)| *v != Vec3::zeros()).collect())
    }
}

/// `KIND, STATUS, STATUS, STATUS, VALUE`: each status `inactive`, `active` (or the
/// holonomic word, or 0/1), or the rate word; VALUE a template drive caller.
fn constraint(c: &mut Cursor, ctx: &ElementContext, kind: &str, words: &[&'static str; 2]) -> Result<Constraint, MbdynError> {
    let mut out = Constraint { holonomic: [false; 3], rate: [false; 3], value: VectorDrive::default() };
    if !c.accept(kind) {
        return Ok(out);
    }
    for k in 0..3 {
        match c.accept_any(&["inactive", "active", words[0], words[1]]) {
            Some("inactive") => {}
            Some(w) if w == words[1] => out.rate[k] = true,
            Some(_) => out.holonomic[k] = true,
            None => out.holonomic[k] = c.real(&format!("{kind} status (active, inactive, or 0/1)"))? != 0.0,
        }
    }
    out.value = VectorDrive(template_vec3(c, ctx.drives, ctx.seq, &Mat3::identity(), &|c: &mut Cursor| c.vec3_values("imposed value"))?);
    Ok(out)
}
