//! Balanced reduction of an ordinary ROM (issue 37 point 4): balanced truncation or the
//! singular perturbation approximation of its stable part, and a minimal realization.
//!
//! Rigid-body, integrator (λ = 0) and unstable modes have no Gramians: the state matrix is
//! split into a stable part and the rest (additive decomposition, `G = G_s + G_r`,
//! [`super::lyapunov::split`]) and only `G_s` is reduced. Its Gramians solve
//! `A P + P Aᵀ + B Bᵀ = 0` and `Aᵀ Q + Q A + Cᵀ C = 0`; with `P = L_c L_cᵀ`,
//! `Q = L_o L_oᵀ` and `L_oᵀ L_c = U Σ Vᵀ` the Hankel singular values are `Σ`, and the
//! square-root method's `W = L_o U_r Σ_r^{-1/2}`, `V = L_c V_r Σ_r^{-1/2}` give
//! `A_r = Wᵀ A V`, `B_r = Wᵀ B`, `C_r = C V` (Tombs and Postlethwaite, Int. J. Control 46,
//! 1987). Both methods keep `‖G − G_r‖_∞ ≤ 2 Σ_{i>r} σ_i` (Glover, Int. J. Control 39,
//! 1984; Liu and Anderson, Int. J. Control 50, 1989); the singular perturbation
//! approximation also keeps the static gain (residualizing the balanced states it drops).
//!
//! A minimal realization removes the states whose Hankel singular values fall below
//! `tol σ_1` in the system shifted to `A − α I` (controllability and observability do not
//! change with the shift, which makes every mode stable).

use faer::Mat;

use super::dense::solve_nonsingular;
use super::lyapunov::{lyapunov, split};
use super::{OrdinaryRom, RomError};

/// How many stable states a balanced reduction keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BalancedOrder {
    /// This many states in all (the unreduced rigid-body and unstable ones included).
    States(usize),
    /// The stable states whose Hankel singular value exceeds `tol σ_1`.
    HankelTolerance(f64),
}

/// Balanced truncation, or singular perturbation approximation (same static gain).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BalancedMethod {
    Truncation,
    SingularPerturbation,
}

/// A balanced reduction's result.
#[derive(Clone, Debug)]
pub struct BalancedReduction {
    pub rom: OrdinaryRom,
    pub method: BalancedMethod,
    /// Hankel singular values of the stable part, largest first.
    pub hankel: Vec<f64>,
    /// Stable states kept (the first states of `rom`).
    pub kept: usize,
    /// Rigid-body, integrator and unstable states kept unreduced (the last states of `rom`).
    pub unreduced: usize,
    /// `2 Σ` of the dropped Hankel singular values: a bound on `‖G − G_r‖_∞`.
    pub error_bound: f64,
}

/// Eigenvalues of `A` and whether each belongs to the stable part: `Re λ < −1e-9 |λ|_max`
/// and `|λ| > 1e-6 |λ|_max` (a rigid-body pair splits by rounding to ±√ε-sized real
/// eigenvalues: both stay with the rest).
fn stable_part(a: &Mat<f64>) -> Result<(Vec<faer::c64>, Vec<bool>), RomError> {
    if a.nrows() == 0 {
        return Ok((Vec::new(), Vec::new()));
    }
    let ev = a.as_ref().eigenvalues().map_err(|_| RomError::Balanced("the eigenvalues of A did not converge".into()))?;
    let big = ev.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let stable = ev.iter().map(|l| l.re < -1e-9 * big && l.norm() > 1e-6 * big).collect();
    Ok((ev, stable))
}

/// `L` with `L Lᵀ = X` for a symmetric positive semi-definite `X` (its SVD; negative
/// rounding clipped).
fn square_root(x: &Mat<f64>) -> Result<Mat<f64>, RomError> {
    let svd = x.svd().map_err(|_| RomError::Balanced("the SVD of a Gramian did not converge".into()))?;
    let (u, s) = (svd.U(), svd.S());
    Ok(Mat::from_fn(x.nrows(), x.ncols(), |i, j| u[(i, j)] * s[j].max(0.0).sqrt()))
}

/// Hankel singular values (largest first) and the projections `W`, `V` of a balanced
/// realization.
type Balanced = (Vec<f64>, Mat<f64>, Mat<f64>);

/// The balanced realization's projections of a stable `(A, B, C)`: Hankel singular values
/// (largest first) and `W`, `V` for the states whose value exceeds `floor σ_1`.
fn balance(a: &Mat<f64>, b: &Mat<f64>, c: &Mat<f64>, floor: f64) -> Result<Balanced, RomError> {
    let p = lyapunov(a, &(b * b.transpose()))?;
    let q = lyapunov(&a.transpose().to_owned(), &(c.transpose() * c))?;
    let (lc, lo) = (square_root(&p)?, square_root(&q)?);
    let svd = (lo.transpose() * &lc).svd().map_err(|_| RomError::Balanced("the SVD of L_oᵀ L_c did not converge".into()))?;
    let n = a.nrows();
    let sigma: Vec<f64> = (0..n).map(|i| svd.S()[i]).collect();
    let top = sigma.first().copied().unwrap_or(0.0);
    let q = sigma.iter().filter(|s| **s > floor * top && **s > 0.0).count();
    let w = Mat::from_fn(n, q, |i, j| (&lo * svd.U().get(.., j..j + 1))[(i, 0)] / sigma[j].sqrt());
    let v = Mat::from_fn(n, q, |i, j| (&lc * svd.V().get(.., j..j + 1))[(i, 0)] / sigma[j].sqrt());
    Ok((sigma, w, v))
}

/// Hankel singular values below this fraction of the largest are rounding: those states
/// are neither kept nor residualized.
const ROUNDING_FLOOR: f64 = 1e-13;

impl OrdinaryRom {
    /// The ROM whose state basis is `T` (`x = T x̃`): `T⁻¹ A T`, `T⁻¹ B`, `C T`.
    fn transformed(&self, t: &Mat<f64>, tinv: &Mat<f64>) -> (Mat<f64>, Mat<f64>, Mat<f64>) {
        (tinv * &self.a * t, tinv * &self.b, &self.c * t)
    }

    /// Balanced truncation or singular perturbation approximation of the stable part to
    /// `order`; the rigid-body, integrator and unstable part is kept unreduced.
    pub fn balanced(&self, order: BalancedOrder, method: BalancedMethod) -> Result<BalancedReduction, RomError> {
        let n = self.a.nrows();
        let (ev, stable) = stable_part(&self.a)?;
        let sp = split(&self.a, &stable, &ev)?;
        let (ns, nr) = (sp.ns, n - sp.ns);
        if ns == 0 {
            return Err(RomError::Balanced(format!("no mode of the ROM is asymptotically stable (its {n} eigenvalues lie on the imaginary axis or to its right), so none has Gramians to reduce: add modal damping (--damping)")));
        }
        let (a, b, c) = self.transformed(&sp.t, &sp.tinv);
        let (a11, b1, c1) = (a.get(..ns, ..ns).to_owned(), b.get(..ns, ..).to_owned(), c.get(.., ..ns).to_owned());
        let (sigma, w, v) = balance(&a11, &b1, &c1, ROUNDING_FLOOR)?;
        let minimal = w.ncols();
        let top = sigma.first().copied().unwrap_or(0.0);
        let r = match order {
            BalancedOrder::States(total) if total < nr => {
                return Err(RomError::Balanced(format!("the ROM has {nr} states of rigid-body, integrator or unstable modes, which balanced reduction keeps whole: ask for at least {nr} states (got {total})")));
            }
            BalancedOrder::States(total) => (total - nr).min(minimal),
            BalancedOrder::HankelTolerance(tol) => sigma.iter().take(minimal).filter(|s| **s > tol * top).count(),
        };
        // The balanced realization of order `minimal`, its first r states kept.
        let (ab, bb, cb) = (w.transpose() * &a11 * &v, w.transpose() * &b1, &c1 * &v);
        let (mut ar, mut br, mut cr, mut dr) = (ab.get(..r, ..r).to_owned(), bb.get(..r, ..).to_owned(), cb.get(.., ..r).to_owned(), self.d.clone());
        if method == BalancedMethod::SingularPerturbation && r < minimal {
            // Residualized balanced states: 0 = A21 x1 + A22 x2 + B2 u.
            let (a12, a21, a22) = (ab.get(..r, r..).to_owned(), ab.get(r.., ..r).to_owned(), ab.get(r.., r..).to_owned());
            let (b2, c2) = (bb.get(r.., ..).to_owned(), cb.get(.., r..).to_owned());
            let singular = || RomError::Balanced("A22 of the balanced realization is singular: use truncation".into());
            let xa = solve_nonsingular(&a22, &a21).ok_or_else(singular)?;
            let xb = solve_nonsingular(&a22, &b2).ok_or_else(singular)?;
            ar -= &a12 * &xa;
            br -= &a12 * &xb;
            cr -= &c2 * &xa;
            dr -= &c2 * &xb;
        }
        let kept = r + nr;
        let a_out = Mat::from_fn(kept, kept, |i, j| match (i < r, j < r) {
            (true, true) => ar[(i, j)],
            (false, false) => a[(ns + i - r, ns + j - r)],
            _ => 0.0,
        });
        let b_out = Mat::from_fn(kept, b.ncols(), |i, j| if i < r { br[(i, j)] } else { b[(ns + i - r, j)] });
        let c_out = Mat::from_fn(c.nrows(), kept, |i, j| if j < r { cr[(i, j)] } else { c[(i, ns + j - r)] });
        let eigenvalues = if kept == 0 { Vec::new() } else { a_out.as_ref().eigenvalues().unwrap_or_default() };
        let error_bound = 2.0 * sigma.iter().skip(r).sum::<f64>();
        let rom = OrdinaryRom { a: a_out, b: b_out, c: c_out, d: dr, eigenvalues, input_names: self.input_names.clone(), output_names: self.output_names.clone() };
        Ok(BalancedReduction { rom, method, hankel: sigma, kept: r, unreduced: nr, error_bound })
    }

    /// The ROM without its uncontrollable and unobservable states: those whose Hankel
    /// singular value in the shifted system `(A − α I, B, C)` is below `tol σ_1`, `α` putting
    /// every eigenvalue at Re λ ≤ −|λ|_max/10. Returns the ROM (this one, unchanged, when
    /// nothing is removed) and the number of states removed.
    pub fn minimal(&self, tol: f64) -> Result<(OrdinaryRom, usize), RomError> {
        if !(tol > 0.0 && tol < 1.0) {
            return Err(RomError::Balanced(format!("the minimal-realization tolerance must lie in (0, 1), got {tol}")));
        }
        let n = self.a.nrows();
        if n == 0 {
            return Ok((self.clone(), 0));
        }
        let (ev, _) = stable_part(&self.a)?;
        let big = ev.iter().map(|l| l.norm()).fold(0.0, f64::max).max(f64::MIN_POSITIVE);
        let alpha = ev.iter().map(|l| l.re).fold(f64::NEG_INFINITY, f64::max).max(0.0) + 0.1 * big;
        let shifted = &self.a - Mat::<f64>::identity(n, n) * faer::Scale(alpha);
        let (_, w, v) = balance(&shifted, &self.b, &self.c, tol)?;
        let removed = n - w.ncols();
        if removed == 0 {
            return Ok((self.clone(), 0));
        }
        let a = w.transpose() * &self.a * &v;
        let eigenvalues = if a.nrows() == 0 { Vec::new() } else { a.as_ref().eigenvalues().unwrap_or_default() };
        let rom = OrdinaryRom { b: w.transpose() * &self.b, c: &self.c * &v, a, d: self.d.clone(), eigenvalues, input_names: self.input_names.clone(), output_names: self.output_names.clone() };
        Ok((rom, removed))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rom(a: Mat<f64>, b: Mat<f64>, c: Mat<f64>) -> OrdinaryRom {
        let d = Mat::zeros(c.nrows(), b.ncols());
        OrdinaryRom { a, b, c, d, eigenvalues: Vec::new(), input_names: Vec::new(), output_names: Vec::new() }
    }

    /// ẋ = a x + b u, y = c x: P = b²/(2|a|), Q = c²/(2|a|), σ = √(PQ) = |b c|/(2|a|).
    #[test]
    fn hankel_singular_value_of_a_first_order_system() {
        let (a, b, c) = (-4.0, 3.0, -5.0);
        let one = |v: f64| Mat::from_fn(1, 1, |_, _| v);
        let r = rom(one(a), one(b), one(c)).balanced(BalancedOrder::HankelTolerance(0.5), BalancedMethod::Truncation).unwrap();
        assert!((r.hankel[0] - (b * c).abs() / (2.0 * a.abs())).abs() < 1e-15, "{:?}", r.hankel);
        assert_eq!((r.kept, r.unreduced, r.error_bound), (1, 0, 0.0));
    }

    /// x₂ and x₃ are the same state (same pole, same input): x₂ − x₃ is uncontrollable and
    /// the minimal realization removes exactly one state, keeping poles −1, −2 and the
    /// transfer function.
    #[test]
    fn minimal_realization_removes_a_duplicated_state() {
        let a = Mat::from_fn(3, 3, |i, j| if i == j { [-1.0, -2.0, -2.0][i] } else { 0.0 });
        let b = Mat::from_fn(3, 1, |_, _| 1.0);
        let c = Mat::from_fn(1, 3, |_, j| [1.0, 0.5, 0.5][j]);
        let full = rom(a, b, c);
        let (min, removed) = full.minimal(1e-10).unwrap();
        assert_eq!(removed, 1);
        let mut ev: Vec<f64> = min.eigenvalues.iter().map(|l| l.re).collect();
        ev.sort_by(f64::total_cmp);
        assert!((ev[0] + 2.0).abs() < 1e-12 && (ev[1] + 1.0).abs() < 1e-12, "{ev:?}");
        for f in [0.0, 0.1, 1.0, 10.0] {
            let (h0, h1) = (full.frequency_response(&[f])[0][(0, 0)], min.frequency_response(&[f])[0][(0, 0)]);
            assert!((h0 - h1).norm() < 1e-13, "{f}: {h0} vs {h1}");
        }
        // A minimal system loses nothing.
        assert_eq!(min.minimal(1e-10).unwrap().1, 0);
    }

    /// An integrator beside two stable modes: it is kept whole, the stable part reduced,
    /// and singular perturbation keeps the stable part's static gain.
    #[test]
    fn integrator_is_kept_and_spa_keeps_the_static_gain() {
        let a = Mat::from_fn(3, 3, |i, j| if i == j { [0.0, -1.0, -50.0][i] } else { 0.0 });
        let b = Mat::from_fn(3, 1, |i, _| [1.0, 1.0, 1.0][i]);
        let c = Mat::from_fn(1, 3, |_, j| [1.0, 1.0, 0.1][j]);
        let full = rom(a, b, c);
        let spa = full.balanced(BalancedOrder::States(2), BalancedMethod::SingularPerturbation).unwrap();
        assert_eq!((spa.kept, spa.unreduced), (1, 1));
        // The stable part's static gain 1/1 + 0.1/50; σ₂ of 0.1/(s + 50): (0.1)/(2·50) bounds the rest.
        let stable = rom(spa.rom.a.get(..1, ..1).to_owned(), spa.rom.b.get(..1, ..).to_owned(), spa.rom.c.get(.., ..1).to_owned());
        let g = stable.d.clone() + spa.rom.d.clone() - &stable.c * solve_nonsingular(&stable.a, &stable.b).unwrap();
        assert!((g[(0, 0)] - (1.0 + 0.1 / 50.0)).abs() < 1e-12, "{g:?}");
        assert!(spa.error_bound > 0.0 && spa.error_bound < 2.0 * 0.1 / 100.0 * 1.01, "{}", spa.error_bound);
        let e = full.balanced(BalancedOrder::States(0), BalancedMethod::Truncation).unwrap_err();
        assert!(e.to_string().contains("at least 1 states"), "{e}");
    }
}
