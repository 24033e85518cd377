//! A ROM handed to a control tool chain (issue 37 points 3 and 4): a minimal realization,
//! balanced reduction of its stable part ([`crate::rom::BalancedReduction`]) and the
//! discrete-time ROM at a sample rate ([`crate::rom::DiscreteRom`]). The options are
//! checked here, so the command line and the Python package refuse the same values with
//! the same words.

use crate::rom::{BalancedMethod, BalancedOrder, Discretization, DiscreteRom, OrdinaryRom, Sampling};

use super::{RomRequest, Setting, StudyError, Warning};
use crate::linear::hz;

/// Balanced reduction of a ROM's stable part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Balancing {
    pub order: BalancedOrder,
    pub method: BalancedMethod,
}

fn bad(option: Setting, message: impl Into<String>) -> StudyError {
    StudyError::Option { option, message: message.into() }
}

/// The discretization methods by name (`--discretize`, `discretize=`) with what each does.
pub const DISCRETIZATIONS: [(&str, &str); 3] = [
    ("zoh", "zero-order hold: exact for inputs held between samples"),
    ("tustin", "bilinear; DC gain kept"),
    ("matched", "pole-zero mapping, one input and one output"),
];

/// The sampling of `--sample-rate FS --discretize METHOD [--prewarp F]` (`None` without a rate).
pub fn sampling(rate_hz: Option<f64>, method: &str, prewarp_hz: Option<f64>) -> Result<Option<Sampling>, StudyError> {
    let method = match (method, prewarp_hz) {
        ("zoh", None) => Discretization::ZeroOrderHold,
        ("tustin", p) => Discretization::Tustin { prewarp_hz: p },
        ("matched", None) => Discretization::Matched,
        ("zoh" | "matched", Some(_)) => return Err(bad(Setting::Prewarp, "prewarping belongs to the Tustin method: add --discretize tustin")),
        (m, _) => return Err(bad(Setting::Discretize, format!("'{m}': expected {}", DISCRETIZATIONS.map(|(n, what)| format!("{n} ({what})")).join(", ")))),
    };
    let Some(rate) = rate_hz else {
        return match prewarp_hz {
            Some(_) => Err(bad(Setting::Prewarp, "prewarping needs a discrete-time ROM: give --sample-rate")),
            None => Ok(None),
        };
    };
    Sampling::new(rate, method).map(Some).map_err(|e| bad(if e.contains("prewarping") { Setting::Prewarp } else { Setting::SampleRate }, e))
}

/// The balancing of `--balanced N` or `--hankel-tol TOL`, `--spa` (`None` without either).
pub fn balancing(states: Option<usize>, hankel_tol: Option<f64>, spa: bool) -> Result<Option<Balancing>, StudyError> {
    let method = if spa { BalancedMethod::SingularPerturbation } else { BalancedMethod::Truncation };
    let order = match (states, hankel_tol) {
        (Some(_), Some(_)) => return Err(bad(Setting::HankelTol, "give either --balanced (a number of states) or --hankel-tol, not both")),
        (Some(0), None) => return Err(bad(Setting::Balanced, "a balanced ROM keeps at least 1 state")),
        (Some(n), None) => BalancedOrder::States(n),
        (None, Some(t)) if t > 0.0 && t < 1.0 => BalancedOrder::HankelTolerance(t),
        (None, Some(t)) => return Err(bad(Setting::HankelTol, format!("the tolerance relative to the largest Hankel singular value must lie in (0, 1), got {t}"))),
        (None, None) if spa => return Err(bad(Setting::Spa, "the singular perturbation approximation is a balanced reduction: give --balanced or --hankel-tol")),
        (None, None) => return Ok(None),
    };
    Ok(Some(Balancing { order, method }))
}

/// The minimal realization's tolerance, in (0, 1).
pub fn minimal_tolerance(tol: Option<f64>) -> Result<Option<f64>, StudyError> {
    match tol {
        Some(t) if !(t > 0.0 && t < 1.0) => Err(bad(Setting::Minimal, format!("the tolerance relative to the largest Hankel singular value must lie in (0, 1), got {t}"))),
        t => Ok(t),
    }
}

/// What the order reduction did.
#[derive(Clone, Debug)]
pub struct OrderReduction {
    /// The minimal realization's tolerance and the states it removed.
    pub minimal: Option<(f64, usize)>,
    /// The balanced reduction (its `rom` is the ROM's ordinary form).
    pub balanced: Option<crate::rom::BalancedReduction>,
    /// The states' names ("balanced 1", …, "unreduced 1", …), or `None` when they are still
    /// the modal ones.
    pub states: Option<Vec<String>>,
}

/// The ordinary ROM after the minimal realization and the balanced reduction `request` asks for.
pub(super) fn reduce_order(mut rom: OrdinaryRom, request: &RomRequest) -> Result<(OrdinaryRom, Option<OrderReduction>), StudyError> {
    if request.minimal.is_none() && request.balanced.is_none() {
        return Ok((rom, None));
    }
    let mut report = OrderReduction { minimal: None, balanced: None, states: None };
    if let Some(tol) = request.minimal {
        let (min, removed) = rom.minimal(tol)?;
        report.minimal = Some((tol, removed));
        if removed > 0 {
            report.states = Some((1..=min.a.nrows()).map(|k| format!("minimal state {k}")).collect());
        }
        rom = min;
    }
    if let Some(b) = request.balanced {
        let reduced = rom.balanced(b.order, b.method)?;
        rom = reduced.rom.clone();
        let names = (1..=reduced.kept).map(|k| format!("balanced {k}")).chain((1..=reduced.unreduced).map(|k| format!("unreduced {k}")));
        report.states = Some(names.collect());
        report.balanced = Some(reduced);
    }
    Ok((rom, Some(report)))
}

/// The discrete-time ROM `request` asks for, and the warning of modes it aliases.
pub(super) fn discretize(rom: &OrdinaryRom, request: &RomRequest) -> Result<(Option<DiscreteRom>, Option<Warning>), StudyError> {
    let Some(sampling) = &request.sampling else { return Ok((None, None)) };
    let discrete = rom.discretize(sampling)?;
    let eigenvalues = if rom.a.nrows() == 0 { Vec::new() } else { rom.a.as_ref().eigenvalues().unwrap_or_default() };
    // One frequency per pair (its member with Im λ ≥ 0), lowest first.
    let mut freqs: Vec<f64> = eigenvalues.iter().filter(|l| l.im >= 0.0).map(|l| hz(l.norm())).filter(|f| *f >= sampling.rate_hz / 2.0).collect();
    freqs.sort_by(f64::total_cmp);
    let warning = (!freqs.is_empty()).then_some(Warning::AboveNyquist { freqs_hz: freqs, rate_hz: sampling.rate_hz });
    Ok((Some(discrete), warning))
}

impl OrderReduction {
    /// The summary's lines.
    pub fn describe(&self) -> String {
        let mut s = String::new();
        if let Some((tol, removed)) = self.minimal {
            s += &format!("minimal realization (Hankel singular values of the shifted system below {tol:e} of the largest): {removed} uncontrollable or unobservable state(s) removed\n");
        }
        if let Some(b) = &self.balanced {
            let name = match b.method {
                BalancedMethod::Truncation => "balanced truncation",
                BalancedMethod::SingularPerturbation => "singular perturbation approximation (balanced; static gain kept)",
            };
            let hsv: Vec<String> = b.hankel.iter().map(|h| format!("{h:.4e}")).collect();
            s += &format!("{name}: {} of {} stable state(s) kept, {} rigid-body, integrator or unstable state(s) kept unreduced\n", b.kept, b.hankel.len(), b.unreduced);
            s += &format!("  Hankel singular values of the stable part: {}\n", hsv.join(" "));
            s += &format!("  error bound ‖G − G_r‖∞ ≤ 2 Σ dropped σ = {:.4e} (outputs' units per input unit)\n", b.error_bound);
        }
        s
    }
}

/// The summary's line of a discrete-time ROM.
pub(super) fn describe_discrete(d: &DiscreteRom) -> String {
    let largest = d.rom.eigenvalues.iter().map(|z| z.norm()).fold(0.0, f64::max);
    format!("discrete time: sample rate {} Hz, T = {:.6e} s, {}; largest |z| of its eigenvalues {largest:.9}\n", d.sampling.rate_hz, d.sample_time(), d.sampling.method.name())
}
