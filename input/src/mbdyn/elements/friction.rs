//! `friction, [preload, P,] MODEL, SHAPE` after a joint (input manual, §Friction; joint.cc
//! and friction.cc `ParseFriction`, `ParseShapeCoefficient`). romdyn reads the `modlugre`
//! model with the `simple` shape function on an `in line` joint without offset and on a
//! `revolute hinge`, and with the `screw joint` shape function on a `screw`; every other
//! combination is refused by name.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use super::context::ElementContext;
use crate::element::ModLugre;
use crate::mbdyn::drives::scalar_functions;
use crate::mbdyn::syntax::diagnostic;

/// Friction models and shape functions MBDyn 1.7.3 reads (friction.cc).
const MODELS: [&str; 2] = ["modlugre", "discrete coulomb"];
const SHAPES: [&str; 3] = ["simple", "simple plane hinge", "screw joint"];

/// Whether the next word is `friction`.
pub fn follows(c: &Cursor) -> bool {
    c.peek_keyword().is_some_and(|w| w == "friction")
}

/// The joints MBDyn 1.7.3 reads `friction` on (joint.cc: `REVOLUTEHINGE` (with its alias
/// plane hinge), `BRAKE`, `AXIALROTATION`, `J_INLINE`, `SCREWJOINT`).
const MBDYN_FRICTION_JOINTS: [&str; 6] = ["revolute hinge", "plane hinge", "brake", "axial rotation", "in line", "screw"];

/// The clean refusal of friction on a joint romdyn reads it on nowhere (`joint` in MBDyn's
/// words: "plane hinge", "beam slider", …), saying whether MBDyn 1.7.3 reads it there.
pub fn refuse(c: &Cursor, joint: &str) -> MbdynError {
    let what = format!("joint friction on a '{joint}' joint");
    let refusal = if MBDYN_FRICTION_JOINTS.contains(&joint) {
        diagnostic::mbdyn_runs_it(&what)
    } else {
        format!("{what} is read by neither romdyn nor MBDyn 1.7.3 (MBDyn reads friction on revolute hinge, brake, axial rotation, in line and screw joints only)")
    };
    c.error(format!("{refusal} (romdyn reads modlugre friction with the simple shape function on an 'in line' joint without offset and on a 'revolute hinge'; with the screw joint shape function on a 'screw')"))
}

/// Reads `friction, [preload, P,] modlugre, σ₀, σ₁, σ₂, κ, "FUNCTION", simple` and returns
/// the preload [N] (0 if absent, as joint.cc) and the model.
pub fn in_line_friction(c: &mut Cursor, ctx: &ElementContext) -> Result<(f64, ModLugre), MbdynError> {
    c.keyword("friction", &["friction"])?;
    preload_and_model(c, ctx, "in line")
}

/// Reads a revolute hinge's `friction, r, [preload, P,] modlugre, …, simple` (input manual,
/// §Revolute hinge; joint.cc reads the radius first) and returns the radius [m], the preload
/// [N] and the model.
pub fn revolute_hinge_friction(c: &mut Cursor, ctx: &ElementContext) -> Result<(f64, f64, ModLugre), MbdynError> {
    c.keyword("friction", &["friction"])?;
    let radius = positive(c, "friction radius (of the hinge's contact circle) [m]")?;
    let (preload, model) = preload_and_model(c, ctx, "revolute hinge")?;
    Ok((radius, preload, model))
}

/// Reads a screw's `friction, modlugre, …, screw joint, [radius,] r, [half thread angle,] γ`
/// (joint.cc reads no preload on a screw; friction.cc `ParseShapeCoefficient`, the only
/// shape screwjoint.cc accepts) and returns the model, the thread radius [m] and the half
/// thread angle [rad].
pub fn screw_friction(c: &mut Cursor, ctx: &ElementContext) -> Result<(ModLugre, f64, f64), MbdynError> {
    c.keyword("friction", &["friction"])?;
    let model = modlugre(c, ctx)?;
    let span = c.here();
    let shape = c.keyword("a friction shape function", &SHAPES)?;
    if shape != "screw joint" {
        return Err(c.error_at(span, format!("friction shape function '{shape}' on a screw: MBDyn's screw joint accepts only 'screw joint' (screwjoint.cc)")));
    }
    c.accept("radius");
    let radius = positive(c, "screw joint thread radius [m]")?;
    c.accept("half thread angle");
    let angle_span = c.here();
    let angle = c.real("screw joint half thread angle [rad]")?;
    if !(angle.abs() < std::f64::consts::FRAC_PI_2) {
        return Err(c.error_at(angle_span, format!("screw joint: the half thread angle must be below pi/2 in magnitude, found {angle}")));
    }
    Ok((model, radius, angle))
}

/// `[preload, P,] modlugre, σ₀, σ₁, σ₂, κ, "FUNCTION", simple` on a `joint`.
fn preload_and_model(c: &mut Cursor, ctx: &ElementContext, joint: &str) -> Result<(f64, ModLugre), MbdynError> {
    let preload = if c.accept("preload") { c.real("preload (least normal force) [N]")? } else { 0.0 };
    let model = modlugre(c, ctx)?;
    let span = c.here();
    let shape = c.keyword("a friction shape function", &SHAPES)?;
    if shape != "simple" {
        return Err(c.error_at(span, format!("friction shape function '{shape}' on a '{joint}' joint is not supported by romdyn (MBDyn 1.7.3 runs it; supported: simple)")));
    }
    Ok((preload, model))
}

/// `modlugre, σ₀, σ₁, σ₂, κ, "FUNCTION"` (or the refusal of another friction model).
fn modlugre(c: &mut Cursor, ctx: &ElementContext) -> Result<ModLugre, MbdynError> {
    let span = c.here();
    let model = c.keyword("a friction model", &MODELS)?;
    if model != "modlugre" {
        return Err(c.error_at(span, format!("{} (supported: modlugre; discrete coulomb switches its equations between stick and slip, which romdyn's fixed-structure Newton and its linearization do not model)", diagnostic::mbdyn_runs_it(&format!("friction model '{model}'")))));
    }
    let sigma0 = positive(c, "modlugre sigma0 (bristle stiffness per unit normal force) [1/m]")?;
    let sigma1 = c.real("modlugre sigma1 (bristle damping per unit normal force) [s/m]")?;
    let sigma2 = c.real("modlugre sigma2 (viscous friction per unit normal force) [s/m]")?;
    let kappa_span = c.here();
    let kappa = c.real("modlugre kappa (breakaway fraction, 0 < kappa < 1)")?;
    if !(kappa > 0.0 && kappa < 1.0) {
        return Err(c.error_at(kappa_span, format!("modlugre: kappa must be between 0 and 1 (exclusive), found {kappa}")));
    }
    let static_friction = scalar_functions::scalar_function(c, &ctx.drives.functions, ctx.seq)?;
    Ok(ModLugre { sigma0, sigma1, sigma2, kappa, static_friction })
}

fn positive(c: &mut Cursor, what: &str) -> Result<f64, MbdynError> {
    let span = c.here();
    let x = c.real(what)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(c.error_at(span, format!("{what} must be positive, found {x}")))
    }
}
