//! Which eigensolver a [`super::Study`] uses, and what the sparse one certified.

use crate::eigen::krylov::{ModeTarget, SparseModalAnalysis};
use crate::rom::{ModeSelection, Ranking};

use super::{Residualization, RomRequest, StudyError};

/// The eigensolver of a study.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Solver {
    /// [`Solver::Dense`] below [`Solver::AUTO_SPARSE_FROM`] equations (or when the request needs
    /// every mode), [`Solver::Sparse`] from there on.
    #[default]
    Auto,
    /// QZ on the whole (deflated) pencil: every eigenvalue, zero and infinite ones labelled.
    Dense,
    /// Shift-invert Krylov–Schur on the sparse linearization (`eigen::krylov`): only the
    /// modes asked for, no dense n x n matrix.
    Sparse,
}

impl Solver {
    /// Size (equations) from which [`Solver::Auto`] takes the sparse route.
    ///
    /// Measured on 2026-12-01 (2-core machine shared with other builds, load 11–15, so CPU
    /// seconds, user time of the whole `romdyn eig FILE --static --count 10` process, test
    /// profile; the files of `scripts/bench_vs_mbdyn.sh`, chains hanging, no tip force):
    ///
    /// | model | equations | dense | sparse (10 lowest) |
    /// | --- | --- | --- | --- |
    /// | pendulum chain, 10 / 20 / 30 / 50 / 100 links | 182 / 352 / 522 / 862 / 1712 | 0.09 / 0.57 / 1.66 / 7.0 / 52 s | 0.01 / 0.04 / 0.07 / 0.12 / 0.20 s |
    /// | cantilever, 5 / 10 / 20 `beam3` | 138 / 258 / 498 | 0.22 / 1.3 / 8.7 s | 0.04 / 0.05 / 0.30 s |
    ///
    /// For a few modes the sparse route is faster at every size measured (the time crossover
    /// lies below 138 equations), but it returns only the modes asked for, while the dense
    /// route gives the complete spectrum: every mode, the zero and infinite eigenvalues
    /// labelled, ranking by dominance, the modal table `romdyn eig` prints. Auto keeps that
    /// while it costs about a second or less: up to 350 equations it is at most 0.6 s on the
    /// chain and 1.3 s on the beam, at 500 already 1.7 s and 8.7 s, and from there it grows
    /// as n³ (its memory as n², 300 MB at 1712 equations against 15 MB for the sparse
    /// route). Every shipped example (the largest, `cantilever.mbd`, 318 equations) stays on
    /// the dense route.
    pub const AUTO_SPARSE_FROM: usize = 400;

    /// Whether a model of `equations` takes the sparse route. `every_mode`: the request ranks
    /// a `--count` or `--modes` by dominance, which `Auto` leaves to the dense route (it
    /// compares every mode of the model); `Sparse` ranks it among the lowest
    /// [`DOMINANCE_POOL`] times as many modes ([`sparse_target`]).
    pub fn is_sparse(self, equations: usize, every_mode: bool) -> Result<bool, StudyError> {
        Ok(match self {
            Solver::Dense => false,
            Solver::Auto => !every_mode && equations >= Self::AUTO_SPARSE_FROM,
            Solver::Sparse => true,
        })
    }
}

/// On the sparse route a `--count N --by dominance` (or `--modes` ranked by dominance, up to
/// index N) is ranked among the certified lowest `DOMINANCE_POOL · N` modes, not among every
/// mode of the model as on the dense route: the modal table's header names them. Dominance
/// `‖C̃ v‖ ‖uᵀ B̃‖ / |λ|` falls with |λ| for the same port shares, so a mode above three times
/// as many lower ones rarely outranks them; a user who suspects one asks a band
/// (`--band F1:F2 --by dominance`) or the dense route.
pub const DOMINANCE_POOL: usize = 3;

/// The sparse route's modes when nothing asks for particular ones: the lowest 10.
pub const SPARSE_DEFAULT_COUNT: usize = 10;

/// The modes a ROM request needs from the sparse route: the selection's, the lowest modes up
/// to the largest modal-table index it names (ranked by dominance: [`DOMINANCE_POOL`] times
/// as many), and for `--residualize` of a band every mode
/// below the band's top (the modes below the band must be known to be left out of the
/// static correction).
pub fn sparse_target(request: &RomRequest) -> ModeTarget {
    let indices = |list: &[usize]| list.iter().copied().max().unwrap_or(1).max(1);
    let pool = if request.ranking == Ranking::Dominance { DOMINANCE_POOL } else { 1 };
    let residualized = match &request.residualization {
        Residualization::Modes(list) => indices(list),
        _ => 0,
    };
    match &request.selection {
        ModeSelection::Band { fmin_hz, fmax_hz } if residualized == 0 => {
            let fmin_hz = if request.residualization == Residualization::Dropped { 0.0 } else { *fmin_hz };
            ModeTarget::Band { fmin_hz, fmax_hz: *fmax_hz }
        }
        ModeSelection::Band { .. } => ModeTarget::Lowest(residualized),
        ModeSelection::Lowest(n) => ModeTarget::Lowest((*n * pool).max(residualized)),
        ModeSelection::Indices(list) => ModeTarget::Lowest((indices(list) * pool).max(residualized)),
    }
}

/// Whether a request needs every dynamic mode (only the dense route has them): ranking by
/// dominance of a `--count` or index selection compares every mode of the model (the sparse
/// route compares the lowest [`DOMINANCE_POOL`] times as many). Dominance
/// in a band (`--band F1:F2 --by dominance`) ranks the modes of the band only, which the
/// sparse route finds (and certifies) like any band: it needs no other mode.
pub fn needs_every_mode(request: &RomRequest) -> bool {
    request.ranking == Ranking::Dominance && !matches!(request.selection, ModeSelection::Band { .. })
}

/// What the sparse eigensolver returned besides the modes.
#[derive(Clone, Debug)]
pub struct SparseRun {
    pub target: ModeTarget,
    /// The lowest modes: the argument-principle count finds no eigenvalue below the
    /// returned ones that is not listed. A band: every shift window's right and adjoint
    /// runs agreed, no converged pair failed its residual test and the windows cover the
    /// band.
    pub certified: bool,
    pub note: Option<String>,
    /// What certifies the modes, when they are certified.
    pub certificate: Option<String>,
    /// Largest true relative residual of a returned pair (right or left).
    pub max_residual: f64,
    /// Damping ratio up to which the windows cover the band.
    pub damping_covered: f64,
    pub windows: usize,
    /// The true-residual tolerance every returned pair met.
    pub tolerance: f64,
    /// A `--count` or `--modes` is ranked by dominance among these modes
    /// ([`DOMINANCE_POOL`]).
    pub dominance_pool: bool,
}

impl SparseRun {
    pub(super) fn new(target: ModeTarget, tolerance: f64, s: &SparseModalAnalysis) -> Self {
        SparseRun { target, certified: s.certified, note: s.note.clone(), certificate: s.certificate.clone(), max_residual: s.max_residual, damping_covered: s.damping_covered, windows: s.windows.len(), tolerance, dominance_pool: false }
    }

    /// The modes asked for, as a selection of the modal table.
    pub fn selection(&self) -> ModeSelection {
        match self.target {
            ModeTarget::Lowest(n) => ModeSelection::Lowest(n),
            ModeTarget::Band { fmin_hz, fmax_hz } => ModeSelection::Band { fmin_hz, fmax_hz },
        }
    }

    /// The modal table's second header line.
    pub fn header(&self) -> String {
        let certified = if self.certified { format!("certified ({})", self.certificate.as_deref().unwrap_or("right and adjoint Krylov runs agree in every shift window")) } else { format!("NOT certified: {}", self.note.as_deref().unwrap_or("see the warning")) };
        format!(
            "sparse route (shift-invert Krylov–Schur, {} shift window(s)): {}, {certified}; largest true residual {:.1e} (tolerance {:.0e}); the zero and infinite eigenvalues are not computed",
            self.windows,
            self.describe_target(),
            self.max_residual,
            self.tolerance
        )
    }

    /// "20 lowest dynamic modes" or "dynamic modes in 3–40 Hz".
    pub fn describe_target(&self) -> String {
        match self.target {
            ModeTarget::Lowest(n) if self.dominance_pool => format!("the {n} lowest dynamic modes (the candidates the dominance ranking compares, {DOMINANCE_POOL} times the modes asked)"),
            ModeTarget::Lowest(n) => format!("the {n} lowest dynamic modes"),
            ModeTarget::Band { fmin_hz, fmax_hz } => format!("the dynamic modes in {fmin_hz}–{fmax_hz} Hz"),
        }
    }
}
