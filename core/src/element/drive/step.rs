//! Drives with a memory of the accepted time steps: MBDyn's `sample and hold` and
//! `discrete filter` drive callers (input manual, "General", §Sample and hold drive,
//! §Discrete filter drive; drive.h, `DriveHandler::MySH::Set`,
//! `DriveHandler::MyDiscreteFilter::Set`).
//!
//! MBDyn updates their memory once per time step, when the data manager's time is set to
//! the new step's time and the state is still the previous step's converged solution
//! (`DriveHandler::SetTime` with a new step number): the new inputs are evaluated at the
//! new time `t_k` and the state of `t_{k−1}`. Within the step (every Newton iteration)
//! the memory is fixed. romdyn does the same: [`StepDrive::begin_step`] is called once
//! before the predictor of every step, with the last accepted state. A step that is
//! retried (the same step number again) starts from the memory saved before the first
//! attempt, so a rejected attempt leaves no trace.
//!
//! In a linearization the memory is an input, not a state: a sample and hold gives its
//! held value (a constant, zero derivative), a discrete filter `b₀ u + Σ aᵢ yₖ₋ᵢ + Σ bᵢ uₖ₋ᵢ`
//! with the history fixed, i.e. only its direct term `b₀ u` varies, as any drive of its
//! input does.

use std::sync::{Arc, Mutex};

use crate::element::{ElementState, Label, NodeKinematics};
use super::Drive;
use crate::kinematics::Vec3;

/// What a [`StepDrive`] computes.
#[derive(Debug)]
pub enum StepKind {
    /// `sample and hold, FUNCTION, TRIGGER [, initial value, V0]`: FUNCTION's value is
    /// recorded at the start of every step where TRIGGER is non-zero, and returned until
    /// the next record; `V0` (default 0) before the first.
    SampleAndHold { function: Drive, trigger: Drive, initial: f64 },
    /// `discrete filter, n_a, a₁…, b₀, n_b, b₁…, INPUT`:
    /// `y_k = Σ_{i≥1} aᵢ y_{k−i} + b₀ u_k + Σ_{i≥1} bᵢ ũ_{i−1}`, where, as MBDyn computes it
    /// (drive.h, `MyDiscreteFilter::Set` evaluates the input after the time is advanced),
    /// `ũ_0 = u(t_k)` at the previous state, `ũ_1 = ũ_0` of the previous step, …: the
    /// `bᵢ` act on the input one step later than the manual's formula says
    /// (`y_k = … + (b₀ + b₁) u_k + b₂ u_{k−1}` for a function of time), which is what
    /// MBDyn 1.7.3's numbers show (tests/mbdyn/step_drives.rs). romdyn shifts the histories
    /// correctly for any length; MBDyn's shift loop (`x[i] = x[i − 1]` upwards) repeats
    /// the newest entry for histories longer than 2, which romdyn does not copy.
    DiscreteFilter { a: Vec<f64>, b0: f64, b: Vec<f64>, input: Drive },
    /// `meter, T0, {forever | T1} [, steps, N]` (drive.h, `MyMeter`): 1 on `[T0, T1]` at
    /// the steps whose number is a multiple of N (step 0 the initial state), else 0.
    Meter { t0: f64, t1: f64, steps: usize },
    /// `closest next, T0, {forever | T1}, INCREMENT` (drive.h, `MyClosestNext::Set`): a
    /// threshold from T0; at the start of a step, if the last step had reached it, it
    /// moves on by INCREMENT (at the new time) until it passes the new time; else a step
    /// that reaches it is marked. The value on `[T0, T1]` is 1 when the time has reached
    /// the threshold, else 0. An increment that is not positive stops the threshold
    /// (MBDyn would loop for ever): the drive is 0 from then on.
    ClosestNext { t0: f64, t1: f64, increment: Drive },
    /// `random, A, M, T0, {forever | T1} [, steps, N] [, seed, {time | S}]`
    /// (drive_.h, `RandDriveCaller::dGet`): `M + A (2 ((base + r) mod RAND_MAX)/RAND_MAX − 1)`
    /// on `[T0, T1]`, M elsewhere, with `r` the drive's last draw (see
    /// [`super::c_rand::RandomDraws`]).
    Random { amplitude: f64, mean: f64, t0: f64, t1: f64, steps: usize, draws: Arc<super::c_rand::RandomDraws>, id: usize },
    /// A joint's relative rotation counted across turns (its private data `rz`, `r*`): the
    /// memory holds the value at the last accepted step, a state's value is on the branch
    /// nearest to it. [`Turns::Hinge`] is a revolute hinge's angle (planej.cc `NTheta`,
    /// `dThetaWrapped`), [`Turns::Vector`] a total joint's rotation vector (totalj.cc
    /// `ThetaDeltaTrue`, `Unwrap`); before the first step, the rotation as read.
    Turns { rotation: RotationRead, counting: Turns },
}

/// A joint's relative rotation vector at a state (`None` where the state lacks a node).
#[derive(Clone)]
pub struct RotationRead(pub Arc<dyn Fn(&dyn ElementState) -> Option<Vec3> + Send + Sync>);

impl std::fmt::Debug for RotationRead {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("RotationRead")
    }
}

/// How [`StepKind::Turns`] counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turns {
    /// The z component as an angle: `2π (n + m) + θ`, n the turns counted at the accepted
    /// steps, m = ±1 when θ jumped by more than π from the last accepted value.
    Hinge,
    /// The vector, component `k`, by MBDyn's `Unwrap(previous, v)`: `v` scaled to the norm
    /// nearest the previous one's (signed along it) by whole turns of 2π.
    Vector(usize),
}


/// The memory of a [`StepDrive`].
#[derive(Clone, Debug, Default, PartialEq)]
struct Memory {
    /// The held value (sample and hold).
    held: f64,
    /// Past outputs `y_{k−1}, y_{k−2}, …` and inputs `ũ_0, ũ_1, …` (discrete filter).
    outputs: Vec<f64>,
    inputs: Vec<f64>,
    /// The step number (meter, random; 0 before the first step).
    step: usize,
    /// The threshold and whether it must move on (closest next).
    next: f64,
    must_move: bool,
    /// The rotation at the last accepted step, counted across turns, and for a hinge the
    /// turns counted and the angle as read (`None` before the first step).
    turned: Option<(Vec3, i64)>,
}

#[derive(Debug)]
struct Shared {
    kind: StepKind,
    /// The memory in use, the memory before the current step and that step's number.
    memory: Mutex<(Memory, Memory, Option<usize>)>,
}

/// A drive with memory. Clones share it (a `drive caller:` card referenced twice is one
/// filter); equality is identity.
#[derive(Clone, Debug)]
pub struct StepDrive(Arc<Shared>);

impl PartialEq for StepDrive {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl StepDrive {
    pub fn new(kind: StepKind) -> Self {
        let memory = initial_memory(&kind);
        StepDrive(Arc::new(Shared { kind, memory: Mutex::new((memory.clone(), memory, None)) }))
    }

    /// Back to the memory before the first step (a new run of the same model).
    pub fn reset(&self) {
        let memory = initial_memory(&self.0.kind);
        *self.lock() = (memory.clone(), memory, None);
    }

    pub fn kind(&self) -> &StepKind {
        &self.0.kind
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, (Memory, Memory, Option<usize>)> {
        self.0.memory.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The value at time `t` in `state` with the memory of the steps accepted so far.
    pub fn value_at(&self, t: f64, state: Option<&dyn ElementState>) -> f64 {
        let m = &self.lock().0;
        match &self.0.kind {
            StepKind::SampleAndHold { .. } => m.held,
            StepKind::DiscreteFilter { a, b0, b, input } => b0 * input.value_at(t, state) + history(a, b, m),
            StepKind::Meter { t0, t1, steps } => f64::from(u8::from((*t0..=*t1).contains(&t) && m.step.is_multiple_of(*steps))),
            StepKind::ClosestNext { t0, t1, .. } => {
                let time = state.map_or(t, |s| s.time());
                f64::from(u8::from((*t0..=*t1).contains(&t) && time >= m.next))
            }
            StepKind::Random { amplitude, mean, t0, t1, draws, id, .. } => {
                if !(*t0..=*t1).contains(&t) {
                    return *mean;
                }
                let (base, r) = draws.numbers(*id, m.step);
                let max = super::c_rand::RAND_MAX;
                let x = ((u64::from(base) + u64::from(r)) % u64::from(max)) as f64;
                mean + amplitude * (2.0 * x / f64::from(max) - 1.0)
            }
            StepKind::Turns { rotation, counting } => state.and_then(|st| (rotation.0)(st)).map_or(f64::NAN, |v| turned(*counting, m.turned, v).0),
        }
    }

    /// Whether the value within a step depends on the state being assembled: only a
    /// filter's direct term does.
    pub fn reads_state(&self) -> bool {
        match &self.0.kind {
            StepKind::SampleAndHold { .. } | StepKind::Meter { .. } | StepKind::ClosestNext { .. } | StepKind::Random { .. } => false,
            StepKind::DiscreteFilter { b0, input, .. } => *b0 != 0.0 && input.reads_state(),
            StepKind::Turns { .. } => true,
        }
    }

    /// Updates the memory at the start of step `step` (1 for the first) at time `t_new`;
    /// `previous` is the last accepted state (its own time, `t_{k−1}`). Called again with
    /// the same `step` (a retried step), it starts over from the memory before that step.
    pub fn begin_step(&self, step: usize, t_new: f64, previous: &dyn ElementState) {
        let mut guard = self.lock();
        let (current, before, at) = &mut *guard;
        if *at == Some(step) {
            *current = before.clone();
        } else {
            *before = current.clone();
            *at = Some(step);
        }
        let advanced = AtTime { inner: previous, t: t_new };
        match &self.0.kind {
            StepKind::SampleAndHold { function, trigger, .. } => {
                if trigger.value_at(t_new, Some(&advanced)) != 0.0 {
                    current.held = function.value_at(t_new, Some(&advanced));
                }
            }
            StepKind::DiscreteFilter { a, b0, b, input } => {
                // y_{k−1}: the output at the accepted state (MBDyn's last `dGet`).
                let y_previous = b0 * input.value_at(previous.time(), Some(previous)) + history(a, b, current);
                push_front(&mut current.outputs, y_previous);
                push_front(&mut current.inputs, input.value_at(t_new, Some(&advanced)));
            }
            StepKind::Meter { .. } | StepKind::Random { .. } => current.step = step,
            // MBDyn's `AfterConvergence` of the accepted step.
            StepKind::Turns { rotation, counting } => {
                if let Some(v) = (rotation.0)(previous) {
                    current.turned = Some(match counting {
                        Turns::Hinge => (v, turned(*counting, current.turned, v).1),
                        Turns::Vector(_) => (unwrap(current.turned.map(|t| t.0), v), 0),
                    });
                }
            }
            StepKind::ClosestNext { increment, .. } => {
                if current.must_move {
                    // MBDyn's `do … while (Time >= next)`, adding the increment (the same
                    // value each time: it is evaluated at the same time and state) one at a
                    // time, as MBDyn rounds; past 1000 additions the rest in one jump.
                    let dt = increment.value_at(t_new, Some(&advanced));
                    if dt > 0.0 {
                        let mut added = 0;
                        loop {
                            current.next += dt;
                            added += 1;
                            if t_new < current.next {
                                break;
                            }
                            if added == 1000 {
                                current.next += ((t_new - current.next) / dt).floor() * dt;
                                while current.next <= t_new {
                                    current.next += dt;
                                }
                                break;
                            }
                        }
                    } else {
                        current.next = f64::INFINITY;
                    }
                    current.must_move = false;
                } else if t_new >= current.next {
                    current.must_move = true;
                }
            }
        }
    }
}

fn initial_memory(kind: &StepKind) -> Memory {
    match kind {
        StepKind::SampleAndHold { initial, .. } => Memory { held: *initial, ..Memory::default() },
        StepKind::DiscreteFilter { a, b, .. } => Memory { outputs: vec![0.0; a.len()], inputs: vec![0.0; b.len()], ..Memory::default() },
        StepKind::ClosestNext { t0, .. } => Memory { next: *t0, ..Memory::default() },
        StepKind::Meter { .. } | StepKind::Random { .. } | StepKind::Turns { .. } => Memory::default(),
    }
}

/// The value of a [`StepKind::Turns`] at the rotation vector `v` read at a state, with the
/// memory `last` of the accepted steps, and for a hinge the turns counted with it.
fn turned(counting: Turns, last: Option<(Vec3, i64)>, v: Vec3) -> (f64, i64) {
    match counting {
        Turns::Hinge => {
            let theta = v[2];
            let Some((read, turns)) = last else { return (theta, 0) };
            let jump = theta - read[2];
            let n = turns + i64::from(jump < -std::f64::consts::PI) - i64::from(jump > std::f64::consts::PI);
            (2.0 * std::f64::consts::PI * n as f64 + theta, n)
        }
        Turns::Vector(k) => (unwrap(last.map(|t| t.0), v)[k], 0),
    }
}

/// MBDyn's `Unwrap(previous, v)` (matvec3.cc): `v` with its norm θ replaced by the
/// `±θ + 2πj` nearest the previous norm (negative when `v` points against `previous`),
/// unchanged when there is no previous value or it is zero.
fn unwrap(previous: Option<Vec3>, v: Vec3) -> Vec3 {
    let (theta, Some(p)) = (v.norm(), previous) else { return v };
    let before = p.norm();
    if theta == 0.0 || before <= f64::EPSILON {
        return v;
    }
    let start = if p.dot(&v) < 0.0 { -theta } else { theta };
    let mut t = start;
    while t - before > std::f64::consts::PI {
        t -= 2.0 * std::f64::consts::PI;
    }
    while before - t > std::f64::consts::PI {
        t += 2.0 * std::f64::consts::PI;
    }
    if t == start { v } else { v * (t / start) }
}

fn history(a: &[f64], b: &[f64], m: &Memory) -> f64 {
    let ax: f64 = a.iter().zip(&m.outputs).map(|(a, y)| a * y).sum();
    let bu: f64 = b.iter().zip(&m.inputs).map(|(b, u)| b * u).sum();
    ax + bu
}

fn push_front(v: &mut [f64], x: f64) {
    if !v.is_empty() {
        v.rotate_right(1);
        v[0] = x;
    }
}

/// A state seen at another time (MBDyn's `Time` already advanced, the solution not yet).
struct AtTime<'a> {
    inner: &'a dyn ElementState,
    t: f64,
}

impl ElementState for AtTime<'_> {
    fn node(&self, slot: usize) -> &NodeKinematics {
        self.inner.node(slot)
    }
    fn multiplier(&self, k: usize) -> f64 {
        self.inner.multiplier(k)
    }
    fn time(&self) -> f64 {
        self.t
    }
    fn gravity(&self) -> Vec3 {
        self.inner.gravity()
    }
    fn load_factor(&self) -> f64 {
        self.inner.load_factor()
    }
    fn structural_node(&self, label: Label) -> Option<&NodeKinematics> {
        self.inner.structural_node(label)
    }
    fn element_unknown(&self, type_name: &str, label: Label, k: usize) -> Option<(f64, f64)> {
        self.inner.element_unknown(type_name, label, k)
    }
    fn scalar_node(&self, id: crate::element::ScalarNodeId) -> Option<(f64, f64)> {
        self.inner.scalar_node(id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A state with no nodes at time `t`.
    struct Clock(f64);
    impl ElementState for Clock {
        fn node(&self, _slot: usize) -> &NodeKinematics {
            unreachable!("no element reads a node here")
        }
        fn multiplier(&self, _k: usize) -> f64 {
            0.0
        }
        fn time(&self) -> f64 {
            self.0
        }
        fn gravity(&self) -> Vec3 {
            Vec3::zeros()
        }
        fn load_factor(&self) -> f64 {
            1.0
        }
    }

    #[test]
    fn a_rotation_turning_past_pi_is_counted_across_turns_as_mbdyn() {
        // A rotation about z by the clock's time θ = t [rad], read as the rotation vector
        // (wrapped to (−π, π]), advanced in steps of 1 rad to 10 rad: the hinge's angle and
        // the vector's z component keep growing (planej.cc NTheta, matvec3.cc Unwrap), and
        // backwards they come down again.
        let wrap = |t: f64| (t + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI;
        let rotation = RotationRead(Arc::new(move |st: &dyn ElementState| Some(Vec3::new(0.0, 0.0, wrap(st.time())))));
        for counting in [Turns::Hinge, Turns::Vector(2)] {
            let d = StepDrive::new(StepKind::Turns { rotation: rotation.clone(), counting });
            // Before the first step: the rotation as read.
            assert!((d.value_at(0.0, Some(&Clock(4.0))) - wrap(4.0)).abs() < 1e-15);
            let path: Vec<f64> = (0..=10).map(f64::from).chain((0..10).rev().map(f64::from)).collect();
            for (k, w) in path.windows(2).enumerate() {
                d.begin_step(k + 1, w[1], &Clock(w[0]));
                // A Newton iterate 0.9 rad on: the branch nearest the accepted value.
                let v = d.value_at(w[1], Some(&Clock(w[1])));
                assert!((v - w[1]).abs() < 1e-12, "{counting:?}: at {} read {v}", w[1]);
            }
            d.reset();
            assert!((d.value_at(0.0, Some(&Clock(4.0))) - wrap(4.0)).abs() < 1e-15, "reset forgets the turns");
        }
        // Unwrap keeps the direction's sign: a vector read against the previous one is the
        // same rotation with the norm continued through π (θ = 3.0 then −3.0 + 2π = 3.28).
        let v = unwrap(Some(Vec3::new(0.0, 0.0, 3.0)), Vec3::new(0.0, 0.0, -(2.0 * std::f64::consts::PI - 3.28)));
        assert!((v[2] - 3.28).abs() < 1e-12, "{v:?}");
    }

    #[test]
    fn a_filter_with_one_coefficient_is_a_first_order_lag_and_a_retried_step_leaves_no_trace() {
        // y_k = a y_{k−1} + b₀ u_k of u = 1 from y_0 = b₀: y_k = b₀ (1 − a^{k+1})/(1 − a).
        let (a, b0) = (0.5, 0.25);
        let f = StepDrive::new(StepKind::DiscreteFilter { a: vec![a], b0, b: vec![], input: Drive::Const(1.0) });
        for k in 1..=5 {
            // a first attempt at another time, then the retry
            f.begin_step(k, 99.0, &Clock((k - 1) as f64));
            f.begin_step(k, k as f64, &Clock((k - 1) as f64));
            let closed = b0 * (1.0 - a.powi(k as i32 + 1)) / (1.0 - a);
            assert!((f.value_at(k as f64, None) - closed).abs() < 1e-15, "step {k}");
        }
    }

    #[test]
    fn a_sample_and_hold_records_when_triggered_at_the_new_time() {
        let s = StepDrive::new(StepKind::SampleAndHold { function: Drive::Time, trigger: Drive::DoubleStep { t0: 1.5, t1: 2.5, value: 1.0, v0: 0.0 }, initial: -1.0 });
        let mut seen = vec![s.value_at(0.0, None)];
        for k in 1..=4 {
            s.begin_step(k, k as f64, &Clock((k - 1) as f64));
            seen.push(s.value_at(k as f64, None));
        }
        assert_eq!(seen, [-1.0, -1.0, 2.0, 2.0, 2.0]);
    }

    /// The values at steps 0..=n, each step tried twice (first at another time).
    fn run(d: &StepDrive, n: usize, h: f64) -> Vec<f64> {
        let mut seen = vec![d.value_at(0.0, Some(&Clock(0.0)))];
        for k in 1..=n {
            let t = k as f64 * h;
            d.begin_step(k, t - 0.5 * h, &Clock(t - h));
            d.begin_step(k, t, &Clock(t - h));
            seen.push(d.value_at(t, Some(&Clock(t))));
        }
        seen
    }

    #[test]
    fn a_meter_is_one_every_n_steps_within_its_times() {
        // drive.h `MyMeter`: 1 at the step numbers that are multiples of N, from step 0.
        let m = StepDrive::new(StepKind::Meter { t0: 0.0, t1: f64::INFINITY, steps: 3 });
        assert_eq!(run(&m, 7, 1.0), [1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0]);
        let m = StepDrive::new(StepKind::Meter { t0: 1.5, t1: 5.5, steps: 2 });
        assert_eq!(run(&m, 7, 1.0), [0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn closest_next_marks_the_first_step_past_each_threshold() {
        // Thresholds 0.013 + k 0.0237 s, steps of 0.01 s: the steps that first reach
        // 0.013, 0.0367, 0.0604, 0.0841, 0.1078, 0.1315, 0.1552, 0.1789 are 2, 4, 7, 9, 11,
        // 14, 16, 18 (MBDyn 1.7.3's .drv file of tests/mbdyn_files/counter_drives.mbd's
        // drive caller 2 shows the same); a threshold moves on the step after it is reached.
        let c = StepDrive::new(StepKind::ClosestNext { t0: 0.013, t1: f64::INFINITY, increment: Drive::Const(0.0237) });
        let ones: Vec<usize> = run(&c, 20, 0.01).iter().enumerate().filter(|(_, v)| **v == 1.0).map(|(k, _)| k).collect();
        assert_eq!(ones, [2, 4, 7, 9, 11, 14, 16, 18]);
        // A threshold at the initial time is reached at step 0 and step 1 (it moves on at step 2).
        let c = StepDrive::new(StepKind::ClosestNext { t0: 0.0, t1: f64::INFINITY, increment: Drive::Const(2.5) });
        assert_eq!(run(&c, 6, 1.0), [1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0]);
        // An increment 1e7 times smaller than the step: each move passes 1e7 thresholds at
        // once, and the pattern is the same (bounding the additions at 1e6 left the
        // threshold behind the time, reading 1 at every step).
        let c = StepDrive::new(StepKind::ClosestNext { t0: 0.0, t1: f64::INFINITY, increment: Drive::Const(1e-7) });
        assert_eq!(run(&c, 6, 1.0), [1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0]);
    }

    #[test]
    fn a_random_drive_holds_each_draw_for_its_steps() {
        // srand(7), one drive every 2 steps: base r0, first r1, then r2 at step 2, r3 at 4.
        let draws = Arc::new(super::super::c_rand::RandomDraws::new(1));
        let id = draws.register((0, 0), Some(7), 2);
        let d = StepDrive::new(StepKind::Random { amplitude: 2.0, mean: 1.0, t0: 0.0, t1: 3.5, steps: 2, draws, id });
        let r = [1045618677u64, 1863967299, 1272579899, 461085871];
        let max = 2147483647u64;
        let v = |k: usize| 1.0 + 2.0 * (2.0 * ((r[0] + r[k]) % max) as f64 / max as f64 - 1.0);
        // MBDyn 1.7.3's .drv file for `drive caller: 4, random, 2., 1., 0.02, 0.07, steps, 2,
        // seed, 7, output, yes;`, the only random drive of its file: −0.68201866544877121
        // at steps 2 and 3.
        assert!((v(2) + 0.682_018_665_448_771_21).abs() < 1e-15);
        assert_eq!(run(&d, 5, 1.0), [v(1), v(1), v(2), v(2), 1.0, 1.0]);
    }
}
