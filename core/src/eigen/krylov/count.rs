//! How many eigenvalues the pencil `λ E + K` (eq. 29) has in a disc `|λ| < R`: the argument
//! principle on `det(K + λ E)`, a polynomial in λ whose roots are exactly the finite
//! eigenvalues (the constrained variables' and multipliers' infinite ones are no roots).
//!
//! The winding number of `g(λ) = det(K + λ E) / Π (λ − λᵢ)` around the circle `|λ| = R`,
//! the `λᵢ` the eigenvalues already found inside it (each conjugate and each copy of a
//! repeated one), is the number of eigenvalues inside that were *not* found: 0 proves the
//! list complete, whatever the Krylov spaces saw. The pencil is real, so
//! `g(λ̄) = conj g(λ)` and the winding is `Δ arg g / π` along the upper half circle from
//! `λ = R` to `λ = −R`. `arg det` comes from a sparse LU with partial pivoting (backward
//! stable: the phase is that of a nearby pencil, exact while the circle stays clear of the
//! eigenvalues, which the caller ensures by drawing it in a gap of the spectrum found).
//!
//! Sampling: the half circle is cut into 16 arcs, each evaluated at its ends and midpoint;
//! the phase's smooth drift is fitted to those 33 points and divided out of `g` as
//! `exp(p(λ))`, `p` a real polynomial (zero-free, real on the real axis: the winding is the
//! same, [`Drift`]); an arc is accepted when the phase moves by at most π/4 over each of its
//! halves (one bisection checks the step); otherwise both halves are refined. A root within the arc's length of the circle turns the phase by
//! nearly π there, which cannot pass this test, so it is resolved by refinement. The count
//! is given up (`None`) when an arc needs more than 40 bisections or the whole count more
//! than [`MAX_EVALUATIONS`] factorizations, or a point cannot be factored.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::simplicial::{self, SimplicialLu};
use faer::c64;

use super::pencil::Pencil;

/// Most factorizations one count may take.
pub(super) const MAX_EVALUATIONS: usize = 4000;

/// The result of one count.
#[derive(Clone, Copy, Debug)]
pub(super) struct DiscCount {
    /// Eigenvalues inside the disc that are not among the given ones (negative: some given
    /// ones are not eigenvalues inside, e.g. counted twice).
    pub missing: i64,
    /// Sparse LU factorizations taken.
    pub evaluations: usize,
}

/// The phase `arg det(K + λ E)` at any λ, through the pencil's one symbolic analysis (its
/// column ordering; each λ's simplicial factorization is taken here, for its pivots). The
/// factors' storage, the permutation and the scratch are kept from one λ to the next (a
/// count takes from 33 to a few hundred factorizations of the same pattern: 165 on the
/// 96,024-equation spring chain's 20 lowest modes, where growing fresh factors each time
/// and summing the pattern again took two fifths of the count's time).
struct DetPhase<'a> {
    pencil: &'a Pencil,
    col_perm: faer::perm::PermRef<'a, usize>,
    col_sign: f64,
    values: Vec<c64>,
    lu: SimplicialLu<usize, c64>,
    row_fwd: Vec<usize>,
    row_inv: Vec<usize>,
    /// The previous point's row permutation, its inverse and its sign: the next point's
    /// sign follows from the rows whose pivots changed ([`sign_from_previous`]; walking the
    /// whole permutation's cycles each point, scattered reads, was 13 % of a point on the
    /// 96,024-equation spring chain).
    signed_rows: Vec<usize>,
    signed_inv: Vec<usize>,
    row_sign: f64,
    scratch: MemBuffer,
    seen: Vec<bool>,
    evaluations: usize,
}

/// `+1` or `−1`: the sign of the permutation `p` (its parity by cycles), `seen` scratch of
/// its length.
fn permutation_sign(p: &[usize], seen: &mut [bool]) -> f64 {
    seen.fill(false);
    let mut transpositions = 0usize;
    for start in 0..p.len() {
        let mut len = 0usize;
        let mut i = start;
        while !seen[i] {
            seen[i] = true;
            i = p[i];
            len += 1;
        }
        transpositions += len.saturating_sub(1);
    }
    if transpositions % 2 == 0 { 1.0 } else { -1.0 }
}

/// The sign of `σ = p ∘ q⁻¹` (`q_inv` the inverse of `q`), so that `sign p = sign σ · sign q`
/// (the sign is multiplicative): `σ` moves only the entries `x = q[i]` with `p[i] ≠ q[i]`
/// (`σ(q[i]) = p[i]`), so its cycles are walked through those alone. `seen` (false
/// everywhere, of the permutations' length) is left false.
fn sign_from_previous(p: &[usize], q: &[usize], q_inv: &[usize], seen: &mut [bool]) -> f64 {
    let moved = || (0..p.len()).filter(|&i| p[i] != q[i]);
    let mut transpositions = 0usize;
    for i in moved() {
        let start = q[i];
        let mut x = start;
        let mut len = 0usize;
        while !seen[x] {
            seen[x] = true;
            x = p[q_inv[x]];
            len += 1;
        }
        transpositions += len.saturating_sub(1);
    }
    for i in moved() {
        seen[q[i]] = false;
    }
    if transpositions % 2 == 0 { 1.0 } else { -1.0 }
}

/// `z` divided by its larger part's magnitude (no square root): the phase kept, the
/// magnitude in [1, √2].
fn rescaled(z: c64) -> c64 {
    let s = z.re.abs().max(z.im.abs());
    c64::new(z.re / s, z.im / s)
}

impl<'a> DetPhase<'a> {
    fn new(pencil: &'a Pencil) -> Option<Self> {
        let n = pencil.dim();
        let col_perm = pencil.symbolic()?.col_perm();
        let mut seen = vec![false; n];
        let col_sign = permutation_sign(col_perm.arrays().0, &mut seen);
        let scratch = MemBuffer::try_new(simplicial::factorize_simplicial_numeric_lu_scratch::<usize, c64>(n, n)).ok()?;
        Some(DetPhase { pencil, col_perm, col_sign, values: Vec::new(), lu: SimplicialLu::new(), row_fwd: vec![0; n], row_inv: vec![0; n], signed_rows: Vec::new(), signed_inv: Vec::new(), row_sign: 1.0, scratch, seen, evaluations: 0 })
    }

    /// `det(K + λ E) / |det(K + λ E)|`, or `None` when the LU fails (λ on an eigenvalue).
    fn unit(&mut self, lambda: c64) -> Option<c64> {
        self.evaluations += 1;
        let shifted = self.pencil.shifted();
        shifted.values_into(&mut self.values, |k, e| c64::new(k, 0.0) + lambda * e);
        let a = shifted.matrix(&self.values);
        simplicial::factorize_simplicial_numeric_lu(&mut self.row_fwd, &mut self.row_inv, &mut self.lu, a, self.col_perm, MemStack::new(&mut self.scratch)).ok()?;
        let u = self.lu.u_factor_unsorted();
        let (ptr, val) = (u.symbolic().col_ptr(), u.val());
        if self.signed_rows.len() != self.row_fwd.len() {
            self.row_sign = permutation_sign(&self.row_fwd, &mut self.seen);
            self.seen.fill(false);
        } else if self.signed_rows != self.row_fwd {
            self.row_sign *= sign_from_previous(&self.row_fwd, &self.signed_rows, &self.signed_inv, &mut self.seen);
        }
        if self.signed_rows != self.row_fwd {
            self.signed_rows.clone_from(&self.row_fwd);
            self.signed_inv.clone_from(&self.row_inv);
        }
        let mut z = c64::new(self.col_sign * self.row_sign, 0.0);
        for j in 0..ptr.len() - 1 {
            // faer's simplicial U keeps each column's diagonal entry last.
            let d = val[ptr[j + 1] - 1];
            if !(d.re.is_finite() && d.im.is_finite() && (d.re != 0.0 || d.im != 0.0)) {
                return None;
            }
            z = rescaled(z * rescaled(d));
        }
        Some(z / z.norm())
    }
}

/// `x` wrapped to `(−π, π]`.
fn wrap(x: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let y = x - tau * (x / tau).round();
    if y <= -std::f64::consts::PI { y + tau } else { y }
}

/// The number of eigenvalues of `λ E + K` inside `|λ| < radius` that are not in `found`
/// (every eigenvalue inside with its conjugate and each copy of a repeated one), or `None`
/// when the count cannot be resolved (see the module's sampling rules).
///
/// `beyond`: eigenvalues known outside the circle (`|λ| > radius`), divided out of `g` as
/// well. `λ − λⱼ` does not wind around the circle when `|λⱼ| > R`, so the count is the same
/// whatever they are (even when one is no eigenvalue); they only take out the phase's swing
/// where the circle passes near them, which the sampling would otherwise resolve by
/// bisection (on the 96,024-equation spring chain's 20 lowest modes the eigenvalues come
/// every 0.0039 rad/s, the nearest ones a tenth of that from the circle). An entry inside
/// the circle is refused (`None`): it would change the count.
pub(super) fn missing_in_disc(pencil: &Pencil, radius: f64, found: &[c64], beyond: &[c64]) -> Option<DiscCount> {
    count_in_disc(pencil, radius, found, beyond, DRIFT_HARMONICS)
}

/// Sine harmonics of the phase's drift taken out before the refinement ([`Drift`]).
const DRIFT_HARMONICS: usize = 8;

/// Starting arcs of the upper half circle (each with its midpoint: `2 ARCS + 1` points).
const ARCS: usize = 16;

/// The smooth drift of `arg g` along the upper half circle, `c(t) = Σⱼ bⱼ sin(j t)` at
/// `λ = R e^{jt}`: the phase of `exp(p(λ))`, `p(λ) = Σⱼ (bⱼ / Rʲ) λʲ`, a polynomial with
/// real coefficients. `exp(p)` is entire and has no zero, so `g / exp(p)` has the same
/// zeros and poles inside the circle as `g` and the same winding around it (argument
/// principle); `p` is real on the real axis, so `c(0) = c(π) = 0` and `g / exp(p)` stays
/// real there: the count over the upper half circle is unchanged, whatever the `bⱼ` are.
/// What changes is the phase between: the eigenvalues beyond the circle that were not
/// divided out (thousands on the 96,024-equation string, beyond the Ritz values' reach)
/// turn it smoothly, by about `R² sin 2t Σ 1/ωⱼ²` (`arg(1 + λ²/ωⱼ²)` each), several
/// radians whose slope the π/4-per-half-arc rule resolved by bisection; `c` takes most of
/// it out.
///
/// The `bⱼ` are the first [`DRIFT_HARMONICS`] discrete sine coefficients of the phase
/// sampled at the starting points `t_k = kπ/M` (unwrapped, its straight line from `t = 0` to
/// `π` taken off: the sines vanish at both ends, and that line is the winding, which no
/// `exp(p)` can change); on these points the sines are orthogonal, so the coefficients are
/// the least-squares fit. Scaled down, when needed, so that `c` turns by at most π/2 over
/// any starting half arc (`Σ j |bⱼ| π/M`): a 2π alias of the corrected phase over a half arc
/// then still needs the phase itself to turn by more than 5π/4 there, far beyond the π/4
/// the refinement accepts.
struct Drift {
    b: Vec<f64>,
}

impl Drift {
    fn none() -> Self {
        Drift { b: Vec::new() }
    }

    /// The fit to `phases` (wrapped, at `t_k = kπ/M`, `k = 0..=M`) with `harmonics` sines.
    fn fit(phases: &[f64], harmonics: usize) -> Self {
        let m = phases.len() - 1;
        let mut unwrapped = Vec::with_capacity(phases.len());
        let mut u = 0.0;
        unwrapped.push(u);
        for w in phases.windows(2) {
            u += wrap(w[1] - w[0]);
            unwrapped.push(u);
        }
        let total = unwrapped[m];
        let pi = std::f64::consts::PI;
        let mut b: Vec<f64> = (1..=harmonics.min(m.saturating_sub(1)))
            .map(|j| {
                let sum: f64 = (1..m).map(|k| (unwrapped[k] - total * k as f64 / m as f64) * (pi * (j * k) as f64 / m as f64).sin()).sum();
                2.0 * sum / m as f64
            })
            .collect();
        let steepest: f64 = b.iter().enumerate().map(|(i, x)| (i + 1) as f64 * x.abs()).sum::<f64>() * pi / m as f64;
        if steepest > pi / 2.0 {
            let scale = pi / 2.0 / steepest;
            b.iter_mut().for_each(|x| *x *= scale);
        }
        if !b.iter().all(|x| x.is_finite()) {
            return Drift::none();
        }
        Drift { b }
    }

    /// `c(t)`.
    fn at(&self, t: f64) -> f64 {
        self.b.iter().enumerate().map(|(i, x)| x * ((i + 1) as f64 * t).sin()).sum()
    }
}

/// [`missing_in_disc`] with `harmonics` sines of the drift taken out (0: none).
fn count_in_disc(pencil: &Pencil, radius: f64, found: &[c64], beyond: &[c64], harmonics: usize) -> Option<DiscCount> {
    if !(radius > 0.0 && radius.is_finite()) || beyond.iter().any(|l| !(l.norm() > radius)) {
        return None;
    }
    let mut det = DetPhase::new(pencil)?;
    let found: Vec<c64> = found.iter().chain(beyond).copied().collect();
    let mut phase = |t: f64| -> Option<f64> {
        let lambda = c64::new(radius * t.cos(), radius * t.sin());
        let mut z = det.unit(lambda)?;
        for &l in &found {
            let d = lambda - l;
            z = z * (d.conj() / d.norm());
        }
        Some(z.im.atan2(z.re))
    };
    let pi = std::f64::consts::PI;
    // The starting arcs and their midpoints, every one of which the refinement evaluates.
    let ts: Vec<f64> = (0..=2 * ARCS).map(|k| pi * k as f64 / (2 * ARCS) as f64).collect();
    let mut raw = Vec::with_capacity(ts.len());
    for &t in &ts {
        raw.push(phase(t)?);
    }
    let drift = if harmonics > 0 { Drift::fit(&raw, harmonics) } else { Drift::none() };
    // The phase of g / exp(p) from here on.
    let phases: Vec<f64> = ts.iter().zip(&raw).map(|(&t, &p)| p - drift.at(t)).collect();
    let mut corrected = |t: f64| -> Option<f64> { Some(phase(t)? - drift.at(t)) };
    let mut total = 0.0;
    // Depth-first over the arcs: (a, b, φa, φb, φ at the midpoint when known, depth).
    let mut stack: Vec<(f64, f64, f64, f64, Option<f64>, u32)> = (0..ARCS).rev().map(|k| (ts[2 * k], ts[2 * k + 2], phases[2 * k], phases[2 * k + 2], Some(phases[2 * k + 1]), 0)).collect();
    let mut evaluations = ts.len();
    while let Some((a, b, pa, pb, known, depth)) = stack.pop() {
        if depth > 40 || evaluations > MAX_EVALUATIONS {
            return None;
        }
        let m = 0.5 * (a + b);
        let pm = match known {
            Some(p) => p,
            None => {
                evaluations += 1;
                corrected(m)?
            }
        };
        let (d1, d2) = (wrap(pm - pa), wrap(pb - pm));
        let step = pi / 4.0;
        if d1.abs() <= step && d2.abs() <= step {
            total += d1 + d2;
        } else {
            stack.push((m, b, pm, pb, None, depth + 1));
            stack.push((a, m, pa, pm, None, depth + 1));
        }
    }
    let winding = total / pi;
    let missing = winding.round();
    ((winding - missing).abs() < 0.25).then_some(DiscCount { missing: missing as i64, evaluations: det.evaluations })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eigen::krylov::pencil::oscillators;
    use crate::linear::{SparseLinearDae, SparseMatrix};

    /// Four decoupled oscillators ([`oscillators`], ω = 1, 2, 2, 5: a repeated pair),
    /// eigenvalues ±jωₖ (closed form). The count inside |λ| < R is the number of ±jωₖ with
    /// ωₖ < R.
    #[test]
    fn counts_the_oscillators_inside_each_circle() {
        let omegas = [1.0, 2.0, 2.0, 5.0];
        let pencil = oscillators(&omegas);
        let j = |w: f64| [c64::new(0.0, w), c64::new(0.0, -w)];
        // Nothing given: the count itself (2 per oscillator inside).
        for (radius, inside) in [(0.5, 0), (1.5, 2), (3.0, 6), (10.0, 8)] {
            let c = missing_in_disc(&pencil, radius, &[], &[]).unwrap();
            assert_eq!(c.missing, inside, "R = {radius}");
        }
        // The ω = 1 pair and one copy of ω = 2 given: one copy (2 eigenvalues) missing.
        let given: Vec<c64> = j(1.0).into_iter().chain(j(2.0)).collect();
        assert_eq!(missing_in_disc(&pencil, 3.0, &given, &[]).unwrap().missing, 2);
        let all: Vec<c64> = given.iter().copied().chain(j(2.0)).collect();
        assert_eq!(missing_in_disc(&pencil, 3.0, &all, &[]).unwrap().missing, 0);
        // A circle just outside an eigenvalue (R = 1.001 around ω = 1) is still resolved.
        assert_eq!(missing_in_disc(&pencil, 1.001, &[], &[]).unwrap().missing, 2);
        assert_eq!(missing_in_disc(&pencil, 0.999, &[], &[]).unwrap().missing, 0);
        // The ω = 1 pair just outside R = 0.999, divided out: the same count from the 17
        // starting points and one midpoint per arc, the least a count takes (without it the
        // phase swings by nearly π where the circle passes 0.001 from ±j, and the arcs there
        // are bisected: 61 factorizations). A value that is no eigenvalue (±1.5j) changes
        // nothing either; one inside the circle is refused.
        // (`near`: the count without the drift's removal, which takes that swing out too:
        // 33 with it, `the_drift_removed_keeps_the_count`.)
        let near = count_in_disc(&pencil, 0.999, &[], &[], 0).unwrap().evaluations;
        let divided = missing_in_disc(&pencil, 0.999, &[], &j(1.0)).unwrap();
        assert_eq!((divided.missing, divided.evaluations), (0, 33), "{near} evaluations without");
        assert!(near > 33, "{near}");
        let bogus: Vec<c64> = j(1.0).into_iter().chain(j(1.5)).collect();
        assert_eq!(missing_in_disc(&pencil, 0.999, &[], &bogus).unwrap().missing, 0);
        assert_eq!(missing_in_disc(&pencil, 3.0, &given, &j(5.0)).unwrap().missing, 2);
        assert!(missing_in_disc(&pencil, 3.0, &given, &j(4.0)).is_some() && missing_in_disc(&pencil, 3.0, &given, &j(2.5)).is_none());
        // Rough places of the eigenvalues beyond the circle, as a Krylov run's unconverged
        // Ritz values give them (each with its conjugate; off the axis, off in magnitude,
        // one twice, one where no eigenvalue is): the copy of ω = 2 still counted missing,
        // none once it is given.
        let ritz: Vec<c64> = [c64::new(-1e-3, 4.99), c64::new(2e-2, 5.2), c64::new(0.0, 5.0), c64::new(0.0, 5.0), c64::new(-0.3, 3.5)].into_iter().flat_map(|l| [l, l.conj()]).collect();
        assert_eq!(missing_in_disc(&pencil, 3.0, &given, &ritz).unwrap().missing, 2);
        assert_eq!(missing_in_disc(&pencil, 3.0, &all, &ritz).unwrap().missing, 0);
        // One without its conjugate: `g` is not real on the real axis, the phase from λ = R
        // to λ = −R is no multiple of π (3.5j alone turns it by 0.451 π, numpy's unwrapped
        // angle on 2e5 points), and the count is refused, not rounded. (Several such can sum
        // near a whole multiple: the caller passes each with its conjugate.)
        assert!(missing_in_disc(&pencil, 3.0, &all, &[c64::new(0.0, 3.5)]).is_none());
    }

    /// Undamped oscillators `ω = 1, 2, …, 1000`, each twice (4000 unknowns, E = I, K blocks
    /// [[0, −1], [ω², 0]]: eigenvalues ±jω, closed form), counted in `|λ| < 9.5` with the 18
    /// pairs inside given and those at ω = 10…20 divided out as a Krylov run's Ritz values
    /// would be: the 1960 oscillators beyond turn the phase smoothly by about
    /// `2 R² Σ_{ω>20} 1/ω² sin 2t` (8.8 rad at most), which the π/4 steps resolved by
    /// bisection (73 factorizations without the drift's removal; Python's model of the
    /// sampling on the closed-form phase: 73, and 33 with it). With the drift taken out the
    /// count takes the least a count takes (33) and is the same: 0 with everything given, 2
    /// (one pair) with a copy of ω = 4 or of ω = 9 (0.5 from the circle) left out, −2 with a
    /// copy of ω = 4 given once too often.
    #[test]
    fn the_drift_removed_keeps_the_count() {
        let omegas: Vec<f64> = (1..=1000).flat_map(|w| [w as f64, w as f64]).collect();
        let pencil = oscillators(&omegas);
        let j = |w: f64| [c64::new(0.0, w), c64::new(0.0, -w)];
        let pairs = |ws: &[f64]| -> Vec<c64> { ws.iter().flat_map(|&w| j(w)).collect() };
        let inside: Vec<f64> = (1..=9).flat_map(|w| [w as f64, w as f64]).collect();
        let beyond = pairs(&(10..=20).flat_map(|w| [w as f64, w as f64]).collect::<Vec<_>>());
        let radius = 9.5;
        let without = count_in_disc(&pencil, radius, &pairs(&inside), &beyond, 0).unwrap();
        let with = missing_in_disc(&pencil, radius, &pairs(&inside), &beyond).unwrap();
        assert_eq!((without.missing, with.missing), (0, 0));
        assert_eq!(with.evaluations, 33, "{} evaluations without the drift's removal", without.evaluations);
        assert!(without.evaluations > 60, "{}", without.evaluations);
        for left_out in [4.0, 9.0] {
            let mut given = inside.clone();
            given.remove(given.iter().position(|&w| w == left_out).unwrap());
            assert_eq!(missing_in_disc(&pencil, radius, &pairs(&given), &beyond).unwrap().missing, 2, "ω = {left_out} left out");
            assert_eq!(count_in_disc(&pencil, radius, &pairs(&given), &beyond, 0).unwrap().missing, 2, "ω = {left_out} left out");
        }
        let mut twice = inside.clone();
        twice.push(4.0);
        assert_eq!(missing_in_disc(&pencil, radius, &pairs(&twice), &beyond).unwrap().missing, -2);
        // Nothing divided out beyond the circle: the same count.
        assert_eq!(missing_in_disc(&pencil, radius, &pairs(&inside), &[]).unwrap().missing, 0);
    }

    /// The drift's fit to a phase that is the drift itself (`b = (0.3, −1.2, 0.05)` on the
    /// sines, sampled wrapped at the 33 starting points): the coefficients come back
    /// (the sines are orthogonal on these points); one too steep for the cap is scaled to
    /// turn by π/2 over a half arc.
    #[test]
    fn the_drift_fit_recovers_a_sine_series() {
        let m = 2 * ARCS;
        let pi = std::f64::consts::PI;
        let series = |b: &[f64], t: f64| b.iter().enumerate().map(|(i, x)| x * ((i + 1) as f64 * t).sin()).sum::<f64>();
        let b = [0.3, -1.2, 0.05];
        let phases: Vec<f64> = (0..=m).map(|k| wrap(series(&b, pi * k as f64 / m as f64))).collect();
        let d = Drift::fit(&phases, 8);
        for (i, x) in d.b.iter().enumerate() {
            assert!((x - b.get(i).copied().unwrap_or(0.0)).abs() < 1e-13, "b{} = {x}", i + 1);
        }
        let steep = [0.0, 9.0];
        let phases: Vec<f64> = (0..=m).map(|k| wrap(series(&steep, pi * k as f64 / m as f64))).collect();
        let d = Drift::fit(&phases, 8);
        let turn: f64 = d.b.iter().enumerate().map(|(i, x)| (i + 1) as f64 * x.abs()).sum::<f64>() * pi / m as f64;
        assert!((turn - pi / 2.0).abs() < 1e-12 && d.b[1] > 0.0, "{:?}", d.b);
    }

    /// A block whose LU pivots change along the circle: `λ I + M`, M = [[2, −2], [2.5, −2]],
    /// has `det = (λ + 2)(λ − 2) + 5 = λ² + 1` (closed form: ±j), and partial pivoting takes
    /// row 1 of the first column where `|λ + 2| > 2.5` and row 2 elsewhere (the second
    /// column: `|λ − 2|` against 2): on `|λ| = 1.1` and `|λ| = 3` both happen, whichever
    /// column comes first, so the row permutation's sign must be taken again where the
    /// pivots change (a sign kept from an earlier point turns the phase by π there and the
    /// count comes out wrong or unresolved). Beside it an undamped oscillator ω = 4,
    /// outside every circle here.
    #[test]
    fn counts_through_a_change_of_pivots() {
        let n = 4;
        let e = SparseMatrix::from_triplets(n, n, (0..n).map(|i| (i, i, 1.0))).unwrap();
        let k = SparseMatrix::from_triplets(n, n, [(0, 0, 2.0), (0, 1, -2.0), (1, 0, 2.5), (1, 1, -2.0), (2, 3, -1.0), (3, 2, 16.0)]).unwrap();
        let names = (0..n).map(|i| format!("y{i}")).collect();
        let dae = SparseLinearDae { fyd: e, fy: k, b: faer::Mat::zeros(n, 0), c: faer::Mat::zeros(0, n), c_rate: None, unknown_names: names, input_names: Vec::new(), output_names: Vec::new(), constraint_form: None, multipliers: Vec::new() };
        let pencil = Pencil::new(&dae).unwrap();
        let j = c64::new(0.0, 1.0);
        for (radius, inside) in [(0.9, 0), (1.1, 2), (3.0, 2), (3.9, 2)] {
            assert_eq!(missing_in_disc(&pencil, radius, &[], &[]).unwrap().missing, inside, "R = {radius}");
        }
        assert_eq!(missing_in_disc(&pencil, 3.0, &[j, j.conj()], &[]).unwrap().missing, 0);
        assert_eq!(missing_in_disc(&pencil, 1.1, &[j, j.conj()], &[c64::new(0.0, 4.0), c64::new(0.0, -4.0)]).unwrap().missing, 0);
    }

    /// The sign of a permutation from the previous one and the entries that changed
    /// against its sign by cycles from scratch (`permutation_sign`), and against the closed
    /// form: one transposition flips it, a 3-cycle keeps it. Random permutations of 1000
    /// entries, each changed by 0 to 40 random transpositions (the moved entries' cycles
    /// cross each other) and one changed everywhere.
    #[test]
    fn the_sign_from_the_changed_entries_is_the_sign_by_cycles() {
        let n = 1000;
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut next = move |m: usize| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % m as u64) as usize
        };
        let inverse = |p: &[usize]| {
            let mut inv = vec![0; p.len()];
            p.iter().enumerate().for_each(|(i, &x)| inv[x] = i);
            inv
        };
        let mut seen = vec![false; n];
        let mut q: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            q.swap(i, next(i + 1));
        }
        let by_cycles = |p: &[usize], seen: &mut Vec<bool>| {
            let s = permutation_sign(p, seen);
            seen.fill(false);
            s
        };
        for swaps in [0, 1, 2, 3, 7, 40] {
            let mut p = q.clone();
            for _ in 0..swaps {
                let (a, b) = (next(n), next(n));
                p.swap(a, b);
            }
            let relative = sign_from_previous(&p, &q, &inverse(&q), &mut seen) * by_cycles(&q, &mut seen);
            assert_eq!(relative, by_cycles(&p, &mut seen), "{swaps} transpositions");
            assert!(seen.iter().all(|s| !s), "seen left false");
        }
        let mut one = q.clone();
        one.swap(3, 700);
        assert_eq!(sign_from_previous(&one, &q, &inverse(&q), &mut seen), -1.0);
        let mut three = q.clone();
        three.swap(3, 700);
        three.swap(700, 12);
        assert_eq!(sign_from_previous(&three, &q, &inverse(&q), &mut seen), 1.0);
        let reversed: Vec<usize> = q.iter().rev().copied().collect();
        assert_eq!(sign_from_previous(&reversed, &q, &inverse(&q), &mut seen) * by_cycles(&q, &mut seen), by_cycles(&reversed, &mut seen));
    }
}
