//! The two pencils the eigenanalysis can run on, and the small complex-vector algebra shared
//! by the eigen solver and the labelling.

use faer::{c64, Col, Mat};

/// Which pencil the QZ algorithm is run on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EigenRoute {
    /// `(λ F_yd + F_y) Y = 0` (eq. 10).
    Direct,
    /// `(Λ J + J*) Y = 0` (eq. 18), mapped back with eq. 23.
    Lambda,
}

/// One eigenvalue's vectors and the products the error estimate needs.
pub(crate) struct EigenVectors {
    pub v: Col<c64>,
    pub u: Col<c64>,
    pub av: Col<c64>,
    pub bv: Col<c64>,
    pub ua: Col<c64>,
    pub ub: Col<c64>,
}

pub(crate) fn conj(v: &Col<c64>) -> Col<c64> {
    Col::from_fn(v.nrows(), |i| v[i].conj())
}

/// `M v` for real `M` and complex `v`.
pub fn mul_real_complex(m: &Mat<f64>, v: &Col<c64>) -> Col<c64> {
    let re = Col::<f64>::from_fn(v.nrows(), |i| v[i].re);
    let im = Col::<f64>::from_fn(v.nrows(), |i| v[i].im);
    let (r, s) = (m * &re, m * &im);
    Col::from_fn(m.nrows(), |i| c64::new(r[i], s[i]))
}

/// `uᵀ w` (no conjugation).
pub fn dot_t(u: &Col<c64>, w: &Col<c64>) -> c64 {
    u.iter().zip(w.iter()).fold(c64::new(0.0, 0.0), |s, (a, b)| s + a * b)
}

pub(crate) fn norm(v: &Col<c64>) -> f64 {
    v.iter().map(|x| x.norm_sqr()).sum::<f64>().sqrt()
}

/// `|z|` as `√(re² + im²)` (one square root, correctly rounded, of a sum within 1 ulp: the
/// result within 2 ulp of `|z|`) where `re² + im²` is a normal number, 0 for 0, else by
/// `hypot` (scaled: no overflow or underflow). The sparse route's error estimates and
/// entry-wise residuals take `|z|` of every entry of every pair's vectors (many exactly 0:
/// a string's lateral modes do not move it along its axis): glibc's `hypot` took 2.4 % of
/// the 96,024-equation string's whole process.
pub(crate) fn modulus(z: c64) -> f64 {
    let s = z.re * z.re + z.im * z.im;
    if s.is_normal() {
        s.sqrt()
    } else if z.re == 0.0 && z.im == 0.0 {
        0.0
    } else {
        z.re.hypot(z.im)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `|z|` of the Pythagorean triples (3, 4, 5) and (20, 21, 29) scaled by powers of two
    /// (exact: the closed form), from 2⁻¹⁰⁷⁰ (subnormal parts) to 2¹⁰¹⁰ (squares overflow),
    /// and within 2 ulp of `hypot` on pseudo-random entries over 600 binades.
    #[test]
    fn modulus_is_the_closed_form_at_every_scale() {
        for (a, b, c) in [(3.0, 4.0, 5.0), (20.0, 21.0, 29.0)] {
            for e in (-1070..=1010).step_by(7) {
                let s = 2f64.powi(e);
                for (x, y) in [(a * s, b * s), (-a * s, b * s), (b * s, -a * s)] {
                    assert_eq!(modulus(c64::new(x, y)), c * s, "({x:e}, {y:e})");
                }
            }
        }
        assert_eq!(modulus(c64::new(0.0, 0.0)), 0.0);
        assert_eq!(modulus(c64::new(-0.0, 1e-170)), 1e-170);
        assert_eq!(modulus(c64::new(0.0, -2.5)), 2.5);
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..20_000 {
            let (x, y) = ((next() - 0.5) * 2f64.powi((next() * 600.0) as i32 - 300), (next() - 0.5) * 2f64.powi((next() * 600.0) as i32 - 300));
            let (m, h) = (modulus(c64::new(x, y)), x.hypot(y));
            assert!((m - h).abs() <= 2.0 * f64::EPSILON * h, "({x:e}, {y:e}): {m:e} against hypot {h:e}");
        }
    }
}
