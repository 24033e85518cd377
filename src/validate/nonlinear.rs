//! The direct multibody response (the paper's Fig. 7): romdyn's integrator run from the
//! ROM's reference solution with the input signal applied as a load through the same port
//! the ROM's `B̃` column linearizes, each output measured as the nonlinear quantity its `C̃`
//! row linearizes (a point's displacement from its reference position, a rotation vector
//! from the reference orientation, …), not as `C̃ Δy`.

use std::sync::Arc;

use crate::dae::ports::{Direction, Excitation, Frame, InputPort, Location, Measurement, OutputPort, Point};
use crate::dae::{Assembler, DofMap, State};
use crate::element::drive::{Drive, SampledChannel};
use crate::element::{Couple, Element, Force, ForceFrame, Label, NodeKinematics};
use crate::kinematics::{rotation_vector, Mat3, Vec3};
use crate::model::{InitialValueProblem, Model};
use crate::solve::{Integrator, NewtonSettings};

use super::ValidateError;

/// Newton's tolerance relative to the load's RMS (see [`integrate`]).
pub const RELATIVE_TOLERANCE: f64 = 1e-6;

/// Labels of the excitation's load elements, above any a file can give.
const LOAD_LABEL: Label = Label::MAX - 16;

/// Node kinematics of every node of `state`.
fn kinematics(dofs: &DofMap, state: &State) -> Vec<NodeKinematics> {
    (0..state.r_ref.len()).map(|i| state.node_frame(dofs, i).kin).collect()
}

/// The port's geometry resolved at the reference: node index and offset in the node frame.
fn point(model: &Model, reference: &[NodeKinematics], p: &Point, port: &str) -> Result<(usize, Vec3), ValidateError> {
    let i = model.node_index(p.node).ok_or_else(|| ValidateError::Port(format!("'{port}': structural node {} is not defined", p.node)))?;
    let k = &reference[i];
    Ok((i, match p.location {
        Location::Offset(f) => f,
        Location::At(x) => k.r.transpose() * (x - k.x),
    }))
}

/// A direction as a unit vector: global, or in node `i`'s frame (`in_node`: the frame's axes
/// given by `r`).
fn unit(d: &Direction, r: &Mat3, port: &str) -> Result<Vec3, ValidateError> {
    let n = d.vector.norm();
    if !(n > 0.0 && n.is_finite()) {
        return Err(ValidateError::Port(format!("'{port}': the direction is zero or not finite")));
    }
    Ok(match d.frame {
        Frame::Global => d.vector / n,
        Frame::Node => r * d.vector / n,
    })
}

/// The load elements that apply `signal` through `port` (absolute forces and couples whose
/// global direction is the port's at the reference, as the `B̃` column).
fn load_elements(model: &Model, reference: &[NodeKinematics], port: &InputPort, signal: SampledChannel) -> Result<Vec<Box<dyn Element>>, ValidateError> {
    let name = &port.name;
    let drive = || Drive::Sampled(signal.clone());
    let label_of = |i: usize| model.nodes[i].label;
    Ok(match &port.excitation {
        Excitation::Force { point: p, direction } => {
            let (i, offset) = point(model, reference, p, name)?;
            let d = unit(direction, &reference[i].r, name)?;
            vec![Box::new(Force::new(LOAD_LABEL, label_of(i), ForceFrame::Absolute, d, offset, drive()))]
        }
        Excitation::Moment { node, direction } => {
            let (i, _) = point(model, reference, &Point::node(*node), name)?;
            let d = unit(direction, &reference[i].r, name)?;
            vec![Box::new(Couple::new(LOAD_LABEL, label_of(i), ForceFrame::Absolute, d, drive()))]
        }
        Excitation::Actuator { from, to, direction } => {
            let (a, fa) = point(model, reference, from, name)?;
            let (b, fb) = point(model, reference, to, name)?;
            let d = unit(direction, &reference[a].r, name)?;
            vec![
                Box::new(Force::new(LOAD_LABEL, label_of(b), ForceFrame::Absolute, d, fb, drive())),
                Box::new(Force::new(LOAD_LABEL - 1, label_of(a), ForceFrame::Absolute, -d, fa, drive())),
            ]
        }
        Excitation::Scalar { node } => {
            if model.scalar_index(*node).is_none() {
                return Err(ValidateError::Port(format!("'{name}': {node} is not defined")));
            }
            vec![Box::new(crate::element::AbstractForce { label: LOAD_LABEL, node: *node, value: drive() })]
        }
    })
}

/// One output's nonlinear measurement, resolved at the reference.
pub(super) struct Sensor {
    measurement: Measurement,
    /// (node, offset) of the point(s): `[point]` or `[from, to]`.
    points: Vec<(usize, Vec3)>,
    reference_value: f64,
}

impl Sensor {
    pub(super) fn new(model: &Model, reference: &[NodeKinematics], port: &OutputPort) -> Result<Self, ValidateError> {
        let name = &port.name;
        let points = match &port.measurement {
            Measurement::Displacement { point: p, .. } | Measurement::Velocity { point: p, .. } => vec![point(model, reference, p, name)?],
            Measurement::Rotation { node, .. } | Measurement::AngularVelocity { node, .. } => vec![point(model, reference, &Point::node(*node), name)?],
            Measurement::Relative { from, to, .. } => vec![point(model, reference, from, name)?, point(model, reference, to, name)?],
            Measurement::ScalarValue { node } | Measurement::ScalarRate { node } => {
                return Err(ValidateError::Port(format!("'{name}': an output on {node} is not supported by validate yet (its nonlinear run measures structural nodes); the ROM's own responses (rom, freq) support it")));
            }
            Measurement::ModalCoordinate { joint, .. } | Measurement::ModalRate { joint, .. } | Measurement::FemDisplacement { joint, .. } | Measurement::FemVelocity { joint, .. } | Measurement::FemRotation { joint, .. } => {
                return Err(ValidateError::Port(format!("'{name}': an output on modal joint {joint}'s coordinates or FEM nodes is not supported by validate yet (its nonlinear run measures structural nodes); the ROM's own responses (rom, freq) support it")));
            }
        };
        let mut sensor = Sensor { measurement: port.measurement.clone(), points, reference_value: 0.0 };
        // Checks the direction once, here.
        sensor.raw(reference, reference, name)?;
        sensor.reference_value = sensor.raw(reference, reference, name)?;
        Ok(sensor)
    }

    /// The measured quantity at `now` (positions absolute, rotation relative to `reference`).
    fn raw(&self, now: &[NodeKinematics], reference: &[NodeKinematics], name: &str) -> Result<f64, ValidateError> {
        let position = |(i, f): (usize, Vec3)| now[i].x + now[i].r * f;
        let (i, f) = self.points[0];
        Ok(match &self.measurement {
            Measurement::Displacement { direction, .. } => unit(direction, &reference[i].r, name)?.dot(&position((i, f))),
            Measurement::Rotation { direction, .. } => unit(direction, &reference[i].r, name)?.dot(&rotation_vector(&(now[i].r * reference[i].r.transpose()))),
            // The direction turns with node `from`, as the row of C̃ linearizes it.
            Measurement::Relative { direction, .. } => unit(direction, &now[i].r, name)?.dot(&(position(self.points[1]) - position((i, f)))),
            Measurement::Velocity { direction, .. } => unit(direction, &reference[i].r, name)?.dot(&(now[i].xdot + now[i].omega.cross(&(now[i].r * f)))),
            Measurement::AngularVelocity { direction, .. } => unit(direction, &reference[i].r, name)?.dot(&now[i].omega),
            Measurement::ScalarValue { .. } | Measurement::ScalarRate { .. } | Measurement::ModalCoordinate { .. } | Measurement::ModalRate { .. } | Measurement::FemDisplacement { .. } | Measurement::FemVelocity { .. } | Measurement::FemRotation { .. } => return Err(ValidateError::Port(format!("'{name}': this output is not supported by validate yet"))),
        })
    }

    /// The change from the reference.
    fn value(&self, now: &[NodeKinematics], reference: &[NodeKinematics]) -> f64 {
        self.raw(now, reference, "").map_or(f64::NAN, |v| v - self.reference_value)
    }
}

/// What one run needs besides the model.
pub(super) struct RunSpec<'a> {
    pub problem: &'a InitialValueProblem,
    pub reference: &'a State,
    pub input: &'a InputPort,
    pub outputs: &'a [OutputPort],
    /// The input's samples at `dt` from the reference time, linear between them.
    pub signal: Arc<Vec<f64>>,
    pub dt: f64,
}

/// Runs the model with the signal applied; returns one series per output (a sample per
/// step, the first at the reference). `progress` gets the number of steps done.
pub(super) fn run(model: &mut Model, spec: &RunSpec, progress: &mut dyn FnMut(usize)) -> Result<Vec<Vec<f64>>, ValidateError> {
    let dofs = DofMap::new(model);
    let reference = kinematics(&dofs, spec.reference);
    let channel = SampledChannel { t0: spec.reference.t, dt: spec.dt, values: spec.signal.clone(), linear: true, pad_zeros: true, amplitude: 1.0 };
    let loads = load_elements(model, &reference, spec.input, channel)?;
    let sensors = spec.outputs.iter().map(|p| Sensor::new(model, &reference, p)).collect::<Result<Vec<_>, _>>()?;
    let added = loads.len();
    model.elements.extend(loads);
    let result = integrate(model, spec, &sensors, &reference, progress);
    model.elements.truncate(model.elements.len() - added);
    result
}

fn integrate(model: &Model, spec: &RunSpec, sensors: &[Sensor], reference: &[NodeKinematics], progress: &mut dyn FnMut(usize)) -> Result<Vec<Vec<f64>>, ValidateError> {
    let asm = Assembler::new(model);
    let p = spec.problem;
    // The file's tolerance, or 1e-6 of the load's RMS if larger: a static reference of a
    // stiff model stalls Newton at round-off above a tolerance set for its own loads, and a
    // residual of 1e-6 of the excitation changes the response by about as much.
    let rms = (spec.signal.iter().map(|v| v * v).sum::<f64>() / spec.signal.len().max(1) as f64).sqrt();
    let settings = NewtonSettings { tolerance: p.tolerance.max(RELATIVE_TOLERANCE * rms), norm: p.residual_norm, increment_tolerance: p.increment_tolerance, max_iterations: p.max_iterations };
    let mut state = spec.reference.clone();
    state.load = 1.0;
    let steps = spec.signal.len();
    let mut series: Vec<Vec<f64>> = sensors.iter().map(|_| Vec::with_capacity(steps)).collect();
    let record = |state: &State, series: &mut Vec<Vec<f64>>| {
        let now = kinematics(&asm.dofs, state);
        for (s, out) in sensors.iter().zip(series.iter_mut()) {
            out.push(s.value(&now, reference));
        }
    };
    record(&state, &mut series);
    let mut integrator = Integrator::new(&asm, state, p.method, spec.dt, settings);
    for step in 1..steps {
        integrator.step().map_err(|f| ValidateError::Step { step, steps: steps - 1, time: f.time, reason: format!("Newton stopped at residual {:.3e} ({} {:.3e}){}", f.residual_norm, f.worst_equation, f.worst_value, f.reason.map(|r| format!(": {r}")).unwrap_or_default()) })?;
        record(&integrator.state, &mut series);
        if step % 256 == 0 {
            progress(step);
        }
    }
    progress(steps - 1);
    Ok(series)
}
