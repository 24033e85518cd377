//! Python arguments onto romdyn's library options, the same for `Model.study`,
//! `Study.reduce` and a sweep's options dict (the CLI's `--static`, `--input`, `--count`, …).

use std::path::Path;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use romdyn::analysis::Reference;
use romdyn::dae::{NodeInput, NodeOutput};
use romdyn::eigen::EigenRoute;
use romdyn::rom::{ModalDamping, ModeSelection, Ranking};
use romdyn::eigen::krylov::ModeTarget;
use romdyn::study::{BelowBand, EigenSettings, Named, Ports, Residualization, RomForm, RomRequest, Solver};
use romdyn::sweep::SweepOptions;

use crate::py_err;

pub(crate) fn bad(what: &str, message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{what}: {message}"))
}

/// None/"initial", "static", or a time [s].
pub fn reference(r: Option<&Bound<'_, PyAny>>, load_steps: usize) -> PyResult<Reference> {
    let Some(r) = r.filter(|r| !r.is_none()) else { return Ok(Reference::Initial) };
    if let Ok(s) = r.extract::<String>() {
        return match s.as_str() {
            "initial" => Ok(Reference::Initial),
            "static" => Ok(Reference::Static { load_steps }),
            other => Err(bad("reference", format!("'{other}': expected \"initial\", \"static\" or a time [s]"))),
        };
    }
    let t: f64 = r.extract().map_err(|_| bad("reference", "expected \"initial\", \"static\" or a time [s]"))?;
    Ok(Reference::At(t))
}

pub fn ports(inputs: &[String], outputs: &[String], fem_outputs: &[String], file: Option<&Path>, remove_springs: &[u32], imposed: Option<&str>, cuts: &[String]) -> PyResult<Ports> {
    let inputs = inputs.iter().map(|s| s.parse::<NodeInput>().map_err(|e| bad("inputs", e))).collect::<PyResult<Vec<_>>>()?;
    let outputs = outputs.iter().map(|s| s.parse::<NodeOutput>().map_err(|e| bad("outputs", e))).collect::<PyResult<Vec<_>>>()?;
    let fem_outputs = fem_outputs.iter().map(|s| s.parse::<romdyn::dae::FemOutput>().map_err(|e| bad("fem_outputs", e))).collect::<PyResult<Vec<_>>>()?;
    let cuts = cuts.iter().map(|s| s.parse::<romdyn::dae::Cut>().map_err(|e| bad("cut", e))).collect::<PyResult<Vec<_>>>()?;
    Ports::from_parts(file, &inputs, &outputs, &fem_outputs, remove_springs, imposed, &cuts).map_err(py_err)
}

/// A keyword's word as the library's enum, by the library's one table of names (the CLI's
/// too); a bad word raises naming the keyword.
pub fn named<T: Named>(word: &str) -> PyResult<T> {
    T::from_name(word).map_err(py_err)
}

pub fn eigen(route: &str, dcoef: Option<f64>, solver: &str) -> PyResult<EigenSettings> {
    Ok(EigenSettings { route: named::<EigenRoute>(route)?, dcoef, solver: named::<Solver>(solver)?, ..EigenSettings::default() })
}

/// The modes the sparse route computes: `count` lowest or those in `band` (FMIN, FMAX) [Hz];
/// neither: `None` (the library's default). The library checks them
/// (`EigenSettings::validate`: at least 1 mode, 0 <= FMIN < FMAX).
pub fn sparse_target(count: Option<usize>, band: Option<(f64, f64)>) -> PyResult<Option<ModeTarget>> {
    match (count, band) {
        (None, None) => Ok(None),
        (Some(n), None) => Ok(Some(ModeTarget::Lowest(n))),
        (None, Some((fmin_hz, fmax_hz))) => Ok(Some(ModeTarget::Band { fmin_hz, fmax_hz })),
        (Some(_), Some(_)) => Err(bad("count", "give at most one of count (a positive number of modes) and band (FMIN, FMAX) [Hz]")),
    }
}

/// The CLI's `--beam-update`: None or "path-independent" (default), "incremental" (MBDyn
/// 1.7.3's beam update of beam3 and beam2).
pub fn beam_update(u: Option<&str>) -> PyResult<romdyn::input::mbdyn::BeamUpdateChoice> {
    u.map_or(Ok(romdyn::input::mbdyn::BeamUpdateChoice::Auto), named)
}

pub fn form(f: &str) -> PyResult<RomForm> {
    named(f)
}

/// The ROM request of `romdyn rom`'s selection options.
pub fn request(count: Option<usize>, band: Option<(f64, f64)>, modes: Option<Vec<usize>>, residualize: Option<&Bound<'_, PyAny>>, by: &str, below_band: &str, damping: Option<&Bound<'_, PyAny>>) -> PyResult<RomRequest> {
    let selection = match (count, band, modes) {
        (Some(0), None, None) => return Err(bad("count", "a ROM keeps at least 1 mode")),
        (Some(n), None, None) => ModeSelection::Lowest(n),
        (None, Some((a, b)), None) => ModeSelection::band(a, b).map_err(|e| bad("band", e))?,
        (None, None, Some(list)) => ModeSelection::Indices(list),
        _ => return Err(bad("reduce", "give exactly one of count=N, band=(FMIN, FMAX) [Hz], modes=[I, ...]")),
    };
    let residualization = match residualize.filter(|r| !r.is_none()) {
        None => Residualization::None,
        Some(r) => match r.extract::<bool>() {
            Ok(true) => Residualization::Dropped,
            Ok(false) => Residualization::None,
            Err(_) => Residualization::Modes(r.extract().map_err(|_| bad("residualize", "expected True, False or a list of modal-table indices"))?),
        },
    };
    let mut request = RomRequest::new(selection).residualize(residualization).ranked_by(named::<Ranking>(by)?);
    request.below_band = named::<BelowBand>(below_band)?;
    let zeta = |z: f64| if (0.0..1.0).contains(&z) { Ok(z) } else { Err(bad("damping", format!("damping ratio {z} is outside [0, 1)"))) };
    request.damping = match damping.filter(|d| !d.is_none()) {
        None => None,
        Some(d) => match d.extract::<f64>() {
            Ok(z) => Some(ModalDamping::Uniform(zeta(z)?)),
            Err(_) => {
                let map: std::collections::BTreeMap<usize, f64> = d.extract().map_err(|_| bad("damping", "expected a ratio or {mode: ratio}"))?;
                Some(ModalDamping::PerMode(map.into_iter().map(|(k, z)| zeta(z).map(|z| (k, z))).collect::<PyResult<_>>()?))
            }
        },
    };
    Ok(request)
}

/// The control hand-off options of `reduce()` (the CLI's `--minimal`, `--balanced`,
/// `--hankel-tol`, `--spa`, `--sample-rate`, `--discretize`, `--prewarp`), checked by the library.
#[allow(clippy::too_many_arguments)]
pub fn control(mut request: RomRequest, minimal: Option<f64>, balanced: Option<usize>, hankel_tol: Option<f64>, spa: bool, sample_rate: Option<f64>, discretize: &str, prewarp: Option<f64>) -> PyResult<RomRequest> {
    request.minimal = romdyn::study::minimal_tolerance(minimal).map_err(py_err)?;
    request.balanced = romdyn::study::balancing(balanced, hankel_tol, spa).map_err(py_err)?;
    request.sampling = romdyn::study::sampling(sample_rate, discretize, prewarp).map_err(py_err)?;
    Ok(request)
}

fn get<'py, T: FromPyObjectOwned<'py>>(d: &Bound<'py, PyDict>, key: &str) -> PyResult<Option<T>> {
    match d.get_item(key)? {
        Some(v) if !v.is_none() => v.extract().map(Some).map_err(|e| bad(key, Into::<PyErr>::into(e))),
        _ => Ok(None),
    }
}

/// Keys a sweep's options dict may hold (those of `Model.study` and `Study.reduce`, whose
/// balanced and minimal reductions the library refuses in a sweep with the reason, plus
/// "lowest", "continuation" and "beam_update", the CLI's `--beam-update`).
const KEYS: [&str; 30] = ["beam_update", "reference", "load_steps", "inputs", "outputs", "fem_outputs", "ports", "remove_springs", "imposed", "cut", "route", "dcoef", "solver", "count", "band", "modes", "residualize", "by", "below_band", "damping", "form", "lowest", "continuation", "sample_rate", "discretize", "prewarp", "balanced", "hankel_tol", "spa", "minimal"];

/// A sweep's options dict.
pub fn sweep(d: &Bound<'_, PyDict>) -> PyResult<SweepOptions> {
    for k in d.keys() {
        let k: String = k.extract()?;
        if !KEYS.contains(&k.as_str()) {
            return Err(bad("sweep", format!("unknown option '{k}' (options: {})", KEYS.join(", "))));
        }
    }
    let load_steps = get(d, "load_steps")?.unwrap_or(10);
    let reference = reference(d.get_item("reference")?.as_ref(), load_steps)?;
    let ports_file: Option<std::path::PathBuf> = get(d, "ports")?;
    let ports = ports(&get::<Vec<String>>(d, "inputs")?.unwrap_or_default(), &get::<Vec<String>>(d, "outputs")?.unwrap_or_default(), &get::<Vec<String>>(d, "fem_outputs")?.unwrap_or_default(), ports_file.as_deref(), &get::<Vec<u32>>(d, "remove_springs")?.unwrap_or_default(), get::<String>(d, "imposed")?.as_deref(), &get::<Vec<String>>(d, "cut")?.unwrap_or_default())?;
    let eigen = eigen(&get::<String>(d, "route")?.unwrap_or_else(|| "lambda".into()), get(d, "dcoef")?, &get::<String>(d, "solver")?.unwrap_or_else(|| "auto".into()))?;
    let rom = request(
        get(d, "count")?,
        get(d, "band")?,
        get(d, "modes")?,
        d.get_item("residualize")?.as_ref(),
        &get::<String>(d, "by")?.unwrap_or_else(|| "frequency".into()),
        &get::<String>(d, "below_band")?.unwrap_or_else(|| "drop".into()),
        d.get_item("damping")?.as_ref(),
    )?;
    let rom = control(rom, get(d, "minimal")?, get(d, "balanced")?, get(d, "hankel_tol")?, get(d, "spa")?.unwrap_or(false), get(d, "sample_rate")?, &get::<String>(d, "discretize")?.unwrap_or_else(|| "zoh".into()), get(d, "prewarp")?)?;
    let form = form(&get::<String>(d, "form")?.unwrap_or_else(|| "ordinary".into()))?;
    let modes = get(d, "lowest")?.unwrap_or(4);
    // The CLI's --lowest bounds (the points' count is checked with them in run_points).
    romdyn::sweep::check_lowest(modes, 1).map_err(|e| bad("lowest", &e))?;
    let continuation = get(d, "continuation")?.unwrap_or(false);
    if continuation && !matches!(reference, Reference::Static { .. }) {
        return Err(bad("continuation", "needs reference=\"static\" (it starts each static equilibrium from the previous point's)"));
    }
    let beam_update = beam_update(get::<String>(d, "beam_update")?.as_deref())?;
    let options = SweepOptions { reference, ports, eigen, rom, form, modes, continuation, beam_update };
    options.check().map_err(py_err)?;
    Ok(options)
}
