//! MBDyn's scalar functions (input manual, §Scalar functions; ScalarFunctionsImpl.cc):
//! differentiable functions of one variable that drives (`scalar function` drive caller)
//! and constitutive laws (`scalar function elastic`) evaluate.
//!
//! The operands of `sum`, `sub`, `mul` and `div` are shared (`Arc`), as MBDyn shares the
//! named functions (ScalarFunctionsImpl.cc keeps pointers): a chain of N cards each adding
//! the previous function to itself takes memory linear in N, and [`ScalarFunction::cost`]
//! counts the 2^N evaluations one call makes, which the reader refuses past its budget.

use std::collections::HashMap;
use std::sync::Arc;

use super::EvaluationCost;

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
    /// A cubic spline through points with increasing `x` (at least 3), with the end
    /// conditions of Forsythe, Malcolm and Moler's `spline` (the third derivative at each end
    /// is that of the cubic through the four end points; a parabola for three points),
    /// which MBDyn's `cubic spline` uses (interp.cc), `coefficients[i] = (b, c, d)` of
    /// `y_i + b dx + c dx² + d dx³`; continued linearly with the end slopes, or held at the
    /// end values (`extrapolate = false`).
    CubicSpline { points: Vec<(f64, f64)>, coefficients: Vec<(f64, f64, f64)>, extrapolate: bool },
    /// `Σ c_k T_k(ξ)`, `ξ = (2x − (a + b))/(b − a)`, on `[a, b]`; continued linearly
    /// outside (with the end slopes) when `extrapolate`.
    Chebychev { a: f64, b: f64, coefficients: Vec<f64>, extrapolate: bool },
    Sum(Arc<ScalarFunction>, Arc<ScalarFunction>),
    Sub(Arc<ScalarFunction>, Arc<ScalarFunction>),
    Mul(Arc<ScalarFunction>, Arc<ScalarFunction>),
    Div(Arc<ScalarFunction>, Arc<ScalarFunction>),
}

impl ScalarFunction {
    /// The cubic spline through `points` (x increasing, at least 3).
    pub fn cubic_spline(points: Vec<(f64, f64)>, extrapolate: bool) -> Self {
        let coefficients = spline_coefficients(&points);
        ScalarFunction::CubicSpline { points, coefficients, extrapolate }
    }

    pub fn value(&self, x: f64) -> f64 {
        self.value_and_derivative(x).0
    }

    /// The two operands of a `sum`, `sub`, `mul` or `div`.
    pub fn operands(&self) -> Option<[&Arc<ScalarFunction>; 2]> {
        match self {
            ScalarFunction::Sum(a, b) | ScalarFunction::Sub(a, b) | ScalarFunction::Mul(a, b) | ScalarFunction::Div(a, b) => Some([a, b]),
            _ => None,
        }
    }

    /// What one evaluation costs (its depth and the evaluations it makes, see
    /// [`EvaluationCost`]), counted over the shared operands once each: linear in the
    /// number of distinct functions, not in the (possibly exponential) count it returns.
    pub fn cost(&self) -> EvaluationCost {
        self.cost_with(&|_| None)
    }

    /// [`Self::cost`], with the costs of operands already known (`known`: a defined card's
    /// cost, kept by the reader): the walk stops at them, so a card made of defined
    /// functions costs O(1) to check, whatever the depth of what it is made of.
    pub fn cost_with(&self, known: &dyn Fn(&Arc<ScalarFunction>) -> Option<EvaluationCost>) -> EvaluationCost {
        fn walk(f: &ScalarFunction, known: &dyn Fn(&Arc<ScalarFunction>) -> Option<EvaluationCost>, memo: &mut HashMap<*const ScalarFunction, EvaluationCost>) -> EvaluationCost {
            let (ScalarFunction::Sum(a, b) | ScalarFunction::Sub(a, b) | ScalarFunction::Mul(a, b) | ScalarFunction::Div(a, b)) = f else { return EvaluationCost::LEAF };
            let mut part = |g: &Arc<ScalarFunction>| {
                if let Some(c) = known(g) {
                    return c;
                }
                let key = Arc::as_ptr(g);
                if let Some(&c) = memo.get(&key) {
                    return c;
                }
                let c = walk(g, known, memo);
                memo.insert(key, c);
                c
            };
            let (ca, cb) = (part(a), part(b));
            EvaluationCost::around([ca, cb])
        }
        walk(self, known, &mut HashMap::new())
    }

    pub fn derivative(&self, x: f64) -> f64 {
        self.value_and_derivative(x).1
    }

    /// The abscissas where the derivative jumps (a multilinear's interior points where the
    /// slope changes, the ends of a function held at its end values), increasing: there
    /// `f` is not differentiable, [`Self::value_and_derivative`] returns the slope of the
    /// interval to the right, and Newton's iterates that cross such a point can cycle.
    pub fn kinks(&self) -> Vec<f64> {
        let mut out = match self {
            ScalarFunction::Const(_) | ScalarFunction::Exp { .. } | ScalarFunction::Log { .. } | ScalarFunction::Pow(_) => Vec::new(),
            ScalarFunction::Multilinear { points, extrapolate } => {
                let n = points.len();
                let slope = |i: usize| (points[i + 1].1 - points[i].1) / (points[i + 1].0 - points[i].0);
                // Slopes equal to rounding (0.4/0.8 against 0.5/1) make no kink.
                let jumps = |a: f64, b: f64| (a - b).abs() > 1e-9 * a.abs().max(b.abs());
                let mut k: Vec<f64> = (1..n - 1).filter(|&i| jumps(slope(i - 1), slope(i))).map(|i| points[i].0).collect();
                if !extrapolate {
                    if slope(0) != 0.0 {
                        k.insert(0, points[0].0);
                    }
                    if slope(n - 2) != 0.0 {
                        k.push(points[n - 1].0);
                    }
                }
                k
            }
            ScalarFunction::CubicSpline { points, coefficients, extrapolate } => {
                let n = points.len();
                if *extrapolate {
                    Vec::new()
                } else {
                    [(points[0].0, coefficients[0].0), (points[n - 1].0, coefficients[n - 1].0)].into_iter().filter(|&(_, b)| b != 0.0).map(|(x, _)| x).collect()
                }
            }
            // Outside [a, b] without extrapolation the value is NaN (not a kink).
            ScalarFunction::Chebychev { .. } => Vec::new(),
            ScalarFunction::Sum(f, g) | ScalarFunction::Sub(f, g) | ScalarFunction::Mul(f, g) | ScalarFunction::Div(f, g) => f.kinks().into_iter().chain(g.kinks()).collect(),
        };
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
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
            ScalarFunction::CubicSpline { points, coefficients, extrapolate } => spline(points, coefficients, *extrapolate, x),
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

/// The spline's `(b, c, d)` per point: with `h_i` the intervals, `Δ_i` the slopes and `σ_i`
/// a sixth of the second derivative, `h_{i−1} σ_{i−1} + 2 (h_{i−1} + h_i) σ_i + h_i σ_{i+1}
/// = Δ_i − Δ_{i−1}` inside, and at the ends `σ_1 − σ_0` (and `σ_{n−1} − σ_{n−2}`) from the
/// third divided differences of the four end points (zero for three points).
fn spline_coefficients(p: &[(f64, f64)]) -> Vec<(f64, f64, f64)> {
    let n = p.len();
    let h: Vec<f64> = (0..n - 1).map(|i| p[i + 1].0 - p[i].0).collect();
    let delta: Vec<f64> = (0..n - 1).map(|i| (p[i + 1].1 - p[i].1) / h[i]).collect();
    let x = |i: usize| p[i].0;
    // Tridiagonal system: sub[i] σ_{i−1} + diag[i] σ_i + sup[i] σ_{i+1} = rhs[i].
    let (mut sub, mut diag, mut sup, mut rhs) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for i in 1..n - 1 {
        (sub[i], diag[i], sup[i], rhs[i]) = (h[i - 1], 2.0 * (h[i - 1] + h[i]), h[i], delta[i] - delta[i - 1]);
    }
    (diag[0], sup[0]) = (-h[0], h[0]);
    (sub[n - 1], diag[n - 1]) = (h[n - 2], -h[n - 2]);
    if n > 3 {
        let third = |a: usize| (delta[a + 2] - delta[a + 1]) / (x(a + 3) - x(a + 1)) - (delta[a + 1] - delta[a]) / (x(a + 2) - x(a));
        rhs[0] = third(0) * h[0] * h[0] / (x(3) - x(0));
        rhs[n - 1] = -third(n - 4) * h[n - 2] * h[n - 2] / (x(n - 1) - x(n - 4));
    }
    for i in 1..n {
        let t = sub[i] / diag[i - 1];
        diag[i] -= t * sup[i - 1];
        rhs[i] -= t * rhs[i - 1];
    }
    let mut sigma = vec![0.0; n];
    sigma[n - 1] = rhs[n - 1] / diag[n - 1];
    for i in (0..n - 1).rev() {
        sigma[i] = (rhs[i] - sup[i] * sigma[i + 1]) / diag[i];
    }
    let mut out: Vec<(f64, f64, f64)> = (0..n - 1).map(|i| (delta[i] - h[i] * (sigma[i + 1] + 2.0 * sigma[i]), 3.0 * sigma[i], (sigma[i + 1] - sigma[i]) / h[i])).collect();
    out.push((delta[n - 2] + h[n - 2] * (sigma[n - 2] + 2.0 * sigma[n - 1]), 3.0 * sigma[n - 1], out[n - 2].2));
    out
}

fn spline(p: &[(f64, f64)], k: &[(f64, f64, f64)], extrapolate: bool, x: f64) -> (f64, f64) {
    let n = p.len();
    if x <= p[0].0 || x >= p[n - 1].0 {
        let i = if x <= p[0].0 { 0 } else { n - 1 };
        return if extrapolate { (p[i].1 + k[i].0 * (x - p[i].0), k[i].0) } else { (p[i].1, 0.0) };
    }
    let i = p.windows(2).position(|w| x < w[1].0).unwrap_or(n - 2);
    let (dx, (b, c, d)) = (x - p[i].0, k[i]);
    (p[i].1 + dx * (b + dx * (c + dx * d)), b + dx * (2.0 * c + 3.0 * dx * d))
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
    use std::sync::Arc;

    /// 40 functions, each the sum of the previous one with itself, shared: the cost walk
    /// visits each once and counts 2^41 − 1 evaluations (T_k = 1 + 2 T_{k−1}, T_0 = 1) at
    /// depth 41; the value at any x is 2^40 (1 doubled 40 times), here for 20 of them.
    #[test]
    fn shared_operands_are_counted_with_their_repetitions() {
        let mut f = Arc::new(F::Const(1.0));
        for _ in 0..40 {
            f = Arc::new(F::Sum(f.clone(), f));
        }
        let cost = f.cost();
        assert_eq!((cost.depth, cost.terms), (41, (1u64 << 41) - 1));
        let mut g = Arc::new(F::Const(1.0));
        for _ in 0..20 {
            g = Arc::new(F::Sum(g.clone(), g));
        }
        assert_eq!(g.value(0.3), (1u64 << 20) as f64);
    }

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
            (F::Div(Arc::new(F::Pow(2.0)), Arc::new(F::Const(4.0))), 3.0, 2.25),
            (F::Sub(Arc::new(F::Pow(2.0)), Arc::new(F::Mul(Arc::new(F::Const(2.0)), Arc::new(F::Pow(1.0))))), 3.0, 3.0),
        ];
        for (f, x, want) in &cases {
            let (v, d) = f.value_and_derivative(*x);
            assert!((v - want).abs() < 1e-12 * want.abs().max(1.0), "{f:?} at {x}: {v}, want {want}");
            let h = 1e-6;
            let fd = (f.value(x + h) - f.value(x - h)) / (2.0 * h);
            assert!((d - fd).abs() < 1e-6 * fd.abs().max(1.0), "{f:?} at {x}: derivative {d}, differences {fd}");
        }
        assert!(F::Log { multiplier: 1.0, base: e, coefficient: 1.0 }.value(-1.0).is_nan());
        // The spline's end conditions reproduce a cubic through its points exactly (x³ − x
        // at five uneven points), and a parabola through three; outside, the end tangents.
        let cubic = |x: f64| x * x * x - x;
        let s = F::cubic_spline([-1.0, -0.2, 0.5, 1.0, 2.0].map(|x| (x, cubic(x))).to_vec(), true);
        for x in [-0.7, 0.1, 0.75, 1.9] {
            let (v, d) = s.value_and_derivative(x);
            assert!((v - cubic(x)).abs() < 1e-12 && (d - (3.0 * x * x - 1.0)).abs() < 1e-12, "spline at {x}: {v}, {d}");
        }
        assert!((s.value(3.0) - (cubic(2.0) + 11.0)).abs() < 1e-12 && (s.value(-2.0) - (cubic(-1.0) - 2.0)).abs() < 1e-12);
        let parabola = F::cubic_spline(vec![(0.0, 0.0), (1.0, 1.0), (3.0, 9.0)], false);
        assert!((parabola.value(2.0) - 4.0).abs() < 1e-12 && parabola.value(5.0) == 9.0);
        assert!(F::Chebychev { a: 0.0, b: 1.0, coefficients: vec![1.0], extrapolate: false }.value(2.0).is_nan());
    }

    #[test]
    fn kinks_are_where_the_slope_jumps() {
        // Interior points where the slope changes (not 0.5, on a straight run), the ends
        // when held at their values with a slope inside (not the flat end at 1.2).
        // Not at 2, where the slope is 0.5 on both sides within rounding.
        let points = vec![(0.0, 0.6), (0.1, 0.3), (0.5, 0.3), (1.2, 0.3), (2.0, 0.7), (3.0, 1.2)];
        assert_eq!(F::Multilinear { points: points.clone(), extrapolate: true }.kinks(), vec![0.1, 1.2]);
        assert_eq!(F::Multilinear { points, extrapolate: false }.kinks(), vec![0.0, 0.1, 1.2, 3.0]);
        let spline = |extrapolate| F::cubic_spline(vec![(1.0, 1.0), (2.0, 4.0), (3.0, 9.0)], extrapolate);
        assert!(spline(true).kinks().is_empty());
        assert_eq!(spline(false).kinks(), vec![1.0, 3.0]);
        let ramp = || std::sync::Arc::new(F::Multilinear { points: vec![(0.0, 0.0), (1.0, 1.0), (2.0, 1.0)], extrapolate: true });
        assert_eq!(F::Sum(ramp(), Arc::new(F::Mul(ramp(), Arc::new(F::Pow(2.0))))).kinks(), vec![1.0]);
        assert!(F::Const(0.3).kinks().is_empty());
    }
}
