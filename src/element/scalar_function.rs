//! MBDyn's scalar functions (input manual, §Scalar functions; ScalarFunctionsImpl.cc):
//! differentiable functions of one variable that drives (`scalar function` drive caller)
//! and constitutive laws (`scalar function elastic`) evaluate.

/// `f(x)` with its derivative.
#[derive(Clone, Debug, PartialEq)]
pub enum ScalarFunction {
    /// `c`.
    Const(f64),
    /// `m b^(c x)`.
    Exp { multiplier: f64, base: f64, coefficient: f64 },
    /// `m log_b(c x)` (`c x > 0`).
    Log { multiplier: f64, base: f64, coefficient: f64 },
    /// `x^p`.
    Pow(f64),
    /// Linear interpolation of points with increasing `x`, extrapolated with the nearest
    /// pair's slope, or held at the end values (`extrapolate = false`). Two points are
    /// MBDyn's `linear`, more its `multilinear`.
    Multilinear { points: Vec<(f64, f64)>, extrapolate: bool },
    /// `Σ c_k T_k(ξ)`, `ξ = (2x − (a + b))/(b − a)`, on `[a, b]`; continued linearly
    /// outside (with the end slopes) when `extrapolate`.
    Chebychev { a: f64, b: f64, coefficients: Vec<f64>, extrapolate: bool },
    Sum(Box<ScalarFunction>, Box<ScalarFunction>),
    Sub(Box<ScalarFunction>, Box<ScalarFunction>),
    Mul(Box<ScalarFunction>, Box<ScalarFunction>),
    Div(Box<ScalarFunction>, Box<ScalarFunction>),
}

impl ScalarFunction {
    pub fn value(&self, x: f64) -> f64 {
        self.value_and_derivative(x).0
    }

    pub fn derivative(&self, x: f64) -> f64 {
        self.value_and_derivative(x).1
    }

    /// `(f(x), f'(x))`. Out of a function's domain (a logarithm of a non-positive number,
    /// a division by zero) the value is NaN, which Newton reports as a non-finite residual.
    pub fn value_and_derivative(&self, x: f64) -> (f64, f64) {
        match self {
            ScalarFunction::Const(c) => (*c, 0.0),
            ScalarFunction::Exp { multiplier, base, coefficient } => {
                let v = multiplier * base.powf(coefficient * x);
                (v, v * coefficient * base.ln())
            }
            ScalarFunction::Log { multiplier, base, coefficient } => {
                let u = coefficient * x;
                if !(u > 0.0) {
                    return (f64::NAN, f64::NAN);
                }
                let m = multiplier / base.ln();
                (m * u.ln(), m / x)
            }
            ScalarFunction::Pow(p) => (x.powf(*p), p * x.powf(p - 1.0)),
            ScalarFunction::Multilinear { points, extrapolate } => multilinear(points, *extrapolate, x),
            ScalarFunction::Chebychev { a, b, coefficients, extrapolate } => chebychev(*a, *b, coefficients, *extrapolate, x),
            ScalarFunction::Sum(f, g) | ScalarFunction::Sub(f, g) | ScalarFunction::Mul(f, g) | ScalarFunction::Div(f, g) => {
                let ((fv, fd), (gv, gd)) = (f.value_and_derivative(x), g.value_and_derivative(x));
                match self {
                    ScalarFunction::Sum(..) => (fv + gv, fd + gd),
                    ScalarFunction::Sub(..) => (fv - gv, fd - gd),
                    ScalarFunction::Mul(..) => (fv * gv, fd * gv + fv * gd),
                    _ if gv == 0.0 => (f64::NAN, f64::NAN),
                    _ => (fv / gv, (fd * gv - fv * gd) / (gv * gv)),
                }
            }
        }
    }
}

fn multilinear(points: &[(f64, f64)], extrapolate: bool, x: f64) -> (f64, f64) {
    let n = points.len();
    if !extrapolate {
        if x <= points[0].0 {
            return (points[0].1, 0.0);
        }
        if x >= points[n - 1].0 {
            return (points[n - 1].1, 0.0);
        }
    }
    // The interval holding x, or the end interval beyond the ends.
    let i = points.windows(2).position(|w| x < w[1].0).unwrap_or(n - 2);
    let ((x0, y0), (x1, y1)) = (points[i], points[i + 1]);
    let slope = (y1 - y0) / (x1 - x0);
    (y0 + slope * (x - x0), slope)
}

/// `Σ c_k T_k(ξ)` and its derivative in `x`, by the recurrences of the manual.
fn chebychev_series(a: f64, b: f64, c: &[f64], x: f64) -> (f64, f64) {
    let xi = (2.0 * x - (a + b)) / (b - a);
    let (mut t, mut dt) = ([1.0, xi], [0.0, 1.0]);
    let mut value = c[0] + c.get(1).map_or(0.0, |c1| c1 * xi);
    let mut slope = c.get(1).copied().unwrap_or(0.0);
    for ck in c.iter().skip(2) {
        let tn = 2.0 * xi * t[1] - t[0];
        let dtn = 2.0 * t[1] + 2.0 * xi * dt[1] - dt[0];
        value += ck * tn;
        slope += ck * dtn;
        t = [t[1], tn];
        dt = [dt[1], dtn];
    }
    (value, slope * 2.0 / (b - a))
}

fn chebychev(a: f64, b: f64, c: &[f64], extrapolate: bool, x: f64) -> (f64, f64) {
    let end = if x < a { a } else if x > b { b } else { return chebychev_series(a, b, c, x) };
    if !extrapolate {
        return (f64::NAN, f64::NAN);
    }
    let (v, d) = chebychev_series(a, b, c, end);
    (v + d * (x - end), d)
}

#[cfg(test)]
mod tests {
    use super::ScalarFunction as F;

    #[test]
    fn scalar_functions_follow_the_manual_and_their_derivatives_differences() {
        let e = std::f64::consts::E;
        let cases = [
            (F::Const(2.0), 0.3, 2.0),
            (F::Exp { multiplier: 1e-2, base: e, coefficient: 1.0 }, 1.0, 1e-2 * e),
            (F::Exp { multiplier: 2.0, base: 10.0, coefficient: 0.5 }, 2.0, 20.0),
            (F::Log { multiplier: 3.0, base: 10.0, coefficient: 2.0 }, 50.0, 6.0),
            (F::Pow(3.0), 2.0, 8.0),
            (F::Multilinear { points: vec![(0.0, 0.0), (1.0, 1.0)], extrapolate: true }, 2.5, 2.5),
            (F::Multilinear { points: vec![(-1.0, -100.0), (-0.5, -70.0), (0.0, 0.0), (0.5, 70.0), (1.0, 100.0)], extrapolate: true }, 0.75, 85.0),
            (F::Multilinear { points: vec![(-1.0, -100.0), (-0.5, -70.0), (0.0, 0.0), (0.5, 70.0), (1.0, 100.0)], extrapolate: true }, 2.0, 160.0),
            (F::Multilinear { points: vec![(0.0, 0.0), (1.0, 1.0)], extrapolate: false }, 2.5, 1.0),
            // T₀ + 2 T₁ + 3 T₂ on [0, 2] at x = 1.5 (ξ = 0.5): 1 + 1 + 3 (2·0.25 − 1) = 0.5.
            (F::Chebychev { a: 0.0, b: 2.0, coefficients: vec![1.0, 2.0, 3.0], extrapolate: true }, 1.5, 0.5),
            (F::Div(Box::new(F::Pow(2.0)), Box::new(F::Const(4.0))), 3.0, 2.25),
            (F::Sub(Box::new(F::Pow(2.0)), Box::new(F::Mul(Box::new(F::Const(2.0)), Box::new(F::Pow(1.0))))), 3.0, 3.0),
        ];
        for (f, x, want) in &cases {
            let (v, d) = f.value_and_derivative(*x);
            assert!((v - want).abs() < 1e-12 * want.abs().max(1.0), "{f:?} at {x}: {v}, want {want}");
            let h = 1e-6;
            let fd = (f.value(x + h) - f.value(x - h)) / (2.0 * h);
            assert!((d - fd).abs() < 1e-6 * fd.abs().max(1.0), "{f:?} at {x}: derivative {d}, differences {fd}");
        }
        assert!(F::Log { multiplier: 1.0, base: e, coefficient: 1.0 }.value(-1.0).is_nan());
        assert!(F::Chebychev { a: 0.0, b: 1.0, coefficients: vec![1.0], extrapolate: false }.value(2.0).is_nan());
    }
}
