//! Component mode synthesis (issue 35 point 3): a substructure written in MBDyn's input
//! language (structural nodes, bodies, beams, deformable springs) reduced to the FEM file
//! of MBDyn's `modal` joint ([`crate::input::fem`]) with fixed-interface (Craig–Bampton)
//! modes at chosen interface nodes.
//!
//! **Mass and stiffness in node coordinates.** The substructure is linearized at its
//! reference solution (`F_/ẏ Δẏ + F_/y Δy = 0`, eqs. 13–16) at rest. A dynamic node's
//! unknowns are its position `x`, rotation parameters `g` (at the linearization base
//! `g = 0`, so `δg` is the virtual rotation `δθ`, global axes) and momenta `β`, `γ`; its
//! momentum definitions read `β − ∂T/∂ẋ = 0`, `γ − ∂T/∂ω = 0` and its equilibrium rows
//! `β̇ − f = 0`. With `u = (δx, δθ)` per node (six coordinates each), at zero velocity
//!
//! ```text
//! M = −F_/ẏ [momentum definitions, u]      K = F_/y [equilibrium, u]
//! ```
//!
//! (a static node has no momentum definitions: no mass). Elements with own unknowns
//! (joints, multipliers) are refused: the substructure is free, and its supports belong to
//! the model that attaches it.
//!
//! **Craig–Bampton.** With `b` the interface nodes' coordinates and `i` the others,
//!
//! ```text
//! u = T (q_n, q_b),   T = [ Φ_n  Ψ ]      Ψ = [ I ; −K_ii⁻¹ K_ib ]  (constraint modes)
//!                          [ 0         ]
//! K_ii φ = ω² M_ii φ  (fixed-interface normal modes, the N lowest, φᵀ M_ii φ = 1)
//! M_cb = Tᵀ M T,   K_cb = Tᵀ K T
//! ```
//!
//! The normal modes come from the symmetric problem `L⁻¹ M_ii L⁻ᵀ v = (1/ω²) v` with
//! `K_ii = L Lᵀ` (Cholesky), so massless coordinates (a node without a body, a body
//! without rotary inertia) give `1/ω² = 0` and are never among the lowest modes. The
//! constraint modes span the substructure's rigid-body motions, so the FEM file is for a
//! `clamped` modal joint (the floating frame fixed at the FEM frame, the global one): the
//! linear model of the substructure for small motions about its reference.
//!
//! The FEM file lists every structural node of the substructure (label = the node's label),
//! at its reference position, with the mode shapes `T` at its six coordinates; record 11
//! holds the diagonal of each node's mass block, record 12 the rigid-body inertia of `M`
//! (exact, `Rᵀ M R` with `R` the six rigid motions).

mod reduce;

pub use reduce::{craig_bampton, structural_matrices, CmsError, CmsRequest, CraigBampton, StructuralMatrices};
