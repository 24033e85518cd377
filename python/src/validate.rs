//! `romdyn.validate(model, ...)`: `romdyn validate` from Python (library:
//! `romdyn::validate::validate`), the arguments mapped onto `ValidateOptions`, the result as
//! NumPy arrays with the verdict.

use std::path::PathBuf;

use numpy::{IntoPyArray, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use romdyn::validate::{validate as validate_rom, SignalKind, ValidateError, ValidateOptions};

use crate::convert::complex_vec;
use crate::{options, py_err, Model, RomdynError};

fn signal_of(s: &str) -> PyResult<SignalKind> {
    match s {
        "random" => Ok(SignalKind::Random),
        "multisine" => Ok(SignalKind::Multisine),
        "chirp" => Ok(SignalKind::Chirp),
        s => Err(options::bad("signal", format!("'{s}': expected \"random\", \"multisine\" or \"chirp\""))),
    }
}

fn validate_err(e: ValidateError) -> PyErr {
    match e {
        ValidateError::Study(e) => py_err(e),
        // The setting by its keyword argument (`validation_band`, not `--validation-band`).
        ValidateError::Option { option, message } => options::bad(option.python_name(), romdyn::study::python_spelling(&message)),
        e => RomdynError::new_err(romdyn::study::python_spelling(&e.to_string())),
    }
}

/// Validates a ROM of `model` against its nonlinear run (as `romdyn validate`): reference,
/// load_steps, inputs, outputs, ports as `Model.study()`; count, band, modes, residualize as
/// `Study.reduce()`; signal "random"|"multisine"|"chirp"; amplitudes: input RMS values [N or
/// N m] (the linearity range; default one, a static response of 1e-4 of the model's size);
/// validation_band (FMIN, FMAX) [Hz]; resolution [Hz]; averages; time_step [s]; seed;
/// coherence, tolerance, fit: the verdict's thresholds; measured: a CSV file.
///
/// Returns {"freq_hz" (bins,), "estimate", "full", "rom" (amplitudes, bins, outputs, inputs)
/// complex, "coherence" (amplitudes, bins, outputs, inputs), "fit" (amplitudes, outputs,
/// inputs), "amplitudes" (amplitudes, inputs) [N or N m], "time" [s] (samples,), "input"
/// (inputs, samples), "nonlinear" and "rom_time" (inputs, outputs, samples) of the smallest
/// amplitude, "represents" (bool), "verdict", "summary", "linearity_limit" ((last described
/// amplitude or None, first not described) or None), "measured" [{"name", "full_error",
/// "rom_error"}]}.
#[pyfunction]
#[pyo3(signature = (model, reference = None, load_steps = 10, inputs = Vec::new(), outputs = Vec::new(), ports = None, count = None, band = None, modes = None, residualize = None, signal = "random", amplitudes = Vec::new(), validation_band = None, resolution = None, averages = 8, time_step = None, seed = 1, coherence = 0.95, tolerance = 0.1, fit = 0.5, measured = None))]
#[allow(clippy::too_many_arguments)]
pub fn validate<'py>(py: Python<'py>, model: &Model, reference: Option<&Bound<'_, PyAny>>, load_steps: usize, inputs: Vec<String>, outputs: Vec<String>, ports: Option<PathBuf>, count: Option<usize>, band: Option<(f64, f64)>, modes: Option<Vec<usize>>, residualize: Option<&Bound<'_, PyAny>>, signal: &str, amplitudes: Vec<f64>, validation_band: Option<(f64, f64)>, resolution: Option<f64>, averages: usize, time_step: Option<f64>, seed: u64, coherence: f64, tolerance: f64, fit: f64, measured: Option<PathBuf>) -> PyResult<Bound<'py, PyDict>> {
    let reference = options::reference(reference, load_steps)?;
    let ports = options::ports(&inputs, &outputs, &[], ports.as_deref(), &[], None, &[])?;
    let request = options::request(count, band, modes, residualize, "frequency", "drop", None)?;
    let opts = ValidateOptions { signal: signal_of(signal)?, amplitudes, band_hz: validation_band, resolution_hz: resolution, averages, time_step, seed, coherence, tolerance, fit, measured };
    opts.check().map_err(validate_err)?;
    let (v, t0, warnings) = py.detach(|| -> Result<_, ValidateError> {
        let mut study = model.builder(reference.integrates())?.reference(reference).ports(ports.clone()).for_request(&request).build()?;
        let (state, problem) = study.reference_and_problem()?;
        let rom = study.reduce(&request)?;
        let warnings: Vec<_> = study.warnings().iter().chain(&rom.warnings).cloned().collect();
        Ok((validate_rom(&mut study, &problem, &state, &ports, &rom, &opts, &mut |_, _| {})?, state.t, warnings))
    }).map_err(validate_err)?;
    // What the CLI prints, as Python warnings: the study's and the ROM's, then the verdict's.
    crate::warnings::warn_all(py, &warnings)?;
    if let Some(w) = v.warning() {
        crate::warnings::warn_accuracy(py, w)?;
    }
    let run = &v.runs[0];
    let (ni, no) = (run.time.len(), run.time[0].nonlinear.len());
    let nb = run.channels[0].estimate.freq_hz.len();
    let na = v.runs.len();
    // (amplitude, bin, output, input) from channels[j * no + i].
    let cube = |f: &dyn Fn(&romdyn::validate::Channel, usize) -> numpy::Complex64| {
        let mut out = Vec::with_capacity(na * nb * no * ni);
        for r in &v.runs {
            for k in 0..nb {
                for i in 0..no {
                    for j in 0..ni {
                        out.push(f(&r.channels[j * no + i], k));
                    }
                }
            }
        }
        out.into_pyarray(py).reshape([na, nb, no, ni])
    };
    let c = |x: faer::c64| numpy::Complex64::new(x.re, x.im);
    let d = PyDict::new(py);
    d.set_item("freq_hz", run.channels[0].estimate.freq_hz.clone().into_pyarray(py))?;
    d.set_item("estimate", cube(&|ch, k| c(ch.estimate.h[k]))?)?;
    d.set_item("full", cube(&|ch, k| c(ch.full[k]))?)?;
    d.set_item("rom", cube(&|ch, k| c(ch.rom[k]))?)?;
    let coh: Vec<f64> = v.runs.iter().flat_map(|r| (0..nb).flat_map(move |k| (0..no).flat_map(move |i| (0..ni).map(move |j| r.channels[j * no + i].estimate.coherence[k])))).collect();
    d.set_item("coherence", coh.into_pyarray(py).reshape([na, nb, no, ni])?)?;
    let fits: Vec<f64> = v.runs.iter().flat_map(|r| (0..no).flat_map(move |i| (0..ni).map(move |j| r.channels[j * no + i].fit))).collect();
    d.set_item("fit", fits.into_pyarray(py).reshape([na, no, ni])?)?;
    let amps: Vec<f64> = v.runs.iter().flat_map(|r| r.amplitude.clone()).collect();
    d.set_item("amplitudes", amps.into_pyarray(py).reshape([na, ni])?)?;
    let ns = v.plan.samples;
    d.set_item("time", (0..ns).map(|k| t0 + k as f64 * v.plan.dt).collect::<Vec<_>>().into_pyarray(py))?;
    d.set_item("input", PyArray2::from_vec2(py, &run.time.iter().map(|r| r.u.to_vec()).collect::<Vec<_>>())?)?;
    let series = |rom: bool| run.time.iter().flat_map(|r| (if rom { &r.rom } else { &r.nonlinear }).iter().flatten().copied()).collect::<Vec<f64>>();
    d.set_item("nonlinear", series(false).into_pyarray(py).reshape([ni, no, ns])?)?;
    d.set_item("rom_time", series(true).into_pyarray(py).reshape([ni, no, ns])?)?;
    d.set_item("represents", v.represents)?;
    d.set_item("verdict", v.verdict())?;
    d.set_item("summary", v.summary())?;
    d.set_item("linearity_limit", v.linearity_limit)?;
    let measured: Vec<Bound<'py, PyDict>> = v.measured.iter().map(|m| {
        let e = PyDict::new(py);
        e.set_item("name", &m.name)?;
        e.set_item("full_error", m.full_error)?;
        e.set_item("rom_error", m.rom_error)?;
        e.set_item("measured", complex_vec(py, &m.measured))?;
        Ok(e)
    }).collect::<PyResult<_>>()?;
    d.set_item("measured", measured)?;
    Ok(d)
}
