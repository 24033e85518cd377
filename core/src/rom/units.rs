//! Modes as a control engineer counts them: a complex-conjugate pair `σ ± jω` is one mode,
//! and so is a `±a` real pair, the two real eigenvalues of an undamped mechanical degree of
//! freedom with negative stiffness (the inverted pendulum's ±3.13 rad/s, CASES C3).

use crate::eigen::{ModalAnalysis, ModeKind};

/// Relative distance `|λ₁ + λ₂| / |λ₁|` under which two real eigenvalues form a `±a` pair
/// (beyond the two eigenvalues' error estimates).
pub const REAL_PAIR_TOLERANCE: f64 = 1e-6;

/// The dynamic modes grouped into units (each a sorted list of one or two 0-based indices
/// into `modal.modes`), in the order of the modal analysis (increasing |λ|).
pub fn mode_units(modal: &ModalAnalysis) -> Vec<Vec<usize>> {
    let dynamic: Vec<usize> = modal.of_kind(ModeKind::Dynamic).collect();
    let mut taken = vec![false; modal.modes.len()];
    let mut units = Vec::new();
    for &i in &dynamic {
        if taken[i] {
            continue;
        }
        taken[i] = true;
        let m = &modal.modes[i];
        let partner = match m.partner {
            Some(p) => Some(p),
            None if m.lambda.im == 0.0 => dynamic.iter().copied().find(|&j| {
                let o = &modal.modes[j];
                !taken[j]
                    && o.partner.is_none()
                    && o.lambda.im == 0.0
                    && (m.lambda.re + o.lambda.re).abs() <= REAL_PAIR_TOLERANCE * m.lambda.re.abs() + m.error + o.error
                    && m.lambda.re != 0.0
            }),
            None => None,
        };
        let mut unit = vec![i];
        if let Some(p) = partner {
            taken[p] = true;
            unit.push(p);
            unit.sort_unstable();
        }
        units.push(unit);
    }
    units
}

/// The unit of mode `i` (0-based) among `units`.
pub fn unit_of(units: &[Vec<usize>], i: usize) -> Option<usize> {
    units.iter().position(|u| u.contains(&i))
}
