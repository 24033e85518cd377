//! The 6x6 section law of a beam evaluation point: generalized forces
//! `[F; M] = K ([ε; κ] − e_p) + V [ε̇; κ̇] + f_p` in the section frame (axis 1 along the beam; ε axial and
//! shear strains, κ torsional and bending curvatures). MBDyn's `linear elastic generic`
//! (`V = 0`), `linear elastic isotropic` (`K = k I`) and `linear viscoelastic generic`; with
//! [`LawFunctions`], its `nlsf` laws (each component also `f′_i(e_i − e_p,i) + f″_i(ė_i)`)
//! and `scalar function elastic isotropic | orthotropic` (`K = 0`, `f′_i` only); with a
//! [`TimeVariance`], its `linear time variant viscoelastic generic` (`K`, `V` times the drives'
//! values `s_K(t)`, `s_V(t)` at the state).

use nalgebra::{Matrix6, Vector6};

use crate::element::contract::ElementState;
use crate::element::time_variant_law::{scales_of, TimeVariance};
use crate::element::LawFunctions;

/// Linear viscoelastic 6x6 section law [N, N m², N s, N m² s], with a constant prestrain
/// `e_p` and prestress `f_p` (MBDyn's `prestrain`, `prestress`), and the per-component
/// scalar functions of a nonlinear law.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionLaw {
    pub stiffness: Matrix6<f64>,
    pub viscosity: Matrix6<f64>,
    pub prestrain: Vector6<f64>,
    pub prestress: Vector6<f64>,
    pub functions: LawFunctions,
    /// The drives scaling `K` and `V` in time (`None`: constant).
    pub time_variance: Option<TimeVariance>,
}

impl SectionLaw {
    pub fn elastic(stiffness: Matrix6<f64>) -> Self {
        Self::viscoelastic(stiffness, Matrix6::zeros())
    }

    pub fn viscoelastic(stiffness: Matrix6<f64>, viscosity: Matrix6<f64>) -> Self {
        SectionLaw { stiffness, viscosity, prestrain: Vector6::zeros(), prestress: Vector6::zeros(), functions: LawFunctions::default(), time_variance: None }
    }

    /// Diagonal section: axial EA, shear GA₂ GA₃, torsional GJ, bending EJ₂ EJ₃.
    pub fn diagonal(ea: f64, ga2: f64, ga3: f64, gj: f64, ej2: f64, ej3: f64) -> Self {
        Self::elastic(Matrix6::from_diagonal(&Vector6::new(ea, ga2, ga3, gj, ej2, ej3)))
    }

    /// The law with the nonlinear terms `functions` (6 components, or fewer from the first).
    pub fn with_functions(mut self, functions: LawFunctions) -> Self {
        self.functions = functions;
        self
    }

    /// The law whose `K` and `V` are scaled in time by `variance`'s drives.
    pub fn with_time_variance(mut self, variance: Option<TimeVariance>) -> Self {
        self.time_variance = variance;
        self
    }

    /// Whether a drive of the law reads the model's state.
    pub fn reads_state(&self) -> bool {
        self.time_variance.as_ref().is_some_and(TimeVariance::reads_state)
    }

    /// Whether forces depend on strain rates.
    pub fn is_viscous(&self) -> bool {
        self.viscosity.iter().any(|v| *v != 0.0) || self.functions.is_viscous()
    }

    /// The generalized force at the state `st` (the time of a time-variant law's drives),
    /// strain `e` and strain rate `ė` (rate terms only when given), with its tangents `∂/∂e`
    /// and `∂/∂ė` (the drives held).
    pub fn evaluate_in(&self, st: &dyn ElementState, e: &Vector6<f64>, rate: Option<&Vector6<f64>>) -> (Vector6<f64>, Matrix6<f64>, Matrix6<f64>) {
        self.evaluate_scaled(scales_of(self.time_variance.as_ref(), st), e, rate)
    }

    /// The generalized force alone at the state `st` (what a residual needs): the first
    /// value of [`SectionLaw::evaluate_in`], by the same operations, without forming the
    /// tangents (a constant law's `K`, `V` are not copied: `1 · K` is `K`).
    pub fn force_in(&self, st: &dyn ElementState, e: &Vector6<f64>, rate: Option<&Vector6<f64>>) -> Vector6<f64> {
        let (sk, sc) = scales_of(self.time_variance.as_ref(), st);
        let elastic = e - self.prestrain;
        let mut f = if sk == 1.0 { self.stiffness * elastic } else { (sk * self.stiffness) * elastic } + self.prestress;
        if let Some(r) = rate {
            f += if sc == 1.0 { self.viscosity * r } else { (sc * self.viscosity) * r };
        }
        for i in 0..self.functions.len().min(6) {
            let r = rate.map_or(0.0, |r| r[i]);
            f[i] += self.functions.component(i, elastic[i], r).0;
        }
        f
    }

    /// [`SectionLaw::evaluate_in`] with a time-variant law's drives at 1 (a constant law's
    /// force: a unit test of the law alone).
    pub fn evaluate(&self, e: &Vector6<f64>, rate: Option<&Vector6<f64>>) -> (Vector6<f64>, Matrix6<f64>, Matrix6<f64>) {
        self.evaluate_scaled((1.0, 1.0), e, rate)
    }

    /// The law with `K`, `V` scaled by `(s_K, s_V)`.
    fn evaluate_scaled(&self, (sk, sc): (f64, f64), e: &Vector6<f64>, rate: Option<&Vector6<f64>>) -> (Vector6<f64>, Matrix6<f64>, Matrix6<f64>) {
        let elastic = e - self.prestrain;
        let (mut k, mut c) = (sk * self.stiffness, sc * self.viscosity);
        let mut f = k * elastic + self.prestress;
        if let Some(r) = rate {
            f += c * r;
        }
        for i in 0..self.functions.len().min(6) {
            let r = rate.map_or(0.0, |r| r[i]);
            let (v, dk, dc) = self.functions.component(i, elastic[i], r);
            f[i] += v;
            k[(i, i)] += dk;
            c[(i, i)] += dc;
        }
        (f, k, c)
    }
}
