//! Modal damping added to a ROM (never to the full model): many multibody models have no
//! dampers, control design needs some.
//!
//! Each kept oscillatory mode `λ = σ ± jω` with damping ratio below the requested `ζ` gets
//! the poles of a single-DOF oscillator with the same natural frequency `ω_n = |λ|`:
//! `λ' = −ζ ω_n ± j ω_n √(1 − ζ²)`. In the mode's 2×2 block, `E⁻¹A = σ I + ω K` (`K² = −I`)
//! becomes `σ' I + ω' K`, so the eigenvectors stay, and the block's rows of `B` are scaled by
//! `ω/ω'`: the residue of `m q̈ + c q̇ + k q = f`, `1/(2 j m ω_d)`, so the mode's static
//! contribution `1/k` is unchanged (exactly so for an undamped or proportionally damped mode).

use faer::{c64, Mat};

use super::{DescriptorRom, RomError};

/// The damping ratio a ROM's modes get.
#[derive(Clone, Debug, PartialEq)]
pub enum ModalDamping {
    /// The same `ζ` for every kept oscillatory mode.
    Uniform(f64),
    /// `ζ` for some kept modes (1-based modal-table indices; either member of a pair).
    PerMode(Vec<(usize, f64)>),
}

/// A mode whose ROM eigenvalue was moved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DampingChange {
    /// 0-based index of the mode (the member with positive imaginary part).
    pub mode: usize,
    pub before: c64,
    pub after: c64,
}

impl ModalDamping {
    fn zeta_of(&self, mode: usize, partner: Option<usize>) -> Option<f64> {
        match self {
            ModalDamping::Uniform(z) => Some(*z),
            ModalDamping::PerMode(list) => list.iter().find(|(m, _)| *m == mode + 1 || partner.is_some_and(|p| *m == p + 1)).map(|(_, z)| *z),
        }
    }
}

impl DescriptorRom {
    /// Applies `damping` to the kept oscillatory modes (see the module documentation).
    /// `partner(i)` is the conjugate of mode `i`. Modes already damped more than requested,
    /// and real modes, are left as they are (real modes are reported by the caller).
    pub fn add_modal_damping(&mut self, damping: &ModalDamping, partner: impl Fn(usize) -> Option<usize>) -> Result<Vec<DampingChange>, RomError> {
        let mut changes = Vec::new();
        let kept_states = self.state_modes.len() - self.static_states;
        let mut s = 0;
        while s < kept_states {
            let mode = self.state_modes[s];
            let pair = s + 1 < kept_states && self.state_modes[s + 1] == mode;
            if !pair {
                s += 1;
                continue;
            }
            if let Some(zeta) = damping.zeta_of(mode, partner(mode)) {
                if !(0.0..1.0).contains(&zeta) {
                    return Err(RomError::Selection(format!("modal damping ratio {zeta} is outside [0, 1)")));
                }
                if let Some(change) = self.damp_pair(s, mode, zeta)? {
                    changes.push(change);
                }
            }
            s += 2;
        }
        Ok(changes)
    }

    /// Moves the poles of the 2×2 block at states `s, s+1` to damping ratio `zeta`.
    fn damp_pair(&mut self, s: usize, mode: usize, zeta: f64) -> Result<Option<DampingChange>, RomError> {
        let e = Mat::from_fn(2, 2, |i, j| self.e[(s + i, s + j)]);
        let a = Mat::from_fn(2, 2, |i, j| self.a[(s + i, s + j)]);
        let det = e[(0, 0)] * e[(1, 1)] - e[(0, 1)] * e[(1, 0)];
        if !(det.abs() > 0.0) {
            return Err(RomError::SingularStatic("the E block of a kept mode"));
        }
        let einv = Mat::from_fn(2, 2, |i, j| match (i, j) { (0, 0) => e[(1, 1)], (1, 1) => e[(0, 0)], (0, 1) => -e[(0, 1)], _ => -e[(1, 0)] } / det);
        let m = &einv * &a;
        // Eigenvalues σ ± jω of the real 2×2 M.
        let sigma = 0.5 * (m[(0, 0)] + m[(1, 1)]);
        let disc = (m[(0, 0)] - m[(1, 1)]).powi(2) / 4.0 + m[(0, 1)] * m[(1, 0)];
        if disc >= 0.0 {
            return Ok(None);
        }
        let omega = (-disc).sqrt();
        let wn = sigma.hypot(omega);
        if -sigma / wn >= zeta {
            return Ok(None);
        }
        let (sigma2, omega2) = (-zeta * wn, wn * (1.0 - zeta * zeta).sqrt());
        // M' = σ' I + ω' K with K = (M − σ I)/ω.
        let m2 = Mat::from_fn(2, 2, |i, j| if i == j { sigma2 } else { 0.0 } + omega2 / omega * (m[(i, j)] - if i == j { sigma } else { 0.0 }));
        let a2 = &e * &m2;
        for i in 0..2 {
            for j in 0..2 {
                self.a[(s + i, s + j)] = a2[(i, j)];
            }
            for c in 0..self.b.ncols() {
                self.b[(s + i, c)] *= omega / omega2;
            }
        }
        let (before, after) = (c64::new(sigma, omega), c64::new(sigma2, omega2));
        for l in self.eigenvalues.iter_mut() {
            if (*l - before).norm() <= 1e-6 * wn {
                *l = after;
            } else if (*l - before.conj()).norm() <= 1e-6 * wn {
                *l = after.conj();
            }
        }
        Ok(Some(DampingChange { mode, before, after }))
    }
}
