//! Modal coordinates with their first and second time derivatives, for MBDyn's `.mod` file
//! (modal.cc, `Modal::Output`: `q`, `q̇`, `q̈` per mode).
//!
//! `q` and `q̇` are unknowns; `q̈` is not (romdyn integrates the modal momenta `p`). It comes,
//! as the nodes' accelerations do ([`super::node_accelerations`]), from the momentum
//! definitions `r = p − D(y, v)` (`D` linear in the rates `v`: the element's `q̇`, its
//! dynamic nodes' `ẋ`, `ġ`) differentiated along the motion, `ṗ = D_/v v̇ + D_/y ẏ`, with
//! `D_/v = −F_/ẏ` and `D_/y = −F_/y` on those rows (the momenta's own columns left out):
//!
//! ```text
//! F_/ẏ[R, V] v̇ = −ṗ_R − F_/y[R, ·] ẏ
//! ```
//!
//! over the element's momentum rows and those of the dynamic nodes its `q̇` enters, solved
//! in the least-squares sense (a direction without inertia gets no acceleration, as MBDyn's
//! nodes do).

use std::collections::HashMap;

use super::{Assembler, Coefficients, State};
use crate::model::{ConstraintForm, Label, NodeKind};

/// One mode of one element at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModalRow {
    pub element: Label,
    /// The mode's number in the FEM file.
    pub mode: usize,
    pub q: f64,
    pub rate: f64,
    pub acceleration: f64,
}

/// Every element's modal coordinates ([`crate::element::Outputs::modal_coordinates`]).
pub fn modal_coordinates(asm: &Assembler, st: &State) -> Vec<ModalRow> {
    let dofs = &asm.dofs;
    let owners: Vec<usize> = (0..asm.model.elements.len()).filter(|&e| asm.model.elements[e].outputs().is_some_and(|o| !o.modal_coordinates().is_empty())).collect();
    if owners.is_empty() {
        return Vec::new();
    }
    let fyd = asm.jacobian(st, Coefficients { a: 1.0, b: 0.0, form: ConstraintForm::Plain, dcoef: 1.0 });
    let fy = asm.jacobian(st, Coefficients { a: 0.0, b: 1.0, form: ConstraintForm::Plain, dcoef: 1.0 });
    // Momentum unknowns: dynamic nodes' β, γ and elements' own momenta (their columns drop).
    let mut momentum = vec![false; dofs.len];
    for (i, kind) in dofs.node_kind.iter().enumerate() {
        if *kind == NodeKind::Dynamic {
            momentum[dofs.node_first[i] + 6..dofs.node_first[i] + 12].fill(true);
        }
    }
    for (e, el) in asm.model.elements.iter().enumerate() {
        for k in el.momentum_unknowns() {
            momentum[dofs.element_first[e] + k] = true;
        }
    }
    let mut out = Vec::new();
    for e in owners {
        let el = &asm.model.elements[e];
        let first = dofs.element_first[e];
        let modes = el.outputs().map(|o| o.modal_coordinates()).unwrap_or_default();
        let q_cols: Vec<usize> = modes.iter().map(|(k, _)| first + k).collect();
        // The dynamic nodes whose momentum rows read q̇.
        let nodes: Vec<usize> = dofs.element_nodes[e].iter().copied().filter(|&n| dofs.node_kind[n] == NodeKind::Dynamic).filter(|&n| {
            let rows = dofs.node_first[n]..dofs.node_first[n] + 6;
            (0..fyd.values.len()).any(|t| rows.contains(&fyd.rows[t]) && q_cols.contains(&fyd.cols[t]) && fyd.values[t] != 0.0)
        }).collect();
        let rows: Vec<usize> = nodes.iter().flat_map(|&n| dofs.node_first[n]..dofs.node_first[n] + 6).chain(el.momentum_unknowns().map(|k| first + k)).collect();
        let cols: Vec<usize> = nodes.iter().flat_map(|&n| dofs.node_first[n]..dofs.node_first[n] + 6).chain(q_cols.iter().copied()).collect();
        let row_at: HashMap<usize, usize> = rows.iter().enumerate().map(|(k, &r)| (r, k)).collect();
        let col_at: HashMap<usize, usize> = cols.iter().enumerate().map(|(k, &c)| (c, k)).collect();
        let mut a = nalgebra::DMatrix::<f64>::zeros(rows.len(), cols.len());
        for t in 0..fyd.values.len() {
            if let (Some(&r), Some(&c)) = (row_at.get(&fyd.rows[t]), col_at.get(&fyd.cols[t])) {
                a[(r, c)] += fyd.values[t];
            }
        }
        // −ṗ: a node's row k defines its momentum unknown node_first + 6 + k, an element's
        // row defines its own unknown.
        let mut b = nalgebra::DVector::<f64>::from_iterator(rows.len(), rows.iter().map(|&r| {
            let p = if r < first { r + 6 } else { r };
            -st.yp[p]
        }));
        for t in 0..fy.values.len() {
            if let Some(&r) = row_at.get(&fy.rows[t]) && !momentum[fy.cols[t]] {
                b[r] -= fy.values[t] * st.yp[fy.cols[t]];
            }
        }
        let scale = a.amax().max(f64::MIN_POSITIVE);
        let v = a.svd(true, true).solve(&b, 1e-12 * scale).unwrap_or_else(|_| nalgebra::DVector::from_element(cols.len(), f64::NAN));
        for (j, (k, mode)) in modes.iter().enumerate() {
            let i = first + k;
            out.push(ModalRow { element: el.label(), mode: *mode, q: st.y[i], rate: st.yp[i], acceleration: v[6 * nodes.len() + j] });
        }
    }
    out
}
