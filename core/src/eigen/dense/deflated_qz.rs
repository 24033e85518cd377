//! Eigenanalysis of a linear DAE with the structurally known zero and infinite eigenvalues
//! deflated first ([`super::deflate`]): QZ runs on the dynamic part only (about 2N for an
//! N-link chain instead of 17N), and the vectors are lifted back to the whole model.
//!
//! Why QZ and not the standard problem `A = −E₁⁻¹ K₁` (Hessenberg QR: 38 M instructions
//! against QZ's 211 M on `examples/ham_sas.mbd`'s 132 x 132 dynamic part), measured there
//! (issue 11): the pairs' residuals are not at rounding level, for two reasons. (1) The
//! spectrum's range: a standard-form pair has the pencil residual `ε ‖E₁‖ ‖A‖` whatever its
//! |λ|, and `‖A‖_F = 5.4e8` (3.5e4 rad/s fastest, 0.03 rad/s slowest): LAPACK `dgeev` in
//! Octave puts the 0.03 rad/s modes 5.8e-6 (unbalanced) or 6.6e-8 (`dgebal`) off relative,
//! backward errors up to 1.4e-9 / 3.9e-10, against QZ's 3e-16; on the balanced whole
//! pencil (the `η` of the labels' error estimate), 39 of the 66 pairs were above 1e-13.
//! (2) The legs' and little pendulums' exact four- and eight-fold clusters: faer's
//! eigenvectors from the Schur form come out nearly parallel inside a cluster (residuals up
//! to 7e-8 even on the unbalanced whole pencil, `V` numerically singular, so `V⁻¹` gives no
//! left vectors), and separately computed left vectors do not pair with the right ones
//! (`uᵀ F_yd v ≈ 0`: 18 modes then labelled infinite, error estimates 2e9). One step of
//! inverse iteration per pair on the pencil itself brings every residual to 1.6e-14 but costs
//! a complex LU (3 M instructions) per pair: 222 M in all, and the clusters stay unpaired.
//! What could pay: an O(n²) refinement per pair from `A`'s Hessenberg form (Newton on the
//! pencil's true residual), a Rayleigh–Ritz step per cluster for the pairing, QZ kept as the
//! fallback whenever a residual is not at rounding level.

use faer::{c64, Col, Mat};
use rayon::prelude::*;

use super::balance::balance_pencil;
use super::deflate::DynamicPart;
use super::qz::{qz, Products};
use super::second_order::{half_size_modes, split};
use crate::eigen::classify::{classify, classify_without_vectors, resolved_kind, Classification, ModeKind};
use crate::eigen::modes::{conjugate_mode, normalize, sort_units};
use crate::eigen::route::{EigenRoute, EigenVectors};
use crate::eigen::{EigenError, ModalAnalysis, Mode};
use crate::linear::{Jacobians, LinearDae, SparseMatrix};

/// A mode the deflation fixed exactly: λ = 0 or λ = ∞, in the route's variable μ
/// (direct: μ = 0 or ∞; Λ form: Λ = −1 or Λ = 1).
fn deflated_mode(kind: ModeKind, route: EigenRoute) -> Mode {
    let (alpha, beta, lambda) = match (kind, route) {
        (ModeKind::Zero, EigenRoute::Direct) => (0.0, 1.0, 0.0),
        (ModeKind::Zero, EigenRoute::Lambda) => (-1.0, 1.0, 0.0),
        (_, EigenRoute::Direct) => (1.0, 0.0, f64::INFINITY),
        (_, EigenRoute::Lambda) => (1.0, 1.0, f64::INFINITY),
    };
    let zero = kind == ModeKind::Zero;
    Mode {
        lambda: c64::new(lambda, 0.0),
        kind,
        error: if zero { 0.0 } else { f64::INFINITY },
        classification: Classification {
            kind,
            alpha: c64::new(alpha, 0.0),
            beta,
            to_zero: if zero { 0.0 } else { 1.0 },
            to_infinity: if zero { 1.0 } else { 0.0 },
            uncertainty: 0.0,
        },
        right: None,
        left: None,
        partner: None,
    }
}

impl ModalAnalysis {
    /// Size of the pencil QZ runs on in [`ModalAnalysis::of_dae`] when the constraint
    /// structure allows deflation, `None` when the whole pencil is used.
    pub fn deflated_size(dae: &LinearDae) -> Option<usize> {
        let (fyd, fy) = dae.jacobians.derivatives();
        DynamicPart::new(&fyd, &fy, dae.constraint_form, &dae.multipliers).map(|p| p.dim())
    }

    /// Eigenanalysis of a linear DAE by the chosen route, with the zero and infinite
    /// eigenvalues that its constraint structure fixes deflated exactly before QZ. The
    /// finite eigenvalues, labels and vectors are those of [`ModalAnalysis::compute`] on the
    /// whole pencil (to rounding); when the structure is not there it runs that.
    /// `dcoef` as in [`ModalAnalysis::compute_with_dcoef`].
    pub fn of_dae(dae: &LinearDae, route: EigenRoute, dcoef: Option<f64>) -> Result<Self, EigenError> {
        Self::of_dae_with(dae, route, dcoef, true)
    }

    /// [`ModalAnalysis::of_dae`] with QZ on the whole dynamic part even where the half-size
    /// route applies: the general route the half-size one is checked against.
    pub fn of_dae_by_qz(dae: &LinearDae, route: EigenRoute, dcoef: Option<f64>) -> Result<Self, EigenError> {
        Self::of_dae_with(dae, route, dcoef, false)
    }

    /// Half the size of the dynamic part when it is an undamped structure at rest's (the
    /// size of the problem [`ModalAnalysis::of_dae`] then solves in the Λ route), `None`
    /// otherwise.
    pub fn half_size(dae: &LinearDae) -> Option<usize> {
        let (fyd, fy) = dae.jacobians.derivatives();
        let part = DynamicPart::new(&fyd, &fy, dae.constraint_form, &dae.multipliers)?;
        split(&part.e, &part.k).map(|sets| sets[0].len())
    }

    fn of_dae_with(dae: &LinearDae, route: EigenRoute, dcoef: Option<f64>, half_size: bool) -> Result<Self, EigenError> {
        let jacobians = &dae.jacobians;
        if jacobians.dim() == 0 {
            return Err(EigenError::Empty);
        }
        // Non-finite pencils are refused before any deflation; pencils of extreme magnitude
        // take the dense route, which rescales them exactly. Singular pencils (det ≡ 0) are
        // refused too: a pencil whose dynamic part has a nonsingular E₁ is regular
        // (det(λ F_yd + F_y) = ± det R_G det R_H det(λ E₁ + K₁), up to the eq. 30 factor
        // λ^2m, with leading coefficient ≠ 0), as is one whose index-1 block A₂₂ is certified
        // nonsingular ([`DynamicPart::regular`]); any other is checked (up to two LUs).
        if super::degenerate::pencil_scale(jacobians, dcoef)? != 1.0 {
            return Self::compute_with_dcoef(jacobians, route, dcoef);
        }
        // F_yd and F_y as stored (Derivatives), or formed once from J, J* (eq. 16).
        let formed;
        let (fyd, fy) = match jacobians {
            Jacobians::Derivatives { fyd, fy } => (fyd, fy),
            Jacobians::Coefficient { .. } => {
                formed = jacobians.derivatives();
                (&formed.0, &formed.1)
            }
        };
        // An unknown or equation with no entry at all: singular for every λ, said before any
        // factorization.
        super::degenerate::check_no_empty_lines(fyd, fy)?;
        let Some(part) = DynamicPart::new(&fyd, &fy, dae.constraint_form, &dae.multipliers) else {
            return Self::compute_with_dcoef(jacobians, route, dcoef);
        };
        if !part.regular {
            super::degenerate::prepare(jacobians, dcoef)?;
        }
        let dcoef = match (jacobians, dcoef) {
            (Jacobians::Derivatives { .. }, Some(c)) => c,
            (Jacobians::Derivatives { .. }, None) => spectral_dcoef(&part).unwrap_or_else(|| jacobians.dcoef()),
            _ => jacobians.dcoef(),
        };
        let mut units: Vec<Vec<Mode>> = Vec::with_capacity(fyd.nrows());
        units.extend((0..part.zeros).map(|_| vec![deflated_mode(ModeKind::Zero, route)]));
        units.extend((0..part.infinities).map(|_| vec![deflated_mode(ModeKind::Infinite, route)]));
        let r = part.dim();
        if r > 0 {
            // QZ and the whole pencil the labels are decided on do not depend on each other:
            // rayon::join runs them on both cores when one is free (inside a busy pool, as
            // a sweep's point, one after the other on the same worker: no thread waits).
            // QZ's sweeps are bounded (faer: 30 r per eigenvalue, then rotated retries,
            // `super::qz::qz`); should it still not converge on the route's pencil, the
            // other route's pencil of the same dynamic part (a different Möbius image of the
            // spectrum, so different clusters) is tried before giving up. The labels are
            // decided on the whole pencil of `route` either way.
            let other = match route {
                EigenRoute::Direct => EigenRoute::Lambda,
                EigenRoute::Lambda => EigenRoute::Direct,
            };
            // An undamped structure at rest: half the size, two standard eigenproblems
            // instead of QZ (`super::second_order`); QZ when that structure is missing.
            let solve = || match half_size.then(|| half_size_reduced(&part, route, dcoef)).flatten() {
                Some(found) => Ok(found),
                None => qz_modes(&part, route, dcoef).or_else(|_| qz_modes(&part, other, dcoef)),
            };
            let (found, whole) = rayon::join(solve, || WholePencil::new(&fyd, &fy, route, dcoef));
            let mut found = found?;
            let with: Vec<(usize, Col<c64>, Col<c64>)> = found.iter_mut().enumerate().filter_map(|(i, f)| f.1.take().map(|(v, u)| (i, v, u))).collect();
            let lambdas: Vec<c64> = with.iter().map(|w| found[w.0].0.lambda).collect();
            let gather = |left: bool| Mat::from_fn(r, with.len(), |i, j| if left { with[j].2[i] } else { with[j].1[i] });
            let (right, left) = rayon::join(|| part.right(&gather(false), &lambdas), || part.left(&gather(true), &lambdas));
            // Labels and error estimates on the whole pencil, as the undeflated route has them:
            // each mode on its own, in parallel.
            let labelled: Vec<(c64, Classification, ModeKind, f64, Option<(Col<c64>, Col<c64>)>)> = (0..with.len())
                .into_par_iter()
                .map(|j| {
                    let v = Col::from_fn(dae.dim(), |k| right[(k, j)]);
                    let u = Col::from_fn(dae.dim(), |k| left[(k, j)]);
                    let lambda = found[with[j].0].0.lambda;
                    let class = whole.classify(lambda, &v, &u, route, dcoef);
                    let error = class.lambda_and_error(route, whole.mu_scale, dcoef).1;
                    let quotient = whole.rayleigh_quotient(&v, &u);
                    let finite = lambda.re.is_finite() && lambda.im.is_finite();
                    let error = if finite { error.max(quotient.map_or(f64::INFINITY, |q| (q - lambda).norm())) } else { error };
                    let kind = resolved_kind(&class, lambda, error, dcoef);
                    let vectors = (kind != ModeKind::Infinite).then(|| normalize(&v, &u, |x| whole.fyd.mul_complex(x), |a, b| whole.fyd.abs_bilinear(a, b)));
                    // A dynamic mode's eigenvalue is its compensated two-sided quotient: QZ's
                    // own is ε ‖pencil‖ off, which a stiff beam's lowest pair feels (EA/EJ =
                    // 1e7, 8 elements: 1.2e-8 relative; the quotient: 1e-15).
                    let lambda = match quotient {
                        Some(q) if kind == ModeKind::Dynamic => q,
                        _ => lambda,
                    };
                    (lambda, class, kind, error, vectors)
                })
                .collect();
            for (&(i, _, _), (lambda, class, kind, error, vectors)) in with.iter().zip(labelled) {
                let mode = &mut found[i].0;
                mode.lambda = lambda;
                mode.error = error;
                mode.kind = kind;
                mode.classification = class;
                if let Some((v, u)) = vectors {
                    mode.right = Some(v);
                    mode.left = Some(u);
                }
            }
            for (mode, _, pair) in found {
                if pair {
                    let partner = conjugate_mode(&mode);
                    units.push(vec![mode, partner]);
                } else {
                    units.push(vec![mode]);
                }
            }
        }
        Ok(ModalAnalysis { route, dcoef, modes: sort_units(units, dcoef) })
    }
}

/// A mode of the dynamic part with its reduced right and left vectors (`None` for λ = 0
/// or ∞, whose vectors the form of eq. 30 cannot lift) and whether it stands for a pair.
type ReducedMode = (Mode, Option<(Col<c64>, Col<c64>)>, bool);

/// The dynamic part's modes at half its size (Λ route only), each with its vectors; labels
/// and errors are placeholders, decided on the whole pencil by the caller as for QZ's.
fn half_size_reduced(part: &DynamicPart, route: EigenRoute, dcoef: f64) -> Option<Vec<ReducedMode>> {
    if route != EigenRoute::Lambda {
        return None;
    }
    let modes = half_size_modes(&part.e, &part.k, dcoef)?;
    Some(
        modes
            .into_iter()
            .map(|m| {
                // Eq. 23 inverted, as WholePencil::classify: Λ = (cλ + 1)/(cλ − 1).
                let mu = (m.lambda * dcoef + 1.0) / (m.lambda * dcoef - 1.0);
                let s = 1.0 / (1.0 + mu.norm_sqr()).sqrt();
                let class = classify_without_vectors(mu * s, s, route);
                let mode = Mode { lambda: m.lambda, kind: class.kind, error: f64::INFINITY, classification: class, right: None, left: None, partner: None };
                (mode, Some((m.right, m.left)), m.pair)
            })
            .collect(),
    )
}

/// The dynamic part's modes by QZ on the route's pencil (balanced), labelled on it.
fn qz_modes(part: &DynamicPart, route: EigenRoute, dcoef: f64) -> Result<Vec<ReducedMode>, EigenError> {
    let r = part.dim();
    let (a, b, mu_scale) = route_pencil(&part.k, &part.e, route, dcoef);
    let balanced = balance_pencil(&a, &b);
    let raw = qz(&balanced.a, &balanced.b, Products::PerVector)?;
    let norms = (balanced.a.norm_l2(), balanced.b.norm_l2());
    let mut found = Vec::new();
    let mut k = 0;
    while k < r {
        let pair = raw.alpha_im[k] != 0.0 && k + 1 < r;
        let alpha = c64::new(raw.alpha_re[k], raw.alpha_im[k]);
        // λ follows from (α, β) alone; a finite nonzero λ is labelled on the whole pencil
        // from its lifted vectors, so only the others need the reduced pencil's products.
        let (lambda, _) = classify(alpha, raw.beta[k], None, norms, route).lambda_and_error(route, mu_scale, dcoef);
        let liftable = lambda.re.is_finite() && lambda.im.is_finite() && lambda.norm() > 0.0;
        let class = if liftable {
            classify(alpha, raw.beta[k], None, norms, route)
        } else {
            classify(alpha, raw.beta[k], raw.vectors(k, pair).as_ref(), norms, route)
        };
        let (lambda, error) = class.lambda_and_error(route, mu_scale, dcoef);
        let lambda = if lambda.re.is_finite() && lambda.im.is_finite() { lambda } else { c64::new(f64::INFINITY, 0.0) };
        // The form of eq. 30 divides multipliers by λ: no vectors for λ = 0.
        let z = raw.bare_vectors(k, pair).filter(|_| liftable).map(|(v, u)| (balanced.unscale_right(&v), balanced.unscale_left(&u)));
        // A finite nonzero λ without finite vectors (an exactly defective root): labelled
        // as the undeflated route labels it, never dynamic.
        let (class, error) = if liftable && z.is_none() { (classify_without_vectors(alpha, raw.beta[k], route), f64::INFINITY) } else { (class, error) };
        let kind = resolved_kind(&class, lambda, error, dcoef);
        found.push((Mode { lambda, kind, error, classification: class, right: None, left: None, partner: None }, z, pair));
        k += if pair { 2 } else { 1 };
    }
    Ok(found)
}

/// The Λ form's dCoef chosen from the dynamic part's own spectrum, not from matrix norms:
/// `c = 1/ω̄` with `ω̄ = |det K / det E|^(1/r)`, the geometric mean of the `r` eigenvalues'
/// moduli of `λ E + K`. It maps the spectrum's logarithmic centre to `|Λ| = 1` (eq. 23), so
/// the slowest and fastest modes sit equally far (in `c|λ|` decades) from the points
/// `Λ = −1` and `Λ = 1` that stand for zero and infinity, and it follows any change of units
/// exactly (a time unit scales every λ and `ω̄` alike; mass and length units scale rows and
/// columns, which leave the eigenvalues and `ω̄` unchanged). Pivots of `K`'s LU at rounding
/// level (zero eigenvalues of free motions) are left out of the mean. `None` when either
/// determinant is not usable (then the norms decide, as before).
///
/// The previous default `‖F_yd‖/‖F_y‖` of the whole pencil followed the stiffest entry: on a
/// 32-element `beam3` cantilever (786 equations, EA = 1e8 N) it gave 8.2e-11 s, which put
/// every mode below a kHz within 1e-7 of `Λ = −1` (issue 30).
fn spectral_dcoef(part: &DynamicPart) -> Option<f64> {
    let r = part.dim();
    if r == 0 {
        return None;
    }
    let log_pivots = |m: &Mat<f64>| -> Option<Vec<f64>> {
        let lu = m.partial_piv_lu();
        let u = lu.U();
        let p: Vec<f64> = (0..r).map(|i| u[(i, i)].abs()).collect();
        p.iter().all(|x| x.is_finite()).then_some(p)
    };
    let (pk, pe) = (log_pivots(&part.k)?, log_pivots(&part.e)?);
    let (top_k, top_e) = (pk.iter().copied().fold(0.0, f64::max), pe.iter().copied().fold(0.0, f64::max));
    let negligible = |x: f64, top: f64| !(x > r as f64 * f64::EPSILON * top);
    if pe.iter().any(|&x| negligible(x, top_e)) || top_k == 0.0 {
        return None;
    }
    let kept: Vec<f64> = pk.iter().copied().filter(|&x| !negligible(x, top_k)).collect();
    if kept.is_empty() {
        return None;
    }
    // With z pivots of K dropped (about z zero eigenvalues), the mean runs over the other
    // r − z: an estimate of the nonzero eigenvalues' geometric mean, good enough to centre Λ.
    let log_k: f64 = kept.iter().map(|x| x.ln()).sum();
    let log_e: f64 = pe.iter().map(|x| x.ln()).sum();
    let omega = ((log_k - log_e) / kept.len() as f64).exp();
    let c = 1.0 / omega;
    (c.is_normal() && c > 0.0).then_some(c)
}

/// `(A, B, σ)` of the route's pencil `A v = μ B v` built from `λ E + K`: direct
/// `(K, −σ E)` with `σ = ‖K‖/‖E‖` (μ = λ/σ); Λ form `(E − c K, −(E + c K))` (eq. 18).
fn route_pencil(k: &Mat<f64>, e: &Mat<f64>, route: EigenRoute, dcoef: f64) -> (Mat<f64>, Mat<f64>, f64) {
    match route {
        EigenRoute::Direct => {
            let (na, nb) = (k.norm_l2(), e.norm_l2());
            let sigma = if na > 0.0 && nb > 0.0 { na / nb } else { 1.0 };
            (k.clone(), e * faer::Scale(-sigma), sigma)
        }
        EigenRoute::Lambda => (e - k * faer::Scale(dcoef), (e + k * faer::Scale(dcoef)) * faer::Scale(-1.0), 1.0),
    }
}

/// The whole route pencil, balanced as the undeflated eigenanalysis balances it, stored
/// sparse: the labels (eqs. 32–35) are decided on it with the lifted vectors.
struct WholePencil {
    a: SparseMatrix,
    b: SparseMatrix,
    row: Vec<f64>,
    col: Vec<f64>,
    norms: (f64, f64),
    mu_scale: f64,
    /// `F_yd` itself (unbalanced), for the vectors' normalization.
    fyd: SparseMatrix,
    /// `F_y` itself (unbalanced), for the two-sided Rayleigh quotient.
    fy: SparseMatrix,
}

impl WholePencil {
    fn new(fyd: &Mat<f64>, fy: &Mat<f64>, route: EigenRoute, dcoef: f64) -> Self {
        let (a, b, mu_scale) = route_pencil(fy, fyd, route, dcoef);
        let bal = balance_pencil(&a, &b);
        let norms = (bal.a.norm_l2(), bal.b.norm_l2());
        let (fyd, fy) = (SparseMatrix::from_dense(fyd), SparseMatrix::from_dense(fy));
        WholePencil { a: SparseMatrix::from_dense(&bal.a), b: SparseMatrix::from_dense(&bal.b), row: bal.row, col: bal.col, norms, mu_scale, fyd, fy }
    }

    /// `λ_R = −uᵀ F_y v / uᵀ F_yd v`, the two-sided Rayleigh quotient of the lifted vectors
    /// on the pencil of eq. 10 itself, its sums compensated
    /// ([`SparseMatrix::bilinear_compensated`]). It does not depend on the route, on dCoef or
    /// on the scaling of rows and columns (units), and it is second-order accurate in the
    /// vectors' errors: an eigenvalue that the map of eq. 23 moved off its vectors (Λ rounded
    /// next to 1 or −1 when `c |λ|` is far from 1) shows in `|λ_R − λ|`. `None` when
    /// `uᵀ F_yd v` vanishes.
    fn rayleigh_quotient(&self, v: &Col<c64>, u: &Col<c64>) -> Option<c64> {
        self.fy.two_sided_quotient(&self.fyd, u, v)
    }

    /// Label of the eigenvalue `lambda` with right and left vectors `v`, `u` of `λ F_yd + F_y`.
    fn classify(&self, lambda: c64, v: &Col<c64>, u: &Col<c64>, route: EigenRoute, dcoef: f64) -> Classification {
        let mu = match route {
            EigenRoute::Direct => lambda / self.mu_scale,
            // Eq. 23 inverted: Λ = (cλ + 1)/(cλ − 1).
            EigenRoute::Lambda => (lambda * dcoef + 1.0) / (lambda * dcoef - 1.0),
        };
        let s = 1.0 / (1.0 + mu.norm_sqr()).sqrt();
        let v = Col::from_fn(v.nrows(), |i| v[i] / self.col[i]);
        let u = Col::from_fn(u.nrows(), |i| u[i] / self.row[i]);
        let w = EigenVectors { av: self.a.mul_complex(&v), bv: self.b.mul_complex(&v), ua: self.a.mul_t_complex(&u), ub: self.b.mul_t_complex(&u), v, u };
        classify(mu * s, s, Some(&w), self.norms, route)
    }
}
