//! Modal dominance: how much each mode contributes to the chosen inputs and outputs.
//!
//! With `uᵀ F_yd v = 1`, the full model's transfer function is
//! `C̃ (s F_yd + F_y)⁻¹ B̃ = Σ_k (C̃ v_k)(u_kᵀ B̃) / (s − λ_k) + (terms of the infinite
//! eigenvalues)`, so a mode's share of the low-frequency response is
//! `d_k = ‖C̃ v_k‖ ‖u_kᵀ B̃‖ / |λ_k|` (2-norms, in the ports' units); its resonance peak is
//! `d_k |λ_k| / |Re λ_k|`, i.e. about `d_k / (2ζ)`. A unit (pair) sums its members. A mode
//! the inputs cannot excite or the outputs cannot see has `d = 0` to rounding.

use faer::c64;

use super::units::mode_units;
use crate::eigen::ModalAnalysis;
use crate::linear::LinearDae;

/// Dominance below this fraction of the largest unit's is "contributes nothing to these
/// ports" (rounding of exactly-zero products is ~1e-16 relative).
pub const NEGLIGIBLE_DOMINANCE: f64 = 1e-8;

/// The dominance of every dynamic mode unit.
#[derive(Clone, Debug)]
pub struct Dominance {
    /// Units as [`mode_units`] groups them.
    pub units: Vec<Vec<usize>>,
    /// `d` of each unit, same order.
    pub values: Vec<f64>,
}

fn norm(v: impl Iterator<Item = c64>) -> f64 {
    v.map(|x| x.norm_sqr()).sum::<f64>().sqrt()
}

impl Dominance {
    pub fn new(dae: &LinearDae, modal: &ModalAnalysis) -> Self {
        Self::of_ports(&dae.b, &dae.c, modal)
    }

    /// The same from `B̃` and `C̃` alone (a sparse linearization's).
    pub fn of_ports(b: &faer::Mat<f64>, c: &faer::Mat<f64>, modal: &ModalAnalysis) -> Self {
        let units = mode_units(modal);
        let mode_value = |i: usize| {
            let m = &modal.modes[i];
            let (Some(v), Some(u)) = (&m.right, &m.left) else { return 0.0 };
            let n = v.nrows();
            let cv = norm((0..c.nrows()).map(|r| (0..n).fold(c64::new(0.0, 0.0), |s, k| s + v[k] * c[(r, k)])));
            let ub = norm((0..b.ncols()).map(|j| (0..n).fold(c64::new(0.0, 0.0), |s, k| s + u[k] * b[(k, j)])));
            let l = m.lambda.norm();
            if l > 0.0 { cv * ub / l } else { 0.0 }
        };
        let values = units.iter().map(|u| u.iter().map(|&i| mode_value(i)).sum()).collect();
        Dominance { units, values }
    }

    /// The largest unit dominance.
    pub fn largest(&self) -> f64 {
        self.values.iter().copied().fold(0.0, f64::max)
    }

    /// Dominance of the unit holding mode `i`, relative to the largest (0 when all are 0).
    pub fn relative(&self, i: usize) -> f64 {
        let big = self.largest();
        match self.units.iter().position(|u| u.contains(&i)) {
            Some(k) if big > 0.0 => self.values[k] / big,
            _ => 0.0,
        }
    }

    /// Whether mode `i` contributes nothing to these ports.
    pub fn is_negligible(&self, i: usize) -> bool {
        self.relative(i) <= NEGLIGIBLE_DOMINANCE
    }
}
