//! What a user must know about a study or a ROM that is not an error: each warning says
//! what is wrong, by how much, and what to do.

use std::fmt;
use crate::linear::hz;

/// A warning about the linear model or a ROM built from it.
#[derive(Clone, Debug, PartialEq)]
pub enum Warning {
    /// The reference solution is neither an equilibrium nor a steady motion: `F` with the
    /// velocities held and the accelerations zero is not (unbalanced gravity or loads, an
    /// accelerating motion at `--at`); the eigenvalues are the frozen Jacobians'.
    NotInEquilibrium { residual: f64, equation: String, tolerance: f64 },
    /// An input moves no unknown of the model statically (e.g. a force on a clamped node).
    InputMovesNothing { input: String },
    /// An output does not move under any input statically (e.g. a clamped node).
    OutputSeesNothing { output: String },
    /// Modes below the band of interest were dropped instead of statically residualized.
    BelowBandDropped { modes: Vec<(usize, f64)>, top_hz: f64 },
    /// Modes below the band of interest were kept as dynamic modes.
    BelowBandKept { modes: Vec<(usize, f64)>, top_hz: f64 },
    /// Kept modes that the inputs cannot excite or the outputs cannot see.
    Invisible { modes: Vec<(usize, f64)> },
    /// Kept modes whose left vector could not be scaled to `uᵀ F_yd v = 1` (that product is
    /// rounding against its own terms): a modal ROM cannot represent them.
    Unscaled { modes: Vec<(usize, f64)> },
    /// The ROM's static gain differs from the full model's.
    StaticGain { relative: f64, channel: String, reason: String },
    /// A real kept mode could not take modal damping.
    DampingNotApplied { mode: usize, reason: String },
    /// The sparse eigensolver could not certify that it found every mode asked for.
    SparseNotCertified { target: String, reason: String, damping_covered: f64 },
    /// A count or modes ranked by dominance on a sparse study that was not computed for
    /// that ranking: only the modes it found were compared.
    DominanceAmongComputed { target: String },
    /// The ROM's response departs from the full model's on the response grid, within the
    /// frequencies of interest (its channel on its own scale).
    /// `full` and `rom`: the two magnitudes there (the channel's units).
    ResponseDeparts { response: Response, channel: String, relative: f64, at_hz: f64, full: f64, rom: f64, top_hz: f64, advice: String },
    /// With an imposed motion, the ROM's transmissibility could not be formed (its imposed
    /// block is singular at a grid frequency), so it was not checked.
    TransmissibilityUnavailable { reason: String, top_hz: f64 },
    /// Eigenvalues whose error estimate is not below their modulus, labelled zero or infinite
    /// instead of dynamic: `(mode number, λ [rad/s], error [rad/s], label)`.
    UnresolvedEigenvalues { modes: Vec<(usize, faer::c64, f64, &'static str)> },
    /// Eigenvalues labelled zero by the eigenanalysis' uncertainty although their error
    /// estimate is below |λ|: `(mode number, λ [rad/s], error [rad/s])`.
    DoubtfulZeros { modes: Vec<(usize, faer::c64, f64)> },
    /// Kept modes whose reported eigenvalue the ROM's exported `A` does not have (`modes` of
    /// them; the worst: its number, the reported and nearest exported λ, relative gap).
    RomEigenvalues { modes: usize, mode: usize, reported: faer::c64, exported: faer::c64, relative: f64 },
    /// A static reference of beams with MBDyn's incremental update: the whole load is one
    /// step from the initial configuration, whatever the load steps.
    IncrementalBeamsStatic { beams: usize },
    /// A beam the `auto` update leaves path independent in a time integration (its section
    /// law cannot take MBDyn's incremental update): `why` names it.
    BeamKeptPathIndependent { why: String },
    /// The run that reached the reference warned (its initial velocities, its derivatives
    /// phase): the reference state carries what the warning says.
    Run { warning: crate::analysis::RunWarning },
    /// An element's residual is not differentiable at the reference (friction at rest past
    /// breakaway, …): the linearization is one-sided. `why` names the element.
    OneSided { why: String },
    /// An element's linearization scales with reaction multipliers' values as integrated
    /// (friction's normal force), whose noise the eigenvalues carry. `why` names the element.
    ReactionDependent { why: String },
    /// A discrete-time ROM whose continuous eigenvalues have natural frequencies |λ|/2π
    /// (one per pair, [Hz]) at or above the Nyquist frequency `rate/2`: they alias.
    AboveNyquist { freqs_hz: Vec<f64>, rate_hz: f64 },
    /// What the reader noticed in an element's own input file and let pass
    /// ([`crate::model::Model::input_warnings`]).
    InputFile { message: String },
}

/// Which of a ROM's responses a [`Warning::ResponseDeparts`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Response {
    /// The transfer matrix from the inputs (forces, moments) to the outputs.
    Inputs,
    /// The transmissibility `z/z_e` from the imposed motion (eq. 100).
    Transmissibility,
}

fn modes_hz(m: &[(usize, f64)]) -> String {
    m.iter().map(|(k, f)| format!("{k} ({f:.4} Hz)")).collect::<Vec<_>>().join(", ")
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::InputFile { message } => write!(f, "{message}"),
            Warning::BeamKeptPathIndependent { why } => write!(f, "{why} (--beam-update path-independent silences this)"),
            Warning::NotInEquilibrium { residual, equation, tolerance } => write!(
                f,
                "the reference solution is neither an equilibrium nor a steady motion: with its velocities held and its accelerations set to zero the residual is {residual:.3e} (tolerance {tolerance:.1e}) at '{equation}'. The eigenvalues are those of the Jacobians frozen at this instant (as MBDyn's eigenanalysis computes them), not the frequencies and damping of small motions about this trajectory, which follow a time-varying linear system (a swinging pendulum's frozen eigenvalues take the centripetal tension as a stiffness); the ROM is the frozen system's. Use --static for the static equilibrium, or a reference at rest or in steady motion (a uniform spin about an axis of symmetry; a motion steady in a turning frame, a top's precession or a rotor's blades, once the model is written in that frame with MBDyn's `rigid body kinematics`)"
            ),
            Warning::InputMovesNothing { input } => write!(f, "no output responds to input {input} (a load on a clamped node, or in a direction the outputs do not see?): every response to it is zero (to rounding)"),
            Warning::OutputSeesNothing { output } => write!(f, "output {output} responds to no input (a clamped node, or a direction the inputs do not move?): its every response is zero (to rounding)"),
            Warning::BelowBandDropped { modes, top_hz } => write!(
                f,
                "mode(s) {} lie below the frequencies of interest (up to {top_hz:.4} Hz) and were dropped, not statically residualized: static residualization is valid only for modes above the band (--below-band keep keeps them, refuse stops)",
                modes_hz(modes)
            ),
            Warning::BelowBandKept { modes, top_hz } => write!(f, "mode(s) {} lie below the frequencies of interest (up to {top_hz:.4} Hz) and were kept as dynamic modes (--below-band keep)", modes_hz(modes)),
            Warning::Invisible { modes } => write!(
                f,
                "kept mode(s) {} contribute nothing to these inputs and outputs (not excited or not seen): their states add no response (--by dominance leaves them out)",
                modes_hz(modes)
            ),
            Warning::Unscaled { modes } => write!(
                f,
                "kept mode(s) {} have left and right vectors orthogonal through F_yd to rounding (uᵀ F_yd v = 0: a repeated eigenvalue with a single vector, such as a critically damped mode with ζ = 1 exactly, or a model scaled beyond double precision): a modal ROM cannot represent them and their states add no response; change that damping by a part in a million, or rescale the model",
                modes_hz(modes)
            ),
            Warning::StaticGain { relative, channel, reason } => write!(f, "the ROM's static gain differs from the full model's by {relative:.2e} (relative, {channel}): {reason}"),
            Warning::DampingNotApplied { mode, reason } => write!(f, "modal damping not applied to mode {mode}: {reason}"),
            Warning::SparseNotCertified { target, reason, damping_covered } => write!(
                f,
                "the sparse eigenanalysis of {target} is not certified: {reason} (shift windows cover damping ratios up to {damping_covered:.2}); a mode may be missing from the table and the ROM: check with --solver dense, or narrow the band"
            ),
            Warning::DominanceAmongComputed { target } => write!(
                f,
                "the dominance ranking compared only the modes the sparse eigenanalysis computed ({target}): a more dominant mode outside them was not considered; build the study for the ROM's request (the CLI does: --count N --by dominance ranks among the 3N lowest) or use --solver dense"
            ),
            Warning::ResponseDeparts { response, channel, relative, at_hz, full, rom, top_hz, advice } => write!(
                f,
                "the ROM's {} {channel} departs from the full model's by {relative:.2e} (relative, on its own scale) at {at_hz:.4} Hz (|ROM| {rom:.3e}, |full| {full:.3e}), within the frequencies of interest (up to {top_hz:.4} Hz): {advice}",
                match response {
                    Response::Inputs => "response",
                    Response::Transmissibility => "transmissibility (eq. 100)",
                }
            ),
            Warning::TransmissibilityUnavailable { reason, top_hz } => write!(
                f,
                "the ROM's transmissibility (eq. 100) could not be checked against the full model's (frequencies of interest up to {top_hz:.4} Hz): {reason}"
            ),
            Warning::UnresolvedEigenvalues { modes } => write!(
                f,
                "{} eigenvalue(s) are not resolved in double precision: {}; each error estimate is not below |λ| (± inf: its left and right vectors are orthogonal through F_yd to rounding, so its condition number is beyond double precision and no ROM can use the mode), so the value says nothing (not even its order of magnitude) and the mode is not listed as dynamic. A repeated eigenvalue with a single vector (a critically damped mode, ζ = 1 exactly) gives ± inf: a modal ROM cannot represent it, so change that damping by a part in a million. Masses or stiffnesses spanning many decades, or a dCoef far from 1/|λ| (--dcoef), cause the others: rescale the model or give --dcoef near 1/|λ| of the modes of interest",
                modes.len(),
                modes.iter().map(|(k, l, e, kind)| format!("mode {k} λ = {:.4e}{:+.4e}j rad/s ± {e:.1e}, labelled {kind}", l.re, l.im)).collect::<Vec<_>>().join(", ")
            ),
            Warning::DoubtfulZeros { modes } => write!(
                f,
                "{} eigenvalue(s) are labelled zero by the eigenanalysis' uncertainty although their own error estimate is smaller than |λ|: {}; they may be slow real modes (stiffnesses or masses spanning many decades): check them with --dcoef near 1/|λ| or --route direct",
                modes.len(),
                modes.iter().map(|(k, l, e)| format!("mode {k} |λ| = {:.4e} rad/s ± {e:.1e}", l.norm())).collect::<Vec<_>>().join(", ")
            ),
            Warning::AboveNyquist { freqs_hz, rate_hz } => write!(
                f,
                "the ROM has {} mode(s) at or above the Nyquist frequency of --sample-rate {rate_hz} ({} Hz): {} Hz; the discrete-time ROM aliases them (their response appears folded below {} Hz): raise --sample-rate, or leave those modes out (--band, --count)",
                freqs_hz.len(),
                rate_hz / 2.0,
                freqs_hz.iter().map(|f| format!("{f:.4}")).collect::<Vec<_>>().join(", "),
                rate_hz / 2.0
            ),
            Warning::RomEigenvalues { modes, mode, reported, exported, relative } => write!(
                f,
                "the ROM's matrices do not have the eigenvalues its summary reports for {modes} kept mode(s): mode {mode} is reported at λ = {:.6e}{:+.6e}j rad/s ({:.4} Hz) but the nearest eigenvalue of the exported A is {:.6e}{:+.6e}j rad/s ({:.4} Hz), {relative:.1e} relative; trust the exported matrices' eigenvalues, and check the mode's error estimate in `romdyn eig`",
                reported.re,
                reported.im,
                hz(reported.norm()),
                exported.re,
                exported.im,
                hz(exported.norm())
            ),
            Warning::IncrementalBeamsStatic { beams } => write!(
                f,
                "{beams} beam(s) use MBDyn's incremental update (--beam-update incremental): their static equilibrium takes the whole load as one step from the initial configuration, whatever --load-steps (MBDyn 1.7.3's one-step result), and differs from the path-independent beams' by the discretization of large rotations; linearize after a time integration (--at) to follow a load path, or use the default update"
            ),
            Warning::Run { warning } => write!(f, "reference solution: {warning}"),
            Warning::OneSided { why } => write!(f, "{why}; the linearization takes a one-sided derivative there, and its eigenvalues and ROM describe only motion to that side"),
            Warning::ReactionDependent { why } => write!(f, "{why}"),
        }
    }
}
