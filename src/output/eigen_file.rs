//! The content of one eigenanalysis file, shared by the Octave `.m` writer (MBDyn's layout)
//! and romdyn's JSON: `J(±c)`, the eigenvalues as MBDyn's `alpha` rows, eigenvectors and
//! the structural nodes' configuration (MBDyn manual, "Eigenanalysis", output).

use std::borrow::Cow;

use faer::{c64, Mat};

use crate::eigen::EnergyShare;
use crate::kinematics::Vec3;
use crate::eigen::{EigenRoute, ModalAnalysis, Mode};
use crate::linear::SparseMatrix;
use crate::model::Label;

/// How `Aplus`/`Aminus` are written (`output full matrices` / `output sparse matrices`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MatrixLayout {
    /// `Aplus = [a11 a12 ... ; ...];`
    Full,
    /// `Aplus = [i j v; ...]; Aplus = spconvert(Aplus);`
    Sparse,
}

/// `Aplus = J(+c)` and `Aminus = J(−c)` as the eigenanalysis built them: dense for the dense
/// route, sparse as assembled for the sparse one (no n x n matrix on that path unless the
/// full layout is asked for), or not assembled at all on the sparse route when the file asks
/// for neither layout (the sparse route solves on `F_/ẏ`, `F_/y`; `J(±c)` are only written).
pub enum PencilMatrices {
    Dense { aplus: Mat<f64>, aminus: Mat<f64> },
    Sparse { aplus: SparseMatrix, aminus: SparseMatrix },
    /// Not assembled: `dim` equations. [`EigenFile::matrices`] is `None` with it.
    Unassembled { dim: usize },
}

/// What a writer says when a file asks for `Aplus`/`Aminus` that were not assembled (never,
/// by `Eigenanalysis::file`; a file without them must not look complete).
pub(crate) const UNASSEMBLED: &str = "J(+c) and J(-c) were not assembled for this eigenanalysis";

impl PencilMatrices {
    /// Number of equations.
    pub fn dim(&self) -> usize {
        match self {
            PencilMatrices::Dense { aplus, .. } => aplus.nrows(),
            PencilMatrices::Sparse { aplus, .. } => aplus.nrows(),
            PencilMatrices::Unassembled { dim } => *dim,
        }
    }

    /// Whether `Aplus` and `Aminus` are held (anything but [`PencilMatrices::Unassembled`]).
    pub fn is_assembled(&self) -> bool {
        !matches!(self, PencilMatrices::Unassembled { .. })
    }

    /// `Aplus` (`plus`) or `Aminus` as a dense matrix (a copy on the sparse route: only for
    /// the full layout, whose size the eigenanalysis checked against the dense budget);
    /// `None` when not assembled.
    pub fn full(&self, plus: bool) -> Option<Cow<'_, Mat<f64>>> {
        match self {
            PencilMatrices::Dense { aplus, aminus } => Some(Cow::Borrowed(if plus { aplus } else { aminus })),
            PencilMatrices::Sparse { aplus, aminus } => Some(Cow::Owned(if plus { aplus } else { aminus }.to_dense())),
            PencilMatrices::Unassembled { .. } => None,
        }
    }

    /// The non-zero entries `(i, j, v)` (0-based) of `Aplus` (`plus`) or `Aminus`, column by
    /// column; `None` when not assembled.
    pub fn nonzeros(&self, plus: bool) -> Option<Vec<(usize, usize, f64)>> {
        let mut entries: Vec<_> = match self {
            PencilMatrices::Dense { aplus, aminus } => {
                let m = if plus { aplus } else { aminus };
                (0..m.ncols()).flat_map(|j| (0..m.nrows()).map(move |i| (i, j, m[(i, j)]))).filter(|e| e.2 != 0.0).collect()
            }
            PencilMatrices::Sparse { aplus, aminus } => if plus { aplus } else { aminus }.triplets().filter(|e| e.2 != 0.0).collect(),
            PencilMatrices::Unassembled { .. } => return None,
        };
        entries.sort_by_key(|&(i, j, _)| (j, i));
        Some(entries)
    }
}

/// Configuration of the structural nodes at the analysis (`output geometry`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Geometry {
    pub labels: Vec<Label>,
    /// 0-based index of each node's first unknown: `VR(idx + 1, :)` is its x motion.
    pub first_index: Vec<usize>,
    /// Positions [m].
    pub position: Vec<Vec3>,
    /// Orientations as rotation vectors φ n [rad].
    pub rotation_vector: Vec<Vec3>,
}

/// One eigenanalysis: `Aplus = J(+c) = F_/ẏ + c F_/y`, `Aminus = J(−c)` (eqs. 13–14), its
/// modal analysis and what the request asks to write.
pub struct EigenFile<'a> {
    /// 0-based number of the analysis in the run.
    pub index: usize,
    /// Time of the analysis [s].
    pub time: f64,
    /// `c` [s].
    pub dcoef: f64,
    pub pencil: &'a PencilMatrices,
    /// Whether and how the matrices are written.
    pub matrices: Option<MatrixLayout>,
    /// How the modes were computed (the `.m` file's comment and the JSON's `solver`).
    pub solver: &'a str,
    pub modal: &'a ModalAnalysis,
    /// Indices (into `modal.modes`) of the modes written (frequency limits applied).
    pub written: &'a [usize],
    /// Whether `VR`, `VL` are written.
    pub eigenvectors: bool,
    pub geometry: Option<&'a Geometry>,
    pub unknown_names: &'a [String],
    /// Kinetic-energy shares of every mode of `modal` (may be empty lists).
    pub energy: &'a [Vec<EnergyShare>],
}

/// MBDyn's `alpha` row `[αr, αi, β]` of a mode: the discrete eigenvalue
/// `Λ = (αr + j αi)/β` of `Aminus v = Λ Aplus v`, so that `λ = (1/c)(Λ − 1)/(Λ + 1)`
/// (MBDyn manual, eigenanalysis output). romdyn's Λ route solves `J* v = μ (−J) v`
/// (eq. 18), so `Λ = −μ` and QZ's own `(α, β)` are written; for the direct route `Λ` is
/// formed from λ as `(1 + cλ)/(1 − cλ)`. `β ≥ 0`; `αi` has the sign of `Im λ`.
pub fn mbdyn_alpha(mode: &Mode, route: EigenRoute, dcoef: f64) -> [f64; 3] {
    let (mut alpha, mut beta) = match route {
        EigenRoute::Lambda => (-mode.classification.alpha, mode.classification.beta),
        EigenRoute::Direct => {
            if !(mode.lambda.re.is_finite() && mode.lambda.im.is_finite()) {
                (c64::new(-1.0, 0.0), 1.0)
            } else {
                let cl = mode.lambda * dcoef;
                let one = c64::new(1.0, 0.0);
                ((one + cl) * (one - cl).conj(), (one - cl).norm_sqr())
            }
        }
    };
    if beta < 0.0 {
        alpha = -alpha;
        beta = -beta;
    }
    let im = if mode.lambda.im != 0.0 && mode.lambda.im.is_finite() { alpha.im.abs().copysign(mode.lambda.im) } else { alpha.im };
    [alpha.re, im, beta]
}
