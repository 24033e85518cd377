//! The result of an eigenanalysis, whichever solver gave it (dense QZ, [`super::dense`]; sparse
//! Krylov–Schur, [`super::krylov`]): each eigenvalue λ of `(λ F_yd + F_y) v = 0` (eq. 10) with its
//! right and adjoint vectors (eq. 11) and its label (eqs. 32–35), and the normalization and
//! ordering both solvers share.

use faer::{c64, Col};

use super::classify::{Classification, ModeKind};
use super::route::{conj, dot_t, norm, EigenRoute};

/// One eigenvalue with its vectors and label.
#[derive(Clone, Debug)]
pub struct Mode {
    /// Continuous-time eigenvalue λ [rad/s]; `±∞`/NaN parts only for infinite modes
    /// whose QZ β was exactly zero.
    pub lambda: c64,
    pub kind: ModeKind,
    /// Estimated absolute error of λ [rad/s] (eqs. 32–35 for the Λ route).
    pub error: f64,
    /// Chordal distance of the computed eigenvalue to the nearest of zero/infinity and the
    /// uncertainty it was compared with (both in the route's variable, balanced pencil).
    pub classification: Classification,
    /// Right vector `v`: `(λ F_yd + F_y) v = 0`, unit 2-norm, largest entry real positive.
    pub right: Option<Col<c64>>,
    /// Left (adjoint) vector `u`: `uᵀ (λ F_yd + F_y) = 0`, scaled so `uᵀ F_yd v = 1`
    /// whenever that product is not negligible.
    pub left: Option<Col<c64>>,
    /// Index (in [`ModalAnalysis::modes`]) of the complex-conjugate partner, if any.
    pub partner: Option<usize>,
}

impl Mode {
    /// Natural frequency `|λ|/(2π)` [Hz].
    pub fn freq_hz(&self) -> f64 {
        self.lambda.norm() / (2.0 * std::f64::consts::PI)
    }
    /// Damping ratio `−Re λ / |λ|` (0 for λ = 0).
    pub fn damping(&self) -> f64 {
        let m = self.lambda.norm();
        if m > 0.0 { -self.lambda.re / m } else { 0.0 }
    }
}

/// All eigenvalues of a linear DAE, sorted: dynamic by increasing |λ| (positive imaginary
/// part first within a pair), then zero, then infinite.
#[derive(Clone, Debug)]
pub struct ModalAnalysis {
    pub route: EigenRoute,
    /// The dCoef of the Λ form (also reported for the direct route).
    pub dcoef: f64,
    pub modes: Vec<Mode>,
}

impl ModalAnalysis {
    /// Indices of the modes of one kind.
    pub fn of_kind(&self, kind: ModeKind) -> impl Iterator<Item = usize> + '_ {
        self.modes.iter().enumerate().filter(move |(_, m)| m.kind == kind).map(|(i, _)| i)
    }

    /// Number of modes of one kind.
    pub fn count(&self, kind: ModeKind) -> usize {
        self.of_kind(kind).count()
    }

    /// Modes (one per pair) whose values say nothing: the chordal test would have labelled
    /// them dynamic, but their error estimate is not below |λ|, so they carry the label
    /// zero or infinite instead ([`super::classify::resolved_kind`]).
    pub fn unresolved(&self) -> impl Iterator<Item = (usize, &Mode)> + '_ {
        self.modes.iter().enumerate().filter(|(_, m)| m.kind != ModeKind::Dynamic && m.classification.kind == ModeKind::Dynamic && m.lambda.im >= 0.0)
    }

    /// Modes (one per pair) labelled zero by the chordal test although their own error
    /// estimate is below |λ|: maybe slow real modes of a model whose stiffnesses or masses
    /// span many decades (issue 30: 7e-4 rad/s modes of a 1e18 stiffness ratio). Eigenvalues
    /// the constraint structure fixes at zero are not among them.
    pub fn doubtful_zeros(&self) -> impl Iterator<Item = (usize, &Mode)> + '_ {
        self.modes.iter().enumerate().filter(|(_, m)| {
            m.kind == ModeKind::Zero && m.classification.uncertainty > 0.0 && m.lambda.norm() > 0.0 && m.error < m.lambda.norm() && m.lambda.im >= 0.0
        })
    }
}

pub(crate) fn conjugate_mode(m: &Mode) -> Mode {
    Mode {
        lambda: m.lambda.conj(),
        kind: m.kind,
        error: m.error,
        classification: m.classification.clone(),
        right: m.right.as_ref().map(conj),
        left: m.left.as_ref().map(conj),
        partner: None,
    }
}

/// The entry of largest modulus (the first of equal ones), compared by `|x|²` and by `|x|`
/// (`hypot`, slow: 40 % of the sparse route's post-processing at 10⁵ unknowns when it was
/// taken for every entry) only where the squares are too close to tell, so the pick is the
/// one the moduli give.
pub(crate) fn largest_entry(v: &Col<c64>) -> c64 {
    v.iter().copied().fold(c64::new(0.0, 0.0), |a, x| {
        let (p, q) = (x.norm_sqr(), a.norm_sqr());
        let larger = if (p - q).abs() > 1e-12 * p.max(q) { p > q } else { x.norm() > a.norm() };
        if larger { x } else { a }
    })
}

/// `v` to unit norm with its largest entry real positive; `u` so that `uᵀ F_yd v = 1`
/// when that product is not rounding, else to unit norm. Rounding is judged against the
/// magnitude of the product's own terms, `|u|ᵀ |F_yd| |v|` (`fyd_magnitude`), not against
/// `‖u‖ ‖F_yd‖ ‖v‖`: vectors dominated by unknowns `F_yd` does not weigh (a clamp's reaction
/// moment, 1e4 times the base's momentum in a slow mode of `examples/ham_sas.mbd`) have a
/// small but exact product (6e-12 there), and a ROM that left them unscaled lost the mode
/// (the base's horizontal modes, so its transmissibility was 60 times the full model's at
/// 2 Hz however many modes it kept).
pub(crate) fn normalize(v: &Col<c64>, u: &Col<c64>, fyd_v: impl Fn(&Col<c64>) -> Col<c64>, fyd_magnitude: impl Fn(&Col<c64>, &Col<c64>) -> f64) -> (Col<c64>, Col<c64>) {
    let big = largest_entry(v);
    let phase = if big.norm() > 0.0 { big.conj() / big.norm() } else { c64::new(1.0, 0.0) };
    let nv = norm(v);
    let v = Col::from_fn(v.nrows(), |i| v[i] * phase / nv);
    let p = dot_t(u, &fyd_v(&v));
    let nu = norm(u);
    let scale = if p.norm() > 1e3 * f64::EPSILON * fyd_magnitude(u, &v) && p.norm() > 0.0 { c64::new(1.0, 0.0) / p } else { c64::new(1.0 / nu, 0.0) };
    let u = Col::from_fn(u.nrows(), |i| u[i] * scale);
    (v, u)
}

/// Sorts modes (a complex pair is one unit, positive imaginary part first): dynamic by
/// increasing |λ|, then zero, then infinite; records each pair's partner index.
pub(crate) fn sort_units(mut units: Vec<Vec<Mode>>) -> Vec<Mode> {
    let rank = |k: ModeKind| match k {
        ModeKind::Dynamic => 0,
        ModeKind::Zero => 1,
        ModeKind::Infinite => 2,
    };
    for u in units.iter_mut() {
        if u.len() == 2 && u[0].lambda.im < 0.0 {
            u.swap(0, 1);
        }
    }
    let size = |m: &Mode| if m.lambda.norm().is_finite() { m.lambda.norm() } else { f64::MAX };
    units.sort_by(|a, b| {
        rank(a[0].kind)
            .cmp(&rank(b[0].kind))
            .then(size(&a[0]).total_cmp(&size(&b[0])))
            .then(b[0].lambda.re.total_cmp(&a[0].lambda.re))
    });
    let mut modes = Vec::with_capacity(units.iter().map(Vec::len).sum());
    for unit in units {
        let i = modes.len();
        let paired = unit.len() == 2;
        for (k, mut m) in unit.into_iter().enumerate() {
            if paired {
                m.partner = Some(if k == 0 { i + 1 } else { i });
            }
            modes.push(m);
        }
    }
    modes
}
