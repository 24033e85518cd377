//! Reference frames (input manual, "General", §Reference and §Use of Reference Frames):
//! `reference: LABEL, position, orientation, velocity, angular velocity;` and every entity
//! written `reference, {global | local | node | other node | other position |
//! other orientation | LABEL}, …` wherever MBDyn reads a position, an orientation, a
//! velocity, an angular velocity, a vector or a matrix.
//!
//! A frame is `(x_F, R_F, v_F, ω_F)`. In frame F, an absolute position `p` is
//! `x_F + R_F p`, an orientation `R_F R`, a vector `R_F v`, a velocity of a point at `x`
//! `R_F v + v_F + ω_F × (x − x_F)`, an angular velocity `R_F ω + ω_F`. Entities relative
//! to a node `n` (element offsets) are the same global quantities seen from the node:
//! `R_nᵀ (P − x_n)`, `R_nᵀ Q`, `R_nᵀ V`. A reference must be defined before it is used.

use std::collections::HashMap;

use super::cursor::Cursor;
use super::diagnostic::{MbdynError, Span};
use super::orientation::orientation_values;
use super::parser::Statement;
use crate::kinematics::{Mat3, Vec3};
use crate::model::StructuralNode;

/// Position, orientation, velocity and angular velocity of a frame, in the global frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub x: Vec3,
    pub r: Mat3,
    pub v: Vec3,
    pub w: Vec3,
}

impl Frame {
    pub fn global() -> Frame {
        Frame { x: Vec3::zeros(), r: Mat3::identity(), v: Vec3::zeros(), w: Vec3::zeros() }
    }
    pub fn of_node(n: &StructuralNode) -> Frame {
        Frame { x: n.position, r: n.orientation, v: n.velocity, w: n.angular_velocity }
    }
}

/// The `reference:` cards read so far, and the labels of those still to come.
#[derive(Default)]
pub struct Frames {
    table: HashMap<u32, (Frame, usize, Span)>,
    later: HashMap<u32, Span>,
}

impl Frames {
    /// Frame `label` as seen from statement `seq`.
    pub fn get(&self, label: u32, seq: usize, span: Span, c: &Cursor, defining: Option<u32>) -> Result<Frame, MbdynError> {
        if defining == Some(label) {
            return Err(c.error_at(span, format!("reference {label} is used in its own definition")));
        }
        match self.table.get(&label) {
            Some((f, s, _)) if *s < seq => Ok(*f),
            Some((_, _, at)) => Err(c.error_at(span, format!("reference {label} is used before its definition (line {}): a reference must be defined before it is used", at.line))),
            None => match self.later.get(&label) {
                Some(at) => Err(c.error_at(span, format!("reference {label} is used before its definition (line {}): a reference must be defined before it is used", at.line))),
                None => Err(c.error_at(span, format!("reference {label} is not defined"))),
            },
        }
    }

    /// Notes that reference `label` is defined at `span` further on (for messages).
    pub fn announce(&mut self, label: u32, span: Span) {
        self.later.entry(label).or_insert(span);
    }
}

/// The second node of a two-node element refers to the first with `other …`.
#[derive(Clone, Copy)]
pub struct OtherSide {
    pub frame: Frame,
    /// Offset and orientation already read for the first node, in its frame.
    pub offset: Vec3,
    pub orientation: Mat3,
}

/// What the frames of a `reference, …` prefix mean where an entity is read.
#[derive(Clone, Copy)]
pub struct Context<'a> {
    pub frames: &'a Frames,
    /// The statement reading the entity: references must come before it.
    pub seq: usize,
    /// The element's node (`reference, node`; relative entities are seen from it).
    pub node: Option<Frame>,
    pub other: Option<OtherSide>,
    /// The reference being defined (to report its use in its own definition).
    pub defining: Option<u32>,
}

impl<'a> Context<'a> {
    pub fn global(frames: &'a Frames, seq: usize) -> Self {
        Context { frames, seq, node: None, other: None, defining: None }
    }
    pub fn on_node(frames: &'a Frames, seq: usize, node: &StructuralNode) -> Self {
        Context { frames, seq, node: Some(Frame::of_node(node)), other: None, defining: None }
    }

    /// Reads an optional `reference, X,` prefix; `None` when absent.
    fn prefix(&self, c: &mut Cursor) -> Result<Option<Frame>, MbdynError> {
        if !c.accept("reference") {
            return Ok(None);
        }
        let span = c.here();
        let kinds = ["global", "local", "node", "other node", "other position", "other orientation"];
        if let Some(kind) = c.accept_any(&kinds) {
            return Ok(Some(match kind {
                "global" => Frame::global(),
                "local" => self.node.unwrap_or_else(Frame::global),
                "node" => self.node.ok_or_else(|| c.error_at(span, "'reference, node' has no node here"))?,
                _ => {
                    let o = self.other.ok_or_else(|| c.error_at(span, format!("'reference, {kind}' is only allowed for the second node of a joint")))?;
                    match kind {
                        "other node" => o.frame,
                        "other position" => Frame { x: o.frame.x + o.frame.r * o.offset, ..o.frame },
                        _ => Frame { r: o.frame.r * o.orientation, ..o.frame },
                    }
                }
            }));
        }
        let label = c.label("a reference frame: global, node, other node, other position, other orientation, or a reference label")?;
        self.frames.get(label, self.seq, span, c, self.defining).map(Some)
    }

    fn default_frame(&self) -> Frame {
        self.node.unwrap_or_else(Frame::global)
    }

    /// An absolute position (default frame: global).
    pub fn position(&self, c: &mut Cursor, what: &str) -> Result<Vec3, MbdynError> {
        let f = self.prefix(c)?.unwrap_or_else(Frame::global);
        Ok(f.x + f.r * c.vec3_values(what)?)
    }

    /// An absolute orientation (default frame: global).
    pub fn orientation(&self, c: &mut Cursor, what: &str) -> Result<Mat3, MbdynError> {
        let f = self.prefix(c)?.unwrap_or_else(Frame::global);
        Ok(f.r * orientation_values(c, what)?)
    }

    /// The absolute velocity of the point at `x` (default frame: global).
    pub fn velocity(&self, c: &mut Cursor, what: &str, x: &Vec3) -> Result<Vec3, MbdynError> {
        let f = self.prefix(c)?.unwrap_or_else(Frame::global);
        Ok(f.r * c.vec3_values(what)? + f.v + f.w.cross(&(x - f.x)))
    }

    /// An absolute angular velocity (default frame: global).
    pub fn angular_velocity(&self, c: &mut Cursor, what: &str) -> Result<Vec3, MbdynError> {
        let f = self.prefix(c)?.unwrap_or_else(Frame::global);
        Ok(f.r * c.vec3_values(what)? + f.w)
    }

    /// A vector in the global frame; `default` is the frame when no prefix is given.
    pub fn vector_in(&self, c: &mut Cursor, what: &str, default: Frame) -> Result<Vec3, MbdynError> {
        let f = self.prefix(c)?.unwrap_or(default);
        Ok(f.r * c.vec3_values(what)?)
    }

    /// A point relative to the node: offset in the node frame (default frame: the node).
    pub fn relative_position(&self, c: &mut Cursor, what: &str) -> Result<Vec3, MbdynError> {
        let n = self.default_frame();
        let f = self.prefix(c)?.unwrap_or(n);
        Ok(n.r.transpose() * (f.x + f.r * c.vec3_values(what)? - n.x))
    }

    /// An orientation relative to the node (default frame: the node).
    pub fn relative_orientation(&self, c: &mut Cursor, what: &str) -> Result<Mat3, MbdynError> {
        let n = self.default_frame();
        let f = self.prefix(c)?.unwrap_or(n);
        Ok(n.r.transpose() * f.r * orientation_values(c, what)?)
    }

    /// A vector in the node frame (default frame: the node).
    pub fn relative_vector(&self, c: &mut Cursor, what: &str) -> Result<Vec3, MbdynError> {
        let n = self.default_frame();
        let f = self.prefix(c)?.unwrap_or(n);
        Ok(n.r.transpose() * f.r * c.vec3_values(what)?)
    }

    /// A tensor (inertia) in the node frame (default frame: the node).
    pub fn relative_matrix(&self, c: &mut Cursor, what: &str) -> Result<Mat3, MbdynError> {
        let n = self.default_frame();
        let f = self.prefix(c)?.unwrap_or(n);
        let q = n.r.transpose() * f.r;
        Ok(q * c.mat3x3(what)? * q.transpose())
    }
}

/// Reads a `reference:` card into `frames`.
pub fn reference(st: &Statement, c: &mut Cursor, frames: &mut Frames) -> Result<(), MbdynError> {
    let span = c.here();
    let label = c.label("reference label")?;
    if let Some((_, _, at)) = frames.table.get(&label) {
        return Err(c.error_at(span, format!("reference {label} is defined twice (first at line {})", at.line)));
    }
    if c.accept("name") {
        c.string("reference name")?;
    }
    let ctx = Context { defining: Some(label), ..Context::global(frames, st.seq) };
    let frame = if c.accept("denavit hartenberg") {
        denavit_hartenberg(&ctx, c)?
    } else {
        // Each entity may be introduced by its keyword (input manual, §Reference).
        c.accept("position");
        let x = ctx.position(c, "reference position [m]")?;
        c.accept("orientation");
        let r = ctx.orientation(c, "reference orientation")?;
        c.accept("velocity");
        let v = ctx.velocity(c, "reference velocity [m/s]", &x)?;
        c.accept("angular velocity");
        let w = ctx.angular_velocity(c, "reference angular velocity [rad/s]")?;
        Frame { x, r, v, w }
    };
    c.finish()?;
    frames.table.insert(label, (frame, st.seq, st.span));
    Ok(())
}

/// `Denavit Hartenberg, [reference, X,] d, theta, a, alpha` (input manual, §Reference).
fn denavit_hartenberg(ctx: &Context, c: &mut Cursor) -> Result<Frame, MbdynError> {
    let old = ctx.prefix(c)?.unwrap_or_else(Frame::global);
    let (d, theta, a, alpha) = (c.real("d [m]")?, c.real("theta [rad]")?, c.real("a [m]")?, c.real("alpha [rad]")?);
    let rz = *nalgebra::Rotation3::from_axis_angle(&Vec3::z_axis(), theta).matrix();
    let rx = *nalgebra::Rotation3::from_axis_angle(&Vec3::x_axis(), alpha).matrix();
    let arm = old.r * (d * Vec3::z() + rz * (a * Vec3::x()));
    Ok(Frame { x: old.x + arm, r: old.r * rz * rx, v: old.v + old.w.cross(&arm), w: old.w })
}
