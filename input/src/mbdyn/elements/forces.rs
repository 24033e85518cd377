//! Forces and couples between two nodes (input manual, §Structural internal force,
//! §Structural internal couple; strforce.cc, `ReadStructuralForce`; force.cc, `ReadForce`):
//! `{absolute | follower} internal` forces and couples, the `total internal` force, and the
//! `absolute [internal] displacement` forces.
//! `total` (one node) is refused as MBDyn 1.7.3 refuses it (force.cc builds only the
//! internal one).

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use crate::mbdyn::drives::callers::{drive, template_vec3};
use super::context::ElementContext;
use crate::mbdyn::syntax::references::{Context, Frame, OtherSide};
use crate::element::{Element, Force, ForceFrame, InternalCouple, InternalForce, TotalInternalForce, VectorDrive};
use crate::kinematics::{Mat3, Vec3};
use crate::model::Label;

/// `{absolute | follower} internal, NODE_1, [position, ARM_1,] NODE_2, [position, ARM_2,]
/// VALUE`: VALUE in the global frame (absolute) or node 1's (follower); ARM_2 may refer to
/// node 1's point (`reference, other node`). A force without `position` is MBDyn's older
/// form `NODE_1, DIR, ARM_1, NODE_2, ARM_2, DRIVE` (unit direction).
pub fn internal(couple: bool, frame: ForceFrame, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let what = if couple { "couple" } else { "force" };
    let n1 = ctx.node(c, &format!("node 1 of the {what}"))?;
    let on1 = ctx.on(n1);
    let direction = |c: &mut Cursor| match frame {
        ForceFrame::Absolute => on1.vector_in(c, &format!("{what} value"), Frame::global()),
        ForceFrame::Follower => on1.relative_vector(c, &format!("{what} value")),
    };
    let mut arms = [Vec3::zeros(); 2];
    let mut legacy = None;
    if c.accept("position") {
        arms[0] = on1.relative_position(c, "arm of node 1 [m]")?;
    } else if !couple {
        let span = c.here();
        let dir = direction(c)?.try_normalize(0.0).ok_or_else(|| c.error_at(span, "the force direction is null"))?;
        arms[0] = on1.relative_position(c, "arm of node 1 [m]")?;
        legacy = Some(dir);
    }
    let n2 = ctx.node(c, &format!("node 2 of the {what}"))?;
    let on2 = Context { other: Some(OtherSide { frame: Frame::of_node(n1), offset: arms[0], orientation: Mat3::identity() }), ..ctx.on(n2) };
    if c.accept("position") || legacy.is_some() {
        arms[1] = on2.relative_position(c, "arm of node 2 [m]")?;
    }
    let value = match legacy {
        Some(dir) => VectorDrive(vec![(dir, drive(c, ctx.drives, ctx.seq)?)]),
        None => VectorDrive(template_vec3(c, ctx.drives, ctx.seq, &Mat3::identity(), &direction)?),
    };
    if frame == ForceFrame::Follower {
        c.accept("output relative");
    }
    let nodes = [n1.label, n2.label];
    Ok(if couple { Box::new(InternalCouple { label, nodes, frame, value }) } else { Box::new(InternalForce { label, nodes, frame, arms, value }) })
}

/// `total internal, NODE_1, [position, A_1,] [force orientation, R,] [moment orientation,
/// R,] NODE_2, [position, A_2,] [force orientation, R,] [moment orientation, R,] [force,
/// VALUE,] [moment, VALUE]` (force.cc); VALUEs are template drives in node 1's force and
/// moment orientations.
pub fn total_internal(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let side = |c: &mut Cursor, which: &str| -> Result<(Label, Vec3, Mat3, Mat3), MbdynError> {
        let n = ctx.node(c, &format!("node {which} of the total force"))?;
        let on = ctx.on(n);
        let arm = if c.accept("position") { on.relative_position(c, &format!("arm of node {which} [m]"))? } else { Vec3::zeros() };
        let rf = if c.accept("force orientation") { on.relative_orientation(c, "force orientation")? } else { Mat3::identity() };
        let rm = if c.accept("moment orientation") { on.relative_orientation(c, "moment orientation")? } else { Mat3::identity() };
        Ok((n.label, arm, rf, rm))
    };
    let (l1, _, force_orientation, moment_orientation) = side(c, "1")?;
    let (l2, arm, _, _) = side(c, "2")?;
    let value = |c: &mut Cursor, kw: &str| -> Result<VectorDrive, MbdynError> {
        if !c.accept(kw) || c.accept("null") {
            return Ok(VectorDrive(Vec::new()));
        }
        Ok(VectorDrive(template_vec3(c, ctx.drives, ctx.seq, &Mat3::identity(), &|c: &mut Cursor| c.vec3_values(&format!("{kw} value")))?))
    };
    let force = value(c, "force")?;
    let moment = value(c, "moment")?;
    Ok(Box::new(TotalInternalForce { label, nodes: [l1, l2], force_orientation, moment_orientation, arm, force, moment }))
}

/// `absolute displacement, NODE, VALUE` and `absolute internal displacement, NODE_1, NODE_2,
/// VALUE` (strforce.cc, `AbsoluteDispForce`, `AbsoluteInternalDispForce`): VALUE in the
/// global frame on the node's position equations (on node 1, and its opposite on node 2),
/// no arm and no moment: romdyn's absolute force and absolute internal force with null arms.
pub fn displacement(internal: bool, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let n1 = ctx.point_node(c, "node 1 of the force")?.0;
    let n2 = if internal { Some(ctx.point_node(c, "node 2 of the force")?.0) } else { None };
    let on1 = ctx.on(n1);
    let value = VectorDrive(template_vec3(c, ctx.drives, ctx.seq, &Mat3::identity(), &|c: &mut Cursor| on1.vector_in(c, "force value", Frame::global()))?);
    Ok(match n2 {
        Some(n2) => Box::new(InternalForce { label, nodes: [n1.label, n2.label], frame: ForceFrame::Absolute, arms: [Vec3::zeros(); 2], value }),
        None => Box::new(Force { label, node: n1.label, frame: ForceFrame::Absolute, value, offset: Vec3::zeros() }),
    })
}
