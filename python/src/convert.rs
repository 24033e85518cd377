//! romdyn's matrices and results as NumPy arrays and dicts.

use faer::{c64, Mat};
use numpy::ndarray::{Array2, Array3};
use numpy::{Complex64, IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::conversion::FromPyObjectOwned;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use romdyn::output::rom_file::RomExport;
use romdyn::sweep::{PointFailure, PointMode, PointResult};

/// A real matrix as a (rows, columns) float64 array.
pub fn mat<'py>(py: Python<'py>, m: &Mat<f64>) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((m.nrows(), m.ncols()), |(i, j)| m[(i, j)]).into_pyarray(py)
}

/// Complex values as a complex128 array.
pub fn complex_vec<'py>(py: Python<'py>, v: &[c64]) -> Bound<'py, PyArray1<Complex64>> {
    v.iter().map(|x| Complex64::new(x.re, x.im)).collect::<Vec<_>>().into_pyarray(py)
}

/// Transfer matrices at each frequency as a (frequencies, outputs, inputs) complex array.
pub fn responses<'py>(py: Python<'py>, h: &[Mat<c64>], no: usize, ni: usize) -> PyResult<Bound<'py, PyArray3<Complex64>>> {
    Ok(Array3::from_shape_fn((h.len(), no, ni), |(k, i, j)| Complex64::new(h[k][(i, j)].re, h[k][(i, j)].im)).into_pyarray(py))
}

/// A design point's result as a dict (plain values and arrays, cheap to pickle): "A" … "E",
/// "full_static_gain", "rom_static_gain" (None if absent), "eigenvalues",
/// "full_eigenvalues", "state_modes", "state_freq_hz", names, units, "kind", "warnings",
/// "reference_time" [s], "dcoef" [s]; the candidate modes for tracking: "modes" (eigenvalues
/// [rad/s]), "mode_labels", "mode_members" (1-based modal-table indices), "mode_shapes" (per
/// mode, per member, the right vector on the motion unknowns), "mode_adjoints"; or
/// {"error": message}. [`point_from_dict`] reads it back.
pub fn point<'py>(py: Python<'py>, r: Result<PointResult, String>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let r = match r {
        Ok(r) => r,
        Err(e) => {
            d.set_item("error", e)?;
            return Ok(d);
        }
    };
    rom_items(py, &d, &r.rom)?;
    d.set_item("modes", complex_vec(py, &r.modes.iter().map(|m| m.lambda).collect::<Vec<_>>()))?;
    d.set_item("mode_labels", r.modes.iter().map(|m| m.label.clone()).collect::<Vec<_>>())?;
    d.set_item("mode_members", r.modes.iter().map(|m| m.members.clone()).collect::<Vec<_>>())?;
    d.set_item("mode_shapes", r.modes.iter().map(|m| m.shapes.iter().map(|v| complex_vec(py, v)).collect::<Vec<_>>()).collect::<Vec<_>>())?;
    d.set_item("mode_adjoints", r.modes.iter().map(|m| complex_vec(py, &m.adjoint)).collect::<Vec<_>>())?;
    d.set_item("warnings", r.warnings.clone())?;
    Ok(d)
}

/// A ROM's fields as items of `d` ([`point_from_dict`] reads them back): "E" … "D", static
/// gains, eigenvalues, state modes and frequencies, names, units, "kind", "reference_time"
/// [s] (None without one), "dcoef" [s].
pub fn rom_items<'py>(py: Python<'py>, d: &Bound<'py, PyDict>, x: &RomExport) -> PyResult<()> {
    for (name, m) in [("E", &x.e), ("A", &x.a), ("B", &x.b), ("C", &x.c), ("D", &x.d)] {
        d.set_item(name, mat(py, m))?;
    }
    d.set_item("full_static_gain", x.full_static_gain.as_ref().map(|m| mat(py, m)))?;
    d.set_item("rom_static_gain", x.rom_static_gain.as_ref().map(|m| mat(py, m)))?;
    d.set_item("eigenvalues", complex_vec(py, &x.eigenvalues))?;
    d.set_item("full_eigenvalues", complex_vec(py, &x.full_eigenvalues))?;
    d.set_item("state_modes", x.state_modes.clone())?;
    d.set_item("state_freq_hz", x.state_freq_hz.clone())?;
    d.set_item("state_units", x.state_units.clone())?;
    d.set_item("inputs", x.inputs.clone())?;
    d.set_item("outputs", x.outputs.clone())?;
    d.set_item("states", x.states.clone())?;
    d.set_item("input_units", x.input_units.clone())?;
    d.set_item("output_units", x.output_units.clone())?;
    d.set_item("kind", x.kind)?;
    d.set_item("reference_time", x.reference_time)?;
    d.set_item("dcoef", x.dcoef)?;
    Ok(())
}

fn item<'py, T: FromPyObjectOwned<'py>>(d: &Bound<'py, PyDict>, key: &str) -> PyResult<T> {
    let v = d.get_item(key)?.ok_or_else(|| pyo3::exceptions::PyKeyError::new_err(format!("design point result without '{key}'")))?;
    v.extract::<T>().map_err(|e| {
        let e: PyErr = e.into();
        pyo3::exceptions::PyTypeError::new_err(format!("design point result '{key}': {e}"))
    })
}

/// A 1-D complex array (or anything NumPy makes one of) as romdyn's complex numbers.
fn complex_values(v: &Bound<'_, PyAny>) -> PyResult<Vec<c64>> {
    let np = v.py().import("numpy")?;
    let a = np.getattr("asarray")?.call1((v, "complex128"))?;
    let a: PyReadonlyArray1<Complex64> = a.extract()?;
    Ok(a.as_array().iter().map(|x| c64::new(x.re, x.im)).collect())
}

fn complex_item(d: &Bound<'_, PyDict>, key: &str) -> PyResult<Vec<c64>> {
    complex_values(&item::<Bound<'_, PyAny>>(d, key)?)
}

fn matrix<'py>(d: &Bound<'py, PyDict>, key: &str) -> PyResult<Option<Mat<f64>>> {
    let Some(v) = d.get_item(key)? else { return Ok(None) };
    if v.is_none() {
        return Ok(None);
    }
    let a: PyReadonlyArray2<f64> = v.extract().map_err(|e| pyo3::exceptions::PyTypeError::new_err(format!("design point result '{key}': {e}")))?;
    let a = a.as_array();
    Ok(Some(Mat::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)])))
}

/// A dict of [`point`] back as the library's result (the sweep's tables, arrays, tracking
/// and interpolation then run on it, wherever the point was computed).
pub fn point_from_dict(d: &Bound<'_, PyDict>) -> PyResult<Result<PointResult, PointFailure>> {
    if let Some(e) = d.get_item("error")? {
        return Ok(Err(PointFailure { message: e.extract()? }));
    }
    let need = |k: &str| -> PyResult<Mat<f64>> { matrix(d, k)?.ok_or_else(|| pyo3::exceptions::PyKeyError::new_err(format!("design point result without '{k}'"))) };
    let kind: String = item(d, "kind")?;
    let rom = RomExport {
        kind: if kind == "descriptor" { "descriptor" } else { "ordinary" },
        e: need("E")?,
        a: need("A")?,
        b: need("B")?,
        c: need("C")?,
        d: need("D")?,
        eigenvalues: complex_item(d, "eigenvalues")?,
        full_eigenvalues: complex_item(d, "full_eigenvalues")?,
        inputs: item(d, "inputs")?,
        outputs: item(d, "outputs")?,
        states: item(d, "states")?,
        input_units: item(d, "input_units")?,
        output_units: item(d, "output_units")?,
        state_units: item(d, "state_units")?,
        state_modes: item(d, "state_modes")?,
        state_freq_hz: item(d, "state_freq_hz")?,
        reference_time: item(d, "reference_time")?,
        dcoef: item(d, "dcoef")?,
        full_static_gain: matrix(d, "full_static_gain")?,
        rom_static_gain: matrix(d, "rom_static_gain")?,
        // A sweep's points are continuous ROMs (the sweep has no sampling options).
        sample_time: None,
        discretization: "continuous".into(),
        hankel_singular_values: Vec::new(),
        error_bound: None,
    };
    let lambdas = complex_item(d, "modes")?;
    let labels: Vec<String> = item(d, "mode_labels")?;
    let members: Vec<Vec<usize>> = item(d, "mode_members")?;
    let shapes: Vec<Vec<Bound<'_, PyAny>>> = item(d, "mode_shapes")?;
    let adjoints: Vec<Bound<'_, PyAny>> = item(d, "mode_adjoints")?;
    let modes = lambdas
        .into_iter()
        .zip(labels)
        .zip(members)
        .zip(shapes)
        .zip(adjoints)
        .map(|((((lambda, label), members), shapes), adjoint)| Ok(PointMode { lambda, label, members, shapes: shapes.iter().map(complex_values).collect::<PyResult<_>>()?, adjoint: complex_values(&adjoint)? }))
        .collect::<PyResult<_>>()?;
    Ok(Ok(PointResult { rom, modes, warnings: item(d, "warnings")?, state: None }))
}
