//! The assembled DAE: numbering of unknowns and equations, the state vector, assembly of
//! `F(y, ẏ, t)` and `J(c) = F_/ẏ + c F_/y` (eqs. 1, 5), and linearization (eqs. 13–16).
//!
//! Conventions (METHOD §2, §5):
//! - Newton solves `J(c) δẏ = −F`, then `ẏ += δẏ`, `y += c δẏ` for differential unknowns.
//! - Node unknowns: static `[x, g]`, dynamic `[x, g, β, γ]`; `R = R(g) R_ref`, `ω = G(g) ġ`,
//!   `R_ref` re-based every step so that `g = 0` at a converged solution.
//! - Node equations: dynamic rows 0–5 are the momentum definitions, rows 6–11 the force and
//!   moment equilibrium (`β̇ − f`, `γ̇ + ẋ × β − m`); static rows 0–5 the equilibrium. A
//!   displacement-only node's rotation rows hold `g = 0` (static: the moment rows read `g`;
//!   dynamic: `γ = 0` and `γ̇ + g`); a moving frame (`Model::frame_motion`) adds `2 W × β`
//!   and `W × γ` to the equilibrium.
//! - Multipliers follow the [`ConstraintForm`]: `Scaled` (eq. 30, MBDyn's): algebraic
//!   unknowns updated by `δ` with Jacobian coefficient 1, constraint rows `Φ/c` with Jacobian
//!   `Φ_/q`; `Plain` (eq. 29): treated like `y` (coefficient `c`), rows `Φ` with `c Φ_/q`.
//!   Static analysis solves `F(y, 0, t) = 0` with `F_/y` in the plain form.
//!
//! [`ConstraintForm`]: crate::model::ConstraintForm

mod accelerations;
mod modal_rates;
mod assembled_check;
mod assembly;
mod check;
mod cut;
mod dofs;
mod element_part;
mod eliminate;
mod factored;
mod jacobian_sink;
mod linearize;
mod prefetch;
pub mod ports;
mod sparse;
mod state;

pub use accelerations::node_accelerations;
pub use modal_rates::{modal_coordinates, ModalRow};
pub use assembled_check::{check_assembled, AssembledMismatch};
pub use assembly::{Assembler, Coefficients, Frames};
pub use jacobian_sink::Shape;
pub use check::{check_jacobians, JacobianMismatch};
pub use cut::{cut_parts, Cut, CutError, CutFamily, CutPart};
pub use dofs::{DofMap, Owner};
pub use element_part::{element_part, ElementPart, ElementPartError};
pub use linearize::{linearize, linearize_ports, linearize_sparse, sparse_jacobian_pair, NodeInput, NodeOutput};
pub use ports::{FemOutput, InputPort, OutputPort, PortError, PortMap};
pub use sparse::{LuPath, SparseLu, Triplets, BAND_WORK_PER_ENTRY};
pub use state::State;
