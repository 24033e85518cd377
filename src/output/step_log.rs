//! The step log in MBDyn's `.out` layout (MBDyn's solver output; manual, "Initial-Value
//! Problem" and "Eigenanalysis: Output"): comment lines start with `#`; after the initial
//! derivatives a key line and one line per time step,
//!
//! ```text
//! # Step Time TStep NIter ResErr SolErr SolConv Out
//! Step 1 1.000000000000e-03 1.000000000000e-03 2 3.4e-12 0 0 1
//! ```
//!
//! `Step 0` is the initial state after the derivatives. Each eigenanalysis adds a table
//! `Mode n.  Real  Imag  Damp %  Freq Hz` with rows `k: σ + ω j  ζ%  f` (λ = σ + jω in
//! rad/s, ζ in percent, f = ω/2π in Hz). romdyn's ResErr is `‖F‖∞` in the units of the
//! worst equation; it has no solution test, so SolErr and SolConv are 0. The file ends with
//! an `# End of simulation` line and is put in place only when the run finishes.

use std::path::Path;

use faer::c64;

use super::atomic::{AtomicFile, OutputError};
use super::scientific::{push_scientific, push_unsigned};
use crate::linear::hz;

/// One time step as the log records it (SI: s).
#[derive(Clone, Copy, Debug)]
pub struct StepLine {
    pub step: usize,
    pub time: f64,
    pub time_step: f64,
    pub iterations: usize,
    pub residual_norm: f64,
    /// Whether the step's rows were written to the `.mov` (MBDyn's `Out` column: the output
    /// meter or frequency).
    pub written: bool,
}

/// A `.out` file being written.
pub struct StepLog {
    file: AtomicFile,
    /// A `Step` line being formed (its numbers by [`push_scientific`], byte for byte
    /// `format!`'s).
    line: Vec<u8>,
}

impl StepLog {
    /// Creates the log with a header naming the input and the units.
    pub fn create(path: &Path, input: &str) -> Result<Self, OutputError> {
        let mut file = AtomicFile::create(path)?;
        file.write_with(|w| {
            writeln!(w, "# romdyn {} step log of {input} (MBDyn .out layout)", env!("CARGO_PKG_VERSION"))?;
            writeln!(w, "# units: Time, TStep [s]; ResErr = max |F_i| in the units of equation i (N, N m, kg m/s, m, rad)")
        })?;
        Ok(StepLog { file, line: Vec::new() })
    }

    /// `# Derivatives solution step at time t performed in n iterations with e error`.
    pub fn derivatives(&mut self, time: f64, iterations: usize, error: f64) -> Result<(), OutputError> {
        self.file.write_with(|w| writeln!(w, "# Derivatives solution step at time {time} performed in {iterations} iterations with {error:.6e} error"))
    }

    /// One `Step` line; step 0 is preceded by the key line.
    pub fn step(&mut self, s: &StepLine) -> Result<(), OutputError> {
        let line = &mut self.line;
        line.clear();
        if s.step == 0 {
            line.extend_from_slice(b"# Key for lines starting with \"Step\":\n# Step Time TStep NIter ResErr SolErr SolConv Out\n");
        }
        // `Step {} {:.12e} {:.12e} {} {:.6e} 0 0 {}`.
        line.extend_from_slice(b"Step ");
        push_unsigned(line, s.step as u64);
        line.push(b' ');
        push_scientific(line, s.time, 12);
        line.push(b' ');
        push_scientific(line, s.time_step, 12);
        line.push(b' ');
        push_unsigned(line, s.iterations as u64);
        line.push(b' ');
        push_scientific(line, s.residual_norm, 6);
        line.extend_from_slice(if s.written { b" 0 0 1\n" } else { b" 0 0 0\n" });
        self.file.write_with(|w| w.write_all(line))
    }

    /// An eigenvalue table: `title` as a comment line, then one row per `(number, λ)`.
    pub fn eigenvalues(&mut self, title: &str, rows: &[(usize, c64)]) -> Result<(), OutputError> {
        self.file.write_with(|w| {
            writeln!(w, "# {title}")?;
            writeln!(w, "Mode n.       Real           Imag              Damp %        Freq Hz")?;
            for &(k, l) in rows {
                let (damping, freq) = damping_percent_and_hz(l);
                writeln!(w, "{k:>8}: {:>13.6e} + {:>13.6e} j    {damping:>13.6e}    {freq:>13.6e}", l.re, l.im)?;
            }
            Ok(())
        })
    }

    /// The closing comment: final time, steps and Newton iterations.
    pub fn end(&mut self, time: f64, steps: usize, iterations: usize) -> Result<(), OutputError> {
        self.file.write_with(|w| writeln!(w, "# End of simulation at time {time:.12e} after {steps} steps; total iterations: {iterations}"))
    }

    /// The last line of a run that stopped: why, after how many converged steps.
    pub fn failed(&mut self, time: f64, steps: usize, iterations: usize, why: &str) -> Result<(), OutputError> {
        let why = why.replace('\n', " ");
        self.file.write_with(|w| writeln!(w, "# Simulation FAILED after {steps} converged steps (last converged time {time:.12e}; total iterations: {iterations}): {why}"))
    }

    /// The file, to be put in place with the rest of its set.
    pub fn into_file(self) -> AtomicFile {
        self.file
    }

    pub fn finish(self) -> Result<(), OutputError> {
        self.file.commit()
    }
}

/// MBDyn's damping column (`−100 σ/|λ|` for complex λ, `∓100` for real ones) and frequency
/// `ω/2π` (0 for real λ).
fn damping_percent_and_hz(l: c64) -> (f64, f64) {
    if l.im != 0.0 {
        (-100.0 * l.re / l.norm(), hz(l.im))
    } else if l.re == 0.0 {
        (0.0, 0.0)
    } else {
        (-100.0 * l.re.signum(), 0.0)
    }
}
