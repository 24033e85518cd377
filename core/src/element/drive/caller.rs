//! Scalar functions of time that drive forces and couples (MBDyn's drive callers, input
//! manual "General", §Drive Caller: the formulas are the manual's).

use std::cell::RefCell;
use std::fmt;
use std::sync::Arc;

use crate::element::ElementState;

/// What one evaluation of a drive or a scalar function costs: how deep its evaluations
/// nest (the stack it takes: a `reference`, a `model::drive` or `model::sf` call, an
/// operand each add a level) and how many evaluations it makes, repetitions counted (its
/// time: `sum` of a function with itself doubles it). The reader refuses a drive or
/// function over [`crate::limits::MAX_EVALUATION_DEPTH`] or
/// [`crate::limits::MAX_EVALUATION_TERMS`], where it is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EvaluationCost {
    pub depth: usize,
    pub terms: u64,
}

impl EvaluationCost {
    /// An evaluation that calls no other.
    pub const LEAF: EvaluationCost = EvaluationCost { depth: 1, terms: 1 };

    /// One evaluation that makes each of `parts` once.
    pub fn around(parts: impl IntoIterator<Item = EvaluationCost>) -> EvaluationCost {
        parts.into_iter().fold(Self::LEAF, |acc, p| EvaluationCost { depth: acc.depth.max(p.depth.saturating_add(1)), terms: acc.terms.saturating_add(p.terms) })
    }

    /// Why this cost is over romdyn's budget, if it is (`what` names the drive or function).
    pub fn over_budget(&self, what: &str) -> Option<String> {
        use crate::limits::{MAX_EVALUATION_DEPTH, MAX_EVALUATION_TERMS};
        if self.depth > MAX_EVALUATION_DEPTH {
            Some(format!("{what} nests {} evaluations deep (drive callers, references to drive caller cards, model::drive and model::sf calls, scalar function operands), more than romdyn's limit of {MAX_EVALUATION_DEPTH}", self.depth))
        } else if self.terms > MAX_EVALUATION_TERMS {
            Some(format!("{what} makes {} evaluations each time it is called (each use of a drive or scalar function counts, repetitions included), more than romdyn's limit of {MAX_EVALUATION_TERMS}", self.terms))
        } else {
            None
        }
    }
}

thread_local! {
    /// The last drive evaluation that failed or gave a value that is not finite, with its
    /// time ([`note_evaluation_failure`]).
    static FAILURE: RefCell<Option<(f64, String)>> = const { RefCell::new(None) };
}

/// Notes that a drive's evaluation at time `t` failed (`why`: the drive, where it is
/// written, and what went wrong), for the failure of the Newton iteration the value spoils
/// to name ([`take_evaluation_failure`]). The first note at a time is kept (a drive that
/// calls a failing one fails after it).
pub fn note_evaluation_failure(t: f64, why: impl FnOnce() -> String) {
    FAILURE.with(|f| {
        let mut f = f.borrow_mut();
        if f.as_ref().is_none_or(|(at, _)| *at != t) {
            *f = Some((t, why()));
        }
    });
}

/// The note of [`note_evaluation_failure`] made at time `t` on this thread, if any
/// (taken: the next call gives `None`).
pub fn take_evaluation_failure(t: f64) -> Option<String> {
    FAILURE.with(|f| f.borrow_mut().take()).filter(|(at, _)| *at == t).map(|(_, why)| why)
}

/// The evaluation of a [`TimeFunction`]: the time, and the model's state when the caller
/// has one (an element's residual).
type Evaluation = dyn Fn(f64, Option<&dyn ElementState>) -> f64 + Send + Sync;

/// A function of time given as text by the input (MBDyn's `string` drive, an expression of
/// `Time` for its math parser): the text names it in messages and decides equality; the
/// reader supplies the evaluation.
///
/// An expression may also read the model's state (MBDyn's `model::position(N)`, …,
/// modelns.cc): MBDyn's `StringDriveCaller::dGet` evaluates it at every call, and its
/// elements call it in every residual assembly, so it reads the current Newton iterate
/// (`StructNode::GetXCurr`), and no element adds its derivative to the Jacobian. romdyn
/// does the same: [`Drive::value_in`] passes the element's [`ElementState`], whose
/// [`ElementState::structural_node`] is the iterate being assembled; the elements'
/// Jacobians hold the drive's value fixed. The converged solution is the same; Newton
/// converges more slowly where the dependence is strong, and a linearization misses it
/// (romdyn refuses to linearize such a model, see [`Drive::reads_state`]).
#[derive(Clone)]
pub struct TimeFunction {
    pub text: String,
    f: Arc<Evaluation>,
    reads_state: bool,
    /// What one evaluation costs (the drives and functions it calls included).
    cost: EvaluationCost,
}

impl TimeFunction {
    pub fn new(text: impl Into<String>, f: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Self {
        TimeFunction { text: text.into(), f: Arc::new(move |t, _| f(t)), reads_state: false, cost: EvaluationCost::LEAF }
    }
    /// The same function, declared to cost `cost` per evaluation (the drives and
    /// functions its evaluation calls).
    pub fn with_cost(mut self, cost: EvaluationCost) -> Self {
        self.cost = cost;
        self
    }
    pub fn cost(&self) -> EvaluationCost {
        self.cost
    }
    /// A function of its argument that may also read the time of the state it is evaluated
    /// in (MBDyn's `string` drive: `Var` the argument, `Time` the simulation's time, which
    /// differ inside a `dof`, `element` or `periodic` drive caller), but not the model's
    /// state: no linearization is refused for it.
    pub fn of_argument(text: impl Into<String>, f: impl Fn(f64, Option<&dyn ElementState>) -> f64 + Send + Sync + 'static) -> Self {
        TimeFunction { text: text.into(), f: Arc::new(f), reads_state: false, cost: EvaluationCost::LEAF }
    }
    /// An expression that reads the model's state: `f(t, None)` is called where no state
    /// exists (it should then give NaN).
    pub fn reading_state(text: impl Into<String>, f: impl Fn(f64, Option<&dyn ElementState>) -> f64 + Send + Sync + 'static) -> Self {
        TimeFunction { text: text.into(), f: Arc::new(f), reads_state: true, cost: EvaluationCost::LEAF }
    }
    pub fn value(&self, t: f64) -> f64 {
        (self.f)(t, None)
    }
    pub fn value_at(&self, t: f64, state: Option<&dyn ElementState>) -> f64 {
        (self.f)(t, state)
    }
    pub fn reads_state(&self) -> bool {
        self.reads_state
    }
}

impl fmt::Debug for TimeFunction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "TimeFunction({:?})", self.text)
    }
}

impl PartialEq for TimeFunction {
    fn eq(&self, other: &Self) -> bool {
        self.text == other.text
    }
}

/// A drive `v(t)`.
#[derive(Clone, Debug, PartialEq)]
pub enum Drive {
    /// `v`.
    Const(f64),
    /// `t` itself.
    Time,
    /// `v0` before `t0`, `v0 + slope (t − t0)` until `t1`, constant after.
    Ramp { slope: f64, t0: f64, t1: f64, v0: f64 },
    /// `v0` before `t0`, `v0 + value` after, `(v0 + value)/2` at `t0` itself (MBDyn 1.7.3's
    /// `step`, drive_.h `StepDriveCaller::dGet`: half the sum, not `v0 + value/2`).
    Step { t0: f64, value: f64, v0: f64 },
    /// `v0 + A sin(ω (t − t0))` from `t0` on, for `cycles` periods (`None`: forever), then
    /// held at its final value.
    Sine { t0: f64, omega: f64, amplitude: f64, cycles: Option<f64>, v0: f64 },
    /// `v0 + A (1 − cos(ω (t − t0)))` from `t0` on (MBDyn's cosine), for `cycles` periods.
    Cosine { t0: f64, omega: f64, amplitude: f64, cycles: Option<f64>, v0: f64 },
    /// Linear interpolation between `(t, v)` points, constant outside.
    PiecewiseLinear(Vec<(f64, f64)>),
    /// `Σ c_k t^k` (MBDyn's `linear`, `parabolic`, `cubic`).
    Polynomial(Vec<f64>),
    /// `v0 + A (1 − exp(−(t − t0)/τ))` from `t0` on (MBDyn's `exponential`).
    Exponential { amplitude: f64, tau: f64, t0: f64, v0: f64 },
    /// `v0 + A tanh(s (t − t0))` (MBDyn's `tanh`).
    Tanh { t0: f64, amplitude: f64, slope: f64, v0: f64 },
    /// Ramp `a` on `[a_t0, a_t1]`, held, then ramp `d` on `[d_t0, d_t1]`, held (MBDyn's
    /// `double ramp`).
    DoubleRamp { a_slope: f64, a_t0: f64, a_t1: f64, d_slope: f64, d_t0: f64, d_t1: f64, v0: f64 },
    /// `v0 + value` on `(t0, t1)`, `v0` outside `[t0, t1]`, `(v0 + value)/2` at `t0` and at
    /// `t1` (MBDyn 1.7.3's `double step`, drive_.h `DoubleStepDriveCaller::dGet`). A step
    /// at the initial time therefore acts with half its value in the derivatives phase.
    DoubleStep { t0: f64, t1: f64, value: f64, v0: f64 },
    /// The sum of the drives (MBDyn's `array`).
    Sum(Vec<Drive>),
    /// The product of two drives (MBDyn's `mult`).
    Product(Box<Drive>, Box<Drive>),
    /// `f(g(x))`: the first drive of the second's value (MBDyn's `drive` drive caller,
    /// ddrive.h, `DriveDriveCaller::dGet`).
    Compose(Box<Drive>, Box<Drive>),
    /// `f_i` before `t_i`, `f_i + A(t) sin(ω(t) (t − t_i))` on `[t_i, t_f]`, `f_f` after
    /// (MBDyn's `frequency sweep`).
    FrequencySweep { t0: f64, omega: Box<Drive>, amplitude: Box<Drive>, v0: f64, t1: f64, v1: f64 },
    /// `v0 + a₀/2 + Σ_k (a_k cos(kω(t − t0)) + b_k sin(kω(t − t0)))` on `t0 ≤ t < t1`,
    /// `v0` elsewhere (MBDyn's `fourier series`, drive_.h `FourierSeriesDriveCaller::dGet`:
    /// back to `v0`, not held, after the last cycle); `terms` holds `a₀/2, a₁, b₁, …`.
    FourierSeries { t0: f64, omega: f64, terms: Vec<f64>, t1: f64, v0: f64 },
    /// 0 before `t0`, then `f` of the time since the start of the current period (MBDyn's
    /// `periodic`).
    Periodic { t0: f64, period: f64, f: Box<Drive> },
    /// An expression of time (MBDyn's `string`).
    Expression(TimeFunction),
    /// A scalar function of time (MBDyn's `scalar function` drive caller).
    Function(super::ScalarFunction),
    /// One channel of a fixed step file driver (MBDyn's `file` drive caller).
    Sampled(SampledChannel),
    /// A drive with a memory of the accepted steps (MBDyn's `sample and hold`, `discrete
    /// filter`).
    Stepped(super::StepDrive),
}

/// One channel of MBDyn's fixed step file driver (fixedstep.cc, `ServePending`) times an
/// amplitude: samples `v_k` at `t0 + k dt`, interpolated linearly (or held, `const`) between
/// them; before the first and after the last, zero (`pad zeros`, MBDyn's default) or the
/// first and last sample.
#[derive(Clone, Debug, PartialEq)]
pub struct SampledChannel {
    pub t0: f64,
    pub dt: f64,
    pub values: Arc<Vec<f64>>,
    pub linear: bool,
    pub pad_zeros: bool,
    pub amplitude: f64,
}

impl SampledChannel {
    pub fn value(&self, t: f64) -> f64 {
        let (v, n) = (&self.values, self.values.len());
        let Some(&last) = v.last() else { return 0.0 };
        let tt = t - self.t0;
        let x = if tt < 0.0 {
            if self.pad_zeros { 0.0 } else { v[0] }
        } else if tt > self.dt * (n - 1) as f64 {
            if self.pad_zeros { 0.0 } else { last }
        } else {
            let j = ((tt / self.dt).floor() as usize).min(n - 1);
            if !self.linear || j == n - 1 {
                v[j]
            } else {
                let t1 = self.t0 + j as f64 * self.dt;
                let t2 = t1 + self.dt;
                v[j + 1] * ((t - t1) / self.dt) + v[j] * ((t2 - t) / self.dt)
            }
        };
        self.amplitude * x
    }
}

impl Drive {
    /// The value at time `t`, without the model's state (a drive that reads it gives NaN).
    pub fn value(&self, t: f64) -> f64 {
        self.value_at(t, None)
    }

    /// The value in an element's residual: at its time, reading the state it is assembled
    /// at (see [`TimeFunction`]).
    pub fn value_in(&self, st: &dyn ElementState) -> f64 {
        self.value_at(st.time(), Some(st))
    }

    /// Whether the drive reads the model's state (MBDyn's `model::` functions in a `string`
    /// drive): its derivatives with respect to the state are in no Jacobian, as in MBDyn,
    /// so a linearization of a model that holds one would be wrong.
    pub fn reads_state(&self) -> bool {
        match self {
            Drive::Expression(f) => f.reads_state(),
            Drive::Sum(drives) => drives.iter().any(Drive::reads_state),
            Drive::Product(a, b) | Drive::Compose(a, b) => a.reads_state() || b.reads_state(),
            Drive::FrequencySweep { omega, amplitude, .. } => omega.reads_state() || amplitude.reads_state(),
            Drive::Periodic { f, .. } => f.reads_state(),
            Drive::Stepped(s) => s.reads_state(),
            _ => false,
        }
    }

    /// What one evaluation costs (see [`EvaluationCost`]); walks the drive (bounded: the
    /// reader checks every drive it builds, so the parts are within budget).
    pub fn cost(&self) -> EvaluationCost {
        use super::StepKind;
        let around = |parts: &[&Drive]| EvaluationCost::around(parts.iter().map(|d| d.cost()));
        match self {
            Drive::Sum(drives) => EvaluationCost::around(drives.iter().map(Drive::cost)),
            Drive::Product(a, b) | Drive::Compose(a, b) => around(&[a, b]),
            Drive::FrequencySweep { omega, amplitude, .. } => around(&[omega, amplitude]),
            Drive::Periodic { f, .. } => around(&[f]),
            Drive::Expression(f) => f.cost(),
            Drive::Function(f) => EvaluationCost::around([f.cost()]),
            Drive::Stepped(s) => match s.kind() {
                StepKind::SampleAndHold { function, trigger, .. } => around(&[function, trigger]),
                StepKind::DiscreteFilter { input, .. } => around(&[input]),
                StepKind::ClosestNext { increment, .. } => around(&[increment]),
                _ => EvaluationCost::LEAF,
            },
            _ => EvaluationCost::LEAF,
        }
    }

    /// The value at time `t` with the model's state, if any.
    pub fn value_at(&self, t: f64, state: Option<&dyn ElementState>) -> f64 {
        match self {
            Drive::Const(v) => *v,
            Drive::Time => t,
            Drive::Ramp { slope, t0, t1, v0 } => v0 + slope * (t.clamp(*t0, *t1) - t0),
            Drive::Step { t0, value, v0 } => at_step(t > *t0, t < *t0, *value, *v0),
            Drive::Sine { t0, omega, amplitude, cycles, v0 } => v0 + amplitude * periodic(t, *t0, *omega, *cycles).sin(),
            Drive::Cosine { t0, omega, amplitude, cycles, v0 } => v0 + amplitude * (1.0 - periodic(t, *t0, *omega, *cycles).cos()),
            Drive::PiecewiseLinear(points) => piecewise(points, t),
            Drive::Polynomial(c) => c.iter().rev().fold(0.0, |acc, k| acc * t + k),
            Drive::Exponential { amplitude, tau, t0, v0 } => v0 + if t < *t0 { 0.0 } else { amplitude * (1.0 - (-(t - t0) / tau).exp()) },
            Drive::Tanh { t0, amplitude, slope, v0 } => v0 + amplitude * (slope * (t - t0)).tanh(),
            Drive::DoubleRamp { a_slope, a_t0, a_t1, d_slope, d_t0, d_t1, v0 } => {
                let a = a_slope * (t.clamp(*a_t0, *a_t1) - a_t0);
                let d = if t < *d_t0 { 0.0 } else { d_slope * (t.min(*d_t1) - d_t0) };
                v0 + a + d
            }
            Drive::DoubleStep { t0, t1, value, v0 } => at_step(t > *t0 && t < *t1, t < *t0 || t > *t1, *value, *v0),
            Drive::Sum(drives) => drives.iter().map(|d| d.value_at(t, state)).sum(),
            Drive::Product(a, b) => a.value_at(t, state) * b.value_at(t, state),
            Drive::Compose(f, g) => f.value_at(g.value_at(t, state), state),
            Drive::FrequencySweep { t0, omega, amplitude, v0, t1, v1 } => {
                if t < *t0 {
                    *v0
                } else if t > *t1 {
                    *v1
                } else {
                    v0 + amplitude.value_at(t, state) * (omega.value_at(t, state) * (t - t0)).sin()
                }
            }
            Drive::FourierSeries { t0, omega, terms, t1, v0 } => {
                if t < *t0 || t >= *t1 {
                    return *v0;
                }
                let s = t - t0;
                let series: f64 = terms[1..].chunks(2).enumerate().map(|(k, ab)| {
                    let theta = (k + 1) as f64 * omega * s;
                    ab[0] * theta.cos() + ab.get(1).map_or(0.0, |b| b * theta.sin())
                }).sum();
                v0 + terms.first().copied().unwrap_or(0.0) + series
            }
            Drive::Periodic { t0, period, f } => {
                if t < *t0 {
                    0.0
                } else {
                    let s = t - t0;
                    f.value_at(s - period * (s / period).floor(), state)
                }
            }
            Drive::Expression(f) => f.value_at(t, state),
            Drive::Function(f) => f.value(t),
            Drive::Sampled(c) => c.value(t),
            Drive::Stepped(s) => s.value_at(t, state),
        }
    }
}

/// A step's value: `v0 + value` where it is on, `v0` where it is off, and where it is
/// neither (exactly at a step time) `(v0 + value)/2`, as MBDyn's step drives test `on`
/// first, then `off`.
fn at_step(on: bool, off: bool, value: f64, v0: f64) -> f64 {
    if on {
        v0 + value
    } else if off {
        v0
    } else {
        (v0 + value) / 2.0
    }
}

/// Phase `ω (t − t0)`, zero before `t0` and frozen after the last cycle.
fn periodic(t: f64, t0: f64, omega: f64, cycles: Option<f64>) -> f64 {
    let phase = omega * (t - t0).max(0.0);
    match cycles {
        Some(n) => phase.min(2.0 * std::f64::consts::PI * n),
        None => phase,
    }
}

fn piecewise(points: &[(f64, f64)], t: f64) -> f64 {
    match points {
        [] => 0.0,
        [(_, v)] => *v,
        _ => {
            if t <= points[0].0 {
                return points[0].1;
            }
            for w in points.windows(2) {
                let ((ta, va), (tb, vb)) = (w[0], w[1]);
                if t <= tb {
                    return if tb > ta { va + (vb - va) * (t - ta) / (tb - ta) } else { vb };
                }
            }
            points[points.len() - 1].1
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drives_follow_their_definitions() {
        assert_eq!(Drive::Const(2.5).value(7.0), 2.5);
        let ramp = Drive::Ramp { slope: 2.0, t0: 1.0, t1: 3.0, v0: 1.0 };
        assert_eq!([ramp.value(0.0), ramp.value(2.0), ramp.value(5.0)], [1.0, 3.0, 5.0]);
        let step = Drive::Step { t0: 1.0, value: 4.0, v0: -1.0 };
        // At the step time itself MBDyn 1.7.3 takes half of v0 + value (drive_.h).
        assert_eq!([step.value(0.5), step.value(1.0), step.value(1.5)], [-1.0, 1.5, 3.0]);
        let pi = std::f64::consts::PI;
        let sine = Drive::Sine { t0: 0.0, omega: pi, amplitude: 2.0, cycles: Some(1.0), v0: 0.0 };
        assert!((sine.value(0.5) - 2.0).abs() < 1e-15 && sine.value(10.0).abs() < 1e-12);
        let cosine = Drive::Cosine { t0: 0.0, omega: pi, amplitude: 1.0, cycles: None, v0: 0.0 };
        assert!((cosine.value(1.0) - 2.0).abs() < 1e-15);
        let pl = Drive::PiecewiseLinear(vec![(0.0, 0.0), (1.0, 10.0), (2.0, 0.0)]);
        assert_eq!([pl.value(-1.0), pl.value(0.5), pl.value(1.5), pl.value(9.0)], [0.0, 5.0, 5.0, 0.0]);
    }

    #[test]
    fn the_other_scalar_drives_follow_the_manual_formulas() {
        // Input manual, §Drive Caller: cubic 1 + 2t + 3t² + 4t³ at t = 2 is 49.
        assert_eq!(Drive::Polynomial(vec![1.0, 2.0, 3.0, 4.0]).value(2.0), 49.0);
        // exponential, 10, 0.2, 5, 0: the step response of 1/(1 + 0.2 s), 10 (1 − e⁻¹) one
        // time constant after t = 5.
        let e = Drive::Exponential { amplitude: 10.0, tau: 0.2, t0: 5.0, v0: 0.0 };
        assert_eq!(e.value(4.0), 0.0);
        assert!((e.value(5.2) - 10.0 * (1.0 - (-1f64).exp())).abs() < 1e-12);
        let th = Drive::Tanh { t0: 1.0, amplitude: 2.0, slope: 3.0, v0: 0.5 };
        assert!((th.value(1.5) - (0.5 + 2.0 * 1.5f64.tanh())).abs() < 1e-15);
        // double ramp: +1/s on [1, 2], held at 1, −2/s on [3, 4], held at −1.
        let dr = Drive::DoubleRamp { a_slope: 1.0, a_t0: 1.0, a_t1: 2.0, d_slope: -2.0, d_t0: 3.0, d_t1: 4.0, v0: 0.0 };
        assert_eq!([0.0, 1.5, 2.5, 3.5, 5.0].map(|t| dr.value(t)), [0.0, 0.5, 1.0, 0.0, -1.0]);
        let ds = Drive::DoubleStep { t0: 1.0, t1: 2.0, value: 3.0, v0: 1.0 };
        assert_eq!([0.5, 1.0, 1.5, 2.0, 2.5].map(|t| ds.value(t)), [1.0, 2.0, 4.0, 2.0, 1.0]);
        let sum = Drive::Sum(vec![Drive::Const(1.0), Drive::Time]);
        let product = Drive::Product(Box::new(Drive::Const(2.0)), Box::new(Drive::Time));
        assert_eq!((sum.value(3.0), product.value(3.0)), (4.0, 6.0));
        // drive, f, g: f(g(t)); here (2 t)² at t = 3.
        let square = Drive::Expression(TimeFunction::new("Var^2", |x| x * x));
        assert_eq!(Drive::Compose(Box::new(square), Box::new(product)).value(3.0), 36.0);
        // frequency sweep from t = 1 with ω = t rad/s, A = 2, to t = 3, then 7.
        let fs = Drive::FrequencySweep { t0: 1.0, omega: Box::new(Drive::Time), amplitude: Box::new(Drive::Const(2.0)), v0: 0.5, t1: 3.0, v1: 7.0 };
        assert_eq!((fs.value(0.0), fs.value(4.0)), (0.5, 7.0));
        assert!((fs.value(2.0) - (0.5 + 2.0 * (2.0f64 * 1.0).sin())).abs() < 1e-15);
        // periodic from t = 1 with period 2 of f(s) = s: 0, then the time into the period.
        let p = Drive::Periodic { t0: 1.0, period: 2.0, f: Box::new(Drive::Time) };
        assert_eq!([0.5, 1.5, 3.5].map(|t| p.value(t)), [0.0, 0.5, 0.5]);
        let f = Drive::Expression(TimeFunction::new("2*Time", |t| 2.0 * t));
        assert_eq!(f.value(1.5), 3.0);
        // fourier series from t = 1, ω = 2, a₀ = 3, a₁ = 1, b₁ = 0, a₂ = 0, b₂ = 4, one
        // cycle (to 1 + π), on 0.5: 0.5 + 1.5 + cos 2s + 4 sin 4s with s = t − 1.
        let fs = Drive::FourierSeries { t0: 1.0, omega: 2.0, terms: vec![1.5, 1.0, 0.0, 0.0, 4.0], t1: 1.0 + std::f64::consts::PI, v0: 0.5 };
        let s = 0.3f64;
        assert!((fs.value(1.0 + s) - (2.0 + (2.0 * s).cos() + 4.0 * (4.0 * s).sin())).abs() < 1e-15);
        assert_eq!((fs.value(0.9), fs.value(1.0), fs.value(5.0)), (0.5, 3.0, 0.5));
    }
}
