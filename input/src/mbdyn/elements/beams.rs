//! `beam3` (input manual, "Elements", §Three-node beam element): three nodes with offsets
//! (and optional orientations), then for evaluation points I and II a section orientation
//! (global, or `from nodes`) and a 6-D constitutive law, `same` repeating point I's, then an
//! optional `piezoelectric actuator` ([`super::beam_piezo`]).
//! `beam:` is the same card as `beam3` (MBDyn reads both with one reader). `beam2`: two
//! nodes with offsets (and optional orientations), one section orientation (global, or
//! `from nodes`), one 6-D law (elastic: a viscous one is refused) and an optional
//! `piezoelectric actuator` with one matrix.

use nalgebra::{Matrix6, Vector6};

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use super::beam_piezo::piezoelectric_actuator;
use super::context::{ElementContext, Parsed};
use super::laws::{nonlinear_law, LinearLaw};
use crate::mbdyn::read_options::BeamUpdateRule;
use crate::element::{Beam2, Beam3, BeamNode, BeamUpdate, SectionLaw, SectionOrientation};
use crate::model::Label;

/// Why `hbeam` is refused. MBDyn's hbeam.cc is a two-node beam whose position and
/// orientation follow the screw motion from node 1's pose to node 2's (strains from the
/// relative pose's SE(3) logarithm); the input manual calls it experimental, "only for
/// development purposes", its reader takes node 1's absolute orientation for both nodes'
/// beam frames when none is given (the frames are then wrong for nodes not at `eye`), and
/// its viscoelastic variant is not built.
pub const HBEAM_REFUSED: &str = "element type 'hbeam' is not supported by romdyn (MBDyn 1.7.3 runs it, but its manual calls it experimental, for development only); use beam2, whose curvature is exact for a uniformly bent element";

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

pub(in crate::mbdyn) fn section_law(law: &LinearLaw) -> SectionLaw {
    let m = |d: &nalgebra::DMatrix<f64>| Matrix6::from_fn(|i, j| d[(i, j)]);
    let v = |d: &nalgebra::DVector<f64>| Vector6::from_fn(|i, _| d[i]);
    let mut s = SectionLaw::viscoelastic(m(&law.stiffness), m(&law.viscosity)).with_functions(law.functions.clone()).with_time_variance(law.time_variance.clone());
    s.prestrain = v(&law.prestrain);
    s.prestress = v(&law.prestress);
    s
}

/// `custom output, FLAGS…` (NetCDF only, input manual: romdyn writes its own).
fn custom_output(c: &mut Cursor) -> Result<(), MbdynError> {
    if c.accept("custom output") {
        c.keyword("a custom output flag", &CUSTOM_OUTPUT)?;
        while c.accept_any(&CUSTOM_OUTPUT).is_some() {}
    }
    Ok(())
}

/// `beam3: LABEL, NODE_1, …, NODE_3, …, R_I, LAW_I, {same | R_II}, {same | LAW_II}
/// [, piezoelectric actuator, …] [, custom output, FLAGS…]`; `beam2: LABEL, NODE_1, …,
/// NODE_2, …, R_I, LAW_I [, piezoelectric actuator, …] [, custom output, FLAGS…]`.
pub fn beam(keyword: &str, label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    if keyword == "beam2" {
        let nodes = [beam_node(c, ctx, "node 1")?, beam_node(c, ctx, "node 2")?];
        let orientation = section_orientation(c, ctx, "orientation of section I")?;
        let law = nonlinear_law(c, 6, ctx.laws, ctx.drives, ctx.seq)?;
        let piezo = piezoelectric_actuator(c, ctx, keyword, label, 1)?;
        custom_output(c)?;
        let span = c.statement().span;
        let mut beam = Beam2::new(label, nodes, orientation, section_law(&law)).map_err(|e| c.error_at(span, e.to_string()))?;
        if let Some(piezo) = piezo {
            beam = beam.with_piezo(piezo).map_err(|e| c.error_at(span, e.to_string()))?;
        }
        let beam = match updated(c, ctx, &format!("beam2 {label}"), Ok(()))? {
            Some(update) => beam.with_update(update),
            None => beam,
        };
        return Ok(Parsed::Element(Box::new(beam)));
    }
    if keyword != "beam3" && keyword != "beam" {
        return Err(c.error_at(c.statement().span, format!("element type '{keyword}' ({keyword} {label}) is not supported by romdyn (supported: beam2, beam3)")));
    }
    let nodes = [beam_node(c, ctx, "node 1")?, beam_node(c, ctx, "node 2")?, beam_node(c, ctx, "node 3")?];
    let orientation_i = section_orientation(c, ctx, "orientation of section I")?;
    let law_i = nonlinear_law(c, 6, ctx.laws, ctx.drives, ctx.seq)?;
    let orientation_ii = if c.accept("same") { orientation_i.clone() } else { section_orientation(c, ctx, "orientation of section II")? };
    let law_ii = if c.accept("same") { law_i.clone() } else { nonlinear_law(c, 6, ctx.laws, ctx.drives, ctx.seq)? };
    let piezo = piezoelectric_actuator(c, ctx, keyword, label, 2)?;
    custom_output(c)?;
    let span = c.statement().span;
    let mut beam = Beam3::new(label, nodes, [orientation_i, orientation_ii], [section_law(&law_i), section_law(&law_ii)]).map_err(|e| c.error_at(span, e.to_string()))?;
    if let Some(piezo) = piezo {
        beam = beam.with_piezo(piezo).map_err(|e| c.error_at(span, e.to_string()))?;
    }
    let takes_incremental = beam.check_update(BeamUpdate::Incremental).map_err(|e| e.to_string());
    let beam = match updated(c, ctx, &format!("beam3 {label}"), takes_incremental)? {
        Some(update) => beam.with_update(update).map_err(|e| c.error_at(span, e.to_string()))?,
        None => beam,
    };
    Ok(Parsed::Element(Box::new(beam)))
}

/// The update the beam `name` takes under the reader's rule ([`BeamUpdateRule`]), `None`
/// for the path-independent default; `takes_incremental` says why the beam itself cannot
/// take the incremental one. A driven beam cannot either: its history would be latched by
/// the beam's events, which a driven element does not carry (driven.rs). Where the rule asks
/// for the incremental update wherever possible, a beam that cannot take it keeps the
/// path-independent one with a note; where it asks for it on every beam, that is an error at
/// the card.
fn updated(c: &Cursor, ctx: &ElementContext, name: &str, takes_incremental: Result<(), String>) -> Result<Option<BeamUpdate>, MbdynError> {
    let cannot = if c.statement().driven.is_some() {
        Err(format!("{name}: the incremental beam update of a driven beam is not supported by romdyn (MBDyn 1.7.3 runs it)"))
    } else {
        takes_incremental
    };
    match ctx.beam_update {
        BeamUpdateRule::Every(BeamUpdate::PathIndependent) => Ok(None),
        BeamUpdateRule::Every(BeamUpdate::Incremental) => match cannot {
            Ok(()) => Ok(Some(BeamUpdate::Incremental)),
            Err(why) => Err(c.error_at(c.statement().span, why)),
        },
        BeamUpdateRule::IncrementalWherePossible => match cannot {
            Ok(()) => Ok(Some(BeamUpdate::Incremental)),
            Err(why) => {
                ctx.beam_notes.borrow_mut().push(format!("{why}; this beam keeps the path-independent update, so its numbers can differ from MBDyn's (MBDyn's beam.cc is incremental)"));
                Ok(None)
            }
        },
    }
}
