//! The `hydraulic fluid` card (input manual §Hydraulic fluid; hfluid.cc,
//! `ReadHydraulicFluid`; mbpar.cc, `GetHydraulicFluid`) and the `hydraulic` element cards
//! (§Hydraulic Element; preselem.cc, `ReadHydraulicElem`): `actuator`, `minor loss`,
//! `control valve` and `pipe` (`dynamic pipe`, `accumulator`, `tank` and `orifice` in
//! [`super::hydraulic_elements`]). The other fluids and hydraulic elements of MBDyn 1.7.3
//! are refused by name.

use crate::mbdyn::syntax::cursor::Cursor;
use super::hydraulic_args::{element_fluid, fluid_properties, initial_value, output_flag, pipe_card, positive, PipeCard};
use crate::mbdyn::syntax::diagnostic::{mbdyn_runs_it, MbdynError};
use crate::mbdyn::nodes::scalar::scalar_node_of;
use super::context::{ElementContext, Fluids};
use crate::element::{Actuator, ControlValve, Element, MinorLoss, Pipe};
use crate::model::{Label, ScalarNodeKind};
use crate::mbdyn::drives::callers;
use crate::mbdyn::syntax::diagnostic;


/// The hydraulic element types of MBDyn 1.7.3 romdyn does not build.
const OTHER_ELEMENTS: [&str; 6] = ["three way minor loss", "control valve 2", "dynamic control valve", "pressure flow control", "pressure valve", "flow valve"];

/// The hydraulic element types romdyn builds.
const TYPES: [&str; 8] = ["actuator", "minor loss", "control valve", "dynamic pipe", "pipe", "accumulator", "tank", "orifice"];

/// `hydraulic fluid: LABEL [, name, "…"], FLUID;`.
pub fn fluid_card(c: &mut Cursor, seq: usize, fluids: &mut Fluids) -> Result<(), MbdynError> {
    let span = c.here();
    let label = c.label("hydraulic fluid label")?;
    if c.accept("name") {
        c.string("hydraulic fluid name")?;
    }
    let fluid = fluid_properties(c, &format!("hydraulic fluid {label}"))?;
    c.finish()?;
    if let Some((_, _, first)) = fluids.insert(label, (fluid, seq, span)) {
        return Err(c.error_at(span, format!("hydraulic fluid {label} is defined twice (first at line {})", first.line)));
    }
    Ok(())
}

/// `hydraulic: LABEL, TYPE, …` after the label.
pub fn hydraulic(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Box<dyn Element>, MbdynError> {
    let span = c.here();
    let types = TYPES.join(", ");
    if let Some(k) = c.accept_any(&OTHER_ELEMENTS) {
        return Err(c.error_at(span, format!("{} (supported: {types})", mbdyn_runs_it(&format!("hydraulic element type '{k}'")))));
    }
    let Some(kind) = c.accept_any(&TYPES) else {
        return Err(match c.peek_keyword() {
            Some(w) => c.error(format!("{} (romdyn reads: {types})", diagnostic::unknown_to_both("hydraulic element type", w))),
            None => c.error(format!("expected the hydraulic element type ({types}), found {}", c.found())),
        });
    };
    let what = format!("hydraulic {label} ({kind})");
    let pressure = |c: &mut Cursor| scalar_node_of(c, &ctx.nodes.2, ScalarNodeKind::Hydraulic, &what);
    if kind == "accumulator" {
        let node = pressure(c)?;
        return super::hydraulic_elements::accumulator(label, c, ctx, &what, node);
    }
    if matches!(kind, "pipe" | "dynamic pipe" | "tank" | "orifice") {
        let pressures = [pressure(c)?, pressure(c)?];
        return match kind {
            "pipe" => pipe(label, c, ctx, &what, pressures),
            "dynamic pipe" => super::hydraulic_elements::dynamic_pipe(label, c, ctx, &what, pressures),
            "tank" => super::hydraulic_elements::tank(label, c, ctx, &what, pressures),
            _ => super::hydraulic_elements::orifice(label, c, ctx, &what, pressures),
        };
    }
    if kind == "control valve" {
        let pressures = [pressure(c)?, pressure(c)?, pressure(c)?, pressure(c)?];
        let area = positive(c, &format!("{what}: area [m^2]"), "")?;
        let loss = if c.accept("loss") {
            let span = c.here();
            let loss = c.real("loss (leaking fraction of the area)")?;
            if !(loss >= 0.0) {
                return Err(c.error_at(span, format!("{what}: the loss must not be negative, found {loss} (MBDyn 1.7.3: \"negative loss_area\")")));
            }
            loss
        } else {
            0.0
        };
        let state = callers::drive(c, ctx.drives, ctx.seq)?;
        let density = element_fluid(c, ctx, &what)?.reference_density();
        let output = output_flag(c, ctx)?;
        return Ok(Box::new(ControlValve { label, pressures, area, loss, state, density, output }));
    }
    let pressures = [pressure(c)?, pressure(c)?];
    if kind == "minor loss" {
        let why = " (MBDyn 1.7.3 refuses a negative one and divides by it)";
        let loss = [positive(c, &format!("{what}: loss coefficient K12"), why)?, positive(c, &format!("{what}: loss coefficient K21"), why)?];
        let area = positive(c, &format!("{what}: area [m^2]"), "")?;
        let fluid = element_fluid(c, ctx, &what)?;
        let output = output_flag(c, ctx)?;
        return Ok(Box::new(MinorLoss { label, pressures, loss, area, fluid, output }));
    }
    let mut nodes = [0; 2];
    let mut offsets = [crate::kinematics::Vec3::zeros(); 2];
    let mut first = None;
    for k in 0..2 {
        let n = ctx.node(c, &format!("{what}: structural node {}", k + 1))?;
        nodes[k] = n.label;
        offsets[k] = ctx.on(n).relative_position(c, &format!("{what}: offset {} [m]", k + 1))?;
        first.get_or_insert(n);
    }
    let axis = if c.accept("direction") {
        let dir_span = c.here();
        let Some(first) = first else { return Err(c.error_at(dir_span, format!("{what}: a direction needs structural node 1"))) };
        let v = ctx.on(first).relative_vector(c, &format!("{what}: direction"))?;
        v.try_normalize(0.0).ok_or_else(|| c.error_at(dir_span, format!("{what}: the direction is null (MBDyn 1.7.3: \"need a definite direction\")")))?
    } else {
        crate::kinematics::Vec3::z()
    };
    let areas = [positive(c, &format!("{what}: area 1 [m^2]"), "")?, positive(c, &format!("{what}: area 2 [m^2]"), "")?];
    let length = positive(c, &format!("{what}: cylinder length [m]"), "")?;
    let fluid1 = element_fluid(c, ctx, &what)?;
    let fluid2 = if c.accept("same") { fluid1 } else { element_fluid(c, ctx, &what)? };
    let initial_pressures = pressures.map(|id| initial_value(ctx, id));
    let output = output_flag(c, ctx)?;
    Ok(Box::new(Actuator { label, pressures, nodes, offsets, axis, areas, length, fluids: [fluid1, fluid2], initial_pressures, output }))
}

/// `pipe, P1, P2, DIAMETER, [area, A,] LENGTH, [turbulent,] [initial value, Q0,] fluid, …`
/// after its nodes (the area defaults to the diameter's circle).
fn pipe(label: Label, c: &mut Cursor, ctx: &ElementContext, what: &str, pressures: [crate::model::ScalarNodeId; 2]) -> Result<Box<dyn Element>, MbdynError> {
    let PipeCard { diameter, area, length, turbulent, initial_flow, fluid } = pipe_card(c, ctx, what)?;
    let rho = fluid.density(0.5 * (initial_value(ctx, pressures[0]) + initial_value(ctx, pressures[1])));
    let coefficients = Pipe::coefficients(diameter, area, length, rho, fluid.viscosity());
    let output = output_flag(c, ctx)?;
    Ok(Box::new(Pipe { label, pressures, diameter, area, viscosity: fluid.viscosity(), coefficients, turbulent, initial_flow, fluid, output }))
}
