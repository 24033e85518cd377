//! The sweep's library work on results gathered in Python (locally or from an executor's
//! workers): tables, stacked arrays in the tracked modes' basis, interpolation and its check,
//! all by `romdyn::sweep::SweepResults` as the CLI does.

use std::path::PathBuf;

use numpy::IntoPyArray;
use numpy::ndarray::{ArrayD, IxDyn, ShapeBuilder};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use romdyn::output::rom_file::RomExport;
use romdyn::sweep::{StackError, SweepResults};

use crate::convert::{point_from_dict, rom_items};
use crate::RomdynError;

fn stack_err(e: StackError) -> PyErr {
    match e {
        StackError::Sizes(_) | StackError::Interpolation(_) => pyo3::exceptions::PyValueError::new_err(romdyn::study::python_spelling(&e.to_string())),
        e => RomdynError::new_err(e.to_string()),
    }
}

/// The library's sweep results from the gathered point dicts.
fn results(file: PathBuf, names: Vec<String>, points: Vec<Vec<f64>>, dicts: &[Bound<'_, PyDict>], lowest: usize) -> PyResult<SweepResults> {
    let results = dicts.iter().map(point_from_dict).collect::<PyResult<Vec<_>>>()?;
    Ok(SweepResults { file, names, points, results, modes: lowest })
}

/// The stacked arrays and string lists of `romdyn sweep -o` (`stacked()`), plus "table"
/// (the CSV text of `--table`); `{"table": ...}` alone when no point succeeded.
#[pyfunction]
pub fn sweep_arrays<'py>(py: Python<'py>, file: PathBuf, names: Vec<String>, points: Vec<Vec<f64>>, results_: Vec<Bound<'py, PyDict>>, lowest: usize) -> PyResult<Bound<'py, PyDict>> {
    let r = results(file, names, points, &results_, lowest)?;
    let d = PyDict::new(py);
    d.set_item("table", r.modes_csv())?;
    let stacked = match r.stacked() {
        Ok(s) => s,
        Err(StackError::NoPoint) => return Ok(d),
        Err(e) => return Err(stack_err(e)),
    };
    for a in stacked.arrays {
        // Column-major data, as MATLAB's and the .npz file's.
        let array = ArrayD::from_shape_vec(IxDyn(&a.dims).f(), a.data).map_err(|e| RomdynError::new_err(e.to_string()))?;
        d.set_item(a.name, array.into_pyarray(py))?;
    }
    for (name, list) in stacked.strings {
        d.set_item(name, list)?;
    }
    d.set_item("kind", stacked.kind)?;
    Ok(d)
}

fn rom_dict<'py>(py: Python<'py>, r: &RomExport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    rom_items(py, &d, r)?;
    Ok(d)
}

/// The ROM at `values` (one per parameter) interpolated from the stacked ROMs in the
/// tracked modes' basis; with `exact` (the point's own result dict) also the ROM computed
/// there in the same basis and the relative differences ("check").
#[pyfunction]
#[pyo3(signature = (file, names, points, results_, lowest, values, exact = None))]
#[allow(clippy::too_many_arguments)]
pub fn interpolate_sweep<'py>(py: Python<'py>, file: PathBuf, names: Vec<String>, points: Vec<Vec<f64>>, results_: Vec<Bound<'py, PyDict>>, lowest: usize, values: Vec<f64>, exact: Option<Bound<'py, PyDict>>) -> PyResult<Bound<'py, PyDict>> {
    let r = results(file, names, points, &results_, lowest)?;
    let Some(exact) = exact else { return rom_dict(py, &r.interpolate(&values).map_err(stack_err)?) };
    let exact = match point_from_dict(&exact)? {
        Ok(p) => p,
        Err(e) => return Err(RomdynError::new_err(format!("the ROM at the point itself failed: {}", e.message))),
    };
    let (rom, exact_rom, check) = r.check_interpolation(&values, &exact).map_err(stack_err)?;
    let d = rom_dict(py, &rom)?;
    d.set_item("exact", rom_dict(py, &exact_rom)?)?;
    let c = PyDict::new(py);
    for (name, e) in &check.matrices {
        c.set_item(*name, *e)?;
    }
    c.set_item("eigenvalues", check.eigenvalues)?;
    c.set_item("static_gain", check.static_gain)?;
    c.set_item("text", check.describe())?;
    d.set_item("check", c)?;
    Ok(d)
}
