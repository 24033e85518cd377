//! The drive callers of the step counter and the C library's random numbers (drive_.cc,
//! `MeterDCR`, `ClosestNextDCR`, `RandomDCR`; input manual §Meter drive, §Closest next
//! drive, §Random drive), and the `fourier series` (`FourierSeriesDCR`).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use crate::element::drive::c_rand::{time_seed, RandomDraws};
use crate::element::drive::{Drive, StepDrive, StepKind};

/// The drives with a memory of the steps read so far (`sample and hold`, `discrete filter`,
/// the counters and `random`), which the model advances at every step, and the numbers the
/// `random` drives draw with the count of drives created so far (their order).
#[derive(Default)]
pub struct StepDrives {
    stepped: Mutex<Vec<StepDrive>>,
    random: Arc<RandomDraws>,
    created: AtomicUsize,
}

impl StepDrives {
    /// A drive with memory, registered for the model to advance at every step.
    pub fn register(&self, kind: StepKind) -> Drive {
        let d = StepDrive::new(kind);
        self.stepped.lock().unwrap_or_else(|e| e.into_inner()).push(d.clone());
        Drive::Stepped(d)
    }

    /// The drives registered so far (emptied).
    pub fn take(&self) -> Vec<StepDrive> {
        std::mem::take(&mut *self.stepped.lock().unwrap_or_else(|e| e.into_inner()))
    }
}

/// `{forever | T1}`.
fn final_time(c: &mut Cursor) -> Result<f64, MbdynError> {
    if c.accept("forever") { Ok(f64::INFINITY) } else { c.real("final time [s] (or forever)") }
}

/// `steps, N` with N ≥ 1 (MBDyn warns and takes 1 for N ≤ 0: romdyn refuses it).
fn steps(c: &mut Cursor) -> Result<usize, MbdynError> {
    let at = c.here();
    let n = c.integer("number of steps")?;
    if n <= 0 {
        return Err(c.error_at(at, format!("steps must be at least 1, found {n}")));
    }
    Ok(n as usize)
}

/// `meter, T0, {forever | T1} [, steps, N]`.
pub fn meter(c: &mut Cursor, drives: &StepDrives) -> Result<Drive, MbdynError> {
    let t0 = c.real("initial time [s]")?;
    let t1 = final_time(c)?;
    let mut n = 1;
    while c.accept("steps") {
        n = steps(c)?;
    }
    Ok(drives.register(StepKind::Meter { t0, t1, steps: n }))
}

/// `closest next, T0, {forever | T1}, INCREMENT`.
pub fn closest_next(c: &mut Cursor, drives: &StepDrives, inner: &dyn Fn(&mut Cursor) -> Result<Drive, MbdynError>) -> Result<Drive, MbdynError> {
    let t0 = c.real("initial time [s]")?;
    let t1 = final_time(c)?;
    let at = c.here();
    let increment = inner(c)?;
    if let Drive::Const(dt) = increment
        && dt <= 0.0
    {
        return Err(c.error_at(at, format!("closest next: the increment must be positive, found {dt}")));
    }
    Ok(drives.register(StepKind::ClosestNext { t0, t1, increment }))
}

/// `random, A, M, T0, {forever | T1} [, steps, N] [, seed, {time | S}]` (either optional
/// entry in any order, as MBDyn reads them); `seed` seeds the generator of all the random
/// drives read from here on, `srand(S)` (S as a C `unsigned int`), `time` with the clock.
pub fn random(c: &mut Cursor, drives: &StepDrives, seq: usize) -> Result<Drive, MbdynError> {
    let amplitude = c.real("amplitude")?;
    let mean = c.real("mean value")?;
    let t0 = c.real("initial time [s]")?;
    let t1 = final_time(c)?;
    let (mut n, mut seed) = (1, None);
    loop {
        if c.accept("steps") {
            n = steps(c)?;
        } else if c.accept("seed") {
            seed = Some(if c.accept("time") { time_seed() } else { c.integer("seed (an integer, or time)")? as u32 });
        } else {
            break;
        }
    }
    Ok(new_random(drives, seq, amplitude, mean, t0, t1, n, seed))
}

#[allow(clippy::too_many_arguments)]
fn new_random(drives: &StepDrives, seq: usize, amplitude: f64, mean: f64, t0: f64, t1: f64, steps: usize, seed: Option<u32>) -> Drive {
    let order = drives.created.fetch_add(1, Ordering::Relaxed);
    let draws = drives.random.clone();
    let id = draws.register((seq, order), seed, steps);
    drives.register(StepKind::Random { amplitude, mean, t0, t1, steps, draws, id })
}

/// A drive caller card used by `reference` read at statement `seq`, or by `postponed`
/// (`seq` = `usize::MAX`: MBDyn copies the card when the drive is first called, in the run,
/// after every drive was read): MBDyn copies it (`pCopy`), and a copied `random` drive is
/// a new one, which draws its own numbers. The other drives with memory stay shared.
pub fn copied(d: &Drive, drives: &StepDrives, seq: usize) -> Drive {
    let copy = |d: &Drive| copied(d, drives, seq);
    match d {
        Drive::Stepped(s) => match s.kind() {
            StepKind::Random { amplitude, mean, t0, t1, steps, .. } => new_random(drives, seq, *amplitude, *mean, *t0, *t1, *steps, None),
            _ => d.clone(),
        },
        Drive::Sum(v) => Drive::Sum(v.iter().map(copy).collect()),
        Drive::Product(a, b) => Drive::Product(Box::new(copy(a)), Box::new(copy(b))),
        Drive::Compose(a, b) => Drive::Compose(Box::new(copy(a)), Box::new(copy(b))),
        Drive::Periodic { t0, period, f } => Drive::Periodic { t0: *t0, period: *period, f: Box::new(copy(f)) },
        Drive::FrequencySweep { t0, omega, amplitude, v0, t1, v1 } => {
            Drive::FrequencySweep { t0: *t0, omega: Box::new(copy(omega)), amplitude: Box::new(copy(amplitude)), v0: *v0, t1: *t1, v1: *v1 }
        }
        _ => d.clone(),
    }
}

/// `fourier series, T0, ω, n, a₀, a₁, b₁, …, a_n, b_n, {forever | one | P}, V0` (P ≥ 0
/// cycles, 0 as forever as in MBDyn).
pub fn fourier_series(c: &mut Cursor) -> Result<Drive, MbdynError> {
    let t0 = c.real("initial time [s]")?;
    let omega = c.real("angular velocity [rad/s]")?;
    let at = c.here();
    let n = c.integer("number of terms")?;
    if n <= 0 {
        return Err(c.error_at(at, format!("fourier series: the number of terms must be at least 1, found {n}")));
    }
    let mut terms = vec![c.real("a_0")? / 2.0];
    for k in 1..=n {
        terms.push(c.real(&format!("a_{k}"))?);
        terms.push(c.real(&format!("b_{k}"))?);
    }
    let cycles = match c.accept_any(&["forever", "one"]) {
        Some("forever") => 0,
        Some(_) => 1,
        None => {
            let at = c.here();
            let p = c.integer("number of cycles (or forever, one)")?;
            if p < 0 {
                return Err(c.error_at(at, format!("fourier series: the number of cycles must not be negative, found {p}")));
            }
            p
        }
    };
    if cycles > 0 && omega == 0.0 {
        return Err(c.error_at(at, "fourier series: a number of cycles needs a non-zero angular velocity"));
    }
    let t1 = if cycles == 0 { f64::INFINITY } else { t0 + 2.0 * std::f64::consts::PI / omega * cycles as f64 };
    Ok(Drive::FourierSeries { t0, omega, terms, t1, v0: c.real("initial value")? })
}
