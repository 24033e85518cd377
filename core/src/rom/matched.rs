//! Matched pole-zero discretization of a single-input, single-output ROM (Franklin, Powell
//! and Workman, *Digital Control of Dynamic Systems*, §6.3.3): `H(s) = g Π(s − z_j)/Π(s − λ_i)`
//! becomes `H_d(z) = K Π(z − e^{z_j T}) (z + 1)^r / Π(z − e^{λ_i T})` (the `r` zeros at
//! infinity, `r` the relative degree, at z = −1), `K` such that the low-frequency asymptotes
//! agree: `lim s^k H(s)` (s → 0) equals `lim ((z − 1)/T)^k H_d(z)` (z → 1), `k` the number of
//! poles at the origin less that of zeros there (k = 0: the static gains are equal).
//!
//! The zeros are the eigenvalues of the zero dynamics: with `g = C A^{r−1} B` the first
//! nonzero Markov parameter, `A_z = A − B C A^r / g` restricted to the null space of
//! `[C; C A; …; C A^{r−1}]` (invariant under `A_z`); with `D ≠ 0`, those of `A − B C/D`.

use faer::{c64, Mat};

use super::{OrdinaryRom, RomError};

fn eigenvalues(m: &Mat<f64>) -> Result<Vec<c64>, RomError> {
    if m.nrows() == 0 {
        return Ok(Vec::new());
    }
    m.as_ref().eigenvalues().map_err(|_| RomError::Discrete("matched: an eigenvalue computation did not converge".into()))
}

/// Coefficients `[1, a_1, …, a_n]` of `Π (z − r_i)` (real: the roots come in conjugate pairs).
fn poly(roots: &[c64]) -> Vec<f64> {
    let mut p = vec![c64::new(1.0, 0.0)];
    for r in roots {
        let mut next = p.clone();
        next.push(c64::new(0.0, 0.0));
        for k in 0..p.len() {
            next[k + 1] -= p[k] * r;
        }
        p = next;
    }
    p.iter().map(|c| c.re).collect()
}

/// The transfer function's finite zeros, its leading coefficient `g` and relative degree `r`.
fn zeros(rom: &OrdinaryRom) -> Result<(Vec<c64>, f64, usize), RomError> {
    let (a, b, c, d) = (&rom.a, &rom.b, &rom.c, rom.d[(0, 0)]);
    let n = a.nrows();
    if d != 0.0 {
        return Ok((eigenvalues(&(a - b * c * faer::Scale(1.0 / d)))?, d, 0));
    }
    let norm_a = a.norm_max().max(f64::MIN_POSITIVE);
    // c A^{k−1} rows, k = 1..n.
    let mut rows = vec![c.clone()];
    for k in 1..=n {
        let g = (&rows[k - 1] * b)[(0, 0)];
        let scale = c.norm_max() * b.norm_max() * norm_a.powi(k as i32 - 1);
        if g.abs() > 1e-12 * scale {
            let cr = &rows[k - 1] * a;
            let az = a - b * &cr * faer::Scale(1.0 / g);
            let stacked = Mat::from_fn(k, n, |i, j| rows[i][(0, j)]);
            let svd = stacked.svd().map_err(|_| RomError::Discrete("matched: an SVD did not converge".into()))?;
            let null = svd.V().get(.., k..).to_owned();
            return Ok((eigenvalues(&(null.transpose() * &az * &null))?, g, k));
        }
        rows.push(&rows[k - 1] * a);
    }
    Err(RomError::Discrete("matched: the ROM's transfer function is zero (its input reaches no output through its states)".into()))
}

/// `(A_d, B_d, C_d, D_d)` of the matched pole-zero discretization at step `t` [s], in
/// controllable canonical form.
pub(super) fn matched_realization(rom: &OrdinaryRom, t: f64) -> Result<[Mat<f64>; 4], RomError> {
    if rom.b.ncols() != 1 || rom.c.nrows() != 1 {
        return Err(RomError::Discrete(format!("the matched pole-zero method maps the poles and zeros of one transfer function: this ROM has {} inputs and {} outputs (use zoh or tustin, or a single input and output)", rom.b.ncols(), rom.c.nrows())));
    }
    let n = rom.a.nrows();
    let poles = eigenvalues(&rom.a)?;
    let (zs, g, r) = zeros(rom)?;
    let big = poles.iter().chain(&zs).map(|l| l.norm()).fold(0.0, f64::max);
    let at_origin = |l: &c64| l.norm() <= 1e-9 * big;
    let k = poles.iter().filter(|l| at_origin(l)).count() as i32 - zs.iter().filter(|l| at_origin(l)).count() as i32;
    // lim s^k H(s) = g Π'(−z) / Π'(−λ), the primes leaving out the roots at the origin.
    let prod = |v: &[c64], f: &dyn Fn(c64) -> c64| v.iter().filter(|l| !at_origin(l)).fold(c64::new(1.0, 0.0), |acc, &l| acc * f(l));
    let continuous = c64::new(g, 0.0) * prod(&zs, &|z| -z) / prod(&poles, &|l| -l);
    let map = |l: &c64| if at_origin(l) { c64::new(1.0, 0.0) } else { (*l * t).exp() };
    let dpoles: Vec<c64> = poles.iter().map(map).collect();
    let mut dzeros: Vec<c64> = zs.iter().map(map).collect();
    dzeros.extend(std::iter::repeat_n(c64::new(-1.0, 0.0), r));
    let one = c64::new(1.0, 0.0);
    let near_one = |l: &c64| (l - one).norm() == 0.0;
    let dprod = |v: &[c64]| v.iter().filter(|l| !near_one(l)).fold(one, |acc, &l| acc * (one - l));
    let gain = (continuous * t.powi(k) * dprod(&dpoles) / dprod(&dzeros)).re;
    let den = poly(&dpoles);
    let num: Vec<f64> = poly(&dzeros).iter().map(|c| c * gain).collect();
    let a = Mat::from_fn(n, n, |i, j| if i == 0 { -den[j + 1] } else if i == j + 1 { 1.0 } else { 0.0 });
    let b = Mat::from_fn(n, 1, |i, _| if i == 0 { 1.0 } else { 0.0 });
    let c = Mat::from_fn(1, n, |_, j| num[j + 1] - num[0] * den[j + 1]);
    let d = Mat::from_fn(1, 1, |_, _| num[0]);
    Ok([a, b, c, d])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rom::{Discretization, Sampling};

    fn siso(a: &[&[f64]], b: &[f64], c: &[f64], d: f64) -> OrdinaryRom {
        let n = b.len();
        OrdinaryRom { a: Mat::from_fn(n, n, |i, j| a[i][j]), b: Mat::from_fn(n, 1, |i, _| b[i]), c: Mat::from_fn(1, n, |_, j| c[j]), d: Mat::from_fn(1, 1, |_, _| d), eigenvalues: Vec::new(), input_names: Vec::new(), output_names: Vec::new() }
    }

    /// b/(s + a): H_d = K (z + 1)/(z − e^{−aT}), K = b (1 − e^{−aT})/(2a) (the same DC gain
    /// b/a), Franklin, Powell and Workman §6.3.3.
    #[test]
    fn first_order_lag() {
        let (a, b, fs) = (50.0, 3.0, 1000.0);
        let t = 1.0 / fs;
        let d = siso(&[&[-a]], &[b], &[1.0], 0.0).discretize(&Sampling::new(fs, Discretization::Matched).unwrap()).unwrap();
        let p = (-a * t).exp();
        assert!((d.rom.a[(0, 0)] - p).abs() < 1e-15);
        let k = b * (1.0 - p) / (2.0 * a);
        // K (z + 1)/(z − p) = K + K (1 + p)/(z − p): D = K, C B = K (1 + p).
        assert!((d.rom.d[(0, 0)] - k).abs() < 1e-15, "{}", d.rom.d[(0, 0)]);
        assert!(((d.rom.c[(0, 0)] * d.rom.b[(0, 0)]) - k * (1.0 + p)).abs() < 1e-15);
        assert!((d.static_gain().unwrap()[(0, 0)] - b / a).abs() < 1e-13);
    }

    /// (s + 2)/((s + 1)(s + 3)) in a non-canonical realization: zero e^{−2T}, poles e^{−T},
    /// e^{−3T}, one zero at −1, DC gain 2/3.
    #[test]
    fn zero_of_a_second_order_system() {
        // A = diag(−1, −3), residues 1/2 and 1/2: (1/2)/(s+1) + (1/2)/(s+3) = (s + 2)/((s+1)(s+3)).
        let rom = siso(&[&[-1.0, 0.0], &[0.0, -3.0]], &[1.0, 1.0], &[0.5, 0.5], 0.0);
        let (zs, g, r) = zeros(&rom).unwrap();
        assert_eq!((g, r), (1.0, 1));
        assert!((zs[0] - c64::new(-2.0, 0.0)).norm() < 1e-14, "{zs:?}");
        let t = 0.1;
        let d = rom.discretize(&Sampling::new(1.0 / t, Discretization::Matched).unwrap()).unwrap();
        assert!((d.static_gain().unwrap()[(0, 0)] - 2.0 / 3.0).abs() < 1e-13);
        // Numerator K (z − e^{−2T})(z + 1) vanishes at z = e^{−2T}.
        let h = |z: c64| {
            let m = Mat::from_fn(2, 2, |i, j| c64::new(if i == j { 1.0 } else { 0.0 }, 0.0) * z - c64::new(d.rom.a[(i, j)], 0.0));
            use faer::linalg::solvers::Solve;
            let x = m.partial_piv_lu().solve(super::super::dense::to_complex(&d.rom.b));
            (super::super::dense::to_complex(&d.rom.c) * x)[(0, 0)] + d.rom.d[(0, 0)]
        };
        assert!(h(c64::new((-2.0 * t).exp(), 0.0)).norm() < 1e-13);
    }

    #[test]
    fn several_channels_are_refused() {
        let mut rom = siso(&[&[-1.0]], &[1.0], &[1.0], 0.0);
        rom.b = Mat::from_fn(1, 2, |_, _| 1.0);
        rom.d = Mat::zeros(1, 2);
        let e = rom.discretize(&Sampling::new(10.0, Discretization::Matched).unwrap()).unwrap_err();
        assert!(e.to_string().contains("1 outputs") && e.to_string().contains("2 inputs"), "{e}");
    }
}
