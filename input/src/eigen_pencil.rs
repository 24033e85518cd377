//! An MBDyn eigenanalysis `.m` file (MBDyn manual, "Eigenanalysis", output; or one romdyn
//! `run` wrote) read as a linear DAE: `Aplus = J(+c)`, `Aminus = J(−c)` and `dCoef = c`
//! give `F_yd = (J + J*)/2`, `F_y = (J − J*)/(2c)` (eqs. 13–16). The matrices must have
//! been written (`output matrices`, full or sparse).
//!
//! The file has no inputs or outputs; they are chosen by index:
//! - input row `I` (1-based equation): a generalized force `u` entering equation `I` as
//!   `−ΔF_I = u` (B̃ has a 1 in row I, eq. 38) — e.g. a force or moment component in a
//!   node's equilibrium rows;
//! - output column `J` (1-based unknown): `z = Δy_J` (C̃ has a 1 in column J, eq. 39) — e.g.
//!   a node's displacement or rotation component. With `output geometry`, node `k` starts
//!   at unknown `idx(k) + 1`.

use std::path::{Path, PathBuf};

use faer::Mat;

use super::octave_m::{read_octave_script, OctaveError, OctaveMatrix, OctaveScript};
use crate::linear::{Jacobians, LinearDae};

/// Equations taken as inputs and unknowns taken as outputs (1-based).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PencilPorts {
    pub input_rows: Vec<usize>,
    pub output_cols: Vec<usize>,
}

impl PencilPorts {
    pub fn is_empty(&self) -> bool {
        self.input_rows.is_empty() && self.output_cols.is_empty()
    }
}

/// Why an `.m` file is not a usable pencil.
#[derive(Debug, thiserror::Error)]
pub enum EigenPencilError {
    #[error(transparent)]
    Script(#[from] OctaveError),
    #[error("{file}: '{name}' is missing; {hint}")]
    Missing { file: PathBuf, name: &'static str, hint: &'static str },
    #[error("{file}:{line}:{column}: '{name}' {message}")]
    Variable { file: PathBuf, name: &'static str, line: usize, column: usize, message: String },
    #[error("{file}: {message}")]
    Ports { file: PathBuf, message: String },
}

fn variable<'s>(s: &'s OctaveScript, name: &'static str, hint: &'static str) -> Result<&'s OctaveMatrix, EigenPencilError> {
    s.get(name).ok_or_else(|| EigenPencilError::Missing { file: s.file.clone(), name, hint })
}

fn invalid(s: &OctaveScript, name: &'static str, message: String) -> EigenPencilError {
    let at = s.position(name).unwrap_or(super::octave_m::Position { line: 0, column: 0 });
    EigenPencilError::Variable { file: s.file.clone(), name, line: at.line, column: at.column, message }
}

/// `n x n` real matrix of a variable; a sparse one is padded to `n` (its size is only its
/// largest index).
fn square(s: &OctaveScript, name: &'static str, m: &OctaveMatrix, n: usize) -> Result<Mat<f64>, EigenPencilError> {
    if m.im.is_some() {
        return Err(invalid(s, name, "has complex entries; a Jacobian is real".into()));
    }
    if !(m.rows == n && m.cols == n || m.from_sparse && m.rows <= n && m.cols <= n) {
        return Err(invalid(s, name, format!("is {}x{}, expected {n}x{n} (square, the size of the other matrix)", m.rows, m.cols)));
    }
    if let Some(k) = m.re.iter().position(|x| !x.is_finite()) {
        return Err(invalid(s, name, format!("entry ({}, {}) is {}: a Jacobian must be finite", k / m.cols.max(1) + 1, k % m.cols.max(1) + 1, m.re[k])));
    }
    crate::limits::check_dense(n, n, || format!("'{name}'")).map_err(|e| invalid(s, name, e.to_string()))?;
    Ok(Mat::from_fn(n, n, |i, j| if i < m.rows && j < m.cols { m.get(i, j) } else { 0.0 }))
}

/// The pencil of an MBDyn eigenanalysis file, with the inputs and outputs of `ports`.
/// Returns the linear DAE (`Jacobians::Coefficient`) and `dCoef`.
pub fn read_eigen_pencil(path: &Path, ports: &PencilPorts) -> Result<(LinearDae, f64), EigenPencilError> {
    pencil_from_script(&read_octave_script(path)?, ports)
}

/// The pencil of a parsed eigenanalysis script (see [`read_eigen_pencil`]).
pub fn pencil_from_script(s: &OctaveScript, ports: &PencilPorts) -> Result<(LinearDae, f64), EigenPencilError> {
    const MATRICES: &str = "write the eigenanalysis with 'output matrices' (MBDyn) or 'output full matrices'";
    let aplus = variable(s, "Aplus", MATRICES)?;
    let aminus = variable(s, "Aminus", MATRICES)?;
    let dcoef = variable(s, "dCoef", "the file must define dCoef = c, the coefficient of J(+c) and J(-c)")?;
    // A subnormal dCoef (below 2.2e-308) cannot divide J(+c) - J(-c) (eq. 16) without overflow.
    let c = dcoef.scalar().filter(|c| c.is_normal() && *c > 0.0).ok_or_else(|| invalid(s, "dCoef", format!("must be a positive normal number (s), found {}", crate::limits::readable(dcoef.re.first().copied().unwrap_or(f64::NAN)))))?;
    let n = [aplus.rows, aplus.cols, aminus.rows, aminus.cols].into_iter().max().unwrap_or(0);
    let (j, jstar) = (square(s, "Aplus", aplus, n)?, square(s, "Aminus", aminus, n)?);
    let out_of_range = |what: &str, k: usize, of: &str| EigenPencilError::Ports { file: s.file.clone(), message: format!("{what} {k} is out of range: the pencil has {n} {of} (1-based)") };
    let mut b = Mat::<f64>::zeros(n, ports.input_rows.len());
    for (k, &row) in ports.input_rows.iter().enumerate() {
        if !(1..=n).contains(&row) {
            return Err(out_of_range("input row", row, "equations"));
        }
        b[(row - 1, k)] = 1.0;
    }
    let mut cm = Mat::<f64>::zeros(ports.output_cols.len(), n);
    for (k, &col) in ports.output_cols.iter().enumerate() {
        if !(1..=n).contains(&col) {
            return Err(out_of_range("output column", col, "unknowns"));
        }
        cm[(k, col - 1)] = 1.0;
    }
    let dae = LinearDae {
        jacobians: Jacobians::Coefficient { j, jstar, dcoef: c },
        b,
        c: cm,
        unknown_names: (1..=n).map(|i| format!("y{i}")).collect(),
        input_names: ports.input_rows.iter().map(|r| format!("equation {r} (generalized force)")).collect(),
        output_names: ports.output_cols.iter().map(|c| format!("unknown {c}")).collect(),
        constraint_form: None,
        multipliers: Vec::new(),
        c_rate: None,
    };
    Ok((dae, c))
}
