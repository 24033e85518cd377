//! Drive callers (MBDyn input manual, "General", §Drive Caller): the scalar functions of
//! time, and of the model's state where a caller reads it, that drive forces, couples,
//! imposed motions and constitutive laws. [`Drive`] and [`TimeFunction`] are the callers
//! (`caller.rs`), with their time derivatives where an element needs `ḋ(t)` (`rate.rs`);
//! [`StepDrive`] the callers with a memory of the accepted steps (`step.rs`);
//! [`ScalarFunction`] MBDyn's named scalar functions; [`c_rand`] the C library's `rand()`
//! of the `random` caller. They read an element's state through
//! [`crate::element::ElementState`], which is why they sit under the elements.

mod caller;
pub mod c_rand;
mod rate;
mod scalar_function;
mod step;

pub use caller::{note_evaluation_failure, take_evaluation_failure, Drive, EvaluationCost, SampledChannel, TimeFunction};
pub use scalar_function::ScalarFunction;
pub use step::{RotationRead, StepDrive, StepKind, Turns};
