//! A beam's `piezoelectric actuator` (input manual, "Three-node beam element", "Two-node
//! beam element"; MBDyn 1.7.3 beam.cc `ReadBeam`, beam2.cc `ReadBeam2`), after the section
//! laws:
//!
//! ```text
//! piezoelectric actuator, N, ABSTRACT_NODE_1, …, ABSTRACT_NODE_N,
//!     MAT6xN_I [, {same | MAT6xN_II}]          (the second matrix: beam3 only)
//! MAT6xN ::= null | [anba | matr,] 6 N values by rows [, scale, FACTOR]
//! ```
//!
//! The electrodes are abstract nodes, read by label among the abstract nodes (a
//! `ScalarDifferentialNode` in MBDyn: an algebraic abstract node is refused there, "unable
//! to cast"); each matrix is 3 rows of local force per volt, then 3 of moment per volt
//! (mbpar.cc `GetMat6xN`; `anba` reads each half's rows in the order 2, 3, 1).

use nalgebra::DMatrix;

use super::context::ElementContext;
use crate::element::{PiezoActuator, ScalarNodeId, ScalarNodeKind};
use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use crate::model::Label;

/// The actuator of beam `keyword label` with `points` evaluation points, if the card has
/// one here; `None` otherwise.
pub fn piezoelectric_actuator(c: &mut Cursor, ctx: &ElementContext, keyword: &str, label: Label, points: usize) -> Result<Option<PiezoActuator>, MbdynError> {
    let at = c.here();
    if !c.accept("piezoelectric actuator") {
        return Ok(None);
    }
    let name = format!("{keyword} {label}, piezoelectric actuator");
    let count_at = c.here();
    let n = c.count(&format!("{name}: number of electrodes"))?;
    if n == 0 {
        return Err(c.error_at(count_at, format!("{name}: the number of electrodes must be at least 1 (MBDyn 1.7.3: \"illegal number of electric nodes 0\")")));
    }
    let mut electrodes = Vec::with_capacity(n);
    for k in 1..=n {
        electrodes.push(electrode(c, ctx, &format!("{name}, electrode {k}"))?);
    }
    let mut matrices = vec![mat6xn(c, n, &format!("{name}: actuation matrix of section I [N/V, N m/V]"))?];
    if points == 2 {
        let second = if c.accept("same") { matrices[0].clone() } else { mat6xn(c, n, &format!("{name}: actuation matrix of section II ('same' or 6x{n} values) [N/V, N m/V]"))? };
        matrices.push(second);
    }
    PiezoActuator::new(label, electrodes, matrices).map(Some).map_err(|e| c.error_at(at, e.to_string()))
}

/// An electrode: the label of a differential abstract node.
fn electrode(c: &mut Cursor, ctx: &ElementContext, what: &str) -> Result<ScalarNodeId, MbdynError> {
    let at = c.here();
    let id = ScalarNodeId { kind: ScalarNodeKind::Abstract, label: c.label(&format!("{what}: abstract node label"))? };
    match ctx.nodes.2.iter().find(|e| e.node.id == id) {
        None => Err(c.error_at(at, format!("{what}: {id} is not defined (MBDyn 1.7.3 reads the electrodes among the abstract nodes)"))),
        Some(e) if !e.node.differential => Err(c.error_at(at, format!("{what}: {id} is algebraic, and MBDyn 1.7.3 takes differential abstract nodes only (\"unable to cast\" to a ScalarDifferentialNode): declare it 'differential'"))),
        Some(_) => Ok(id),
    }
}

/// A 6 × N matrix as mbpar.cc's `GetMat6xN` reads it: `null`, or 6 N values by rows
/// (optionally after `matr`, or after `anba`: each half's rows in the order 2, 3, 1), then
/// an optional `scale, FACTOR`.
fn mat6xn(c: &mut Cursor, n: usize, what: &str) -> Result<DMatrix<f64>, MbdynError> {
    let mut m = DMatrix::zeros(6, n);
    if c.accept("null") {
        return Ok(m);
    }
    let rows = if c.accept("anba") {
        [1, 2, 0]
    } else {
        c.accept("matr");
        [0, 1, 2]
    };
    for half in [0, 3] {
        for row in rows {
            for col in 0..n {
                m[(half + row, col)] = c.real(what)?;
            }
        }
    }
    if c.accept("scale") {
        m *= c.real(&format!("{what}: scale factor"))?;
    }
    Ok(m)
}
