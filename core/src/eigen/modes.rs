//! The result of an eigenanalysis, whichever solver gave it (dense QZ, [`super::dense`]; sparse
//! Krylov–Schur, [`super::krylov`]): each eigenvalue λ of `(λ F_yd + F_y) v = 0` (eq. 10) with its
//! right and adjoint vectors (eq. 11) and its label (eqs. 32–35), and the normalization and
//! ordering both solvers share.

use faer::{c64, Col};

use super::classify::{Classification, ModeKind};
use super::route::{conj, dot_t, norm, EigenRoute};
use crate::linear::hz;

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
        hz(self.lambda.norm())
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
/// product's own terms `|u|ᵀ |F_yd| |v|` (`fyd_magnitude`), not against the normwise bound
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
    let resolved = p.norm() > 1e3 * f64::EPSILON * fyd_magnitude(u, &v) && p.norm() > 0.0;
    let scale = if resolved { c64::new(1.0, 0.0) / p } else { c64::new(1.0 / nu, 0.0) };
    let u = Col::from_fn(u.nrows(), |i| u[i] * scale);
    (v, u)
}

/// Widens the error estimates of dynamic eigenvalues that first-order theory cannot tell
/// apart, then relabels any whose estimate reached its own modulus
/// ([`super::classify::resolved_kind`]). Where two computed eigenvalues lie within four
/// times the smaller of their estimates of each other (each is within reach of the other:
/// a sharp eigenvalue inside a wide one's disc keeps its own estimate), the estimates
/// (first-order, eqs. 32–35) no longer hold: a nearly defective cluster (a critically damped mode, ζ = 1, splits into
/// two roots √ε apart) is only known as a whole, so each member's error is at least the
/// cluster's diameter (issue 30: the −2 rad/s double root was printed as −2 ± 9.5e-8 j
/// rad/s with an estimate of 5.7e-8).
fn widen_cluster_errors(units: &mut [Vec<Mode>], dcoef: f64) {
    let index: Vec<(usize, usize)> = units.iter().enumerate().flat_map(|(i, u)| (0..u.len()).map(move |k| (i, k))).filter(|&(i, k)| units[i][k].kind == ModeKind::Dynamic).collect();
    let n = index.len();
    let mut root: Vec<usize> = (0..n).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    let mode = |units: &[Vec<Mode>], j: usize| -> (c64, f64) {
        let m = &units[index[j].0][index[j].1];
        (m.lambda, m.error)
    };
    // Sorted by real part, a pair can only be linked to neighbours within reach.
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| mode(units, a).0.re.total_cmp(&mode(units, b).0.re));
    let reach = index.iter().map(|&(i, k)| units[i][k].error).filter(|e| e.is_finite()).fold(0.0, f64::max);
    for a in 0..n {
        let (la, ea) = mode(units, order[a]);
        for &jb in &order[a + 1..] {
            let (lb, eb) = mode(units, jb);
            if lb.re - la.re > 4.0 * ea.min(reach) {
                break;
            }
            if (la - lb).norm() <= 4.0 * ea.min(eb) {
                let (ra, rb) = (find(&mut root, order[a]), find(&mut root, jb));
                root[ra] = rb;
            }
        }
    }
    let mut members: std::collections::HashMap<usize, Vec<usize>> = std::collections::HashMap::new();
    for j in 0..n {
        let r = find(&mut root, j);
        members.entry(r).or_default().push(j);
    }
    for group in members.values().filter(|g| g.len() > 1) {
        let diameter = group.iter().flat_map(|&a| group.iter().map(move |&b| (a, b))).map(|(a, b)| (mode(units, a).0 - mode(units, b).0).norm()).fold(0.0, f64::max);
        for &j in group {
            let m = &mut units[index[j].0][index[j].1];
            m.error = m.error.max(diameter);
            m.kind = super::classify::resolved_kind(&m.classification, m.lambda, m.error, dcoef);
        }
    }
}

/// Sorts modes (a complex pair is one unit, positive imaginary part first): dynamic by
/// increasing |λ|, then zero, then infinite; records each pair's partner index. Clusters
/// first-order estimates cannot separate get their errors widened ([`widen_cluster_errors`]).
pub(crate) fn sort_units(mut units: Vec<Vec<Mode>>, dcoef: f64) -> Vec<Mode> {
    widen_cluster_errors(&mut units, dcoef);
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
    // |λ| to 12 significant digits: modes of equal |λ| (the same mass and spring, one damped,
    // examples/mass_on_springs.mbd) are a tie broken by Re λ, not by their last bits (the
    // eigenvalue's rounding, which changed when the two-sided quotients became compensated
    // and swapped node 2's and node 3's y modes).
    let size = |m: &Mode| {
        let r = m.lambda.norm();
        if !r.is_finite() {
            return f64::MAX;
        }
        if r == 0.0 {
            return 0.0;
        }
        let quantum = 10f64.powf(r.log10().floor() - 11.0);
        (r / quantum).round() * quantum
    };
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
