//! The `electric` element cards (input manual §Electric Elements; elec.cc, `ReadElectric`):
//! `motor`, `displacement` and `accelerometer` (translational, rotational); the legacy
//! accelerometer with its built-in transfer function and `discrete control` are refused by
//! name.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{mbdyn_runs_it, MbdynError};
use super::context::ElementContext;
use crate::mbdyn::nodes::scalar::{scalar_node_of, ScalarEntry};
use crate::element::drive::Drive;
use crate::element::{Accelerometer, AccelerometerKind, Cogging, DisplacementSensor, Element, Motor};
use crate::model::{Label, ScalarNodeId, ScalarNodeKind};
use crate::mbdyn::drives::callers;
use crate::mbdyn::syntax::diagnostic;

/// `electric: LABEL, TYPE, …` after the label.
pub fn electric(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let span = c.here();
    let types = ["motor", "displacement", "accelerometer"];
    if c.accept("discrete control") {
        return Err(c.error_at(span, format!("{} (supported: {})", mbdyn_runs_it("electric element type 'discrete control'"), types.join(", "))));
    }
    let Some(kind) = c.accept_any(&types) else {
        return Err(match c.peek_keyword() {
            Some(w) => c.error(format!("{} (romdyn reads: {})", diagnostic::unknown_to_both("electric element type", w), types.join(", "))),
            None => c.error(format!("expected the electric element type ({}), found {}", types.join(", "), c.found())),
        });
    };
    let what = format!("electric {label} ({kind})");
    let e: Box<dyn Element> = match kind {
        "motor" => motor(label, c, ctx, &what)?,
        "displacement" => {
            let mut nodes = [0; 2];
            let mut offsets = [crate::kinematics::Vec3::zeros(); 2];
            for k in 0..2 {
                let n = ctx.node(c, &format!("{what}: structural node {}", k + 1))?;
                c.accept("position");
                nodes[k] = n.label;
                offsets[k] = ctx.on(n).relative_position(c, &format!("{what}: offset {} [m]", k + 1))?;
            }
            let output = differential_abstract(c, &ctx.nodes.2, &what)?;
            Box::new(DisplacementSensor { label, nodes, offsets, output })
        }
        _ => accelerometer(label, c, ctx, &what)?,
    };
    Ok(e)
}

/// An abstract node that is differential (the sensors' output: MBDyn 1.7.3 reads a
/// `ScalarDifferentialNode`).
fn differential_abstract(c: &mut Cursor, nodes: &[ScalarEntry], what: &str) -> Result<ScalarNodeId, MbdynError> {
    let span = c.here();
    let id = scalar_node_of(c, nodes, ScalarNodeKind::Abstract, what)?;
    if nodes.iter().any(|e| e.node.id == id && !e.node.differential) {
        return Err(c.error_at(span, format!("{what}: {id} is algebraic; MBDyn 1.7.3 writes a sensor into a differential abstract node")));
    }
    Ok(id)
}

/// `motor, NODE1, NODE2, {DIR | orientation, R}, V1, V2, G, L, R [, initial current, I0]`.
fn motor(label: Label, c: &mut Cursor, ctx: &ElementContext, what: &str) -> Result<Box<dyn Element>, MbdynError> {
    let n1 = ctx.node(c, &format!("{what}: structural node 1"))?;
    let n2 = ctx.node(c, &format!("{what}: structural node 2"))?;
    let on = ctx.on(n1);
    let dir_span = c.here();
    let mut frame = None;
    let axis = if c.accept("orientation") {
        let r = on.relative_orientation(c, &format!("{what}: orientation (axis 3 is the motor's)"))?;
        frame = Some(r);
        r.column(2).into_owned()
    } else {
        on.relative_vector(c, &format!("{what}: axis"))?.try_normalize(0.0).ok_or_else(|| c.error_at(dir_span, format!("{what}: the axis is null (MBDyn 1.7.3: \"illegal motor direction\")")))?
    };
    let v1 = scalar_node_of(c, &ctx.nodes.2, ScalarNodeKind::Electric, what)?;
    let v2 = scalar_node_of(c, &ctx.nodes.2, ScalarNodeKind::Electric, what)?;
    let gain = c.real("motor gain G [N m/A]")?;
    let l_span = c.here();
    let inductance = c.real("inductance L [H]")?;
    if !(inductance > 0.0) {
        return Err(c.error_at(l_span, format!("{what}: the inductance must be positive, found {inductance} (the current is a differential unknown with L di/dt in its equation; MBDyn 1.7.3 divides by L for its initial rate)")));
    }
    let r_span = c.here();
    let resistance = match callers::drive(c, ctx.drives, ctx.seq)? {
        Drive::Const(r) => r,
        _ => return Err(c.error_at(r_span, format!("{what}: {}", mbdyn_runs_it("a resistance that varies with the current (a drive caller of |i|)")))),
    };
    let initial_current = if c.accept("initial current") { c.real("initial current [A]")? } else { 0.0 };
    let cogging = cogging(c, ctx, what, frame)?;
    // motor.cc's constructor: `iP = (V₂ − V₁ − G ω − R i₀)/L` at the written state.
    let value = |id| ctx.nodes.2.iter().find(|e: &&ScalarEntry| e.node.id == id).map_or(0.0, |e| e.node.value);
    let omega = (n1.orientation * axis).dot(&(n2.angular_velocity - n1.angular_velocity));
    let initial_rate = (value(v2) - value(v1) - gain * omega - resistance * initial_current) / inductance;
    Ok(Box::new(Motor { label, nodes: [n1.label, n2.label], axis, voltages: [v1, v2], gain, inductance, resistance, initial_current, initial_rate, cogging }))
}

/// `[M0, DRIVE,] [M1, DRIVE,] terminal pairs, P` of a motor with an `orientation` (elec.cc:
/// either drive needs the orientation and the pairs; a missing one is zero).
fn cogging(c: &mut Cursor, ctx: &ElementContext, what: &str, frame: Option<crate::kinematics::Mat3>) -> Result<Option<Cogging>, MbdynError> {
    let span = c.here();
    let read = |c: &mut Cursor, key: &str| -> Result<Option<Drive>, MbdynError> {
        if !c.accept(key) {
            return Ok(None);
        }
        let at = c.here();
        let d = callers::drive(c, ctx.drives, ctx.seq)?;
        if !Cogging::differentiable(&d) {
            return Err(c.error_at(at, format!("{what}: {} (the Jacobian needs the slope of '{key}' in the electrical angle: romdyn differentiates const, ramp, step, sine, cosine, polynomial, exponential, tanh drives, their sums and products)", mbdyn_runs_it("this cogging drive"))));
        }
        Ok(Some(d))
    };
    let (m0, m1) = (read(c, "M0")?, read(c, "M1")?);
    if m0.is_none() && m1.is_none() {
        return Ok(None);
    }
    let Some(frame) = frame else {
        return Err(c.error_at(span, format!("{what}: \"M0\" and \"M1\" require the motor's 'orientation' instead of an axis (MBDyn 1.7.3 refuses it too)")));
    };
    c.keyword(&format!("{what}: 'terminal pairs' (MBDyn 1.7.3 requires it after M0, M1)"), &["terminal pairs"])?;
    let p_span = c.here();
    let pairs = c.integer("number of terminal pairs")?;
    if pairs < 1 {
        return Err(c.error_at(p_span, format!("{what}: the number of terminal pairs must be at least 1, found {pairs} (MBDyn 1.7.3: \"must be greater than zero\")")));
    }
    Ok(Some(Cogging { frame, pairs: pairs as f64, m0: m0.unwrap_or(Drive::Const(0.0)), m1: m1.unwrap_or(Drive::Const(0.0)) }))
}

/// `accelerometer, {translational | rotational}, NODE, ABSTRACT, DIR [, position, OFFSET]`.
fn accelerometer(label: Label, c: &mut Cursor, ctx: &ElementContext, what: &str) -> Result<Box<dyn Element>, MbdynError> {
    let span = c.here();
    let kind = match c.accept_any(&["translational", "rotational"]) {
        Some("translational") => AccelerometerKind::Translational,
        Some(_) => AccelerometerKind::Rotational,
        None => return Err(c.error_at(span, format!("{what}: {} (romdyn reads 'translational' and 'rotational' accelerometers)", mbdyn_runs_it("the legacy accelerometer with its built-in transfer function")))),
    };
    let n = ctx.node(c, &format!("{what}: structural node"))?;
    let output = differential_abstract(c, &ctx.nodes.2, what)?;
    let on = ctx.on(n);
    let dir_span = c.here();
    let direction = on.relative_vector(c, &format!("{what}: direction"))?.try_normalize(0.0).ok_or_else(|| c.error_at(dir_span, format!("{what}: the direction is null (MBDyn 1.7.3: \"null direction\")")))?;
    // accelerometer.cc reads an offset after `position` or `offset`, and always on a
    // translational one.
    let offset = if c.accept_any(&["position", "offset"]).is_some() || kind == AccelerometerKind::Translational {
        on.relative_position(c, &format!("{what}: offset [m]"))?
    } else {
        crate::kinematics::Vec3::zeros()
    };
    let (d, arm) = (n.orientation * direction, n.orientation * offset);
    let initial_velocity = match kind {
        AccelerometerKind::Translational => d.dot(&(n.velocity + n.angular_velocity.cross(&arm))),
        AccelerometerKind::Rotational => d.dot(&n.angular_velocity),
    };
    Ok(Box::new(Accelerometer { label, kind, node: n.label, output, direction, offset, initial_velocity }))
}
