//! romdyn's matrices and results as NumPy arrays and dicts.

use faer::{c64, Mat};
use numpy::ndarray::{Array2, Array3};
use numpy::{Complex64, IntoPyArray, PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use romdyn::sweep::PointResult;

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
/// "full_static_gain", "rom_static_gain" (None if absent), "modes" (lowest dynamic
/// eigenvalues [rad/s]), names, units, "kind", "warnings", "reference_time" [s], "dcoef" [s];
/// or {"error": message}.
pub fn point<'py>(py: Python<'py>, r: Result<PointResult, String>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let r = match r {
        Ok(r) => r,
        Err(e) => {
            d.set_item("error", e)?;
            return Ok(d);
        }
    };
    let x = &r.rom;
    for (name, m) in [("E", &x.e), ("A", &x.a), ("B", &x.b), ("C", &x.c), ("D", &x.d)] {
        d.set_item(name, mat(py, m))?;
    }
    d.set_item("full_static_gain", x.full_static_gain.as_ref().map(|m| mat(py, m)))?;
    d.set_item("rom_static_gain", x.rom_static_gain.as_ref().map(|m| mat(py, m)))?;
    d.set_item("modes", complex_vec(py, &r.modes))?;
    d.set_item("inputs", x.inputs.clone())?;
    d.set_item("outputs", x.outputs.clone())?;
    d.set_item("states", x.states.clone())?;
    d.set_item("input_units", x.input_units.clone())?;
    d.set_item("output_units", x.output_units.clone())?;
    d.set_item("kind", x.kind)?;
    d.set_item("warnings", r.warnings.clone())?;
    d.set_item("reference_time", x.reference_time)?;
    d.set_item("dcoef", x.dcoef)?;
    Ok(d)
}
