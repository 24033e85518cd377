//! The head of a `driven` card (input manual, §Driven Element): `driven: LABEL, DRIVE,
//! [hint, "…", …,] ELEMENT_CARD;`, read after the wrapped element, which it switches on
//! where the drive is non-zero (driven.cc).

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Sources};
use super::context::{ElementContext, Parsed};
use crate::mbdyn::syntax::parser::Statement;
use crate::element::DrivenElement;
use crate::element::UnknownKind;
use crate::mbdyn::drives::callers;
use crate::mbdyn::syntax::diagnostic;

/// Wraps the element `parsed`, read from the statement `head` is the `driven` head of.
pub fn wrap(head: &Statement, parsed: Parsed, src: &Sources, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    let mut c = Cursor::new(head, src);
    let label_span = c.here();
    let label = c.label("driven element label")?;
    let drive = callers::drive(&mut c, ctx.drives, ctx.seq)?;
    // Hints re-set the element's drives from the model's state when it switches on
    // (SimulationEntity::Hints, the joints' `SetValue`; see [`super::hints`]).
    let (mut hints, mut probes) = (Vec::new(), Vec::new());
    while c.accept("hint") {
        let at = c.here();
        let text = c.string("hint text, e.g. \"drive{…}\"")?;
        let (hint, probe) = super::hints::hint(&text, at, src, ctx.drives, ctx.seq)?;
        hints.push(hint);
        probes.push((probe, at));
    }
    c.finish()?;
    match parsed {
        Parsed::Element(inner) => {
            if inner.label() != label {
                // driven.cc: the driving element's label must match the wrapped one's.
                return Err(c.error_at(label_span, format!("driven element {label} wraps {} {}: the labels must match", inner.type_name(), inner.label())));
            }
            // A distance joint's coordinates are its direction, which its constraint
            // determines (linearly) once it is on again: held at the written direction while
            // it is off (MBDyn holds them at zero), they are solved for at the switch-on.
            if inner.type_name() != "distance" && (0..inner.multipliers().len()).any(|k| inner.unknown_kind(k) == UnknownKind::Coordinate) {
                // Switched off, its coordinate (the abscissa) would be held at its initial value.
                return Err(c.error_at(head.span, format!("driven: a driven {} is not supported by romdyn (MBDyn 1.7.3 runs it) (switched off, its abscissa would return to its initial value)", inner.type_name())));
            }
            if (0..inner.multipliers().len()).any(|k| inner.unknown_kind(k) == UnknownKind::State) {
                // Its own differential states (a friction model's bristle deflection) would have
                // to be frozen while it is off and restarted when it switches on.
                return Err(c.error_at(head.span, format!("driven: a driven {} with states of its own (joint friction) is not supported by romdyn (MBDyn 1.7.3 runs it)", inner.type_name())));
            }
            if inner.events().is_some() {
                return Err(c.error_at(head.span, format!("driven: a driven {} with events of its own (a bistop law, a total joint locking some rotation components only) is not supported by romdyn (MBDyn 1.7.3 runs it)", inner.type_name())));
            }
            check_hints_apply(&*inner, &probes, src)?;
            Ok(Parsed::Element(Box::new(DrivenElement { drive, inner, hints })))
        }
        Parsed::Ignored => Ok(Parsed::Ignored),
        _ => Err(c.error_at(head.span, "driven: romdyn switches joints, forces and beams on and off, not bodies or gravity")),
    }
}

/// Each hint applies to the element: its drive as the read-time check built it (each
/// `model::` read 0) is taken by the element re-set by the hints before it.
fn check_hints_apply(inner: &dyn crate::element::Element, probes: &[(crate::element::HintValue, diagnostic::Span)], src: &Sources) -> Result<(), MbdynError> {
    let mut element: Option<Box<dyn crate::element::Element>> = None;
    for (k, (value, at)) in probes.iter().enumerate() {
        let base = element.as_deref().unwrap_or(inner);
        match base.hinted(value) {
            Some(e) => element = Some(e),
            None => return Err(src.error(*at, format!("driven: hint {} does not apply to a {} in romdyn (\"drive{{…}}\" applies to a distance joint, \"drive3{{…}}\" to a drive hinge, \"position-drive3{{…}}\" to a total joint or total pin joint, \"orientation-drive3{{…}}\" to one with all rotations held)", k + 1, base.type_name()))),
        }
    }
    Ok(())
}
