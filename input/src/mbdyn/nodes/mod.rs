//! The `nodes` block: structural nodes (static, dynamic, modal, dummy) and scalar nodes (abstract, electric, hydraulic, parameter).

pub(super) mod scalar;
pub(super) mod structural;
