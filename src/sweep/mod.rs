//! Design-point sweeps (paper §2: ROMs "in a significant number of design points"): an
//! MBDyn file's `set:` variables over a grid or a list, and at each point the reference
//! solution, linearization, modes and ROM of the [`Study`](crate::study::Study) workflow
//! with the same ports. Points run in parallel (rayon), or one after the other with
//! continuation; a failed point is kept with its values and error, the others are
//! unaffected. The lowest modes of the first point are followed through the others by
//! their shapes ([`track`]: crossings and veerings flagged); [`SweepResults`] stacks the ROMs
//! as MATLAB's ss arrays (`A(:,:,k)`) in one modal basis, the tracked modes' ([`basis`]), so
//! that they interpolate ([`SweepResults::interpolate`]), and writes them with the tracked
//! modes against the parameters.
//!
//! A design point's work is [`run_point`] on the model file's text and the parameter
//! values only, so another process or machine can run it (the Python package's executors).

mod basis;
mod grid;
mod interpolate;
mod output;
mod point;
mod track;

use std::path::{Path, PathBuf};

use rayon::prelude::*;

pub use grid::{grid, interpolation_point, single_values, Parameter, MAX_POINTS};
pub use basis::{consistent_rom, ConsistentRom};
pub use interpolate::InterpolationCheck;
pub use output::StackError;
pub use point::{candidates, lowest_modes, motion_indices, overrides, point_modes, run_point, PointResult, SweepOptions};
pub use track::{assign, mac, mode_mac, track, Match, PointMode, Tracking, CONFIDENT_MAC};

/// Most modes per design point in a sweep's table and arrays.
pub const MAX_LOWEST: usize = 10_000;

/// Checks the number of lowest modes tabulated (`--lowest`, Python's `lowest`) for `points`
/// design points, before anything is allocated: at least 1, at most [`MAX_LOWEST`], and
/// points x lowest within the dense budget (`crate::limits::MAX_DENSE_ENTRIES`).
pub fn check_lowest(lowest: usize, points: usize) -> Result<(), String> {
    if lowest == 0 {
        return Err(format!("{lowest}: need at least 1 mode"));
    }
    if lowest > MAX_LOWEST {
        return Err(format!("{lowest}: at most {MAX_LOWEST} modes in a sweep's table and arrays"));
    }
    let max = crate::limits::MAX_DENSE_ENTRIES;
    if points.saturating_mul(lowest) > max {
        return Err(format!("{lowest} over {points} design points: {} values per mode array, more than romdyn's budget of {max} (romdyn::limits::MAX_DENSE_ENTRIES)", points as u128 * lowest as u128));
    }
    Ok(())
}

/// The worker threads for `requested` jobs (`--jobs`, Python's `threads`): at least 1, at
/// most the cores this process may use (more only share the same cores and multiply the
/// memory: 1000 jobs made a 0.35 s sweep take 66 s), which `None` takes. Returns the count
/// and, when the request was reduced, the warning that says so.
pub fn worker_threads(requested: Option<usize>) -> Result<(usize, Option<String>), String> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    match requested {
        None => Ok((cores, None)),
        Some(0) => Err("0: need at least 1 job".into()),
        Some(n) if n > cores => Ok((cores, Some(format!("{n}: this machine runs {cores} threads at once; using {cores}")))),
        Some(n) => Ok((n, None)),
    }
}

/// A design point that failed, with the error as the CLI prints it.
#[derive(Clone, Debug, PartialEq)]
pub struct PointFailure {
    pub message: String,
}

/// Every design point's outcome, in the order of `points`.
#[derive(Debug)]
pub struct SweepResults {
    /// The model file the points override (for messages and the outputs' headers).
    pub file: PathBuf,
    pub names: Vec<String>,
    /// One row per design point, one value per parameter (SI units of the file).
    pub points: Vec<Vec<f64>>,
    pub results: Vec<Result<PointResult, PointFailure>>,
    /// Number of lowest modes tabulated.
    pub modes: usize,
}

impl SweepResults {
    /// The failed points: index, parameter values, error.
    pub fn failures(&self) -> impl Iterator<Item = (usize, &[f64], &str)> {
        self.results.iter().enumerate().filter_map(|(k, r)| r.as_ref().err().map(|e| (k, self.points[k].as_slice(), e.message.as_str())))
    }

    /// The lowest modes of the first point followed through the others ([`track`]).
    pub fn tracking(&self) -> Tracking {
        let modes: Vec<Option<&[PointMode]>> = self.results.iter().map(|r| r.as_ref().ok().map(|r| r.modes.as_slice())).collect();
        track(&self.points, &modes, self.modes)
    }

    /// "L = 1.5, M = 2" for point `k`.
    pub fn describe_point(&self, k: usize) -> String {
        self.names.iter().zip(&self.points[k]).map(|(n, v)| format!("{n} = {v}")).collect::<Vec<_>>().join(", ")
    }
}

/// Checks, before a sweep, that the file (read with its own values) declares every swept
/// variable with `set:`: a misspelt name would otherwise fail every point alike.
pub fn check_parameters(text: &str, file: &Path, names: &[String]) -> Result<(), crate::input::mbdyn::MbdynError> {
    crate::input::mbdyn::parse_text(text, file)?.variables.check_declared(names, file)
}

/// Runs every design point of `points` (values of `names`) on the MBDyn file text `text`
/// (read as the file `file`). `done` is called after each point (a progress bar).
pub fn sweep(text: &str, file: &Path, names: &[String], points: Vec<Vec<f64>>, options: &SweepOptions, done: &(dyn Fn() + Sync)) -> SweepResults {
    let one = |values: &[f64], start: Option<&crate::dae::State>| {
        let r = run_point(text, file, names, values, options, start).map_err(|e| PointFailure { message: e.to_string() });
        done();
        r
    };
    let results = if options.continuation {
        let mut out: Vec<Result<PointResult, PointFailure>> = Vec::with_capacity(points.len());
        for values in &points {
            // The last point that succeeded is the start (a failed one has no solution).
            let start = out.iter().rev().find_map(|r| r.as_ref().ok()).and_then(|r| r.state.as_ref());
            let r = one(values, start);
            out.push(r);
        }
        out
    } else {
        points.par_iter().map(|values| one(values, None)).collect()
    };
    SweepResults { file: file.to_path_buf(), names: names.to_vec(), points, results, modes: options.modes }
}
