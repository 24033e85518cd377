//! `romdyn validate`: a ROM checked against romdyn's own nonlinear model (the paper's Fig. 7:
//! "the frequency content of the direct response of the multibody analysis when excited by
//! a low-pass filtered random input") and against measurements (Fig. 11).
//!
//! [`validate`] excites the model through each ROM input with a small band-limited signal
//! ([`signal`]), integrates it from the ROM's reference solution ([`nonlinear`]), estimates
//! every input/output pair's response by H1 with Welch averaging and its coherence
//! ([`welch`]), and compares on the estimate's bins: estimate, full linear model and ROM. The
//! ROM is also simulated in time with the same input ([`discrete`], exact for the input
//! linear between samples) and its fit to the nonlinear run reported as the normalized
//! root-mean-square error of MATLAB's `compare`, `1 − ‖y − ŷ‖/‖y − mean(y)‖`. At several
//! amplitudes the largest one the ROM still describes is the linearity limit.
//!
//! ```text
//! options ──► plan ──► per amplitude, per input: signal ─► nonlinear run ─► H1 ─┐
//!                                                 └──────► ROM simulation ──────┴► comparison ─► verdict
//! ```

mod compare;
mod discrete;
pub mod files;
pub mod measured;
mod nonlinear;
mod options;
pub mod signal;
pub mod welch;

use std::sync::Arc;

use faer::Mat;

use crate::dae::ports::{InputPort, OutputPort};
use crate::dae::State;
use crate::model::InitialValueProblem;
use crate::study::{Ports, ReducedModel, Setting, Study, StudyError};

pub use compare::{nrmse, AmplitudeRun, Channel, TimeRecord, Validation};
pub use crate::rom::expm;
pub use discrete::simulate as simulate_rom;
pub use measured::{read_measured, MeasuredChannel, MeasuredResponse};
pub use options::{Plan, ValidateOptions};
pub use signal::SignalKind;

/// Why a validation could not be done.
#[derive(Debug, thiserror::Error)]
pub enum ValidateError {
    #[error("{option}: {message}")]
    Option { option: Setting, message: String },
    #[error("{0}")]
    Port(String),
    #[error("the nonlinear run failed at step {step} of {steps} (t = {time} s): {reason}; smaller --amplitudes keep the model nearer its reference, a smaller --time-step helps Newton")]
    Step { step: usize, steps: usize, time: f64, reason: String },
    #[error(transparent)]
    Study(#[from] StudyError),
    #[error(transparent)]
    Measured(#[from] measured::MeasuredError),
}

/// The ROM's inputs and outputs as ports, in the study's order; springs removed from the ROM
/// or an imposed motion have no counterpart in the model as written, and are refused.
pub fn validation_ports(ports: &Ports) -> Result<(Vec<InputPort>, Vec<OutputPort>), ValidateError> {
    match ports {
        Ports::Nodes { inputs, outputs } => Ok((inputs.iter().map(|p| p.port()).collect(), outputs.iter().map(|p| p.port()).collect())),
        Ports::Application(app) if !app.remove_springs.is_empty() => Err(ValidateError::Option { option: Setting::RemoveSprings, message: "the ROM without its dummy springs has no nonlinear counterpart to run (the model as written has them): validate the model without removing springs".into() }),
        Ports::Application(app) if !app.cuts.is_empty() => Err(ValidateError::Option { option: Setting::Cut, message: "a cut loop has no nonlinear counterpart to run (the model as written keeps the cut element closing its loop): validate the closed loop without --cut".into() }),
        Ports::Application(app) if app.imposed.is_some() => Err(ValidateError::Option { option: Setting::Imposed, message: "an imposed motion is not validated (its inputs are the forces that impose it); validate the force inputs".into() }),
        Ports::Application(app) => Ok((app.inputs.clone(), app.outputs.clone())),
    }
}

/// Progress of the nonlinear runs: `(steps done, steps in all)`.
pub type Progress<'a> = &'a mut dyn FnMut(usize, usize);

/// Validates `rom` (a ROM of `study`, linearized at `reference` of `problem` with `ports`)
/// against the nonlinear model and, with `options.measured`, against measurements.
pub fn validate(study: &mut Study, problem: &InitialValueProblem, reference: &State, ports: &Ports, rom: &ReducedModel, options: &ValidateOptions, progress: Progress) -> Result<Validation, ValidateError> {
    Ok(validate_roms(study, problem, reference, ports, std::slice::from_ref(rom), options, progress)?.remove(0))
}

/// Validates several ROMs of the same study and ports against the same nonlinear runs, as the
/// paper's Fig. 7 overlays its ROMs on one direct response: the plan (band, resolution,
/// step, amplitudes) is the first ROM's, the runs are done once.
pub fn validate_roms(study: &mut Study, problem: &InitialValueProblem, reference: &State, ports: &Ports, roms: &[ReducedModel], options: &ValidateOptions, progress: Progress) -> Result<Vec<Validation>, ValidateError> {
    let (inputs, outputs) = validation_ports(ports)?;
    let first = roms.first().ok_or_else(|| ValidateError::Port("no ROM to validate".into()))?;
    for rom in roms {
        if inputs.len() != rom.ordinary.b.ncols() || outputs.len() != rom.ordinary.c.nrows() {
            return Err(ValidateError::Port(format!("the ports ({} inputs, {} outputs) are not the ROM's ({}, {})", inputs.len(), outputs.len(), rom.ordinary.b.ncols(), rom.ordinary.c.nrows())));
        }
    }
    let measured = options.measured.as_deref().map(read_measured).transpose()?;
    let plan = Plan::new(study, first, &outputs, options)?;
    let total = plan.amplitudes.len() * inputs.len() * plan.samples;
    let mut done = 0;
    // Per amplitude, per input: the signal and the nonlinear outputs.
    let mut nonlinear_runs = Vec::new();
    for amplitude in &plan.amplitudes {
        let mut series = Vec::new();
        for (j, input) in inputs.iter().enumerate() {
            let signal = Arc::new(plan.signal(j, amplitude[j]).generate());
            let model = study.model_mut().ok_or(StudyError::NoSource)?;
            let spec = nonlinear::RunSpec { problem, reference, input, outputs: &outputs, signal: signal.clone(), dt: plan.dt };
            let y = nonlinear::run(model, &spec, &mut |k| progress(done + k, total))?;
            done += plan.samples;
            series.push((signal, y));
        }
        nonlinear_runs.push(series);
    }
    roms.iter().map(|rom| {
        let mut runs = Vec::new();
        for (amplitude, series) in plan.amplitudes.iter().zip(&nonlinear_runs) {
            let compared = series.iter().enumerate().map(|(j, (signal, y))| {
                let u = Mat::from_fn(signal.len(), inputs.len(), |k, i| if i == j { signal[k] } else { 0.0 });
                (signal.clone(), y.clone(), simulate_rom(&rom.ordinary, &u, plan.dt))
            }).collect();
            runs.push(AmplitudeRun::new(study, rom, &plan, amplitude.clone(), compared)?);
        }
        Validation::new(study, rom, plan.clone(), runs, measured.clone())
    }).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `nrmse` is 1 for a perfect fit and 0 for the mean (MATLAB's `compare` with 'NRMSE').
    #[test]
    fn fit_of_the_mean_and_of_itself() {
        let y = [1.0, 2.0, 4.0, -1.0];
        assert_eq!(nrmse(&y, &y), 1.0);
        let mean = [1.5; 4];
        assert!(nrmse(&y, &mean).abs() < 1e-15);
    }
}
