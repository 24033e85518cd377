//! `joint: LABEL, beam slider, …` (input manual, §Beam slider; joint.cc, `BEAMSLIDER`):
//!
//! ```text
//! beam slider, NODE, OFFSET, [hinge, R,] [type, {spherical | classic | spline},] N,
//!     { BEAM, {same | O_1}, [hinge, {same | R_1},] O_2, [hinge, R_2,] O_3, [hinge, R_3,] } × N
//!     [, initial beam, K] [, initial node, J] [, smearing, D]
//! ```
//!
//! Offsets and orientations are relative to their node. MBDyn 1.7.3 reads `hinge`; later
//! versions read `orientation` (with `hinge` deprecated): romdyn reads both. The beam nodes'
//! orientations are read and unused, as beamslider.cc's residual does not use them. Beam
//! `i + 1`'s node 1 must be beam `i`'s node 3 and its offset the same (MBDyn's "do not
//! match"). `initial beam` (default 1) and `initial node` (default 2) count from 1 in the
//! list and in the beam; the smearing factor is in `[0, 0.4]`.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use super::context::ElementContext;
use crate::element::{BeamSlider, Element, NodeKinematics, SliderBeam, SliderKind};
use crate::kinematics::{Mat3, Vec3};
use crate::model::Label;

fn orientation(c: &mut Cursor, ctx: &ElementContext, node: Label, what: &str, same: bool) -> Result<(), MbdynError> {
    if c.accept("orientation") || c.accept("hinge") {
        if same && c.accept("same") {
            return Ok(());
        }
        let n = ctx.nodes.find(node).ok_or_else(|| c.error(format!("structural node {node} is not defined")))?;
        ctx.on(&n.node).relative_orientation(c, what)?;
    }
    Ok(())
}

pub fn beam_slider(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<BeamSlider, MbdynError> {
    let node = ctx.node(c, "the slider node")?;
    let on = ctx.on(node);
    let offset = on.relative_position(c, "offset of the slider [m]")?;
    let frame = if c.accept("orientation") || c.accept("hinge") { on.relative_orientation(c, "orientation of the slider")? } else { Mat3::identity() };
    let kind = if c.accept("type") {
        let at = c.here();
        match c.keyword("the slider type", &["spherical", "classic", "spline"])? {
            "spherical" => SliderKind::Spherical,
            "classic" => SliderKind::Classic,
            _ => return Err(c.error_at(at, "beam slider type 'spline' is not supported by romdyn: MBDyn 1.7.3's writes no equation for its third rotation constraint (beamslider.cc, \"FIXME: vincolo spline\"), a singular Jacobian")),
        }
    } else {
        SliderKind::Spherical
    };
    let count_at = c.here();
    let count = c.count("number of beams")?;
    if count == 0 {
        return Err(c.error_at(count_at, "beam slider: at least one beam is needed"));
    }
    let mut beams: Vec<SliderBeam> = Vec::new();
    for i in 0..count {
        let at = c.here();
        let beam = c.label("beam label")?;
        let nodes = *ctx.beams.get(&beam).ok_or_else(|| c.error_at(at, format!("beam slider: beam {beam} is not defined before it (a beam3)")))?;
        let on_node = |c: &Cursor, k: usize| ctx.nodes.find(nodes[k]).map(|n| &n.node).ok_or_else(|| c.error_at(at, format!("structural node {} is not defined", nodes[k])));
        let mut offsets = [Vec3::zeros(); 3];
        if let Some(prev) = beams.last() {
            if nodes[0] != prev.nodes[2] {
                return Err(c.error_at(at, format!("beam slider: node 1 ({}) of beam {beam} is not node 3 ({}) of the previous beam", nodes[0], prev.nodes[2])));
            }
            let o_at = c.here();
            offsets[0] = if c.accept("same") { prev.offsets[2] } else { ctx.on(on_node(c, 0)?).relative_position(c, "offset of node 1 [m]")? };
            if offsets[0] != prev.offsets[2] {
                return Err(c.error_at(o_at, format!("beam slider: the offset of node 1 of beam {beam} differs from that of node 3 of the previous beam")));
            }
        } else {
            offsets[0] = ctx.on(on_node(c, 0)?).relative_position(c, "offset of node 1 [m]")?;
        }
        orientation(c, ctx, nodes[0], "orientation at node 1", i > 0)?;
        for k in 1..3 {
            offsets[k] = ctx.on(on_node(c, k)?).relative_position(c, &format!("offset of node {} [m]", k + 1))?;
            orientation(c, ctx, nodes[k], &format!("orientation at node {}", k + 1), false)?;
        }
        beams.push(SliderBeam { nodes, offsets });
    }
    let index = |c: &mut Cursor, what: &str, max: usize| -> Result<usize, MbdynError> {
        let at = c.here();
        let k = c.count(what)?;
        if k < 1 || k > max {
            return Err(c.error_at(at, format!("beam slider: {what} must be between 1 and {max}, found {k}")));
        }
        Ok(k)
    };
    let initial_beam = if c.accept("initial beam") { index(c, "initial beam", count)? } else { 1 };
    let initial_node = if c.accept("initial node") { index(c, "initial node", 3)? } else { 2 };
    let smearing = if c.accept("smearing") {
        let at = c.here();
        let d = c.real("smearing factor")?;
        if !(0.0..=0.4).contains(&d) {
            return Err(c.error_at(at, format!("beam slider: the smearing factor must be in [0, 0.4], found {d} (MBDyn warns and uses 0)")));
        }
        d
    } else {
        0.0
    };
    if super::friction::follows(c) {
        return Err(super::friction::refuse(c, "beam slider"));
    }
    let initial = 2.0 * (initial_beam as f64 - 1.0) + initial_node as f64 - 2.0;
    let mut slider = BeamSlider { label, node: node.label, offset, orientation: frame, kind, beams, initial, smearing, start_rate: None };
    // MBDyn's derivatives phase solves for the abscissa from the initial node on; romdyn
    // starts from the point of the line nearest the slider as written, moving along it at
    // the written velocities' rate when the slider is on the line.
    let kin: Option<Vec<NodeKinematics>> = slider.nodes().iter().map(|&l| ctx.nodes.find(l).map(|n| NodeKinematics { x: n.node.position, r: n.node.orientation, xdot: n.node.velocity, omega: n.node.angular_velocity })).collect();
    if let Some((s, rate)) = kin.and_then(|k| slider.start(&k)) {
        slider.initial = s;
        slider.start_rate = rate;
    }
    Ok(slider)
}
