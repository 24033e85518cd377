//! Cache hints for the assembler's passes over the elements (issue 36 point 4). Every
//! element is its own heap allocation (a `beam3` with its two section laws over 1.5 kB, a
//! rigid body about 120 B), with its node slots and its latched data in two more; a pass
//! over a large model (the 1000-beam cantilever: megabytes of elements, passed twice per
//! Newton iteration that factors)
//! finds them evicted by the factorization's arrays since the last pass, and each element's
//! first loads then wait on memory (perf, 2026-12-07: a rigid body's residual spends two
//! thirds of its time on its first load). Asking for the element a few places ahead while
//! the current one computes overlaps those waits with work. A hint only: no result changes.

use crate::element::Element;
use crate::lu::prefetch::lines;

/// How many elements ahead of the one being evaluated the passes ask for: a rigid body's
/// residual takes about 100 ns, a memory load about as long.
pub(super) const AHEAD: usize = 2;

/// The most bytes of one element asked for: a bound on the hints per element.
const MOST: usize = 4096;

/// Asks for an element's own data, its node slots and its latched data.
#[inline(always)]
pub(super) fn element(el: &dyn Element, slots: &[usize], latched: Option<&crate::element::Latched>) {
    lines((el as *const dyn Element).cast::<u8>(), std::mem::size_of_val(el).min(MOST));
    lines(slots.as_ptr(), std::mem::size_of_val(slots));
    if let Some(l) = latched {
        lines(std::sync::Arc::as_ptr(l).cast::<u8>(), std::mem::size_of_val(&**l).min(MOST));
    }
}
