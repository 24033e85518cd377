//! The 6x6 section law of a beam evaluation point: generalized forces
//! `[F; M] = K ([ε; κ] − e_p) + V [ε̇; κ̇] + f_p` in the section frame (axis 1 along the beam; ε axial and
//! shear strains, κ torsional and bending curvatures). MBDyn's `linear elastic generic`
//! (`V = 0`), `linear elastic isotropic` (`K = k I`) and `linear viscoelastic generic`; with
//! [`LawFunctions`], its `nlsf` laws (each component also `f′_i(e_i − e_p,i) + f″_i(ė_i)`)
//! and `scalar function elastic isotropic | orthotropic` (`K = 0`, `f′_i` only).

use nalgebra::{Matrix6, Vector6};

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
}

impl SectionLaw {
    pub fn elastic(stiffness: Matrix6<f64>) -> Self {
        Self::viscoelastic(stiffness, Matrix6::zeros())
    }

    pub fn viscoelastic(stiffness: Matrix6<f64>, viscosity: Matrix6<f64>) -> Self {
        SectionLaw { stiffness, viscosity, prestrain: Vector6::zeros(), prestress: Vector6::zeros(), functions: LawFunctions::default() }
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

    /// Whether forces depend on strain rates.
    pub fn is_viscous(&self) -> bool {
        self.viscosity.iter().any(|v| *v != 0.0) || self.functions.is_viscous()
    }

    /// The generalized force at strain `e` and strain rate `ė` (rate terms only when given),
    /// with its tangents `∂/∂e` and `∂/∂ė`.
    pub fn evaluate(&self, e: &Vector6<f64>, rate: Option<&Vector6<f64>>) -> (Vector6<f64>, Matrix6<f64>, Matrix6<f64>) {
        let elastic = e - self.prestrain;
        let mut f = self.stiffness * elastic + self.prestress;
        let (mut k, mut c) = (self.stiffness, self.viscosity);
        if let Some(r) = rate {
            f += self.viscosity * r;
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
