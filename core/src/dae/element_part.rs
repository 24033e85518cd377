//! One deformable element's part of the linearized DAE, factored as a collocated feedback
//! (paper eqs. 92–93): `J_e,y = B̃_e K C̃_e`, `J_e,ẏ = B̃_e C_v C̃_e`.
//!
//! `C̃_e` picks the element's nodes' displacements and rotations (`x`, `g`; `δθ = δg` at the
//! reference), `B̃_e` the same nodes' force and moment equilibrium rows, and `K`, `C_v` are
//! the element's own stiffness and viscous blocks there, read from its Jacobian at the
//! reference (geometric terms of a loaded element included). Nothing is written by hand:
//! any element without multipliers that only touches its nodes' equilibrium rows can be
//! factored (springs, hinges, rods, beams).

use faer::Mat;

use super::{Assembler, Coefficients, State};
use crate::model::ConstraintForm;
use crate::model::{Label, Model};

/// `B̃_e`, `C̃_e`, `K`, `C_v` of one element.
#[derive(Clone, Debug)]
pub struct ElementPart {
    /// "deformable displacement joint 7".
    pub element: String,
    /// Equations × local coordinates (one 1 per column).
    pub b: Mat<f64>,
    /// Local coordinates × unknowns (one 1 per row).
    pub c: Mat<f64>,
    /// Stiffness `∂F_e/∂y` on the local coordinates [N/m, N, N m/rad].
    pub k: Mat<f64>,
    /// Viscous part `∂F_e/∂ẏ` on the local coordinates.
    pub viscosity: Mat<f64>,
    /// Names of the local coordinates ("node 2 x").
    pub coordinates: Vec<String>,
}

/// Why an element cannot be factored.
#[derive(Debug, thiserror::Error)]
pub enum ElementPartError {
    #[error("element {0} is not defined")]
    Unknown(Label),
    #[error("{0} has Lagrange multipliers (a joint): only deformable elements (springs, hinges, rods, beams) can be removed")]
    Joint(String),
    #[error("{0} has Jacobian entries outside its nodes' equilibrium rows and x, g columns; it cannot be removed as a spring")]
    Pattern(String),
}

fn is_deformable(type_name: &str) -> bool {
    ["deformable", "rod", "beam"].iter().any(|w| type_name.contains(w))
}

/// Factors the element with label `label` at `state` (in the linearization form, [`State::linearization_base`]). MBDyn numbers joints,
/// bodies and forces separately, so a label may name several elements: deformable ones
/// (deformable joints and hinges, rods, beams) are tried first, and the first that factors
/// is taken.
pub fn element_part(model: &Model, state: &State, label: Label) -> Result<ElementPart, ElementPartError> {
    let asm = Assembler::new(model);
    let mut candidates: Vec<usize> = (0..model.elements.len()).filter(|&e| model.elements[e].label() == label).collect();
    candidates.sort_by_key(|&e| !is_deformable(model.elements[e].type_name()));
    let mut st = state.clone();
    st.linearization_base(&asm.dofs);
    let mut first_error = None;
    for &e in &candidates {
        match factor(&asm, &st, e) {
            Ok(part) => return Ok(part),
            Err(err) => {
                first_error.get_or_insert(err);
            }
        }
    }
    Err(first_error.unwrap_or(ElementPartError::Unknown(label)))
}

fn factor(asm: &Assembler, st: &State, e: usize) -> Result<ElementPart, ElementPartError> {
    let (model, dofs) = (asm.model, &asm.dofs);
    let el = &model.elements[e];
    let name = format!("{} {}", el.type_name(), el.label());
    if dofs.element_len[e] > 0 {
        return Err(ElementPartError::Joint(name));
    }
    let frames = asm.frames(st);
    // Local coordinates: (x, g) of each node of the element, with their equilibrium rows.
    let mut rows = Vec::new();
    let mut cols = Vec::new();
    let mut coordinates = Vec::new();
    const NAMES: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];
    let mut nodes = dofs.element_nodes[e].clone();
    nodes.dedup();
    for &n in &nodes {
        for k in 0..6 {
            rows.push(dofs.equilibrium_row(n) + k);
            cols.push(dofs.node_first[n] + k);
            coordinates.push(format!("node {} {}", model.nodes[n].label, NAMES[k]));
        }
    }
    let m = rows.len();
    let block = |a: f64, b: f64| -> Result<Mat<f64>, ElementPartError> {
        let t = asm.element_jacobian(st, &frames, e, Coefficients { a, b, form: ConstraintForm::Plain, dcoef: 1.0 });
        let mut out = Mat::<f64>::zeros(m, m);
        for k in 0..t.values.len() {
            match (rows.iter().position(|&r| r == t.rows[k]), cols.iter().position(|&c| c == t.cols[k])) {
                (Some(i), Some(j)) => out[(i, j)] += t.values[k],
                _ if t.values[k] == 0.0 => {}
                _ => return Err(ElementPartError::Pattern(name.clone())),
            }
        }
        Ok(out)
    };
    let k = block(0.0, 1.0)?;
    let viscosity = block(1.0, 0.0)?;
    let n = dofs.len;
    let b = Mat::from_fn(n, m, |i, j| if rows[j] == i { 1.0 } else { 0.0 });
    let c = Mat::from_fn(m, n, |i, j| if cols[i] == j { 1.0 } else { 0.0 });
    Ok(ElementPart { element: name, b, c, k, viscosity, coordinates })
}
