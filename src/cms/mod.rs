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
//! **Craig–Bampton, two-sided.** With `b` the interface nodes' coordinates and `i` the
//! others, the right basis `T` and the left basis `T_L`:
//!
//! ```text
//! T   = [ Φ_n   Ψ ],   Ψ   = [ −K_ii⁻¹ K_ib ; I ]     K_ii Φ_n = M_ii Φ_n Ω²
//! T_L = [ Φ_L   Ψ_L ], Ψ_L = [ −K_ii⁻ᵀ K_biᵀ ; I ]   K_iiᵀ Φ_L = M_ii Φ_L Ω²
//! M_cb = T_Lᵀ M T,   K_cb = T_Lᵀ K T,   Φ_Lᵀ M_ii Φ_n = I,  Φ_nᵀ M_ii Φ_n = diag(1)
//! ```
//!
//! (interior rows first in the blocks as written, interface rows `0` in the normal modes).
//! MBDyn's finite-volume beams have a stiffness that is not symmetric (a beam3's rotation–
//! translation entries differ from their transposes by 18 %), and a one-sided (Galerkin)
//! reduction of it does not converge to the whole model's modes (−12 % at 8 modes on
//! `examples/optical_table_top.mbd`); the two-sided one does. It fits the FEM file: the
//! interface rows of `T` and `T_L` are the same (`I`, `0`), so the interface reactions act
//! on the modes through `T`'s rows as the modal joint applies them, while `T`'s rows are
//! the mode shapes written (record 8). The N lowest normal modes are the eigenvectors of
//! `K_ii⁻¹ M_ii` with the largest `1/ω²` (massless coordinates give 0: never among them); a
//! Cholesky factorization of the symmetric part of `K_ii` first checks that the interface
//! holds the substructure. The constraint modes span the substructure's rigid-body motions,
//! so the FEM file is for a `clamped` modal joint (the floating frame fixed at the FEM
//! frame, the global one): the linear model of the substructure for small motions about its
//! reference.
//!
//! The FEM file lists every structural node of the substructure (label = the node's label),
//! at its reference position, with the mode shapes `T` at its six coordinates; record 11
//! holds the diagonal of each node's mass block, record 12 the rigid-body inertia of `M`
//! (exact, `Rᵀ M R` with `R` the six rigid motions). The inertia invariants MBDyn builds
//! from record 11 use `T` (right) alone: gravity on the modes of a clamped joint is
//! `T_Lᵀ M g` only where the two bases agree (a symmetric stiffness); on beam3 substructures
//! it departs by up to 8e-3 of the largest modal load (docs/src/guide/cms.md, Limits), the
//! weight carried by one interface node's rigid constraint modes exactly.

mod reduce;

pub use reduce::{craig_bampton, structural_matrices, CmsError, CmsRequest, CraigBampton, StructuralMatrices};
