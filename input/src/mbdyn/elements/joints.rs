//! `joint` statements (input manual, "Elements", §Joint): clamp, revolute hinge and pin,
//! spherical hinge and pin, total joint, total pin joint, deformable displacement joint,
//! deformable hinge, rod and rod with offset, mapped onto romdyn's [`Joint`],
//! [`DeformableDisplacement`], [`DeformableHinge`] and [`Rod`].
//!
//! Offsets and orientations are relative to their node (`reference, node` by default);
//! the second node may refer to the first with `reference, other node` (or `other
//! position`, `other orientation`). A constraint need not hold as written: MBDyn's initial
//! assembly (`solve::initial_assembly`) makes it hold before the run.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use crate::mbdyn::drives::callers::template_vec3;
use super::context::ElementContext;
use super::total_joint::total;
use super::laws::{linear_law, nonlinear_law, rest_strain, three, LinearLaw};
use crate::mbdyn::syntax::references::{Context, Frame, OtherSide};
use crate::element::drive::Drive;
use crate::element::{Anchor, AngularAcceleration, ViscousBody, RevoluteHingeFriction, AxialRotation, GimbalRotation, ImposedVelocity, VelocityKind, CardanoHinge, DeformableJoint, DrivenJoint, InvariantDeformableHinge, VectorDrive, DeformableDisplacement, DeformableHinge, Distance, Element, InLineFriction, Joint, Rod, RodViscosity};
use crate::kinematics::{Mat3, Vec3};
use crate::model::{Label, StructuralNode};
use crate::mbdyn::drives::callers;
use crate::mbdyn::drives::scalar_functions;
use crate::mbdyn::syntax::keywords::{mbdyn_only, read, Keyword, KeywordTable, Support};

/// Every joint type of MBDyn 1.7.3 (joint.cc, `ReadJoint`), with whether romdyn reads it.
pub(in crate::mbdyn) const JOINT_TYPES: KeywordTable = KeywordTable {
    what: "joint type",
    keywords: &[
        read("modal"), read("brake"), read("viscous body"), read("angular acceleration"), read("gimbal rotation"), read("pin"),
        read("beam slider"), read("screw"), read("linear velocity"), read("angular velocity"), read("revolute rotation"),
        read("cardano hinge"), read("universal hinge"), read("cardano pin"), read("universal pin"), read("cardano rotation"),
        read("universal rotation"), read("axial rotation"), read("drive displacement"), read("drive displacement pin"),
        read("imposed displacement"), read("imposed displacement pin"), read("drive hinge"), read("deformable joint"),
        read("deformable axial joint"), read("invariant deformable hinge"), read("clamp"), read("revolute hinge"), read("plane hinge"),
        read("revolute pin"), read("plane pin"), read("spherical hinge"), read("spherical pin"), read("total joint"),
        read("total pin joint"), read("deformable displacement joint"), read("deformable displacement hinge"), read("deformable hinge"),
        read("rod"), read("rod with offset"), read("in line"), read("in plane"), read("prismatic"), read("distance"),
        read("distance with offset"),
        mbdyn_only("coincidence"), mbdyn_only("imposed orientation"), mbdyn_only("invariant deformable displacement joint"),
        mbdyn_only("invariant deformable joint"), mbdyn_only("linear acceleration"), mbdyn_only("plane displacement pin"),
        mbdyn_only("point contact"), mbdyn_only("rod bezier"),
        // joint.cc: "PlaneDispJoint: unsupported; use an InPlane and a RevoluteRotation".
        Keyword { name: "plane displacement", support: Support::Refused("joint type 'plane displacement' is not supported by romdyn, nor by MBDyn 1.7.3 (its reader stops: \"unsupported; use an InPlane and a RevoluteRotation\"): write an 'in plane' and a 'revolute rotation'") },
    ],
};

/// One side of a two-node joint: node, offset and orientation in the node frame.
struct Side<'a> {
    node: &'a StructuralNode,
    offset: Vec3,
    orientation: Mat3,
}

impl Side<'_> {
    fn anchor(&self) -> Anchor {
        Anchor::Node { label: self.node.label, offset: self.offset, orientation: self.orientation }
    }
    fn other(&self) -> OtherSide {
        OtherSide { frame: Frame::of_node(self.node), offset: self.offset, orientation: self.orientation }
    }
    /// Global point and frame in the initial configuration.
    fn global(&self) -> (Vec3, Mat3) {
        (self.node.position + self.node.orientation * self.offset, self.node.orientation * self.orientation)
    }
}

/// Whether an offset needs its `position` keyword to be read.
#[derive(Clone, Copy, PartialEq)]
enum Position {
    /// `position` written or not, the offset is read (MBDyn: "position, OFFSET").
    Always,
    /// Read only after `position` (or when it is `null`).
    IfKeyword,
}

fn side<'a>(c: &mut Cursor, ctx: &ElementContext<'a>, what: &str, position: Position, other: Option<&Side>) -> Result<Side<'a>, MbdynError> {
    let node = ctx.node(c, what)?;
    side_of(c, ctx, node, what, position, other)
}

/// [`side`] of a rod or distance joint, whose nodes may be displacement nodes when they
/// take no offset (joint.cc, cases DISTANCE and ROD: "invalid StructNode … for node #1").
/// A displacement node on either side makes both offsets refused (MBDyn 1.7.3 requires
/// both nodes with rotations as soon as one offset is written; a rod with an offset on its
/// 6-DoF node and a displacement node at the other end stops it with a segmentation fault).
fn point_side<'a>(c: &mut Cursor, ctx: &ElementContext<'a>, what: &str, position: Position, other: Option<(&Side, bool)>) -> Result<(Side<'a>, bool), MbdynError> {
    let span = c.here();
    let (node, displacement) = ctx.point_node(c, what)?;
    let side = side_of(c, ctx, node, what, position, other.map(|o| o.0))?;
    let offset = |s: &Side| s.offset != Vec3::zeros() || s.orientation != Mat3::identity() || position == Position::Always;
    let (other_displacement, other_offset) = other.map_or((false, false), |(o, d)| (d, offset(o)));
    if (displacement || other_displacement) && (offset(&side) || other_offset) {
        return Err(c.error_at(span, "a rod or distance joint with an offset needs two nodes with rotations, and one of its nodes is a displacement node (MBDyn 1.7.3: \"invalid StructNode\"; for a rod it stops with a segmentation fault)"));
    }
    Ok((side, displacement))
}

fn side_of<'a>(c: &mut Cursor, ctx: &ElementContext<'a>, node: &'a StructuralNode, what: &str, position: Position, other: Option<&Side>) -> Result<Side<'a>, MbdynError> {
    let on = Context { other: other.map(Side::other), ..ctx.on(node) };
    let written = c.accept("position") || c.peek_keyword().is_some_and(|w| w == "null");
    let offset = if written || position == Position::Always { on.relative_position(c, &format!("offset of {what} [m]"))? } else { Vec3::zeros() };
    let orientation = if c.accept("orientation") || c.accept("hinge") { on.relative_orientation(c, &format!("orientation of {what}"))? } else { Mat3::identity() };
    Ok(Side { node, offset, orientation })
}

/// `joint: LABEL, TYPE, …`.
pub fn joint(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let span = c.here();
    let Some(kind) = c.accept_any(&JOINT_TYPES.read()) else {
        return Err(match c.peek_keyword() {
            Some(w) => c.error(JOINT_TYPES.refusal(w)),
            None => c.error(format!("expected a joint type, found {}", c.found())),
        });
    };
    let element: Box<dyn Element> = match kind {
        "clamp" => Box::new(clamp(label, c, ctx)?),
        "modal" => Box::new(super::modal::modal(label, c, ctx)?),
        "beam slider" => Box::new(super::beam_slider::beam_slider(label, c, ctx)?),
        "screw" => super::screw::screw(label, c, ctx)?,
        "revolute hinge" | "plane hinge" | "spherical hinge" => {
            let revolute = kind != "spherical hinge";
            // MBDyn reads both offsets whether or not `position` is written (joint.cc,
            // MBDYN_X_COMPATIBLE_INPUT, which joint.cc defines).
            let a = side(c, ctx, "node 1", Position::Always, None)?;
            let b = side(c, ctx, "node 2", Position::Always, Some(&a))?;
            if revolute && c.accept("initial theta") {
                c.real("initial theta [rad]")?;
            }
            let friction = match (super::friction::follows(c), kind) {
                (false, _) => None,
                (true, "revolute hinge" | "plane hinge") => Some(super::friction::revolute_hinge_friction(c, ctx)?),
                (true, _) => return Err(super::friction::refuse(c, kind)),
            };
            let j = if revolute { Joint::revolute_hinge(label, a.anchor(), b.anchor()) } else { Joint::spherical_hinge(label, a.anchor(), b.anchor()) };
            match friction {
                Some((radius, preload, model)) => Box::new(RevoluteHingeFriction::new(j, radius, preload, model)),
                None => Box::new(j),
            }
        }
        "brake" => {
            // Input manual §Brake; joint.cc reads the two sides as a revolute hinge's, then
            // `friction, r, [preload, P,] MODEL, SHAPE` (required) and the normal force.
            let a = side(c, ctx, "node 1", Position::Always, None)?;
            let b = side(c, ctx, "node 2", Position::Always, Some(&a))?;
            if !super::friction::follows(c) {
                return Err(c.error("brake: expected 'friction' (a brake is its friction: 'friction, RADIUS, [preload, P,] modlugre, …, simple, NORMAL_FORCE_DRIVE')"));
            }
            let (radius, preload, model) = super::friction::revolute_hinge_friction(c, ctx)?;
            let normal = callers::drive(c, ctx.drives, ctx.seq)?;
            Box::new(RevoluteHingeFriction::brake(Joint::revolute_hinge(label, a.anchor(), b.anchor()), radius, preload, model, normal))
        }
        "axial rotation" => {
            // Input manual §Axial rotation; joint.cc reads both offsets with `position`
            // optional, then the drive, `friction` and the orientation description.
            let a = side(c, ctx, "node 1", Position::Always, None)?;
            let b = side(c, ctx, "node 2", Position::Always, Some(&a))?;
            let omega = callers::drive(c, ctx.drives, ctx.seq)?;
            if super::friction::follows(c) {
                return Err(super::friction::refuse(c, "axial rotation"));
            }
            orientation_description(c)?;
            let hinge = Joint::revolute_hinge(label, a.anchor(), b.anchor());
            Box::new(AxialRotation::new(label, hinge.a, hinge.b, omega))
        }
        // `pin` is MBDyn's deprecated name of the spherical pin (joint.cc: `case PIN: case
        // SPHERICALPIN`, the same reader).
        "pin" => Box::new(pin("spherical pin", label, c, ctx)?),
        "revolute pin" | "plane pin" | "spherical pin" => Box::new(pin(kind, label, c, ctx)?),
        "total joint" | "total pin joint" => Box::new(total(kind == "total pin joint", label, c, ctx, span)?),
        "drive displacement" | "drive displacement pin" | "imposed displacement" | "imposed displacement pin" => Box::new(drive_displacement(kind, label, c, ctx)?),
        "drive hinge" => Box::new(drive_hinge(label, c, ctx)?),
        "linear velocity" | "angular velocity" => {
            // joint.cc: NODE, a unit direction relative to the node (normalized), a drive.
            // drvj.cc turns the angular one's with the node (R d) and uses the linear one's
            // node-frame components as global ones (`Dir.Dot(vNode)`): so does romdyn.
            let n = ctx.node(c, "the node")?;
            let d_span = c.here();
            let d = ctx.on(n).relative_vector(c, "direction")?;
            let d = d.try_normalize(0.0).ok_or_else(|| c.error_at(d_span, format!("{kind}: the direction is null")))?;
            let value = callers::drive(c, ctx.drives, ctx.seq)?;
            let kind = if kind == "linear velocity" { VelocityKind::Linear } else { VelocityKind::Angular };
            Box::new(ImposedVelocity { label, node: n.label, kind, direction: d, value })
        }
        "viscous body" => {
            // joint.cc: NODE, [position,] OFFSET, [orientation | hinge, R,] a 6-D viscous law.
            let n = side(c, ctx, "the node", Position::Always, None)?;
            let span = c.here();
            let law = linear_law(c, 6, ctx.laws, ctx.drives, ctx.seq)?;
            let viscous_only = law.stiffness.iter().all(|&k| k == 0.0) && law.prestrain.iter().chain(law.prestress.iter()).all(|&k| k == 0.0);
            if !viscous_only {
                return Err(c.error_at(span, "viscous body: needs a viscous constitutive law (joint.cc), no stiffness, prestrain or prestress"));
            }
            orientation_description(c)?;
            let viscosity = nalgebra::Matrix6::from_fn(|i, j| law.viscosity[(i, j)]);
            Box::new(ViscousBody { label, node: n.node.label, offset: n.offset, orientation: n.orientation, viscosity })
        }
        "angular acceleration" => {
            // joint.cc: NODE, a unit direction relative to the node (normalized), a drive.
            let n = ctx.node(c, "the node")?;
            let d_span = c.here();
            let d = ctx.on(n).relative_vector(c, "direction")?;
            let d = d.try_normalize(0.0).ok_or_else(|| c.error_at(d_span, "angular acceleration: the direction is null"))?;
            let value = callers::drive(c, ctx.drives, ctx.seq)?;
            let w0 = (n.orientation * d).dot(&n.angular_velocity);
            if w0 != 0.0 {
                // accj.cc's `SetValue` starts its state at the node's (R d) · ω; romdyn
                // starts an element's states at zero.
                return Err(c.error_at(d_span, format!("angular acceleration: node {} starts with an angular velocity of {w0:e} rad/s about the direction; romdyn's angular acceleration starts from rest about it", n.label)));
            }
            Box::new(AngularAcceleration::new(label, n.label, d, value))
        }
        "revolute rotation" => {
            // joint.cc: offsets after `position` read and ignored; the orientation description.
            let mut a = side(c, ctx, "node 1", Position::IfKeyword, None)?;
            let mut b = side(c, ctx, "node 2", Position::IfKeyword, Some(&a))?;
            orientation_description(c)?;
            (a.offset, b.offset) = (Vec3::zeros(), Vec3::zeros());
            Box::new(Joint::revolute_rotation(label, a.anchor(), b.anchor()))
        }
        "gimbal rotation" => {
            // joint.cc, as `revolute rotation`: offsets after `position` read and ignored,
            // orientations, the orientation description.
            let mut a = side(c, ctx, "node 1", Position::IfKeyword, None)?;
            let mut b = side(c, ctx, "node 2", Position::IfKeyword, Some(&a))?;
            orientation_description(c)?;
            (a.offset, b.offset) = (Vec3::zeros(), Vec3::zeros());
            let ((_, qa), (_, qb)) = (a.global(), b.global());
            Box::new(GimbalRotation { label, a: a.anchor(), b: b.anchor(), angles: GimbalRotation::angles_of(&(qa.transpose() * qb)) })
        }
        "cardano hinge" | "universal hinge" | "cardano pin" | "universal pin" | "cardano rotation" | "universal rotation" => Box::new(cardano(kind, label, c, ctx)?),
        "in line" | "in plane" => in_line_or_plane(kind == "in line", label, c, ctx)?,
        "distance" | "distance with offset" => {
            // `distance, NODE_1, [position, O_1,] NODE_2, [position, O_2,] {DRIVE | from nodes}`;
            // the deprecated `distance with offset` always reads both offsets.
            let position = if kind == "distance" { Position::IfKeyword } else { Position::Always };
            let (a, da) = point_side(c, ctx, "node 1", position, None)?;
            let (b, _) = point_side(c, ctx, "node 2", position, Some((&a, da)))?;
            let l0 = (b.global().0 - a.global().0).norm();
            let l_span = c.here();
            // joint.cc: the drive reads `model::current("L")`, the length as written.
            c.publish(&[("L", l0)]);
            let length = if c.accept("from nodes") { Drive::Const(l0) } else { callers::drive(c, ctx.drives, ctx.seq)? };
            c.withdraw();
            let t0 = 0.0;
            let l = length.value(t0);
            if !(l > 0.0) || l0 == 0.0 {
                return Err(c.error_at(l_span, format!("distance: MBDyn's distance joint needs a positive distance (imposed {l} m, initial {l0:.6e} m)")));
            }
            // MBDyn's SetInitialValue: the unit direction between the points as written.
            let direction = (b.global().0 - a.global().0) / l0;
            Box::new(Distance { label, a: a.anchor(), b: b.anchor(), length, direction })
        }
        "prismatic" => {
            let orientation = |c: &mut Cursor, n: &StructuralNode, other: Option<&Side>| -> Result<Mat3, MbdynError> {
                let on = Context { other: other.map(Side::other), ..ctx.on(n) };
                if c.accept("orientation") || c.accept("hinge") { on.relative_orientation(c, "orientation of the joint") } else { Ok(Mat3::identity()) }
            };
            let na = ctx.node(c, "node 1")?;
            let a = Side { node: na, offset: Vec3::zeros(), orientation: orientation(c, na, None)? };
            let nb = ctx.node(c, "node 2")?;
            let b = Side { node: nb, offset: Vec3::zeros(), orientation: orientation(c, nb, Some(&a))? };
            Box::new(Joint::prismatic(label, a.anchor(), b.anchor()))
        }
        "deformable displacement joint" | "deformable displacement hinge" | "deformable hinge" => {
            let hinge = kind == "deformable hinge";
            let position = if hinge { Position::IfKeyword } else { Position::Always };
            let a = side(c, ctx, "node 1", position, None)?;
            let b = side(c, ctx, "node 2", position, Some(&a))?;
            let law_span = c.here();
            let law = nonlinear_law(c, 3, ctx.laws, ctx.drives, ctx.seq)?;
            let v = |d: &nalgebra::DVector<f64>| Vec3::new(d[0], d[1], d[2]);
            if hinge {
                orientation_description(c)?;
                if law.nonlinear.is_some() || law.time_variance.is_some() || law.prestrain.iter().chain(law.prestress.iter()).any(|x| *x != 0.0) {
                    Box::new(DeformableJoint::hinge(label, a.anchor(), b.anchor(), &three(&law), v(&law.prestrain), v(&law.prestress)).with_functions(law.functions.placed(3, 6)).with_time_variance(law.time_variance.clone()))
                } else {
                    Box::new(DeformableHinge { label, a: a.anchor(), b: b.anchor(), law: three(&law) })
                }
            } else if law.nonlinear.is_some() || law.time_variance.is_some() {
                // A nonlinear or time-variant law keeps its prestrain and prestress apart (no
                // rest strain: a time-variant one would move in time).
                Box::new(DeformableJoint::displacement(label, a.anchor(), b.anchor(), &three(&law), v(&law.prestrain), v(&law.prestress)).with_functions(law.functions.placed(0, 6)).with_time_variance(law.time_variance.clone()))
            } else {
                let rest = rest_strain(&law).ok_or_else(|| c.error_at(law_span, "a prestress needs an invertible stiffness matrix in romdyn (it becomes a rest strain)"))?;
                Box::new(DeformableDisplacement { label, a: a.anchor(), b: b.anchor(), law: three(&law), rest })
            }
        }
        "deformable joint" => {
            // joint.cc: both offsets read, `position` optional; a 6-D law.
            let a = side(c, ctx, "node 1", Position::Always, None)?;
            let b = side(c, ctx, "node 2", Position::Always, Some(&a))?;
            let law = super::beams::section_law(&nonlinear_law(c, 6, ctx.laws, ctx.drives, ctx.seq)?);
            orientation_description(c)?;
            Box::new(DeformableJoint::new(label, a.anchor(), b.anchor(), law))
        }
        "deformable axial joint" => {
            // joint.cc: offsets after `position` are read and ignored; a 1-D law.
            let a = side(c, ctx, "node 1", Position::IfKeyword, None)?;
            let b = side(c, ctx, "node 2", Position::IfKeyword, Some(&a))?;
            let law = super::laws::axial_law(c, ctx.laws, ctx.drives, ctx.seq)?;
            let (k, v) = (law.stiffness[(0, 0)], law.viscosity[(0, 0)]);
            Box::new(DeformableJoint::axial(label, a.anchor(), b.anchor(), k, v, law.prestrain[0], law.prestress[0]).with_functions(law.functions.placed(5, 6)).with_time_variance(law.time_variance.clone()))
        }
        "invariant deformable hinge" => {
            let a = side(c, ctx, "node 1", Position::IfKeyword, None)?;
            let b = side(c, ctx, "node 2", Position::IfKeyword, Some(&a))?;
            let law_span = c.here();
            let law = super::laws::linear_or_time_variant_law(c, 3, ctx.laws, ctx.drives, ctx.seq)?;
            orientation_description(c)?;
            if law.prestrain.iter().chain(law.prestress.iter()).any(|x| *x != 0.0) {
                return Err(c.error_at(law_span, "prestrain and prestress of an invariant deformable hinge are not supported by romdyn (MBDyn 1.7.3 runs them)"));
            }
            Box::new(InvariantDeformableHinge { label, a: a.anchor(), b: b.anchor(), law: three(&law), variance: law.time_variance.clone() })
        }
        _ => rod(kind == "rod with offset", label, c, ctx)?,
    };
    Ok(element)
}

/// The optional `orientation description, …` (output only).
fn orientation_description(c: &mut Cursor) -> Result<(), MbdynError> {
    if c.accept("orientation description") {
        c.keyword("an orientation description", &["euler123", "euler313", "euler321", "orientation vector", "orientation matrix"])?;
    }
    Ok(())
}

/// `in line, NODE_1, [position,] P, [orientation,] R, NODE_2 [, offset, O]` (B's point on
/// the line through P along R's axis 3) and `in plane, NODE_1, [position,] P, N, NODE_2 [,
/// offset, O]` (B's point in the plane through P normal to N, normalized): input manual,
/// §In line, §In plane. The plane's frame has N as axis 3 (axes 1 and 2 any pair normal to
/// it: the constraint does not depend on them).
///
/// An in line joint without offset may carry `friction` ([`super::friction`]).
fn in_line_or_plane(line: bool, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let na = ctx.node(c, "node 1")?;
    let on = ctx.on(na);
    c.accept("position");
    let p = on.relative_position(c, if line { "point of the line [m]" } else { "point of the plane [m]" })?;
    let orientation = if line {
        c.accept("orientation");
        on.relative_orientation(c, "orientation of the line (axis 3 along it)")?
    } else {
        let n_span = c.here();
        let n = on.relative_vector(c, "normal of the plane")?;
        let n = n.try_normalize(0.0).ok_or_else(|| c.error_at(n_span, "in plane: the normal is null"))?;
        let t = if n.x.abs() < 0.9 { Vec3::x() } else { Vec3::y() };
        let e1 = (t - n * n.dot(&t)).normalize();
        Mat3::from_columns(&[e1, n.cross(&e1), n])
    };
    let a = Side { node: na, offset: p, orientation };
    let nb = ctx.node(c, "node 2")?;
    let has_offset = c.accept("offset");
    let offset = if has_offset { Context { other: Some(a.other()), ..ctx.on(nb) }.relative_position(c, "offset of node 2 [m]")? } else { Vec3::zeros() };
    let friction = match (super::friction::follows(c), line, has_offset) {
        (false, ..) => None,
        (true, true, false) => Some(super::friction::in_line_friction(c, ctx)?),
        // joint.cc reads the friction of an in line joint with offset and drops it
        // (`InLineWithOffsetJoint`, "TODO: friction to add").
        (true, true, true) => return Err(c.error("joint friction on an 'in line' joint with offset is not supported by romdyn, nor applied by MBDyn 1.7.3 (its reader reads it and drops it): remove the offset or the friction")),
        (true, false, _) => return Err(super::friction::refuse(c, "in plane")),
    };
    let b = Side { node: nb, offset, orientation: Mat3::identity() };
    let j = if line { Joint::in_line(label, a.anchor(), b.anchor()) } else { Joint::in_plane(label, a.anchor(), b.anchor()) };
    // Only position components are locked: B's frame orientation does not matter.
    Ok(match friction {
        Some((preload, model)) => Box::new(InLineFriction::new(j, preload, model)),
        None => Box::new(j),
    })
}

/// `clamp, NODE, [position,] {node | POSITION}, [orientation,] {node | ORIENTATION}`.
fn clamp(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Joint, MbdynError> {
    let n = ctx.node(c, "clamped node")?;
    let on = Context { node: Some(Frame::of_node(n)), ..ctx.global() };
    c.accept("position");
    let position = if c.accept("node") || c.is_done() { n.position } else { on.position(c, "clamp position [m]")? };
    c.accept("orientation");
    let orientation = if c.accept("node") || c.is_done() { n.orientation } else { on.orientation(c, "clamp orientation")? };
    let j = Joint::clamp(label, n.label, position, orientation);
    Ok(j)
}

/// `revolute pin, NODE, [position,] OFFSET [, {orientation | hinge}, R], [position,] PIN [,
/// {orientation | hinge}, R_PIN]` and `spherical pin` alike: the joint with a frame fixed in
/// space. Both `position` keywords are optional and `hinge` is the older word for
/// `orientation` (joint.cc, MBDYN_X_COMPATIBLE_INPUT); a spherical pin reads its
/// orientations and ignores them.
fn pin(kind: &str, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Joint, MbdynError> {
    let revolute = kind != "spherical pin";
    let (a, b) = pin_frames(revolute, c, ctx)?;
    if revolute && c.accept("initial theta") {
        c.real("initial theta [rad]")?;
    }
    let j = if revolute { Joint::revolute_hinge(label, a, b.anchor()) } else { Joint::spherical_hinge(label, a, b.anchor()) };
    Ok(j)
}

/// The node side and the frame fixed in space of a pin (`oriented`: both orientations kept;
/// a spherical pin reads and ignores them).
fn pin_frames<'a>(oriented: bool, c: &mut Cursor, ctx: &ElementContext<'a>) -> Result<(Anchor, Side<'a>), MbdynError> {
    let mut b = side(c, ctx, "the node", Position::Always, None)?;
    if !oriented {
        b.orientation = Mat3::identity();
    }
    let on = Context { node: Some(Frame::of_node(b.node)), ..ctx.global() };
    c.accept("position");
    let position = on.position(c, "pin position [m]")?;
    let orientation = if c.accept("orientation") || c.accept("hinge") { on.orientation(c, "pin orientation")? } else { Mat3::identity() };
    let orientation = if oriented { orientation } else { Mat3::identity() };
    Ok((Anchor::Ground { position, orientation }, b))
}

/// `cardano hinge`/`universal hinge` (both offsets read, `position` optional, as the other
/// hinges), `cardano pin`/`universal pin` (as the revolute pin), `cardano rotation`/`universal
/// rotation` (offsets after `position` read and ignored, joint.cc): input manual §Cardano
/// hinge, §Cardano pin, §Cardano rotation.
fn cardano(kind: &'static str, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<CardanoHinge, MbdynError> {
    let (a, b, with_position) = if kind.ends_with("pin") {
        let (a, b) = pin_frames(true, c, ctx)?;
        (a, b.anchor(), true)
    } else if kind.ends_with("rotation") {
        let a = side(c, ctx, "node 1", Position::IfKeyword, None)?;
        let b = side(c, ctx, "node 2", Position::IfKeyword, Some(&a))?;
        orientation_description(c)?;
        let (mut a, mut b) = (a, b);
        (a.offset, b.offset) = (Vec3::zeros(), Vec3::zeros());
        (a.anchor(), b.anchor(), false)
    } else {
        let a = side(c, ctx, "node 1", Position::Always, None)?;
        let b = side(c, ctx, "node 2", Position::Always, Some(&a))?;
        (a.anchor(), b.anchor(), true)
    };
    let j = CardanoHinge::new(label, a.clone(), b.clone(), with_position, kind);
    Ok(j)
}

/// `drive displacement, NODE_1, [position,] O_1, NODE_2, [position,] O_2, VALUE` (B's point at
/// `D(t)` from A's, in node 1's frame), `drive displacement pin, NODE, [position,] O,
/// [position,] X, VALUE` (the node's point at `X + D(t)`, absolute), and `imposed
/// displacement`/`imposed displacement pin` with the same arguments (joint.cc reads them as
/// total joints with all three positions locked to the template drive VALUE, whatever the
/// manual's "along a direction" says).
fn drive_displacement(kind: &'static str, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<DrivenJoint, MbdynError> {
    let pin = kind.ends_with("pin");
    let first = side(c, ctx, if pin { "the node" } else { "node 1" }, Position::Always, None)?;
    let (a, b, basis) = if pin {
        let on = Context { node: Some(Frame::of_node(first.node)), ..ctx.global() };
        c.accept("position");
        let x = on.position(c, "absolute position [m]")?;
        (Anchor::Ground { position: x, orientation: Mat3::identity() }, Anchor::Node { label: first.node.label, offset: first.offset, orientation: Mat3::identity() }, on)
    } else {
        let second = side(c, ctx, "node 2", Position::Always, Some(&first))?;
        let a = Anchor::Node { label: first.node.label, offset: first.offset, orientation: Mat3::identity() };
        (a, Anchor::Node { label: second.node.label, offset: second.offset, orientation: Mat3::identity() }, ctx.on(first.node))
    };
    let value = if pin {
        template_vec3(c, ctx.drives, ctx.seq, &Mat3::identity(), &|c: &mut Cursor| basis.vector_in(c, "imposed position", Frame::global()))?
    } else {
        template_vec3(c, ctx.drives, ctx.seq, &Mat3::identity(), &|c: &mut Cursor| basis.relative_vector(c, "imposed relative position"))?
    };
    let mut j = DrivenJoint::new(Joint::total(label, a, b, [true; 3], [false; 3]), kind);
    j.position = VectorDrive(value);
    Ok(j)
}

/// `drive hinge, NODE_1 [, orientation, R_1], NODE_2 [, orientation, R_2], VALUE`: the
/// relative rotation vector of the two hinge frames imposed (input manual §Drive hinge;
/// drvhinge.cc: `rotvec(R_1ᵀ R_2) = Θ(t)`).
fn drive_hinge(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<DrivenJoint, MbdynError> {
    let a = side(c, ctx, "node 1", Position::IfKeyword, None)?;
    let b = side(c, ctx, "node 2", Position::IfKeyword, Some(&a))?;
    let value = template_vec3(c, ctx.drives, ctx.seq, &Mat3::identity(), &|c: &mut Cursor| c.vec3_values("imposed relative rotation [rad]"))?;
    let mut j = DrivenJoint::new(Joint::total(label, a.anchor(), b.anchor(), [false; 3], [true; 3]), "drive hinge");
    j.rotation = VectorDrive(value);
    Ok(j)
}

/// `rod, NODE1, [position, O1,] NODE2, [position, O2,] {L0 | from nodes}, LAW` and `rod with
/// offset, NODE1, O1, NODE2, O2, …` (input manual, §Rod): `F = EA (l − l₀)/l₀` plus,
/// with a viscous or viscoelastic law, `C ε̇`; a
/// prestrain `ε_p` and a prestress `F_p` shift the rest length to `l₀ (1 + ε_p − F_p/EA)`.
fn rod(offsets: bool, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let position = if offsets { Position::Always } else { Position::IfKeyword };
    let (a, da) = point_side(c, ctx, "node 1", position, None)?;
    let (b, _) = point_side(c, ctx, "node 2", position, Some((&a, da)))?;
    let distance = (b.global().0 - a.global().0).norm();
    let span = c.here();
    if distance == 0.0 {
        return Err(c.error_at(span, "rod: the two points coincide in the initial configuration"));
    }
    let l0 = if c.accept("from nodes") { distance } else { c.real("rod length [m] (or from nodes)")? };
    if l0 <= 0.0 {
        return Err(c.error_at(span, format!("rod length must be positive, found {l0}")));
    }
    let law_span = c.here();
    // joint.cc: the law reads `model::current("L0")`, the length as input, and
    // `model::current("L")`, the distance between the points as written.
    c.publish(&[("L0", l0), ("L", distance)]);
    // `scalar function elastic [isotropic | orthotropic], FUNCTION`: N = f(ε).
    if c.accept("scalar function elastic isotropic") || c.accept("scalar function elastic orthotropic") || c.accept("scalar function elastic") {
        let f = scalar_functions::scalar_function(c, &ctx.drives.functions, ctx.seq)?;
        return Ok(Box::new(Rod { label, a: a.anchor(), b: b.anchor(), axial_stiffness: 0.0, length: l0, viscous: None, elastic: Some(f) }));
    }
    let (law, prestrain): (LinearLaw, _) = super::laws::law_with_prestrain_drive(c, 1, ctx.laws, ctx.drives, ctx.seq)?;
    c.withdraw();
    match law.nonlinear {
        // A `scalar function elastic` law of a `constitutive law:` card.
        Some(kind) if kind.starts_with("scalar function") => {
            let f = law.functions.elastic[0].clone();
            return Ok(Box::new(Rod { label, a: a.anchor(), b: b.anchor(), axial_stiffness: 0.0, length: l0, viscous: None, elastic: f }));
        }
        Some(kind) => {
            if prestrain.is_some() {
                return Err(c.error_at(law_span, format!("rod: a prestrain that changes in time on an '{kind}' law is not supported by romdyn (MBDyn 1.7.3 runs it)")));
            }
            let (elastic, viscous) = (law.functions.elastic[0].clone(), law.functions.viscous[0].clone());
            let (stiffness, viscosity, prestrain, prestress) = (law.stiffness[(0, 0)], law.viscosity[(0, 0)], law.prestrain[0], law.prestress[0]);
            return Ok(Box::new(crate::element::NlsfRod { label, a: a.anchor(), b: b.anchor(), length: l0, stiffness, viscosity, prestrain, prestress, elastic, viscous }));
        }
        None => {}
    }
    let (ea, viscosity) = (law.stiffness[(0, 0)], law.viscosity[(0, 0)]);
    if ea < 0.0 || viscosity < 0.0 || ea + viscosity == 0.0 {
        return Err(c.error_at(law_span, format!("rod: the axial stiffness EA [N] and viscosity [N s] must not be negative, nor both zero (found {ea}, {viscosity})")));
    }
    if let Some(variance) = law.time_variance.clone() {
        if 1.0 + law.prestrain[0] <= 0.0 {
            return Err(c.error_at(law_span, "rod: the prestrain leaves no positive rest length"));
        }
        return Ok(Box::new(time_variant_rod(label, &a, &b, l0, &law, prestrain, variance)));
    }
    if ea == 0.0 && law.prestress[0] != 0.0 {
        return Err(c.error_at(law_span, "rod: a prestress needs an axial stiffness in romdyn (it becomes a rest length)"));
    }
    let rest = if ea == 0.0 { l0 } else { l0 * (1.0 + law.prestrain[0] - law.prestress[0] / ea) };
    if rest <= 0.0 {
        return Err(c.error_at(law_span, "rod: prestrain and prestress leave no positive rest length"));
    }
    // The viscous part acts on MBDyn's strain rate d·ḋ/(l l₀) (rodj.cc, ViscoElasticRod).
    let viscous = (viscosity > 0.0).then_some(RodViscosity { coefficient: viscosity, length: l0 });
    let rod = Rod { label, a: a.anchor(), b: b.anchor(), axial_stiffness: ea * rest / l0, length: rest, viscous, elastic: None };
    if let Some(b) = law.bistop {
        if prestrain.is_some() {
            return Err(c.error_at(law_span, "rod: a bistop law with a prestrain that changes in time is not supported by romdyn (MBDyn 1.7.3 runs it)"));
        }
        return Ok(Box::new(crate::element::BistopRod { rod, strain_length: l0, initially_active: b.initially_active, activate: b.activate, deactivate: b.deactivate }));
    }
    Ok(match prestrain {
        Some(prestrain) => Box::new(crate::element::PrestrainedRod { rod, prestrain, strain_length: l0 }),
        None => Box::new(rod),
    })
}

/// A rod with a `linear time variant viscoelastic generic` law, `N = F_p + s_K(t) EA (ε −
/// ε_p) + s_C(t) C ε̇` ([`crate::element::TimeVariantRod`]): the rod of `EA` with its
/// prestrain (a constant one in its rest length `l₀ (1 + ε_p)`, a drive apart), the rod of
/// `C`, and the prestress.
fn time_variant_rod(label: Label, a: &Side, b: &Side, l0: f64, law: &LinearLaw, prestrain: Option<Drive>, variance: crate::element::TimeVariance) -> crate::element::TimeVariantRod {
    let (ea, viscosity) = (law.stiffness[(0, 0)], law.viscosity[(0, 0)]);
    let rest = l0 * (1.0 + law.prestrain[0]);
    let elastic = Rod { label, a: a.anchor(), b: b.anchor(), axial_stiffness: ea * rest / l0, length: rest, viscous: None, elastic: None };
    let elastic = crate::element::PrestrainedRod { rod: elastic, prestrain: prestrain.unwrap_or(Drive::Const(0.0)), strain_length: l0 };
    let viscous = (viscosity != 0.0).then_some(RodViscosity { coefficient: viscosity, length: l0 });
    let viscous = Rod { label, a: a.anchor(), b: b.anchor(), axial_stiffness: 0.0, length: l0, viscous, elastic: None };
    crate::element::TimeVariantRod { elastic, viscous, prestress: law.prestress[0], variance }
}
