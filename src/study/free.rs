//! What a front end reports after a ROM, assembled once here (issue 31: it lived in the CLI,
//! so Python lacked it): the eigenvalues of a ROM whose dummy springs were removed (paper
//! §8, eqs. 92–95: rigid-body, unstable and oscillatory ones, a real one with the motion of
//! the free model's mode), the transfer-matrix panels of a response check without the
//! imposed displacements, and the warnings a ROM adds to its study's.

use faer::{c64, Mat};

use crate::linear::FrequencyResponse;
use crate::output::mimo_plot::MimoPlot;

use super::{ReducedModel, RomCheck, Study, Warning};
use crate::linear::hz;

/// Below this fraction of the largest |λ| an eigenvalue is zero (a rigid-body motion of the
/// free ROM): the springs' removal leaves rounding of that order on the exact zeros.
const ZERO_EIGENVALUE: f64 = 1e-6;
/// Below this fraction of the largest |λ| an imaginary (real) part is rounding.
const REAL_EIGENVALUE: f64 = 1e-9;

/// What a free ROM's eigenvalue is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FreeKind {
    Real,
    RealUnstable,
    Oscillatory,
    OscillatoryUnstable,
}

/// One eigenvalue of a free ROM (a pair once, by its upper member).
#[derive(Clone, Debug)]
pub struct FreeEigenvalue {
    /// [rad/s]
    pub lambda: c64,
    pub kind: FreeKind,
    /// A real one's motion, from the free model's real mode nearest it
    /// ([`Study::free_real_mode_label`]).
    pub motion: Option<String>,
}

/// The eigenvalues of a ROM whose dummy springs were removed (the modal table is the
/// grounded model's).
#[derive(Clone, Debug)]
pub struct FreeEigenvalues {
    /// The removed elements ("deformable hinge 902").
    pub removed: Vec<String>,
    /// Eigenvalues at zero: rigid-body motion.
    pub zero: usize,
    /// The others, one line per pair, every real one.
    pub listed: Vec<FreeEigenvalue>,
}

impl Study {
    /// The free ROM's eigenvalues when dummy springs were removed (`None` otherwise).
    pub fn free_eigenvalues(&self, rom: &ReducedModel) -> Option<FreeEigenvalues> {
        let removed = self.removed_springs();
        if removed.is_empty() {
            return None;
        }
        let eig = &rom.descriptor.eigenvalues;
        let big = eig.iter().map(|l| l.norm()).fold(0.0, f64::max);
        let zero = eig.iter().filter(|l| l.norm() <= ZERO_EIGENVALUE * big).count();
        let listed = eig
            .iter()
            .filter(|l| l.norm() > ZERO_EIGENVALUE * big && (l.im > REAL_EIGENVALUE * big || l.im.abs() <= REAL_EIGENVALUE * big))
            .map(|&lambda| {
                let real = lambda.im.abs() <= REAL_EIGENVALUE * big;
                let unstable = lambda.re > if real { 0.0 } else { REAL_EIGENVALUE * big };
                let kind = match (real, unstable) {
                    (true, false) => FreeKind::Real,
                    (true, true) => FreeKind::RealUnstable,
                    (false, false) => FreeKind::Oscillatory,
                    (false, true) => FreeKind::OscillatoryUnstable,
                };
                FreeEigenvalue { lambda, kind, motion: real.then(|| self.free_real_mode_label(lambda.re)).flatten() }
            })
            .collect();
        Some(FreeEigenvalues { removed, zero, listed })
    }

    /// The transfer-matrix panels of `check`'s comparison (paper Figs. 9, 10): the imposed
    /// displacements (last outputs) are inputs of the transmissibility, not responses, so the
    /// panels show the other outputs; `diagonal`: only the diagonal panels.
    pub fn transfer_panels(&self, check: &RomCheck, diagonal: bool) -> MimoPlot {
        let no = self.output_names().len() - self.imposed_len();
        let rows = |h: &[Mat<c64>]| h.iter().map(|m| m.get(..no, ..).to_owned()).collect::<Vec<_>>();
        let c = &check.comparison;
        let mut response = FrequencyResponse::new(c.freq_hz.clone(), c.inputs.clone(), c.outputs[..no].to_vec(), rows(&c.full));
        response.reduced = c.reduced.iter().map(|(label, h)| (label.clone(), rows(h))).collect();
        MimoPlot { title: "Transfer matrix |z/u|".into(), response, diagonal }
    }
}

impl ReducedModel {
    /// The warnings this ROM and its check add to the study's (printed or raised once: the
    /// study's were already), the ROM's first, then the check's.
    pub fn new_warnings(&self, study: &Study, check: Option<&RomCheck>) -> Vec<Warning> {
        let known = study.warnings();
        let checked = check.map_or(&[][..], |c| &c.warnings[..]);
        self.warnings.iter().chain(checked).filter(|w| !known.contains(w)).cloned().collect()
    }
}

impl FreeKind {
    /// As the report words it.
    pub fn name(self) -> &'static str {
        match self {
            FreeKind::Real => "real",
            FreeKind::RealUnstable => "real, unstable",
            FreeKind::Oscillatory => "oscillatory",
            FreeKind::OscillatoryUnstable => "oscillatory, unstable",
        }
    }
}

/// The report `romdyn rom` prints and Python's `Rom.summary` ends with.
impl std::fmt::Display for FreeEigenvalues {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "removed from the full model and the ROM (their force fed back, A + B_e K C_e): {}", self.removed.join(", "))?;
        writeln!(f, "ROM eigenvalues without them [rad/s]: {} zero (rigid-body motion)", self.zero)?;
        for e in &self.listed {
            let kind = match (&e.motion, e.kind) {
                (Some(motion), FreeKind::Real | FreeKind::RealUnstable) => format!("real, {motion}"),
                (_, kind) => kind.name().to_string(),
            };
            writeln!(f, "  {:>14.6e} {:+.6e}j   {:>10.6} Hz   {kind}", e.lambda.re, e.lambda.im, hz(e.lambda.norm()))?;
        }
        Ok(())
    }
}
