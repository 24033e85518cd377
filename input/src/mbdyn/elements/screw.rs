//! `joint: LABEL, screw, NODE_1, [position,] P, [orientation,] R, NODE_2 [, offset, Q],
//! pitch, PITCH` (joint.cc, `SCREWJOINT`; the input manual has no entry): node 1's point
//! `P` and frame `R` (axis 3 the screw axis), node 2's point `Q` (relative to node 2,
//! `reference, other node` meaning node 1's joint frame), the pitch [m per turn]. MBDyn reads
//! `P` and `R` whether or not their keywords are written (MBDYN_X_COMPATIBLE_INPUT).
//! `friction, modlugre, …, screw joint, …` after the pitch: [`ScrewFriction`].

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use super::context::ElementContext;
use crate::mbdyn::syntax::references::{Context, Frame, OtherSide};
use crate::element::{Anchor, Element, Screw, ScrewFriction};
use crate::kinematics::{rotation_vector, Vec3};
use crate::model::Label;

pub fn screw(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let n1 = ctx.node(c, "node 1")?;
    let on1 = ctx.on(n1);
    c.accept("position");
    let p = on1.relative_position(c, "offset of node 1 [m]")?;
    c.accept("orientation");
    let h = on1.relative_orientation(c, "orientation of the screw (axis 3 along it)")?;
    let n2 = ctx.node(c, "node 2")?;
    let q = if c.accept("offset") {
        let other = OtherSide { frame: Frame::of_node(n1), offset: p, orientation: h };
        Context { other: Some(other), ..ctx.on(n2) }.relative_position(c, "offset of node 2 [m]")?
    } else {
        Vec3::zeros()
    };
    c.keyword("'pitch'", &["pitch"])?;
    let pitch = c.real("pitch [m]")?;
    let friction = if super::friction::follows(c) { Some(super::friction::screw_friction(c, ctx)?) } else { None };
    // Initial relative rotation about the axis and displacement along it (screwjoint.cc).
    let (r1, r2) = (n1.orientation, n2.orientation);
    let e = r1 * h * Vec3::z();
    let d0 = e.dot(&(n2.position + r2 * q - n1.position - r1 * p));
    let theta0 = (h * Vec3::z()).dot(&rotation_vector(&(r1.transpose() * r2)));
    let screw = Screw {
        label,
        a: Anchor::Node { label: n1.label, offset: p, orientation: h },
        b: Anchor::Node { label: n2.label, offset: q, orientation: h },
        pitch,
        theta0,
        d0,
    };
    Ok(match friction {
        Some((model, radius, half_thread_angle)) => Box::new(ScrewFriction::new(screw, model, radius, half_thread_angle)),
        None => Box::new(screw),
    })
}
