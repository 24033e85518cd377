//! romdyn's JSON of one eigenanalysis: the content of the `.m` file (see `eigen_m`) plus the
//! modal table (labels, error estimates, kinetic-energy shares) and the unknowns' names.
//! Matrices are arrays of rows; complex numbers `{"re", "im"}`; missing eigenvectors and
//! non-finite numbers are `null`.

use faer::{c64, Col, Mat};
use serde_json::{json, Value};

use super::eigen_file::{mbdyn_alpha, EigenFile, MatrixLayout};
use super::modal::ModalReport;

fn number(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

fn rows(m: &Mat<f64>) -> Value {
    Value::Array((0..m.nrows()).map(|i| Value::Array((0..m.ncols()).map(|j| number(m[(i, j)])).collect())).collect())
}

fn complex(z: c64) -> Value {
    json!({"re": number(z.re), "im": number(z.im)})
}

/// Vectors as rows of the n x k matrix (one column per written mode).
fn vectors(n: usize, cols: &[Option<&Col<c64>>]) -> Value {
    Value::Array((0..n).map(|i| Value::Array(cols.iter().map(|c| c.map_or(Value::Null, |v| complex(v[i]))).collect())).collect())
}

/// The JSON document of one eigenanalysis.
pub fn eigen_json(input: &str, e: &EigenFile) -> Value {
    let n = e.pencil.dim();
    let table = ModalReport::new(e.modal, n).with_energy(e.energy.to_vec());
    let written: Vec<Value> = e.written.iter().map(|&k| serde_json::to_value(&table.eigenvalues[k]).unwrap_or(Value::Null)).collect();
    let mut doc = json!({
        "input": input,
        "analysis": e.index,
        "units": "time and dcoef in s; eigenvalues in rad/s; frequencies in Hz; positions in m; rotation vectors in rad",
        "dTime": e.time,
        "dCoef": e.dcoef,
        "equations": n,
        "route": e.modal.route,
        "solver": e.solver,
        "counts": table.counts,
        "eigenvalues": written,
        "alpha": e.written.iter().map(|&k| mbdyn_alpha(&e.modal.modes[k], e.modal.route, e.dcoef).map(number).to_vec()).collect::<Vec<_>>(),
        "unknowns": e.unknown_names,
    });
    for (plus, name) in [(true, "Aplus"), (false, "Aminus")] {
        match e.matrices {
            None => break,
            Some(MatrixLayout::Full) => doc[name] = rows(&e.pencil.full(plus)),
            Some(MatrixLayout::Sparse) => {
                let entries: Vec<Value> = e.pencil.nonzeros(plus).into_iter().map(|(i, j, v)| json!([i + 1, j + 1, number(v)])).collect();
                doc[name] = json!({"size": [n, n], "entries": entries, "indices": "1-based [row, column, value], as the .m file's spconvert"});
            }
        }
    }
    if let Some(g) = e.geometry {
        doc["labels"] = json!(g.labels);
        doc["idx"] = json!(g.first_index);
        doc["X0"] = Value::Array(g.position.iter().zip(&g.rotation_vector).flat_map(|(x, p)| [x.x, x.y, x.z, p.x, p.y, p.z]).map(number).collect());
    }
    if e.eigenvectors {
        let modes = || e.written.iter().map(|&k| &e.modal.modes[k]);
        doc["VR"] = vectors(n, &modes().map(|m| m.right.as_ref()).collect::<Vec<_>>());
        doc["VL"] = vectors(n, &modes().map(|m| m.left.as_ref()).collect::<Vec<_>>());
    }
    doc
}
