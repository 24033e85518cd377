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

use super::contract::{ElementState, Label, NodeKinematics};
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
    /// MBDyn 1.7.3's numbers show (tests/step_drives.rs). romdyn shifts the histories
    /// correctly for any length; MBDyn's shift loop (`x[i] = x[i − 1]` upwards) repeats
    /// the newest entry for histories longer than 2, which romdyn does not copy.
    DiscreteFilter { a: Vec<f64>, b0: f64, b: Vec<f64>, input: Drive },
}

/// The memory of a [`StepDrive`].
#[derive(Clone, Debug, Default, PartialEq)]
struct Memory {
    /// The held value (sample and hold).
    held: f64,
    /// Past outputs `y_{k−1}, y_{k−2}, …` and inputs `ũ_0, ũ_1, …` (discrete filter).
    outputs: Vec<f64>,
    inputs: Vec<f64>,
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
        }
    }

    /// Whether the value within a step depends on the state being assembled: only a
    /// filter's direct term does.
    pub fn reads_state(&self) -> bool {
        match &self.0.kind {
            StepKind::SampleAndHold { .. } => false,
            StepKind::DiscreteFilter { b0, input, .. } => *b0 != 0.0 && input.reads_state(),
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
        }
    }
}

fn initial_memory(kind: &StepKind) -> Memory {
    match kind {
        StepKind::SampleAndHold { initial, .. } => Memory { held: *initial, ..Memory::default() },
        StepKind::DiscreteFilter { a, b, .. } => Memory { held: 0.0, outputs: vec![0.0; a.len()], inputs: vec![0.0; b.len()] },
    }
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
}
