//! Solvers on the assembled DAE: MBDyn's initial assembly, Newton with sparse LU (symbolic factorization reused),
//! static analysis with load ramping, consistent initial derivatives, and fixed-step
//! implicit multistep integration in predictor–corrector form (eqs. 2–5).

mod forward_difference;
mod initial_assembly;
mod integrate;
mod newton;
mod singular;
mod static_analysis;

pub use crate::model::Method;
pub use initial_assembly::{initial_assembly, AssemblyError, AssemblyReport};
pub use integrate::{BatheCoefficients, constraint_rate, initial_derivatives, initial_derivatives_in, initial_derivatives_with, momentum_velocity_change, newton_dcoef, Integrator, StepRecord};
pub use newton::{newton, Convergence, DerivativeMomenta, NewtonFailure, NewtonSettings, NewtonWorkspace, SolveError, Update, KEEP_JACOBIAN_BELOW};
pub use singular::explain_singular_matrix;
pub use static_analysis::static_solution;
