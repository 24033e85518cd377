//! Plate elements (input manual, "Plate Elements"): `{shell4eas | shell4easans}: LABEL,
//! NODE_1 [, orientation, R], …, NODE_4 [, orientation, R], SHELL_LAW` (§Shell4; a node's
//! `orientation` is read and, as MBDyn 1.7.3 does, not used) and `membrane4eas: LABEL,
//! NODE_1, …, NODE_4, MEMBRANE_LAW` (§Membrane4; displacement nodes or structural nodes),
//! the laws in [`super::plate_laws`].

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use super::context::{ElementContext, Parsed};
use super::plate_laws::{membrane_law, shell_law};
use crate::element::{Membrane4, Shell4, ShellVariant};
use crate::model::Label;
use crate::mbdyn::syntax::diagnostic;

/// `shell4eas`, `shell4easans` and `membrane4eas` (and the refusal of any other plate
/// element).
pub fn plate(keyword: &str, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    let variant = match keyword {
        "shell4eas" => ShellVariant::Eas,
        "shell4easans" => ShellVariant::EasAns,
        "membrane4eas" => return membrane(label, c, ctx),
        _ => return Err(c.error_at(c.statement().span, diagnostic::mbdyn_runs_it(&format!("element type '{keyword}' ({keyword} {label}; romdyn reads the plate elements 'shell4eas', 'shell4easans' and 'membrane4eas')")))),
    };
    let nodes = four(c, |c, k| {
        let n = ctx.node(c, &format!("node {k} of {keyword} {label}"))?;
        if c.accept("orientation") {
            ctx.on(n).relative_orientation(c, &format!("orientation of node {k}"))?;
        }
        Ok((n.label, n.position, n.orientation))
    })?;
    let law = shell_law(c)?;
    let shell = Shell4::new(variant, label, nodes, law).map_err(|e| c.error_at(c.statement().span, e.to_string()))?;
    Ok(Parsed::Element(Box::new(shell)))
}

/// `membrane4eas: LABEL, NODE_1, …, NODE_4, MEMBRANE_LAW` (MBDyn reads `StructDispNode`s:
/// displacement nodes or structural nodes).
fn membrane(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    let nodes = four(c, |c, k| {
        let (n, _) = ctx.point_node(c, &format!("node {k} of membrane4eas {label}"))?;
        Ok((n.label, n.position))
    })?;
    let law = membrane_law(c)?;
    let membrane = Membrane4::new(label, nodes, law).map_err(|e| c.error_at(c.statement().span, e.to_string()))?;
    Ok(Parsed::Element(Box::new(membrane)))
}

/// The four nodes' data, read in order (`read` gets the node's number, 1 to 4).
fn four<T>(c: &mut Cursor, mut read: impl FnMut(&mut Cursor, usize) -> Result<T, MbdynError>) -> Result<[T; 4], MbdynError> {
    Ok([read(c, 1)?, read(c, 2)?, read(c, 3)?, read(c, 4)?])
}
