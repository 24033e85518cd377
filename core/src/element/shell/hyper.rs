//! Hyper-dual numbers and the few 3-D formulas the shell's strains need, generic over the
//! scalar, so that one strain function gives values (`f64`), exact first derivatives and
//! exact mixed second derivatives (hyper-dual `a + b ε₁ + c ε₂ + d ε₁ε₂`, `ε₁² = ε₂² = 0`:
//! Fike & Alonso, AIAA 2011-886). The shell's internal forces are `Bᵀσ` with `B` the strains'
//! derivatives, so its tangent needs the strains' second derivatives (the geometric
//! stiffness): these are exact, not finite differences.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A scalar the strain function computes with.
pub trait Real: Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self> {
    fn cst(v: f64) -> Self;
    fn value(self) -> f64;
    fn sqrt(self) -> Self;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
}

impl Real for f64 {
    fn cst(v: f64) -> Self {
        v
    }
    fn value(self) -> f64 {
        self
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn sin(self) -> Self {
        f64::sin(self)
    }
    fn cos(self) -> Self {
        f64::cos(self)
    }
}

/// `a + b ε₁ + c ε₂ + d ε₁ε₂`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hyper {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
}

impl Hyper {
    /// `f(x)` from `f`, `f′`, `f″` at the value.
    fn chain(self, f: f64, f1: f64, f2: f64) -> Self {
        Hyper { a: f, b: f1 * self.b, c: f1 * self.c, d: f1 * self.d + f2 * self.b * self.c }
    }
}

impl Add for Hyper {
    type Output = Hyper;
    fn add(self, o: Hyper) -> Hyper {
        Hyper { a: self.a + o.a, b: self.b + o.b, c: self.c + o.c, d: self.d + o.d }
    }
}

impl Sub for Hyper {
    type Output = Hyper;
    fn sub(self, o: Hyper) -> Hyper {
        Hyper { a: self.a - o.a, b: self.b - o.b, c: self.c - o.c, d: self.d - o.d }
    }
}

impl Mul for Hyper {
    type Output = Hyper;
    fn mul(self, o: Hyper) -> Hyper {
        Hyper { a: self.a * o.a, b: self.a * o.b + self.b * o.a, c: self.a * o.c + self.c * o.a, d: self.a * o.d + self.b * o.c + self.c * o.b + self.d * o.a }
    }
}

impl Div for Hyper {
    type Output = Hyper;
    fn div(self, o: Hyper) -> Hyper {
        let inv = o.chain(1.0 / o.a, -1.0 / (o.a * o.a), 2.0 / (o.a * o.a * o.a));
        self * inv
    }
}

impl Neg for Hyper {
    type Output = Hyper;
    fn neg(self) -> Hyper {
        Hyper { a: -self.a, b: -self.b, c: -self.c, d: -self.d }
    }
}

impl Real for Hyper {
    fn cst(v: f64) -> Self {
        Hyper { a: v, b: 0.0, c: 0.0, d: 0.0 }
    }
    fn value(self) -> f64 {
        self.a
    }
    fn sqrt(self) -> Self {
        let s = self.a.sqrt();
        self.chain(s, 0.5 / s, -0.25 / (s * self.a))
    }
    fn sin(self) -> Self {
        self.chain(self.a.sin(), self.a.cos(), -self.a.sin())
    }
    fn cos(self) -> Self {
        self.chain(self.a.cos(), -self.a.sin(), -self.a.cos())
    }
}

pub type V3<T> = [T; 3];
pub type M3<T> = [[T; 3]; 3];

pub fn lift(m: &crate::kinematics::Mat3) -> M3<f64> {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

pub fn cst_m<T: Real>(m: &M3<f64>) -> M3<T> {
    m.map(|r| r.map(T::cst))
}

pub fn dot<T: Real>(a: &V3<T>, b: &V3<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn add<T: Real>(a: &V3<T>, b: &V3<T>) -> V3<T> {
    std::array::from_fn(|i| a[i] + b[i])
}

pub fn scale<T: Real>(a: &V3<T>, s: T) -> V3<T> {
    a.map(|x| x * s)
}

pub fn mat_vec<T: Real>(m: &M3<T>, v: &V3<T>) -> V3<T> {
    std::array::from_fn(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
}

/// `mᵀ v`.
pub fn mat_t_vec<T: Real>(m: &M3<T>, v: &V3<T>) -> V3<T> {
    std::array::from_fn(|i| m[0][i] * v[0] + m[1][i] * v[1] + m[2][i] * v[2])
}

pub fn mat_mat<T: Real>(a: &M3<T>, b: &M3<T>) -> M3<T> {
    std::array::from_fn(|i| std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j]))
}

/// The coefficients `a(θ²), b(θ²)` of `I + a [φ×] + b [φ×]²` for the rotation
/// (`sin θ/θ`, `(1 − cos θ)/θ²`) or its tangent `Γ` (`(1 − cos θ)/θ²`, `(θ − sin θ)/θ³`),
/// with Taylor series near θ = 0 so that the derivatives stay exact there.
fn coefficients<T: Real>(phi: &V3<T>, tangent: bool) -> (T, T) {
    let t = dot(phi, phi);
    // Below θ = 0.2 the series (truncation below 3e-15) is more accurate than the
    // cancelling closed forms.
    if t.value() < 0.04 {
        let c = |c: [f64; 5]| T::cst(c[0]) + t * (T::cst(c[1]) + t * (T::cst(c[2]) + t * (T::cst(c[3]) + t * T::cst(c[4]))));
        let sinc = c([1.0, -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362880.0]);
        let cosc = c([0.5, -1.0 / 24.0, 1.0 / 720.0, -1.0 / 40320.0, 1.0 / 3628800.0]);
        let sinc3 = c([1.0 / 6.0, -1.0 / 120.0, 1.0 / 5040.0, -1.0 / 362880.0, 1.0 / 39916800.0]);
        return if tangent { (cosc, sinc3) } else { (sinc, cosc) };
    }
    let th = t.sqrt();
    let (s, co) = (th.sin(), th.cos());
    if tangent {
        ((T::cst(1.0) - co) / t, (th - s) / (t * th))
    } else {
        (s / th, (T::cst(1.0) - co) / t)
    }
}

/// `I + a [φ×] + b [φ×]²`.
fn series<T: Real>(phi: &V3<T>, (a, b): (T, T)) -> M3<T> {
    let (x, y, z) = (phi[0], phi[1], phi[2]);
    let zero = T::cst(0.0);
    let k = [[zero, -z, y], [z, zero, -x], [-y, x, zero]];
    let k2 = mat_mat(&k, &k);
    std::array::from_fn(|i| std::array::from_fn(|j| T::cst(if i == j { 1.0 } else { 0.0 }) + a * k[i][j] + b * k2[i][j]))
}

/// The rotation `exp([φ×])`.
pub fn rotation<T: Real>(phi: &V3<T>) -> M3<T> {
    series(phi, coefficients(phi, false))
}

/// The tangent `Γ(φ)`: `δθ = Γ(φ) δφ` is the virtual rotation of `exp([φ×])` when `φ`
/// changes by `δφ` (`δR Rᵀ = [δθ×]`).
pub fn tangent<T: Real>(phi: &V3<T>) -> M3<T> {
    series(phi, coefficients(phi, true))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `d/dx sin(x²)/x` at x = 0.7 and its second derivative, against the closed forms.
    #[test]
    fn hyper_dual_derivatives_are_exact() {
        let x0 = 0.7;
        let x = Hyper { a: x0, b: 1.0, c: 1.0, d: 0.0 };
        let f = (x * x).sin() / x;
        let d1 = 2.0 * (x0 * x0).cos() - (x0 * x0).sin() / (x0 * x0);
        let d2 = -4.0 * x0 * (x0 * x0).sin() - 2.0 * (x0 * x0).cos() / x0 + 2.0 * (x0 * x0).sin() / (x0 * x0 * x0);
        assert!((f.b - d1).abs() < 1e-14 && (f.c - d1).abs() < 1e-14);
        assert!((f.d - d2).abs() < 1e-13, "{} vs {d2}", f.d);
    }

    /// The series branch and the closed branch agree at the switch, and `Γ` is the
    /// derivative of the rotation: `(R(φ + h δφ) − R(φ)) Rᵀ ≈ h [Γ δφ ×]`.
    #[test]
    fn rotation_tangent_matches_finite_differences() {
        for phi in [[0.3, -0.2, 0.5], [1e-4, 2e-4, -3e-4]] {
            let dphi = [0.1, 0.7, -0.4];
            let h = 1e-7;
            let r = rotation(&phi);
            let rp = rotation(&add(&phi, &scale(&dphi, h)));
            let rt: M3<f64> = std::array::from_fn(|i| std::array::from_fn(|j| r[j][i]));
            let d = mat_mat(&rp, &rt);
            let w = [(d[2][1] - d[1][2]) / (2.0 * h), (d[0][2] - d[2][0]) / (2.0 * h), (d[1][0] - d[0][1]) / (2.0 * h)];
            let g = mat_vec(&tangent(&phi), &dphi);
            for k in 0..3 {
                assert!((w[k] - g[k]).abs() < 1e-6, "{phi:?}: {w:?} vs {g:?}");
            }
        }
    }
}
