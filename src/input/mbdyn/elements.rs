//! The `elements` block: bodies, joints, deformable joints, rods, forces, couples, gravity.

use super::cursor::Cursor;
use super::diagnostic::MbdynError;
use crate::element::{Anchor, Couple, DeformableDisplacement, DeformableHinge, Drive, Element, Force, ForceFrame, Joint, LinearViscoelastic, RigidBody, Rod};
use crate::kinematics::{Mat3, Vec3};
use crate::model::{Label, StructuralNode};

/// What an `elements` statement produced.
pub enum Parsed {
    Element(Box<dyn Element>),
    /// Gravity acceleration [m/s²].
    Gravity(Vec3),
}

fn node<'n>(c: &mut Cursor, nodes: &'n [StructuralNode], what: &str) -> Result<&'n StructuralNode, MbdynError> {
    let label = c.label(what)?;
    nodes.iter().find(|n| n.label == label).ok_or_else(|| c.error(format!("structural node {label} is not defined")))
}

/// `node, [position,] offset [, orientation, R]` — an anchor on a node, in its frame.
fn anchor(c: &mut Cursor, nodes: &[StructuralNode], what: &str) -> Result<Anchor, MbdynError> {
    let n = node(c, nodes, what)?;
    c.accept("position");
    let offset = c.vec3("relative offset")?;
    let orientation = if c.accept("orientation") { c.orientation("relative orientation")? } else { Mat3::identity() };
    Ok(Anchor::Node { label: n.label, offset, orientation })
}

/// A 3x3 matrix: `eye`, `null`, `diag, a, b, c`, `sym, 6 values` or 9 values by rows.
fn matrix(c: &mut Cursor, what: &str) -> Result<Mat3, MbdynError> {
    if c.accept("eye") {
        return Ok(Mat3::identity());
    }
    if c.accept("null") {
        return Ok(Mat3::zeros());
    }
    if c.accept("diag") {
        return Ok(Mat3::from_diagonal(&Vec3::new(c.real(what)?, c.real(what)?, c.real(what)?)));
    }
    if c.accept("sym") {
        let v: Vec<f64> = (0..6).map(|_| c.real(what)).collect::<Result<_, _>>()?;
        return Ok(Mat3::new(v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5]));
    }
    let v: Vec<f64> = (0..9).map(|_| c.real(what)).collect::<Result<_, _>>()?;
    Ok(Mat3::from_row_slice(&v))
}

/// A 3-D constitutive law (isotropic scalars or generic matrices).
fn law(c: &mut Cursor) -> Result<LinearViscoelastic, MbdynError> {
    let kinds = ["linear elastic", "linear elastic isotropic", "linear elastic generic", "linear viscoelastic", "linear viscoelastic isotropic", "linear viscoelastic generic"];
    let kind = c.word("a constitutive law", &kinds)?;
    Ok(match kind.as_str() {
        "linear elastic" | "linear elastic isotropic" => LinearViscoelastic::isotropic(c.real("stiffness")?, 0.0),
        "linear elastic generic" => LinearViscoelastic::elastic(matrix(c, "stiffness matrix")?),
        "linear viscoelastic" | "linear viscoelastic isotropic" => {
            let k = c.real("stiffness")?;
            LinearViscoelastic::isotropic(k, c.real("viscosity")?)
        }
        _ => LinearViscoelastic { stiffness: matrix(c, "stiffness matrix")?, viscosity: matrix(c, "viscosity matrix")? },
    })
}

/// Drive callers: const, time, ramp, step, sine, cosine, piecewise linear.
fn drive(c: &mut Cursor) -> Result<Drive, MbdynError> {
    let kind = c.word("a drive", &["const", "time", "ramp", "step", "sine", "cosine", "piecewise linear"])?;
    let cycles = |c: &mut Cursor| -> Result<Option<f64>, MbdynError> {
        if c.accept("forever") {
            Ok(None)
        } else if c.accept("one") {
            Ok(Some(1.0))
        } else if c.accept("half") {
            Ok(Some(0.5))
        } else {
            c.real("number of cycles (or forever, one, half)").map(Some)
        }
    };
    Ok(match kind.as_str() {
        "const" => Drive::Const(c.real("constant value")?),
        "time" => Drive::Time,
        "ramp" => {
            let (slope, t0) = (c.real("slope")?, c.real("initial time")?);
            let t1 = if c.accept("forever") { f64::INFINITY } else { c.real("final time (or forever)")? };
            Drive::Ramp { slope, t0, t1, v0: c.real("initial value")? }
        }
        "step" => Drive::Step { t0: c.real("initial time")?, value: c.real("step value")?, v0: c.real("initial value")? },
        "sine" | "cosine" => {
            let (t0, omega, amplitude) = (c.real("initial time")?, c.real("angular frequency [rad/s]")?, c.real("amplitude")?);
            let (cycles, v0) = (cycles(c)?, c.real("initial value")?);
            if kind == "sine" { Drive::Sine { t0, omega, amplitude, cycles, v0 } } else { Drive::Cosine { t0, omega, amplitude, cycles, v0 } }
        }
        _ => {
            let n = c.label("number of points")?;
            let points = (0..n).map(|_| Ok((c.real("time")?, c.real("value")?))).collect::<Result<Vec<_>, MbdynError>>()?;
            Drive::PiecewiseLinear(points)
        }
    })
}

/// `single, dx, dy, dz, <drive>` or the older `dx, dy, dz, <drive>`.
fn vector_drive(c: &mut Cursor) -> Result<(Vec3, Drive), MbdynError> {
    c.accept("single");
    let dir = Vec3::new(c.real("direction x")?, c.real("direction y")?, c.real("direction z")?);
    Ok((dir, drive(c)?))
}

fn joint(c: &mut Cursor, label: Label, nodes: &[StructuralNode]) -> Result<Box<dyn Element>, MbdynError> {
    let kinds = ["clamp", "revolute hinge", "spherical hinge", "deformable displacement joint", "deformable hinge", "rod"];
    let Some(kind) = c.peek_word().map(str::to_string) else {
        return Err(c.error(format!("expected a joint type ({})", kinds.join(", "))));
    };
    if !kinds.contains(&kind.as_str()) {
        return Err(c.error(format!("joint type '{kind}' is not supported by romdyn (supported: {})", kinds.join(", "))));
    }
    c.word("a joint type", &kinds)?;
    Ok(match kind.as_str() {
        "clamp" => {
            let n = node(c, nodes, "clamped node")?;
            let position = if c.accept("node") { n.position } else { c.vec3("clamp position")? };
            let orientation = if c.accept("node") { n.orientation } else { c.orientation("clamp orientation")? };
            Box::new(Joint::clamp(label, n.label, position, orientation))
        }
        "revolute hinge" => Box::new(Joint::revolute_hinge(label, anchor(c, nodes, "node 1")?, anchor(c, nodes, "node 2")?)),
        "spherical hinge" => Box::new(Joint::spherical_hinge(label, anchor(c, nodes, "node 1")?, anchor(c, nodes, "node 2")?)),
        "deformable displacement joint" => {
            let (a, b) = (anchor(c, nodes, "node 1")?, anchor(c, nodes, "node 2")?);
            Box::new(DeformableDisplacement { label, a, b, law: law(c)?, rest: Vec3::zeros() })
        }
        "deformable hinge" => {
            let (a, b) = (anchor(c, nodes, "node 1")?, anchor(c, nodes, "node 2")?);
            Box::new(DeformableHinge { label, a, b, law: law(c)? })
        }
        _ => {
            let (a, b) = (anchor(c, nodes, "node 1")?, anchor(c, nodes, "node 2")?);
            let point = |x: &Anchor| match x {
                Anchor::Node { label, offset, .. } => nodes.iter().find(|n| n.label == *label).map_or(*offset, |n| n.position + n.orientation * offset),
                Anchor::Ground { position, .. } => *position,
            };
            let length = if c.accept("from nodes") { (point(&b) - point(&a)).norm() } else { c.real("unstretched length [m] (or from nodes)")? };
            c.word("a rod law", &["linear elastic"])?;
            Box::new(Rod { label, a, b, axial_stiffness: c.real("axial stiffness EA [N]")?, length })
        }
    })
}

/// One statement of the `elements` block.
pub fn element(keyword: &str, c: &mut Cursor, nodes: &[StructuralNode]) -> Result<Parsed, MbdynError> {
    if keyword == "gravity" {
        c.accept("uniform");
        let (dir, d) = vector_drive(c)?;
        return Ok(Parsed::Gravity(dir * d.value(0.0)));
    }
    let label = c.label(&format!("{keyword} label"))?;
    let e: Box<dyn Element> = match keyword {
        "body" => {
            let n = node(c, nodes, "node of the body")?;
            let mass = c.real("mass [kg]")?;
            let offset = c.vec3("centre of mass offset [m]")?;
            Box::new(RigidBody::new(label, n.label, mass, offset, matrix(c, "inertia [kg m^2]")?))
        }
        "joint" => joint(c, label, nodes)?,
        "force" | "couple" => {
            let frame = match c.word("the force frame", &["absolute", "follower"])?.as_str() {
                "absolute" => ForceFrame::Absolute,
                _ => ForceFrame::Follower,
            };
            let n = node(c, nodes, "node")?;
            if keyword == "force" {
                c.accept("position");
                let offset = c.vec3("arm [m]")?;
                let (direction, drive) = vector_drive(c)?;
                Box::new(Force { label, node: n.label, frame, direction, offset, drive })
            } else {
                if c.accept("position") {
                    c.vec3("arm [m]")?;
                }
                let (direction, drive) = vector_drive(c)?;
                Box::new(Couple { label, node: n.label, frame, direction, drive })
            }
        }
        other => return Err(c.error(format!("element type '{other}' is not supported by romdyn"))),
    };
    Ok(Parsed::Element(e))
}
