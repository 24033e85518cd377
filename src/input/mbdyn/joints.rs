//! `joint` statements (input manual, "Elements", §Joint): clamp, revolute hinge and pin,
//! spherical hinge and pin, total joint, total pin joint, deformable displacement joint,
//! deformable hinge, rod and rod with offset, mapped onto romdyn's [`Joint`],
//! [`DeformableDisplacement`], [`DeformableHinge`] and [`Rod`].
//!
//! Offsets and orientations are relative to their node (`reference, node` by default);
//! the second node may refer to the first with `reference, other node` (or `other
//! position`, `other orientation`). A constraint need not hold as written: MBDyn's initial
//! assembly (`solve::initial_assembly`) makes it hold before the run.

use super::cursor::Cursor;
use super::diagnostic::MbdynError;
use super::drives::{single_term, template_vec3};
use super::element_context::ElementContext;
use super::laws::{linear_law, rest_strain, three, LinearLaw};
use super::references::{Context, Frame, OtherSide};
use crate::element::{Anchor, DeformableDisplacement, DeformableHinge, Distance, Drive, Element, Joint, Rod, RodViscosity};
use crate::kinematics::{Mat3, Vec3};
use crate::model::{Label, StructuralNode};

const SUPPORTED: [&str; 19] = [
    "clamp", "revolute hinge", "plane hinge", "revolute pin", "plane pin", "spherical hinge", "spherical pin", "total joint", "total pin joint",
    "deformable displacement joint", "deformable displacement hinge", "deformable hinge", "rod", "rod with offset", "in line", "in plane", "prismatic",
    "distance", "distance with offset",
];

/// MBDyn joints romdyn names in its "not supported" error.
const OTHER_JOINTS: [&str; 28] = [
    "angular acceleration", "angular velocity", "axial rotation", "beam slider", "brake", "cardano hinge", "cardano pin", "cardano rotation",
    "coincidence", "deformable axial joint", "deformable joint", "drive displacement", "drive displacement pin",
    "drive hinge", "gimbal rotation", "imposed displacement", "imposed displacement pin", "imposed orientation",
    "invariant deformable displacement joint", "invariant deformable hinge", "linear acceleration", "linear velocity", "modal",
    "plane displacement", "plane displacement pin", "point contact", "revolute rotation", "rod bezier",
];

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
    let on = Context { other: other.map(Side::other), ..ctx.on(node) };
    let written = c.accept("position") || c.peek_keyword().is_some_and(|w| w == "null");
    let offset = if written || position == Position::Always { on.relative_position(c, &format!("offset of {what} [m]"))? } else { Vec3::zeros() };
    let orientation = if c.accept("orientation") || c.accept("hinge") { on.relative_orientation(c, &format!("orientation of {what}"))? } else { Mat3::identity() };
    Ok(Side { node, offset, orientation })
}

/// `joint: LABEL, TYPE, …`.
pub fn joint(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let span = c.here();
    let Some(kind) = c.accept_any(&SUPPORTED) else {
        if let Some(w) = c.peek_keyword() {
            let name = OTHER_JOINTS.iter().find(|o| super::parser::same_keyword(o, w)).copied().unwrap_or(w);
            return Err(c.error(format!("joint type '{name}' is not supported by romdyn (supported: clamp, revolute hinge, revolute pin, spherical hinge, spherical pin, total joint, total pin joint, deformable displacement joint, deformable hinge, rod, in line, in plane, prismatic, distance)")));
        }
        return Err(c.error(format!("expected a joint type, found {}", c.found())));
    };
    let element: Box<dyn Element> = match kind {
        "clamp" => Box::new(clamp(label, c, ctx)?),
        "revolute hinge" | "plane hinge" | "spherical hinge" => {
            let revolute = kind != "spherical hinge";
            // MBDyn reads both offsets whether or not `position` is written (joint.cc,
            // MBDYN_X_COMPATIBLE_INPUT, which joint.cc defines).
            let a = side(c, ctx, "node 1", Position::Always, None)?;
            let b = side(c, ctx, "node 2", Position::Always, Some(&a))?;
            if revolute && c.accept("initial theta") {
                c.real("initial theta [rad]")?;
            }
            if c.peek_keyword().is_some_and(|w| w == "friction") {
                return Err(c.error("joint friction is not supported by romdyn"));
            }
            let j = if revolute { Joint::revolute_hinge(label, a.anchor(), b.anchor()) } else { Joint::spherical_hinge(label, a.anchor(), b.anchor()) };
            Box::new(assembled(j, &a.global(), &b.global(), c, span)?)
        }
        "revolute pin" | "plane pin" | "spherical pin" => Box::new(pin(kind, label, c, ctx, span)?),
        "total joint" | "total pin joint" => Box::new(total(kind == "total pin joint", label, c, ctx, span)?),
        "in line" | "in plane" => Box::new(in_line_or_plane(kind == "in line", label, c, ctx, span)?),
        "distance" | "distance with offset" => {
            // `distance, NODE_1, [position, O_1,] NODE_2, [position, O_2,] {DRIVE | from nodes}`;
            // the deprecated `distance with offset` always reads both offsets.
            let position = if kind == "distance" { Position::IfKeyword } else { Position::Always };
            let a = side(c, ctx, "node 1", position, None)?;
            let b = side(c, ctx, "node 2", position, Some(&a))?;
            let l0 = (b.global().0 - a.global().0).norm();
            let l_span = c.here();
            let length = if c.accept("from nodes") { Drive::Const(l0) } else { super::drives::drive(c, ctx.drives, ctx.seq)? };
            let t0 = 0.0;
            let l = length.value(t0);
            if !(l > 0.0) || l0 == 0.0 {
                return Err(c.error_at(l_span, format!("distance: MBDyn's distance joint needs a positive distance (imposed {l} m, initial {l0:.6e} m)")));
            }
            Box::new(Distance { label, a: a.anchor(), b: b.anchor(), length })
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
            Box::new(assembled(Joint::prismatic(label, a.anchor(), b.anchor()), &a.global(), &b.global(), c, span)?)
        }
        "deformable displacement joint" | "deformable displacement hinge" | "deformable hinge" => {
            let hinge = kind == "deformable hinge";
            let position = if hinge { Position::IfKeyword } else { Position::Always };
            let a = side(c, ctx, "node 1", position, None)?;
            let b = side(c, ctx, "node 2", position, Some(&a))?;
            let law_span = c.here();
            let law = linear_law(c, 3, ctx.laws, ctx.drives, ctx.seq)?;
            if hinge {
                if c.accept("orientation description") {
                    c.keyword("an orientation description", &["euler123", "euler313", "euler321", "orientation vector", "orientation matrix"])?;
                }
                if law.prestrain.iter().chain(law.prestress.iter()).any(|x| *x != 0.0) {
                    return Err(c.error_at(law_span, "prestrain and prestress of a deformable hinge are not supported by romdyn"));
                }
                Box::new(DeformableHinge { label, a: a.anchor(), b: b.anchor(), law: three(&law) })
            } else {
                let rest = rest_strain(&law).ok_or_else(|| c.error_at(law_span, "a prestress needs an invertible stiffness matrix in romdyn (it becomes a rest strain)"))?;
                Box::new(DeformableDisplacement { label, a: a.anchor(), b: b.anchor(), law: three(&law), rest })
            }
        }
        _ => Box::new(rod(kind == "rod with offset", label, c, ctx)?),
    };
    Ok(element)
}

/// `in line, NODE_1, [position,] P, [orientation,] R, NODE_2 [, offset, O]` (B's point on
/// the line through P along R's axis 3) and `in plane, NODE_1, [position,] P, N, NODE_2 [,
/// offset, O]` (B's point in the plane through P normal to N, normalized): input manual,
/// §In line, §In plane. The plane's frame has N as axis 3 (axes 1 and 2 any pair normal to
/// it: the constraint does not depend on them).
fn in_line_or_plane(line: bool, label: Label, c: &mut Cursor, ctx: &ElementContext, span: super::diagnostic::Span) -> Result<Joint, MbdynError> {
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
    let offset = if c.accept("offset") { Context { other: Some(a.other()), ..ctx.on(nb) }.relative_position(c, "offset of node 2 [m]")? } else { Vec3::zeros() };
    if c.peek_keyword().is_some_and(|w| w == "friction") {
        return Err(c.error("joint friction is not supported by romdyn"));
    }
    let b = Side { node: nb, offset, orientation: Mat3::identity() };
    let (frame_b_point, _) = b.global();
    let (pa, qa) = a.global();
    let j = if line { Joint::in_line(label, a.anchor(), b.anchor()) } else { Joint::in_plane(label, a.anchor(), b.anchor()) };
    // Only position components are locked: B's frame orientation does not matter.
    assembled(j, &(pa, qa), &(frame_b_point, qa), c, span)
}

/// `clamp, NODE, [position,] {node | POSITION}, [orientation,] {node | ORIENTATION}`.
fn clamp(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Joint, MbdynError> {
    let span = c.here();
    let n = ctx.node(c, "clamped node")?;
    let on = Context { node: Some(Frame::of_node(n)), ..ctx.global() };
    c.accept("position");
    let position = if c.accept("node") || c.is_done() { n.position } else { on.position(c, "clamp position [m]")? };
    c.accept("orientation");
    let orientation = if c.accept("node") || c.is_done() { n.orientation } else { on.orientation(c, "clamp orientation")? };
    let j = Joint::clamp(label, n.label, position, orientation);
    assembled(j, &(position, orientation), &(n.position, n.orientation), c, span)
}

/// `revolute pin, NODE, [position,] OFFSET [, {orientation | hinge}, R], [position,] PIN [,
/// {orientation | hinge}, R_PIN]` and `spherical pin` alike: the joint with a frame fixed in
/// space. Both `position` keywords are optional and `hinge` is the older word for
/// `orientation` (joint.cc, MBDYN_X_COMPATIBLE_INPUT); a spherical pin reads its
/// orientations and ignores them.
fn pin(kind: &str, label: Label, c: &mut Cursor, ctx: &ElementContext, span: super::diagnostic::Span) -> Result<Joint, MbdynError> {
    let revolute = kind != "spherical pin";
    let mut b = side(c, ctx, "the node", Position::Always, None)?;
    if !revolute {
        b.orientation = Mat3::identity();
    }
    let on = Context { node: Some(Frame::of_node(b.node)), ..ctx.global() };
    c.accept("position");
    let position = on.position(c, "pin position [m]")?;
    let orientation = if c.accept("orientation") || c.accept("hinge") { on.orientation(c, "pin orientation")? } else { Mat3::identity() };
    let orientation = if revolute { orientation } else { Mat3::identity() };
    if revolute && c.accept("initial theta") {
        c.real("initial theta [rad]")?;
    }
    let a = Anchor::Ground { position, orientation };
    let j = if revolute { Joint::revolute_hinge(label, a, b.anchor()) } else { Joint::spherical_hinge(label, a, b.anchor()) };
    assembled(j, &(position, orientation), &b.global(), c, span)
}

/// One side of a total joint: a node (or the ground, `node: None`, with an absolute
/// position), the offset and the position and rotation orientations.
struct TotalSide<'a> {
    node: Option<&'a StructuralNode>,
    offset: Vec3,
    position: Mat3,
    rotation: Mat3,
}

impl TotalSide<'_> {
    /// The anchor with frame `q` and the point moved by `shift` (in frame `q`).
    fn anchor(&self, q: &Mat3, shift: &Vec3) -> Anchor {
        match self.node {
            Some(n) => Anchor::Node { label: n.label, offset: self.offset + q * shift, orientation: *q },
            None => Anchor::Ground { position: self.offset + q * shift, orientation: *q },
        }
    }
    fn global(&self, q: &Mat3, shift: &Vec3) -> (Vec3, Mat3) {
        match self.node {
            Some(n) => (n.position + n.orientation * (self.offset + q * shift), n.orientation * q),
            None => (self.offset + q * shift, *q),
        }
    }
}

/// `[position, OFFSET] [, position orientation, R] [, rotation orientation, R]`.
fn total_side<'a>(c: &mut Cursor, on: &Context, node: Option<&'a StructuralNode>) -> Result<TotalSide<'a>, MbdynError> {
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
/// active components of relative position and rotation are locked, in the frame of node 1
/// (total joint) or in the absolute frame (total pin joint). romdyn's total joint has one
/// frame per side, so where both kinds of constraint are active the position and rotation
/// orientations of that frame must agree. Imposed values must be constant: a constant
/// imposed position moves the constraint point, a non-zero imposed rotation is an error.
fn total(pin: bool, label: Label, c: &mut Cursor, ctx: &ElementContext, span: super::diagnostic::Span) -> Result<Joint, MbdynError> {
    let node = ctx.node(c, if pin { "the node" } else { "node 1" })?;
    let first = total_side(c, &ctx.on(node), Some(node))?;
    let second = if pin {
        let ground = Context { node: Some(Frame::of_node(node)), ..ctx.global() };
        total_side(c, &ground, None)?
    } else {
        let node_b = ctx.node(c, "node 2")?;
        let other = OtherSide { frame: Frame::of_node(node), offset: first.offset, orientation: first.position };
        total_side(c, &Context { other: Some(other), ..ctx.on(node_b) }, Some(node_b))?
    };
    let (pos_locked, imposed_pos) = constraint(c, ctx, "position constraint", &["position", "velocity"])?;
    let (rot_locked, imposed_rot) = constraint(c, ctx, "orientation constraint", &["rotation", "angular velocity"])?;
    if imposed_rot.iter().zip(rot_locked).any(|(x, on)| on && *x != 0.0) {
        return Err(c.error_at(span, "a non-zero imposed relative rotation is not supported by romdyn's total joint"));
    }
    let (any_pos, any_rot) = (pos_locked.contains(&true), rot_locked.contains(&true));
    // A: where the constraints are written (the ground of a pin joint, node 1 otherwise).
    let (a, b) = if pin { (second, first) } else { (first, second) };
    if any_pos && any_rot && (a.position - a.rotation).norm() > 1e-12 {
        return Err(c.error_at(span, "romdyn's total joint uses one constraint frame: with both position and orientation constraints active, 'position orientation' and 'rotation orientation' must be the same"));
    }
    let qa = if any_pos { a.position } else { a.rotation };
    let qb = if any_rot { b.rotation } else { b.position };
    let shift = Vec3::from_fn(|k, _| if pos_locked[k] { imposed_pos[k] } else { 0.0 });
    let j = Joint::total(label, a.anchor(&qa, &shift), b.anchor(&qb, &Vec3::zeros()), pos_locked, rot_locked);
    assembled(j, &a.global(&qa, &shift), &b.global(&qb, &Vec3::zeros()), c, span)
}

/// `KIND, STATUS, STATUS, STATUS, VALUE`: locked components and the constant imposed value.
fn constraint(c: &mut Cursor, ctx: &ElementContext, kind: &str, words: &[&'static str; 2]) -> Result<([bool; 3], Vec3), MbdynError> {
    if !c.accept(kind) {
        return Ok(([false; 3], Vec3::zeros()));
    }
    let mut locked = [false; 3];
    for l in &mut locked {
        let span = c.here();
        *l = match c.accept_any(&["inactive", "active", words[0], words[1]]) {
            Some("inactive") => false,
            Some(w) if w == words[1] => return Err(c.error_at(span, format!("'{w}' (a non-holonomic constraint) is not supported by romdyn's total joint"))),
            Some(_) => true,
            None => c.real(&format!("{kind} status (active, inactive, or 0/1)"))? != 0.0,
        };
    }
    let span = c.here();
    let terms = template_vec3(c, ctx.drives, ctx.seq, &Mat3::identity(), &|c: &mut Cursor| c.vec3_values("imposed value"))?;
    match single_term(terms) {
        Some((v, Drive::Const(x))) => Ok((locked, v * x)),
        _ => Err(c.error_at(span, format!("a time-varying imposed value in the {kind} is not supported by romdyn"))),
    }
}

/// `rod, NODE1, [position, O1,] NODE2, [position, O2,] {L0 | from nodes}, LAW` and `rod with
/// offset, NODE1, O1, NODE2, O2, …` (input manual, §Rod): `F = EA (l − l₀)/l₀` plus,
/// with a viscous or viscoelastic law, `C ε̇`; a
/// prestrain `ε_p` and a prestress `F_p` shift the rest length to `l₀ (1 + ε_p − F_p/EA)`.
fn rod(offsets: bool, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Rod, MbdynError> {
    let position = if offsets { Position::Always } else { Position::IfKeyword };
    let a = side(c, ctx, "node 1", position, None)?;
    let b = side(c, ctx, "node 2", position, Some(&a))?;
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
    // `scalar function elastic [isotropic | orthotropic], FUNCTION`: N = f(ε).
    if c.accept("scalar function elastic isotropic") || c.accept("scalar function elastic orthotropic") || c.accept("scalar function elastic") {
        let f = super::scalar_functions::scalar_function(c, &ctx.drives.functions, ctx.seq)?;
        return Ok(Rod { label, a: a.anchor(), b: b.anchor(), axial_stiffness: 0.0, length: l0, viscous: None, elastic: Some(f) });
    }
    let law: LinearLaw = linear_law(c, 1, ctx.laws, ctx.drives, ctx.seq)?;
    let (ea, viscosity) = (law.stiffness[(0, 0)], law.viscosity[(0, 0)]);
    if ea < 0.0 || viscosity < 0.0 || ea + viscosity == 0.0 {
        return Err(c.error_at(law_span, format!("rod: the axial stiffness EA [N] and viscosity [N s] must not be negative, nor both zero (found {ea}, {viscosity})")));
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
    Ok(Rod { label, a: a.anchor(), b: b.anchor(), axial_stiffness: ea * rest / l0, length: rest, viscous, elastic: None })
}

/// The joint as read: MBDyn's initial assembly (`solve::initial_assembly`, run before every
/// analysis) makes it hold, or names it when it cannot (or when the assembly is skipped).
fn assembled(j: Joint, _a: &(Vec3, Mat3), _b: &(Vec3, Mat3), _c: &Cursor, _span: super::diagnostic::Span) -> Result<Joint, MbdynError> {
    Ok(j)
}
