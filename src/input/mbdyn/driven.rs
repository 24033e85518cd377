//! The head of a `driven` card (input manual, §Driven Element): `driven: LABEL, DRIVE,
//! [hint, "…", …,] ELEMENT_CARD;`, read after the wrapped element, which it switches on
//! where the drive is non-zero (driven.cc).

use super::cursor::Cursor;
use super::diagnostic::{MbdynError, Sources};
use super::element_context::{ElementContext, Parsed};
use super::parser::Statement;
use crate::element::DrivenElement;

/// Wraps the element `parsed`, read from the statement `head` is the `driven` head of.
pub fn wrap(head: &Statement, parsed: Parsed, src: &Sources, ctx: &ElementContext) -> Result<Parsed, MbdynError> {
    let mut c = Cursor::new(head, src);
    let label_span = c.here();
    let label = c.label("driven element label")?;
    let drive = super::drives::drive(&mut c, ctx.drives, ctx.seq)?;
    if c.peek_keyword().is_some_and(|k| super::parser::same_keyword(k, "hint")) {
        // Hints re-set the element's data from the model's state when it switches on
        // (SimulationEntity::Hints, `SetValue`): romdyn cannot honour them.
        return Err(c.error("driven: hints (which re-set the element from the model's state when it switches on) are not supported by romdyn"));
    }
    c.finish()?;
    match parsed {
        Parsed::Element(inner) => {
            if inner.label() != label {
                // driven.cc: the driving element's label must match the wrapped one's.
                return Err(c.error_at(label_span, format!("driven element {label} wraps {} {}: the labels must match", inner.type_name(), inner.label())));
            }
            if (0..inner.multipliers().len()).any(|k| inner.is_coordinate(k)) {
                // Switched off, its coordinate (the abscissa) would be held at its initial value.
                return Err(c.error_at(head.span, format!("driven: a driven {} is not supported by romdyn (switched off, its abscissa would return to its initial value)", inner.type_name())));
            }
            Ok(Parsed::Element(Box::new(DrivenElement { drive, inner })))
        }
        Parsed::Ignored => Ok(Parsed::Ignored),
        _ => Err(c.error_at(head.span, "driven: romdyn switches joints, forces and beams on and off, not bodies or gravity")),
    }
}
