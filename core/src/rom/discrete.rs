//! Discrete-time ROMs for a controller running at a fixed sample rate (issue 37 point 3; the
//! paper's HAM-SAS controller ran at 2048 Hz, §2): `x[k+1] = A_d x[k] + B_d u[k]`,
//! `z[k] = C_d x[k] + D_d u[k]`, from the ordinary ROM by
//!
//! - zero-order hold (the default): `[[A_d, B_d], [0, I]] = e^{[[A, B], [0, 0]] T}`,
//!   `C_d = C`, `D_d = D` (Franklin, Powell and Workman, *Digital Control of Dynamic Systems*,
//!   §4.3.3): exact for inputs held between samples; eigenvalues `e^{λ T}`;
//! - Tustin (bilinear) with optional prewarping at `f_w`: `s = (2/T')(z − 1)/(z + 1)` with
//!   `T' = T`, or `T' = 2 tan(ω_w T/2)/ω_w` so that the response at `ω_w` is exact (same book
//!   §6.3.1); `A_d = (I − A T'/2)⁻¹ (I + A T'/2)`, `B_d = (I − A T'/2)⁻¹ B T'`,
//!   `C_d = C (I − A T'/2)⁻¹`, `D_d = D + C_d B T'/2`; z = 1 is s = 0, so the DC gain is the
//!   continuous static gain;
//! - matched pole-zero (single input, single output only, as MATLAB's `c2d`): poles and
//!   finite zeros mapped by `e^{s T}`, zeros at infinity to z = −1, the gain matched at low
//!   frequency (same book §6.3.3); its states are a controllable canonical form's.
//!
//! The matrix exponential is Padé(6,6) with scaling and squaring (Moler and Van Loan,
//! "Nineteen dubious ways", method 3); `romdyn::validate` uses it for its exact simulation.

use faer::linalg::solvers::Solve;
use faer::{c64, Mat};

use super::dense::solve_nonsingular;
use super::{OrdinaryRom, RomError};
use crate::linear::rad_per_s;

/// `e^{X}` by the diagonal Padé approximant of degree 6 after scaling `X` to norm ≤ 1/2.
pub fn expm(x: &Mat<f64>) -> Mat<f64> {
    let n = x.nrows();
    let norm = (0..n).map(|i| (0..n).map(|j| x[(i, j)].abs()).sum::<f64>()).fold(0.0, f64::max);
    let squarings = if norm > 0.5 { (norm / 0.5).log2().ceil() as i32 } else { 0 };
    let a = x * faer::Scale(0.5f64.powi(squarings));
    // c_k = c_{k−1} (q − k + 1) / (k (2q − k + 1)), q = 6.
    let q = 6;
    let (mut c, mut power) = (1.0, Mat::<f64>::identity(n, n));
    let (mut num, mut den) = (Mat::<f64>::identity(n, n), Mat::<f64>::identity(n, n));
    for k in 1..=q {
        c *= (q - k + 1) as f64 / (k * (2 * q - k + 1)) as f64;
        power = &power * &a;
        num += &power * faer::Scale(c);
        den += &power * faer::Scale(if k % 2 == 0 { c } else { -c });
    }
    let mut e = den.partial_piv_lu().solve(&num);
    for _ in 0..squarings {
        e = &e * &e;
    }
    e
}

/// How a continuous ROM becomes a discrete one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Discretization {
    /// Zero-order hold: exact for piecewise-constant inputs.
    ZeroOrderHold,
    /// Tustin (bilinear), prewarped at this frequency [Hz] when given.
    Tustin { prewarp_hz: Option<f64> },
    /// Matched pole-zero (single input, single output).
    Matched,
}

impl Discretization {
    /// The name the exports store: "zoh", "tustin", "tustin prewarped at F Hz", "matched".
    pub fn name(&self) -> String {
        match self {
            Discretization::ZeroOrderHold => "zoh".into(),
            Discretization::Tustin { prewarp_hz: None } => "tustin".into(),
            Discretization::Tustin { prewarp_hz: Some(f) } => format!("tustin prewarped at {f} Hz"),
            Discretization::Matched => "matched".into(),
        }
    }
}

/// A sample rate and a discretization method, checked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampling {
    /// Sample rate [Hz].
    pub rate_hz: f64,
    pub method: Discretization,
}

impl Sampling {
    /// A sample rate above 0 and finite, a prewarping frequency within (0, rate/2).
    pub fn new(rate_hz: f64, method: Discretization) -> Result<Self, String> {
        if !(rate_hz > 0.0 && rate_hz.is_finite()) {
            return Err(format!("the sample rate must be a positive finite number of Hz, got {rate_hz}"));
        }
        if let Discretization::Tustin { prewarp_hz: Some(f) } = method
            && !(f > 0.0 && f < rate_hz / 2.0)
        {
            return Err(format!("the prewarping frequency must lie between 0 and the Nyquist frequency {} Hz, got {f} Hz", rate_hz / 2.0));
        }
        Ok(Sampling { rate_hz, method })
    }

    /// The sampling time `1/rate` [s].
    pub fn period(&self) -> f64 {
        1.0 / self.rate_hz
    }
}

/// A discrete-time ROM: `x[k+1] = A x[k] + B u[k]`, `z[k] = C x[k] + D u[k]`; its
/// `eigenvalues` are those of `A` (z-plane), `state_names` its states' (the continuous ROM's,
/// but for the matched method's canonical form).
#[derive(Clone, Debug)]
pub struct DiscreteRom {
    pub rom: OrdinaryRom,
    pub sampling: Sampling,
    /// `Some`: the states are new (matched: a controllable canonical form's), with these names.
    pub state_names: Option<Vec<String>>,
}

impl DiscreteRom {
    /// The sampling time [s].
    pub fn sample_time(&self) -> f64 {
        self.sampling.period()
    }

    /// `C (e^{jωT} I − A)⁻¹ B + D` at each frequency [Hz]: `e^{jθ} I − A = j sin θ I + (cos θ I − A)`.
    pub fn frequency_response(&self, freq_hz: &[f64]) -> Vec<Mat<c64>> {
        let r = &self.rom;
        let id = Mat::<f64>::identity(r.a.nrows(), r.a.nrows());
        freq_hz
            .iter()
            .map(|f| {
                let theta = rad_per_s(*f) * self.sample_time();
                super::dense::transfer(theta.sin(), &id, &(&id * faer::Scale(theta.cos()) - &r.a), &r.b, &r.c, Some(&r.d))
            })
            .collect()
    }

    /// `C (I − A)⁻¹ B + D`: the DC gain (z = 1).
    pub fn static_gain(&self) -> Result<Mat<f64>, RomError> {
        let n = self.rom.a.nrows();
        let x = solve_nonsingular(&(Mat::<f64>::identity(n, n) - &self.rom.a), &self.rom.b).ok_or(RomError::SingularStatic("I − A of the discrete ROM (a pole at z = 1)"))?;
        Ok(&self.rom.d + &self.rom.c * &x)
    }
}

impl OrdinaryRom {
    /// The discrete-time ROM of `sampling`.
    pub fn discretize(&self, sampling: &Sampling) -> Result<DiscreteRom, RomError> {
        let t = sampling.period();
        let (n, m) = (self.a.nrows(), self.b.ncols());
        let (a, b, c, d, names) = match sampling.method {
            Discretization::ZeroOrderHold => {
                let e = expm(&Mat::from_fn(n + m, n + m, |i, j| if i < n && j < n { self.a[(i, j)] * t } else if i < n { self.b[(i, j - n)] * t } else { 0.0 }));
                (e.get(..n, ..n).to_owned(), e.get(..n, n..).to_owned(), self.c.clone(), self.d.clone(), None)
            }
            Discretization::Tustin { prewarp_hz } => {
                let tp = match prewarp_hz {
                    Some(f) => {
                        let w = rad_per_s(f);
                        2.0 * (w * t / 2.0).tan() / w
                    }
                    None => t,
                };
                let id = Mat::<f64>::identity(n, n);
                let left = &id - &self.a * faer::Scale(tp / 2.0);
                let right = &id + &self.a * faer::Scale(tp / 2.0);
                let solve = |m: &Mat<f64>, r: &Mat<f64>| solve_nonsingular(m, r).ok_or(RomError::SingularStatic("I − A T/2 (an eigenvalue at s = 2/T)"));
                let ad = solve(&left, &right)?;
                let bd = solve(&left, &(&self.b * faer::Scale(tp)))?;
                let cd = solve(&left.transpose().to_owned(), &self.c.transpose().to_owned())?.transpose().to_owned();
                let dd = &self.d + &cd * &self.b * faer::Scale(tp / 2.0);
                (ad, bd, cd, dd, None)
            }
            Discretization::Matched => {
                let [a, b, c, d] = super::matched::matched_realization(self, t)?;
                let names = (1..=a.nrows()).map(|k| format!("matched state {k}")).collect();
                (a, b, c, d, Some(names))
            }
        };
        let eigenvalues = if a.nrows() == 0 { Vec::new() } else { a.as_ref().eigenvalues().unwrap_or_default() };
        let rom = OrdinaryRom { a, b, c, d, eigenvalues, input_names: self.input_names.clone(), output_names: self.output_names.clone() };
        Ok(DiscreteRom { rom, sampling: *sampling, state_names: names })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn first_order(a: f64, b: f64, c: f64, d: f64) -> OrdinaryRom {
        let one = |v: f64| Mat::from_fn(1, 1, |_, _| v);
        OrdinaryRom { a: one(a), b: one(b), c: one(c), d: one(d), eigenvalues: Vec::new(), input_names: Vec::new(), output_names: Vec::new() }
    }

    /// e^{[[0, w], [−w, 0]] t} is the rotation by w t.
    #[test]
    fn exponential_of_a_rotation_generator() {
        let (w, t) = (300.0, 0.1);
        let x = Mat::from_fn(2, 2, |i, j| [[0.0, w * t], [-w * t, 0.0]][i][j]);
        let e = expm(&x);
        let (c, s) = ((w * t).cos(), (w * t).sin());
        let exact = [[c, s], [-s, c]];
        for i in 0..2 {
            for j in 0..2 {
                assert!((e[(i, j)] - exact[i][j]).abs() < 1e-12, "{:?}", e);
            }
        }
    }

    /// ẋ = −a x + b u under zero-order hold: A_d = e^{−aT}, B_d = b (1 − e^{−aT})/a
    /// (Franklin, Powell and Workman §4.3.3).
    #[test]
    fn zero_order_hold_of_a_first_order_system() {
        let (a, b, t) = (30.0, 2.0, 1.0 / 2048.0);
        let d = first_order(-a, b, 1.0, 0.5).discretize(&Sampling::new(2048.0, Discretization::ZeroOrderHold).unwrap()).unwrap();
        assert!((d.rom.a[(0, 0)] - (-a * t).exp()).abs() < 1e-15);
        assert!((d.rom.b[(0, 0)] - b * (1.0 - (-a * t).exp()) / a).abs() < 1e-16);
        assert_eq!(d.rom.d[(0, 0)], 0.5);
    }

    /// Tustin prewarped at f_w: the discrete response at f_w equals the continuous one
    /// (b/(jω + a) at ω = 2π f_w) to rounding; unwarped it does not.
    #[test]
    fn prewarped_tustin_is_exact_at_its_frequency() {
        let (a, b, fs, fw) = (300.0, 300.0, 1000.0, 200.0);
        let rom = first_order(-a, b, 1.0, 0.0);
        let exact = c64::new(b, 0.0) / c64::new(a, rad_per_s(fw));
        let warped = rom.discretize(&Sampling::new(fs, Discretization::Tustin { prewarp_hz: Some(fw) }).unwrap()).unwrap();
        let h = warped.frequency_response(&[fw])[0][(0, 0)];
        assert!((h - exact).norm() < 1e-13 * exact.norm(), "{h} vs {exact}");
        let plain = rom.discretize(&Sampling::new(fs, Discretization::Tustin { prewarp_hz: None }).unwrap()).unwrap();
        assert!((plain.frequency_response(&[fw])[0][(0, 0)] - exact).norm() > 1e-3 * exact.norm());
    }

    #[test]
    fn bad_rates_are_refused() {
        assert!(Sampling::new(0.0, Discretization::ZeroOrderHold).unwrap_err().contains("positive"));
        assert!(Sampling::new(100.0, Discretization::Tustin { prewarp_hz: Some(60.0) }).unwrap_err().contains("Nyquist frequency 50 Hz"));
    }
}
