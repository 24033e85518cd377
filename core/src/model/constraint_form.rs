//! How a model writes its constraint equations and their multipliers (paper §6.1, eqs.
//! 29–30): the assembly, Newton and the linearization follow it, the eigenanalysis reads it.

/// Which layout the constraint equations use; it decides how many eigenvalues of the
/// constrained variables come out zero or infinite (paper §6.1, Table 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ConstraintForm {
    /// Eq. 29: multipliers are algebraic unknowns, constraint rows unscaled.
    Plain,
    /// Eq. 30: multipliers treated as derivatives, constraint rows divided by dCoef.
    Scaled,
}

impl ConstraintForm {
    pub fn name(self) -> &'static str {
        match self {
            ConstraintForm::Plain => "plain (eq. 29)",
            ConstraintForm::Scaled => "scaled (eq. 30)",
        }
    }
}
