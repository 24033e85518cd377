//! A control loop cut open at a named genel or abstract force (issue 34 point 4): the
//! element's part of the linearized DAE (`F_/ẏ`, `F_/y`) is taken out and the signal that
//! crossed it becomes a pair of ports, an input `w` injected where the element acted and an
//! output `r` returned by the rest of the model, so that closing `w = r` gives back the
//! linearization of the model as written (the closed loop), entry for entry.
//!
//! Where the loop is broken depends on the element:
//! - **at its output** for an element without own unknowns (a genel spring, spring support,
//!   cross spring support; an abstract force): one input per equation the element writes (a
//!   generalized force added to that scalar node's equation, `−ΔF = B̃ w` as every input,
//!   eq. 38), one output per equation, the element's own contribution as a force
//!   `r = −(F_e,/y Δy + F_e,/ẏ Δẏ)`;
//! - **at its input** for an element with own unknowns (a state-space genel, a scalar filter:
//!   a controller): one input per scalar node the element reads without writing its equation
//!   (the measured signal fed to the controller: its entries in those columns move to
//!   `B̃ = −F_e,/y` columns, or `−F_e,/ẏ` when it reads the derivative), one output per such
//!   node, its value (or derivative).
//!
//! With `H(s)` the transfer matrix from the injected `w` to the returned `r` of the cut
//! model, the loop closes by `w = r`: in the negative-feedback convention of control the loop
//! transfer function at the cut is `L(s) = −H(s)` and the closed loop's sensitivity at the
//! cut is `(I + L)⁻¹`. The reference solution stays the closed loop's (the model as written):
//! only the linearization is cut.

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

use faer::Mat;

use super::linearize::linearization_form;
use super::ports::{Excitation, InputPort, Measurement, OutputPort};
use super::{Assembler, Coefficients, State};
use crate::linear::{Jacobians, LinearDae, SparseLinearDae, SparseMatrix};
use crate::model::{Label, Model, ScalarNodeId};

/// MBDyn's label family of a cut element (genels and forces are numbered separately).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CutFamily {
    /// `genel: LABEL, …`.
    Genel,
    /// `force: LABEL, abstract, …`.
    Force,
}

/// An element named to be cut: `genel:LABEL` or `force:LABEL`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cut {
    pub family: CutFamily,
    pub label: Label,
}

impl FromStr for Cut {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("'{s}': expected genel:LABEL or force:LABEL (a genel or an abstract force of the model)");
        let (family, label) = s.split_once(':').ok_or_else(bad)?;
        let family = match family.trim() {
            f if f.eq_ignore_ascii_case("genel") => CutFamily::Genel,
            f if f.eq_ignore_ascii_case("force") => CutFamily::Force,
            _ => return Err(bad()),
        };
        let label = label.trim().parse().map_err(|_| bad())?;
        Ok(Cut { family, label })
    }
}

impl fmt::Display for Cut {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let family = match self.family {
            CutFamily::Genel => "genel",
            CutFamily::Force => "force",
        };
        write!(f, "{family}:{}", self.label)
    }
}

/// Why a cut cannot be made.
#[derive(Debug, thiserror::Error)]
#[error("{cut}: {message}")]
pub struct CutError {
    pub cut: Cut,
    pub message: String,
}

/// One cut element's part of the linearized DAE and the ports that replace it.
#[derive(Clone, Debug)]
pub struct CutPart {
    /// "genel cross spring support 4".
    pub element: String,
    /// Entries taken out of `F_/ẏ` and `F_/y` (row, column, value).
    pub fyd: Vec<(usize, usize, f64)>,
    pub fy: Vec<(usize, usize, f64)>,
    /// Columns of `B̃` of the injected signals (equations long).
    pub b: Vec<Vec<f64>>,
    /// Rows of `C̃` and `C̃_v` of the returned signals (unknowns long).
    pub c: Vec<Vec<f64>>,
    pub c_rate: Vec<Vec<f64>>,
    /// "cut genel 4 at abstract node 1 (injected) [-]", one per input.
    pub inputs: Vec<String>,
    /// "cut genel 4 at abstract node 1 (returned) [-]", one per output.
    pub outputs: Vec<String>,
}

/// The parts of `cuts` at `state` (in the linearization form of [`super::linearize_ports`]).
pub fn cut_parts(model: &Model, state: &State, cuts: &[Cut]) -> Result<Vec<CutPart>, CutError> {
    for (k, cut) in cuts.iter().enumerate() {
        if cuts[..k].contains(cut) {
            return Err(CutError { cut: *cut, message: "named twice".into() });
        }
    }
    if cuts.is_empty() {
        return Ok(Vec::new());
    }
    let asm = Assembler::new(model);
    let mut st = state.clone();
    st.linearization_base(&asm.dofs);
    cuts.iter().map(|cut| cut_part(&asm, &st, *cut)).collect()
}

/// The element `cut` names, or why none is.
fn find(model: &Model, cut: Cut) -> Result<usize, CutError> {
    let refuse = |message: String| Err(CutError { cut, message });
    let labelled: Vec<usize> = (0..model.elements.len()).filter(|&e| model.elements[e].label() == cut.label).collect();
    let in_family = |e: &usize| {
        let name = model.elements[*e].type_name();
        match cut.family {
            CutFamily::Genel => name.starts_with("genel "),
            CutFamily::Force => name.ends_with(" force") || name.ends_with(" couple"),
        }
    };
    let Some(&e) = labelled.iter().find(|e| in_family(e)) else {
        let family = if cut.family == CutFamily::Genel { "genel" } else { "force" };
        return refuse(format!("the model has no {family} {} (a cut names a genel or an abstract force by its label)", cut.label));
    };
    let name = model.elements[e].type_name();
    if cut.family == CutFamily::Force && name != "abstract force" {
        return refuse(format!("force {} is an {name}: a cut takes a genel or an abstract force (a loop on scalar nodes)", cut.label));
    }
    Ok(e)
}

fn cut_part(asm: &Assembler, st: &State, cut: Cut) -> Result<CutPart, CutError> {
    let (model, dofs) = (asm.model, &asm.dofs);
    let e = find(model, cut)?;
    let element = format!("{} {}", model.elements[e].type_name(), cut.label);
    let refuse = |message: String| Err(CutError { cut, message });
    let frames = asm.frames(st);
    let form = linearization_form(model);
    let entries = |a: f64, b: f64| {
        let t = asm.element_jacobian(st, &frames, e, Coefficients { a, b, form, dcoef: 1.0 });
        let mut sum = BTreeMap::new();
        for k in 0..t.values.len() {
            *sum.entry((t.rows[k], t.cols[k])).or_insert(0.0) += t.values[k];
        }
        sum.retain(|_, v| *v != 0.0);
        sum
    };
    let (fyd, fy) = (entries(1.0, 0.0), entries(0.0, 1.0));
    let scalar_of = |i: usize| (i >= dofs.scalar_first && i < dofs.scalar_first + model.scalar_nodes.len()).then(|| model.scalar_nodes[i - dofs.scalar_first].id);
    let n = dofs.len;
    let (mut b, mut c, mut c_rate, mut inputs, mut outputs) = (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut name = |at: String, input_unit: &str, output_unit: &str| {
        inputs.push(format!("cut {element} at {at} (injected) [{input_unit}]"));
        outputs.push(format!("cut {element} at {at} (returned) [{output_unit}]"));
    };
    let own = dofs.element_len[e];
    let (removed_fyd, removed_fy) = if own == 0 {
        // At the output: one signal per equation written.
        let rows: std::collections::BTreeSet<usize> = fyd.keys().chain(fy.keys()).map(|&(r, _)| r).collect();
        if rows.is_empty() {
            return refuse(format!("{element} does not depend on the state at the reference (its value is a function of time): no loop passes through it"));
        }
        for &r in &rows {
            let Some(node) = scalar_of(r) else {
                return refuse(format!("{element} writes {}, not a scalar node's equation", dofs.equation_name(model, r)));
            };
            let unit = InputPort { name: String::new(), excitation: Excitation::Scalar { node } }.unit();
            let mut col = vec![0.0; n];
            col[r] = 1.0;
            b.push(col);
            let row_of = |m: &BTreeMap<(usize, usize), f64>| {
                let mut row = vec![0.0; n];
                m.iter().filter(|((i, _), _)| *i == r).for_each(|((_, j), v)| row[*j] -= v);
                row
            };
            c.push(row_of(&fy));
            c_rate.push(row_of(&fyd));
            name(format!("{node}"), unit, unit);
        }
        (fyd, fy)
    } else {
        if (0..own).any(|k| dofs.is_multiplier(dofs.element_first[e] + k)) {
            return refuse(format!("{element} is a constraint (it has a reaction), not a signal path: cut the element that carries the signal to or from it"));
        }
        // At the input: one signal per scalar node read whose equation the element does not write.
        let written: std::collections::BTreeSet<usize> = fyd.keys().chain(fy.keys()).map(|&(r, _)| r).collect();
        let read = |m: &BTreeMap<(usize, usize), f64>| -> std::collections::BTreeSet<usize> { m.keys().map(|&(_, j)| j).filter(|&j| scalar_of(j).is_some() && !written.contains(&j)).collect() };
        let (read_values, read_rates) = (read(&fy), read(&fyd));
        if read_values.is_empty() && read_rates.is_empty() {
            return refuse(format!("{element} reads no scalar node other than those whose equations it writes: it is part of a node's dynamics, not a link to cut"));
        }
        let mut removed = [BTreeMap::new(), BTreeMap::new()];
        for (k, (m, cols)) in [(&fyd, &read_rates), (&fy, &read_values)].into_iter().enumerate() {
            for &j in cols {
                let node: ScalarNodeId = scalar_of(j).unwrap_or_else(|| unreachable!("read columns are scalar nodes'"));
                let mut col = vec![0.0; n];
                m.iter().filter(|((_, jj), _)| *jj == j).for_each(|((i, jj), v)| {
                    col[*i] -= v;
                    removed[k].insert((*i, *jj), *v);
                });
                b.push(col);
                let mut row = vec![0.0; n];
                row[j] = 1.0;
                let measured = if k == 0 { Measurement::ScalarRate { node } } else { Measurement::ScalarValue { node } };
                let unit = OutputPort { name: String::new(), measurement: measured }.unit();
                if k == 0 {
                    c.push(vec![0.0; n]);
                    c_rate.push(row);
                    name(format!("{node} rate"), unit, unit);
                } else {
                    c.push(row);
                    c_rate.push(vec![0.0; n]);
                    name(format!("{node}"), unit, unit);
                }
            }
        }
        let [removed_fyd, removed_fy] = removed;
        (removed_fyd, removed_fy)
    };
    let list = |m: BTreeMap<(usize, usize), f64>| m.into_iter().map(|((i, j), v)| (i, j, v)).collect();
    Ok(CutPart { element, fyd: list(removed_fyd), fy: list(removed_fy), b, c, c_rate, inputs, outputs })
}

/// `m` with `cols` inserted as columns before its last `last` columns.
fn with_columns(m: &Mat<f64>, cols: &[Vec<f64>], last: usize) -> Mat<f64> {
    let at = m.ncols() - last;
    Mat::from_fn(m.nrows(), m.ncols() + cols.len(), |i, j| match j {
        j if j < at => m[(i, j)],
        j if j < at + cols.len() => cols[j - at][i],
        j => m[(i, j - cols.len())],
    })
}

/// `m` (`None`: zeros, `before` rows of `n` columns) with `rows` inserted before its last
/// `last` rows.
fn with_rows(m: Option<&Mat<f64>>, before: usize, n: usize, rows: &[Vec<f64>], last: usize) -> Mat<f64> {
    let at = before - last;
    let old = |i: usize, j: usize| m.map_or(0.0, |m| m[(i, j)]);
    Mat::from_fn(before + rows.len(), n, |i, j| match i {
        i if i < at => old(i, j),
        i if i < at + rows.len() => rows[i - at][j],
        i => old(i - rows.len(), j),
    })
}

impl CutPart {
    /// `B̃`, `C̃`, `C̃_v` and the names with the cut's ports inserted before the last `last`
    /// inputs and outputs.
    fn insert_ports(&self, b: &mut Mat<f64>, c: &mut Mat<f64>, c_rate: &mut Option<Mat<f64>>, names: (&mut Vec<String>, &mut Vec<String>), last: usize) {
        let (n, outputs) = (b.nrows(), c.nrows());
        *b = with_columns(b, &self.b, last);
        if c_rate.is_some() || self.c_rate.iter().flatten().any(|v| *v != 0.0) {
            *c_rate = Some(with_rows(c_rate.as_ref(), outputs, n, &self.c_rate, last));
        }
        *c = with_rows(Some(c), outputs, n, &self.c, last);
        let (inputs, outputs) = names;
        let (ni, no) = (inputs.len() - last, outputs.len() - last);
        inputs.splice(ni..ni, self.inputs.iter().cloned());
        outputs.splice(no..no, self.outputs.iter().cloned());
    }

    /// A dense linear DAE (with `F_/ẏ`, `F_/y`) cut here: the entries out, the ports
    /// inserted before its last `last` inputs and outputs (an imposed motion's, which stay last).
    pub fn cut_dense(&self, dae: &mut LinearDae, last: usize) {
        let Jacobians::Derivatives { fyd, fy } = &mut dae.jacobians else {
            unreachable!("a study's linearization holds F_/ẏ and F_/y");
        };
        self.fyd.iter().for_each(|&(i, j, v)| fyd[(i, j)] -= v);
        self.fy.iter().for_each(|&(i, j, v)| fy[(i, j)] -= v);
        self.insert_ports(&mut dae.b, &mut dae.c, &mut dae.c_rate, (&mut dae.input_names, &mut dae.output_names), last);
    }

    /// The same on a sparse linear DAE, the ports last.
    pub fn cut_sparse(&self, dae: &mut SparseLinearDae) {
        let minus = |m: &SparseMatrix, removed: &[(usize, usize, f64)]| {
            let entries = m.triplets().chain(removed.iter().map(|&(i, j, v)| (i, j, -v)));
            SparseMatrix::from_triplets(m.nrows(), m.ncols(), entries).unwrap_or_else(|| unreachable!("the removed entries are inside the matrix"))
        };
        dae.fyd = minus(&dae.fyd, &self.fyd);
        dae.fy = minus(&dae.fy, &self.fy);
        self.insert_ports(&mut dae.b, &mut dae.c, &mut dae.c_rate, (&mut dae.input_names, &mut dae.output_names), 0);
    }
}
