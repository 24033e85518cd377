//! Why an eigenanalysis gave no result: empty, non-finite or singular pencils (with the
//! unknowns of a common null vector), a bad dCoef, or QZ that did not converge.

/// Eigenanalysis failure.
#[derive(Debug, thiserror::Error)]
pub enum EigenError {
    #[error("the QZ iteration did not converge for the {0}x{0} pencil")]
    NoConvergence(usize),
    #[error("the pencil is empty")]
    Empty,
    #[error("the pencil has non-finite entries: {0}")]
    NonFinite(String),
    #[error("dCoef = {} s: the coefficient of J(+c), J(-c) must be a positive normal number", crate::limits::readable(*.0))]
    InvalidDcoef(f64),
    #[error("the pencil is singular: det(λ F_yd + F_y) = 0 for every λ, so it has no eigenvalues to label ({detail}){}; a model with an unknown that no equation determines gives this", list_unknowns(unknowns, unknown_names))]
    Singular {
        detail: String,
        /// Unknowns (0-based) of a common null vector, largest entries first.
        unknowns: Vec<usize>,
        /// Names of all unknowns, when known ([`EigenError::with_unknown_names`]).
        unknown_names: Vec<String>,
    },
}

impl EigenError {
    /// The error with the unknowns of a singular pencil named by `names` (the DAE's).
    pub fn with_unknown_names(self, names: &[String]) -> Self {
        match self {
            EigenError::Singular { detail, unknowns, .. } => EigenError::Singular { detail, unknowns, unknown_names: names.to_vec() },
            e => e,
        }
    }
}

/// ", undetermined unknowns: …" for a message (1-based indices, or names when given).
fn list_unknowns(unknowns: &[usize], names: &[String]) -> String {
    if unknowns.is_empty() {
        return String::new();
    }
    const SHOWN: usize = 8;
    let mut list: Vec<String> = unknowns.iter().take(SHOWN).map(|&k| names.get(k).cloned().unwrap_or_else(|| format!("unknown {}", k + 1))).collect();
    if unknowns.len() > SHOWN {
        list.push(format!("… {} more", unknowns.len() - SHOWN));
    }
    format!("; a common null vector of F_yd and F_y involves {}", list.join(", "))
}
