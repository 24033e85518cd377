//! The 6x6 section law of a beam evaluation point: generalized forces
//! `[F; M] = K ([ε; κ] − e_p) + V [ε̇; κ̇] + f_p` in the section frame (axis 1 along the beam; ε axial and
//! shear strains, κ torsional and bending curvatures). MBDyn's `linear elastic generic`
//! (`V = 0`), `linear elastic isotropic` (`K = k I`) and `linear viscoelastic generic`.

use nalgebra::{Matrix6, Vector6};

/// Linear viscoelastic 6x6 section law [N, N m², N s, N m² s], with a constant prestrain
/// `e_p` and prestress `f_p` (MBDyn's `prestrain`, `prestress`).
#[derive(Clone, Debug, PartialEq)]
pub struct SectionLaw {
    pub stiffness: Matrix6<f64>,
    pub viscosity: Matrix6<f64>,
    pub prestrain: Vector6<f64>,
    pub prestress: Vector6<f64>,
}

impl SectionLaw {
    pub fn elastic(stiffness: Matrix6<f64>) -> Self {
        Self::viscoelastic(stiffness, Matrix6::zeros())
    }

    pub fn viscoelastic(stiffness: Matrix6<f64>, viscosity: Matrix6<f64>) -> Self {
        SectionLaw { stiffness, viscosity, prestrain: Vector6::zeros(), prestress: Vector6::zeros() }
    }

    /// Diagonal section: axial EA, shear GA₂ GA₃, torsional GJ, bending EJ₂ EJ₃.
    pub fn diagonal(ea: f64, ga2: f64, ga3: f64, gj: f64, ej2: f64, ej3: f64) -> Self {
        Self::elastic(Matrix6::from_diagonal(&Vector6::new(ea, ga2, ga3, gj, ej2, ej3)))
    }

    /// Whether forces depend on strain rates.
    pub fn is_viscous(&self) -> bool {
        self.viscosity.iter().any(|v| *v != 0.0)
    }
}
