//! The arguments the `hydraulic` cards share (input manual §Hydraulic fluid, §Hydraulic
//! Element; hfluid.cc, preselem.cc): a fluid's properties, written in place or referenced,
//! positive values, a pipe's geometry, the `output` flag, the nodes' initial pressures.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{mbdyn_runs_it, MbdynError};
use super::context::ElementContext;
use crate::element::HydraulicFluid;

/// A positive real, refused otherwise with `why`.
pub(in crate::mbdyn) fn positive(c: &mut Cursor, what: &str, why: &str) -> Result<f64, MbdynError> {
    let span = c.here();
    let x = c.real(what)?;
    if !(x > f64::EPSILON) {
        return Err(c.error_at(span, format!("{what} must be positive, found {x}{why}")));
    }
    Ok(x)
}

/// `[TYPE,] PROPERTIES` of a fluid (hfluid.cc: the type defaults to `incompressible`):
/// `incompressible, density, RHO, viscosity, MU [, pressure, P0] [, temperature, T0]` and
/// `linear compressible, density, RHO, {BETA | sound celerity, C}, P0, viscosity, MU [,
/// temperature, T0]`, in MBDyn's order.
pub(in crate::mbdyn) fn fluid_properties(c: &mut Cursor, what: &str) -> Result<HydraulicFluid, MbdynError> {
    let span = c.here();
    if let Some(k) = c.accept_any(&["linear thermal compressible", "super", "exponential"]) {
        return Err(c.error_at(span, format!("{what}: {} (supported: incompressible, linear compressible)", mbdyn_runs_it(&format!("the fluid type '{k}'")))));
    }
    let compressible = c.accept("linear compressible");
    if !compressible {
        c.accept_any(&["incompressible", "uncompressible"]);
    }
    // hfluid.cc refuses a missing or non-positive density and viscosity ("illegal density").
    c.keyword(&format!("{what}: 'density'"), &["density"])?;
    let density = positive(c, "density [kg/m^3]", "")?;
    let compressibility = if compressible {
        let beta = if c.accept("sound celerity") { density * positive(c, "sound celerity [m/s]", "")?.powi(2) } else { positive(c, "bulk modulus [Pa]", " (MBDyn 1.7.3 refuses only a null one; a negative one makes a fluid that expands under pressure)")? };
        Some((beta, c.real("reference pressure [Pa]")?))
    } else {
        None
    };
    c.keyword(&format!("{what}: 'viscosity' (MBDyn 1.7.3 requires a positive viscosity)"), &["viscosity"])?;
    let viscosity = positive(c, "viscosity [Pa s]", "")?;
    let fluid = match compressibility {
        Some((bulk_modulus, pressure)) => HydraulicFluid::LinearCompressible { density, bulk_modulus, pressure, viscosity },
        None => HydraulicFluid::Incompressible { density, viscosity },
    };
    if !compressible && c.accept("pressure") {
        c.real("reference pressure [Pa]")?;
    }
    if c.accept("temperature") {
        c.real("reference temperature [K]")?;
    }
    Ok(fluid)
}

/// `fluid, {reference, LABEL | FLUID}` (or `hydraulic fluid, …`) in an element.
pub(in crate::mbdyn) fn element_fluid(c: &mut Cursor, ctx: &ElementContext, what: &str) -> Result<HydraulicFluid, MbdynError> {
    c.keyword(&format!("{what}: 'fluid'"), &["fluid", "hydraulic fluid"])?;
    if !c.accept("reference") {
        return fluid_properties(c, what);
    }
    let span = c.here();
    let label = c.label("hydraulic fluid label")?;
    match ctx.fluids.get(&label) {
        Some((fluid, seq, _)) if *seq < ctx.seq => Ok(*fluid),
        _ => Err(c.error_at(span, format!("{what}: hydraulic fluid {label} is not defined above this element"))),
    }
}

/// The arguments a `pipe` and a `dynamic pipe` share after their nodes.
pub(in crate::mbdyn) struct PipeCard {
    pub diameter: f64,
    pub area: f64,
    pub length: f64,
    pub turbulent: bool,
    pub initial_flow: f64,
    pub fluid: HydraulicFluid,
}

/// `DIAMETER, [area, A,] LENGTH, [turbulent,] [initial value, Q0,] fluid, …` (the area
/// defaults to the diameter's circle).
pub(in crate::mbdyn) fn pipe_card(c: &mut Cursor, ctx: &ElementContext, what: &str) -> Result<PipeCard, MbdynError> {
    let diameter = positive(c, &format!("{what}: hydraulic diameter [m]"), "")?;
    let area = if c.accept("area") { positive(c, &format!("{what}: area [m^2]"), "")? } else { diameter * diameter * std::f64::consts::FRAC_PI_4 };
    let length = positive(c, &format!("{what}: length [m]"), "")?;
    let turbulent = c.accept("turbulent");
    let initial_flow = if c.accept("initial value") { c.real("initial mass flow [kg/s]")? } else { 0.0 };
    let fluid = element_fluid(c, ctx, what)?;
    Ok(PipeCard { diameter, area, length, turbulent, initial_flow, fluid })
}

/// A scalar node's initial value (its card's), where elements start their own unknowns.
pub(in crate::mbdyn) fn initial_value(ctx: &ElementContext, id: crate::model::ScalarNodeId) -> f64 {
    ctx.nodes.2.iter().find(|e| e.node.id == id).map_or(0.0, |e| e.node.value)
}

/// `[output, FLAG]` at the end of a hydraulic element (MBDyn's `fReadOutput`): the card's
/// flag, else control data's `default output` of hydraulic elements.
pub(in crate::mbdyn) fn output_flag(c: &mut Cursor, ctx: &ElementContext) -> Result<bool, MbdynError> {
    if c.accept("output") {
        return c.flag("output flag");
    }
    Ok(ctx.hydraulic_output)
}
