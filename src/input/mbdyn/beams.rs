//! `beam3` (input manual, "Elements", §Three-node beam element): three nodes with offsets
//! (and optional orientations), then for evaluation points I and II a section orientation
//! (global, or `from nodes`) and a 6-D constitutive law, `same` repeating point I's.
//! `beam:` is the same card as `beam3` (MBDyn reads both with one reader); `beam2` is named
//! as not supported.

use nalgebra::{Matrix6, Vector6};

use super::cursor::Cursor;
use super::diagnostic::MbdynError;
use super::element_context::{ElementContext, Parsed};
use super::laws::{linear_law, LinearLaw};
use crate::element::{Beam3, BeamNode, SectionLaw, SectionOrientation};
use crate::model::Label;

/// Flags of `custom output` (input manual, §default beam output).
const CUSTOM_OUTPUT: [&str; 14] = [
    "position", "orientation", "configuration", "force", "moment", "forces", "linear strain", "angular strain", "strains", "linear strain rate",
    "angular strain rate", "strain rates", "all", "none",
];

/// `NODE, [position,] OFFSET [, orientation|rot, R]` (offset and orientation in the node frame).
fn beam_node(c: &mut Cursor, ctx: &ElementContext, what: &str) -> Result<BeamNode, MbdynError> {
    let n = ctx.node(c, what)?;
    let on = ctx.on(n);
    c.accept("position");
    let offset = on.relative_position(c, &format!("offset of {what} [m]"))?;
    let node = BeamNode::new(n.label, n.position, n.orientation, offset);
    if c.accept("orientation") || c.accept("rot") {
        return Ok(node.with_orientation(on.relative_orientation(c, &format!("orientation of {what}"))?));
    }
    Ok(node)
}

/// A section frame: `from nodes` (or `node`), or an orientation in the global frame.
fn section_orientation(c: &mut Cursor, ctx: &ElementContext, what: &str) -> Result<SectionOrientation, MbdynError> {
    if c.accept("from nodes") || c.accept("node") {
        return Ok(SectionOrientation::FromNodes);
    }
    Ok(SectionOrientation::Given(ctx.global().orientation(c, what)?))
}

pub(super) fn section_law(law: &LinearLaw) -> SectionLaw {
    let m = |d: &nalgebra::DMatrix<f64>| Matrix6::from_fn(|i, j| d[(i, j)]);
    let v = |d: &nalgebra::DVector<f64>| Vector6::from_fn(|i, _| d[i]);
    let mut s = SectionLaw::viscoelastic(m(&law.stiffness), m(&law.viscosity));
    s.prestrain = v(&law.prestrain);
    s.prestress = v(&law.prestress);
    s
}

/// `beam3: LABEL, NODE_1, …, NODE_3, …, R_I, LAW_I, {same | R_II}, {same | LAW_II}
/// [, custom output, FLAGS…]`.
pub fn beam(keyword: &str, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    if keyword != "beam3" && keyword != "beam" {
        return Err(c.error_at(c.statement().span, format!("element type '{keyword}' ({keyword} {label}) is not supported by romdyn (supported: beam3)")));
    }
    let nodes = [beam_node(c, ctx, "node 1")?, beam_node(c, ctx, "node 2")?, beam_node(c, ctx, "node 3")?];
    let orientation_i = section_orientation(c, ctx, "orientation of section I")?;
    let law_i = linear_law(c, 6, ctx.laws, ctx.drives, ctx.seq)?;
    let orientation_ii = if c.accept("same") { orientation_i.clone() } else { section_orientation(c, ctx, "orientation of section II")? };
    let law_ii = if c.accept("same") { law_i.clone() } else { linear_law(c, 6, ctx.laws, ctx.drives, ctx.seq)? };
    if c.accept("custom output") {
        // The flags select NetCDF output only (input manual): romdyn writes its own.
        c.keyword("a custom output flag", &CUSTOM_OUTPUT)?;
        while c.accept_any(&CUSTOM_OUTPUT).is_some() {}
    }
    let span = c.statement().span;
    let beam = Beam3::new(label, nodes, [orientation_i, orientation_ii], [section_law(&law_i), section_law(&law_ii)]).map_err(|e| c.error_at(span, e.to_string()))?;
    Ok(Parsed::Element(Box::new(beam)))
}
