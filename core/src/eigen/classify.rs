//! Labelling eigenvalues as dynamic, zero or infinite from an error estimate (eqs. 32–35).
//!
//! QZ returns each eigenvalue as a pair `(α, β)`, `μ = α/β`, of the pencil `A v = μ B v`.
//! Its uncertainty is estimated from first-order perturbation theory in the chordal metric
//! (Stewart & Sun, *Matrix Perturbation Theory*, VI.2):
//!
//! ```text
//! δχ = η ‖(A, B)‖ ‖u‖ ‖v‖ / sqrt(|uᵀAv|² + |uᵀBv|²)
//! ```
//!
//! with `η` the measured backward error of the computed pair (right and left residuals,
//! never below the unit roundoff). An eigenvalue whose chordal distance to the point that
//! stands for λ = 0 (resp. λ = ∞) is within `δχ` cannot be told apart from it: it is
//! labelled zero (resp. infinite). In the Λ form these points are Λ = −1 and Λ = 1, and
//! the error carried to λ is `|dλ/dΛ| |δΛ| = 2 |δΛ| / (c |Λ − 1|²)` (eqs. 33, 35).
//! Defective clusters (index-3 constraint blocks) have huge `‖u‖‖v‖/|uᵀBv|`, so the
//! estimate grows with the rounding split of the cluster and they stay labelled infinite.

use faer::c64;

use super::route::{dot_t, norm, EigenRoute, EigenVectors};

/// What an eigenvalue stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ModeKind {
    /// A finite, nonzero eigenvalue that the estimate separates from 0 and ∞.
    Dynamic,
    /// Indistinguishable from λ = 0 (e.g. constrained variables in the form of eq. 30).
    Zero,
    /// Indistinguishable from λ = ∞ (multipliers; constrained variables in eq. 29).
    Infinite,
}

impl ModeKind {
    pub fn name(self) -> &'static str {
        match self {
            ModeKind::Dynamic => "dynamic",
            ModeKind::Zero => "zero",
            ModeKind::Infinite => "infinite",
        }
    }
}

/// The evidence behind a label, in the route's variable μ (balanced pencil).
#[derive(Clone, Debug)]
pub struct Classification {
    pub kind: ModeKind,
    pub alpha: c64,
    pub beta: f64,
    /// Chordal distance from μ to the point standing for λ = 0.
    pub to_zero: f64,
    /// Chordal distance from μ to the point standing for λ = ∞.
    pub to_infinity: f64,
    /// Estimated chordal error δχ of μ.
    pub uncertainty: f64,
}

/// Chordal distance between `μ = α/β` and a finite point `p`.
fn chordal_to(alpha: c64, beta: f64, p: f64) -> f64 {
    let nrm = (alpha.norm_sqr() + beta * beta).sqrt();
    (alpha - c64::new(p * beta, 0.0)).norm() / (nrm * (1.0 + p * p).sqrt())
}

/// Labels one eigenvalue `(α, β)` of `A v = μ B v`; `norms = (‖A‖_F, ‖B‖_F)`.
pub(crate) fn classify(alpha: c64, beta: f64, vectors: Option<&EigenVectors>, norms: (f64, f64), route: EigenRoute) -> Classification {
    let uncertainty = vectors.map_or(f64::INFINITY, |w| chordal_uncertainty(alpha, beta, w, norms));
    classify_given(alpha, beta, uncertainty, route)
}

/// The evidence for an eigenvalue whose vectors could not be computed (not finite: an
/// exactly defective eigenvalue, a double root with one vector, makes the back-substitution
/// divide by zero). Its value is then still good to about `√ε` (a 2 x 2 Jordan block's
/// sensitivity; the cube root, a 3 x 3 block's, is the uncertainty its label is decided
/// with, as in [`classify`]); its error estimate is
/// the caller's `∞`, so it is never labelled dynamic and a study lists it as unresolved
/// (before, the infinite uncertainty labelled a −2 rad/s double root "infinite" silently).
pub(crate) fn classify_without_vectors(alpha: c64, beta: f64, route: EigenRoute) -> Classification {
    if beta == 0.0 {
        return classify_given(alpha, beta, f64::INFINITY, route);
    }
    classify_given(alpha, beta, f64::EPSILON.cbrt(), route)
}

/// [`classify`] with the chordal uncertainty δχ given (the sparse route's right vectors
/// alone: their backward error with the condition number taken as 1).
pub(crate) fn classify_given(alpha: c64, beta: f64, uncertainty: f64, route: EigenRoute) -> Classification {
    let nrm = (alpha.norm_sqr() + beta * beta).sqrt();
    let (zero_point, inf_point) = match route {
        EigenRoute::Direct => (0.0, None),
        EigenRoute::Lambda => (-1.0, Some(1.0)),
    };
    let to_zero = if nrm > 0.0 { chordal_to(alpha, beta, zero_point) } else { 0.0 };
    let to_infinity = match inf_point {
        _ if nrm == 0.0 => 0.0,
        None => beta.abs() / nrm,
        Some(p) => chordal_to(alpha, beta, p),
    };
    let kind = if to_infinity <= uncertainty && to_infinity <= to_zero {
        ModeKind::Infinite
    } else if to_zero <= uncertainty {
        ModeKind::Zero
    } else {
        ModeKind::Dynamic
    };
    Classification { kind, alpha, beta, to_zero, to_infinity, uncertainty }
}

/// `δχ = η ‖(A,B)‖ κ` with the measured backward error `η` and the chordal condition
/// number `κ = ‖u‖‖v‖ / sqrt(|uᵀAv|² + |uᵀBv|²)`.
fn chordal_uncertainty(alpha: c64, beta: f64, w: &EigenVectors, (na, nb): (f64, f64)) -> f64 {
    let (nv, nu) = (norm(&w.v), norm(&w.u));
    let b = c64::new(beta, 0.0);
    let res_r = norm(&faer::Col::from_fn(w.v.nrows(), |i| b * w.av[i] - alpha * w.bv[i]));
    let res_l = norm(&faer::Col::from_fn(w.u.nrows(), |i| b * w.ua[i] - alpha * w.ub[i]));
    let scale = beta.abs() * na + alpha.norm() * nb;
    let eta = [res_r / (scale * nv), res_l / (scale * nu), f64::EPSILON / 2.0]
        .into_iter()
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max);
    let (uav, ubv) = (dot_t(&w.u, &w.av), dot_t(&w.u, &w.bv));
    let denom = (uav.norm_sqr() + ubv.norm_sqr()).sqrt();
    let kappa = nu * nv / denom;
    let d = eta * (na * na + nb * nb).sqrt() * kappa;
    // Vectors orthogonal through both matrices to rounding (κ beyond 1/ε): a repeated
    // eigenvalue with one vector, as a critically damped mode (ζ = 1) has, or the split
    // index-3 infinite eigenvalues of position constraints (eq. 29). First-order theory
    // says nothing there; an m x m Jordan block moves by the m-th root of the
    // perturbation, and m = 3 is the highest a multibody DAE's index gives, so that is the
    // uncertainty. Without it the label went to whichever of 0 and ∞ was nearer (issue 30:
    // the −2 rad/s double root of m = 1 kg, c = 4 N s/m, k = 4 N/m was listed "infinite"
    // without a word).
    if !(kappa * f64::EPSILON < 1e-3) {
        return eta.cbrt();
    }
    if d.is_finite() { d } else { f64::INFINITY }
}

/// The label a mode is given: the evidence's ([`Classification::kind`]), except that an
/// eigenvalue whose error estimate `error` (absolute, rad/s) is not below its own modulus is
/// never labelled dynamic: its value says nothing, not even its order of magnitude (issue
/// 30: a 1.414e6 rad/s mode printed as a "dynamic" 158.75 rad/s one with error 1.3e2).
/// It is labelled infinite when `c |λ| ≥ 1` (beyond the Λ form's "Nyquist" limit 1/c,
/// eq. 23), zero otherwise; the evidence keeps `kind = Dynamic`, which is how a study tells
/// these modes apart and warns about them.
pub(crate) fn resolved_kind(class: &Classification, lambda: c64, error: f64, dcoef: f64) -> ModeKind {
    if class.kind != ModeKind::Dynamic || error < lambda.norm() {
        return class.kind;
    }
    if dcoef * lambda.norm() >= 1.0 { ModeKind::Infinite } else { ModeKind::Zero }
}

impl Classification {
    /// The continuous-time eigenvalue λ [rad/s] and its estimated absolute error.
    ///
    /// Direct route: `λ = σ μ`, `|δλ| = σ δχ (1 + |μ|²)`. Λ route: eq. 23 and
    /// `|δλ| = 2 |δΛ| / (c |Λ − 1|²)` with `|δΛ| = δχ (1 + |Λ|²)` (eqs. 33, 35).
    pub fn lambda_and_error(&self, route: EigenRoute, mu_scale: f64, dcoef: f64) -> (c64, f64) {
        if self.beta == 0.0 {
            let inf = c64::new(f64::INFINITY, 0.0);
            return match route {
                EigenRoute::Direct => (inf, f64::INFINITY),
                // Λ = ∞ maps to λ = 1/c (eq. 23): finite, but not trustworthy.
                EigenRoute::Lambda => (c64::new(1.0 / dcoef, 0.0), f64::INFINITY),
            };
        }
        let mu = self.alpha / self.beta;
        let dmu = self.uncertainty * (1.0 + mu.norm_sqr());
        match route {
            EigenRoute::Direct => (mu * mu_scale, dmu * mu_scale),
            EigenRoute::Lambda => {
                let one = c64::new(1.0, 0.0);
                let lambda = (mu + one) / (mu - one) / dcoef;
                let dl = 2.0 * dmu / (dcoef * (mu - one).norm_sqr());
                (lambda, if dl.is_finite() { dl } else { f64::INFINITY })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_eigenvalue_not_above_its_error_is_never_dynamic() {
        // Issue 30: 158.75 rad/s with error 1.3e2 is dynamic (the error is below |λ|); with
        // the Rayleigh quotient's 1.4e6 as its error it is not: infinite beyond 1/c, zero below.
        let class = Classification { kind: ModeKind::Dynamic, alpha: c64::new(1.0, 0.0), beta: 1.0, to_zero: 1.0, to_infinity: 1.0, uncertainty: 0.0 };
        let lambda = c64::new(0.0, 158.75);
        assert_eq!(resolved_kind(&class, lambda, 1.3e2, 1e12), ModeKind::Dynamic);
        assert_eq!(resolved_kind(&class, lambda, 1.4e6, 1e12), ModeKind::Infinite);
        assert_eq!(resolved_kind(&class, lambda, 1.4e6, 1e-9), ModeKind::Zero);
        assert_eq!(resolved_kind(&class, lambda, f64::INFINITY, 1e-9), ModeKind::Zero);
        let zero = Classification { kind: ModeKind::Zero, ..class };
        assert_eq!(resolved_kind(&zero, lambda, 1.0, 1e-9), ModeKind::Zero);
    }
}
