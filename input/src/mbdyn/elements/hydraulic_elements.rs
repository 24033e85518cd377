//! The `hydraulic` cards `dynamic pipe`, `accumulator`, `tank` and `orifice` (input manual
//! §Hydraulic Element; preselem.cc, `ReadHydraulicElem`), after the element's type: their
//! arguments in MBDyn 1.7.3's order, refused where preselem.cc refuses them (with its
//! message), and where a value would make the element's equations meaningless.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use super::context::ElementContext;
use super::hydraulic_args::{element_fluid, initial_value, output_flag, pipe_card, positive, PipeCard};
use crate::element::{Accumulator, DynamicPipe, Element, Orifice, Tank};
use crate::model::{Label, ScalarNodeId};

/// A real that must not be negative.
fn not_negative(c: &mut Cursor, what: &str) -> Result<f64, MbdynError> {
    let span = c.here();
    let x = c.real(what)?;
    if !(x >= 0.0) {
        return Err(c.error_at(span, format!("{what} must not be negative, found {x}")));
    }
    Ok(x)
}

/// `dynamic pipe, P1, P2, DIAMETER, [area, A,] LENGTH, [turbulent,] [initial value, Q0,]
/// fluid, …` after its nodes (the area defaults to the diameter's circle).
pub fn dynamic_pipe(label: Label, c: &mut Cursor, ctx: &ElementContext, what: &str, pressures: [ScalarNodeId; 2]) -> Result<Box<dyn Element>, MbdynError> {
    let PipeCard { diameter, area, length, turbulent, initial_flow, fluid } = pipe_card(c, ctx, what)?;
    let initial_pressures = pressures.map(|id| initial_value(ctx, id));
    let output = output_flag(c, ctx)?;
    Ok(Box::new(DynamicPipe { label, pressures, diameter, area, length, fluid, turbulent, initial_pressures, initial_flow, output }))
}

/// `orifice, P1, P2, DIAMETER, ORIFICE_AREA, [area, PIPE_AREA,] [reynolds, RE_CR,] fluid, …`
/// after its nodes.
pub fn orifice(label: Label, c: &mut Cursor, ctx: &ElementContext, what: &str, pressures: [ScalarNodeId; 2]) -> Result<Box<dyn Element>, MbdynError> {
    let span = c.here();
    let diameter = positive(c, &format!("{what}: diameter [m]"), "")?;
    let orifice_area = positive(c, &format!("{what}: orifice area [m^2]"), "")?;
    // preselem.cc's default pipe area, 0.785 D² (π/4 rounded).
    let pipe_area = if c.accept("area") { positive(c, &format!("{what}: pipe area [m^2]"), "")? } else { diameter * diameter * 0.785 };
    let reynolds = if c.accept("reynolds") { positive(c, &format!("{what}: critical Reynolds number"), "")? } else { 10.0 };
    let fluid = element_fluid(c, ctx, what)?;
    let rho = fluid.density(0.5 * (initial_value(ctx, pressures[0]) + initial_value(ctx, pressures[1])));
    let Some((critical_jump, discharge)) = Orifice::coefficients(diameter, orifice_area, pipe_area, reynolds, rho, fluid.viscosity()) else {
        return Err(c.error_at(span, format!("{what}: the orifice area {orifice_area} m^2 against the pipe's {pipe_area} m^2 gives no discharge coefficient (1 - (Cc Ao/Ap)^2 <= 0; MBDyn 1.7.3: \"error computing Cd\")")));
    };
    let output = output_flag(c, ctx)?;
    Ok(Box::new(Orifice { label, pressures, diameter, orifice_area, pipe_area, critical_jump, discharge, fluid, output }))
}

/// `accumulator, P, STROKE, [start, S0,] AREA, PIPE_AREA, MASS, [lossin, H_IN,] [lossout,
/// H_OUT,] [gas, P0, PMAX, KAPPA,] [weight, W,] [spring, K, F0,] C_S, C_V, C_A, fluid, …`
/// after its node.
pub fn accumulator(label: Label, c: &mut Cursor, ctx: &ElementContext, what: &str, pressure: ScalarNodeId) -> Result<Box<dyn Element>, MbdynError> {
    let stroke = positive(c, &format!("{what}: stroke [m]"), "")?;
    let start = if c.accept("start") {
        let span = c.here();
        let s = c.real(&format!("{what}: initial stroke [m]"))?;
        if !(s <= stroke) {
            return Err(c.error_at(span, format!("{what}: the initial stroke {s} m exceeds the stroke {stroke} m (MBDyn 1.7.3: \"stroke less then initial position\")")));
        }
        s
    } else {
        0.0
    };
    let area = positive(c, &format!("{what}: area [m^2]"), "")?;
    let pipe_area = positive(c, &format!("{what}: pipe area [m^2]"), "")?;
    let mass = positive(c, &format!("{what}: mass [kg]"), "")?;
    let loss_in = if c.accept("lossin") { not_negative(c, &format!("{what}: loss coefficient in"))? } else { 1.0 };
    let loss_out = if c.accept("lossout") { not_negative(c, &format!("{what}: loss coefficient out"))? } else { 0.5 };
    let gas = if c.accept("gas") {
        let p0 = positive(c, &format!("{what}: gas pressure when empty [Pa]"), "")?;
        let pmax = positive(c, &format!("{what}: largest gas pressure [Pa]"), "")?;
        [p0, pmax, not_negative(c, &format!("{what}: polytropic exponent"))?]
    } else {
        [0.0; 3]
    };
    let weight = if c.accept("weight") { positive(c, &format!("{what}: weight"), "")? } else { 0.0 };
    let (spring, preload) = if c.accept("spring") { (not_negative(c, &format!("{what}: spring stiffness [N/m]"))?, not_negative(c, &format!("{what}: spring preload [N]"))?) } else { (0.0, 0.0) };
    let stops = [c.real(&format!("{what}: end stop stiffness [N/m]"))?, c.real(&format!("{what}: end stop damping [N s/m]"))?, c.real(&format!("{what}: end stop mass [kg]"))?];
    let fluid = element_fluid(c, ctx, what)?;
    let output = output_flag(c, ctx)?;
    Ok(Box::new(Accumulator { label, pressure, stroke, start, area, pipe_area, mass, loss: [loss_in, loss_out], gas, weight, spring, preload, stops, fluid, output }))
}

/// `tank, P1, P2, PRESSURE, PIPE_AREA, TANK_AREA, S_MAX, [startlevel, S0,] [alarmlevel,
/// S_ALARM,] C_S, fluid, …` after its nodes.
pub fn tank(label: Label, c: &mut Cursor, ctx: &ElementContext, what: &str, pressures: [ScalarNodeId; 2]) -> Result<Box<dyn Element>, MbdynError> {
    let pressure = positive(c, &format!("{what}: pressure [Pa]"), "")?;
    let pipe_area = positive(c, &format!("{what}: pipe area [m^2]"), "")?;
    let tank_area = positive(c, &format!("{what}: tank area [m^2]"), "")?;
    let max_level = not_negative(c, &format!("{what}: largest level [m]"))?;
    let level = if c.accept("startlevel") { not_negative(c, &format!("{what}: initial level [m]"))? } else { 0.5 * max_level };
    if c.accept("alarmlevel") {
        not_negative(c, &format!("{what}: alarm level [m]"))?;
    }
    c.real(&format!("{what}: level coefficient"))?;
    let fluid = element_fluid(c, ctx, what)?;
    let output = output_flag(c, ctx)?;
    Ok(Box::new(Tank { label, pressures, pressure, pipe_area, tank_area, max_level, level, fluid, output }))
}
