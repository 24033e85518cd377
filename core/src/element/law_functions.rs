//! The per-component scalar functions of MBDyn's nonlinear constitutive laws (input manual,
//! "General", §Scalar function elastic, §nlsf viscoelastic): component `i` of the generalized
//! force gains `f′_i(ε_i − ε_p,i) + f″_i(ε̇_i)` and its tangents `f′_i′` (stiffness) and
//! `f″_i′` (viscosity) on the diagonal (constltp_nlsf.cc, ScalarFunctionsImpl.cc's
//! `ScalarFunctionIsotropicCL`, `…OrthotropicCL`). A `scalar function elastic isotropic`
//! law is the same function `f′` on every component, `orthotropic` one per component (or
//! none), with no linear part.

use super::drive::ScalarFunction;

/// `f′_i` and `f″_i` of each component (`None`: no term); both empty for a linear law.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LawFunctions {
    /// `f′_i`, of the component's strain less its prestrain.
    pub elastic: Vec<Option<ScalarFunction>>,
    /// `f″_i`, of the component's strain rate.
    pub viscous: Vec<Option<ScalarFunction>>,
}

impl LawFunctions {
    /// Whether no component has a function.
    pub fn is_empty(&self) -> bool {
        self.elastic.iter().chain(&self.viscous).all(Option::is_none)
    }

    /// Whether a function of a strain rate is present.
    pub fn is_viscous(&self) -> bool {
        self.viscous.iter().any(Option::is_some)
    }

    /// The largest number of components either list holds.
    pub fn len(&self) -> usize {
        self.elastic.len().max(self.viscous.len())
    }

    /// Component `i`'s term `f′_i(e) + f″_i(ė)` and its derivatives `f′_i′(e)`, `f″_i′(ė)`.
    pub fn component(&self, i: usize, e: f64, rate: f64) -> (f64, f64, f64) {
        let (mut value, mut stiffness, mut viscosity) = (0.0, 0.0, 0.0);
        if let Some(Some(f)) = self.elastic.get(i) {
            let (v, d) = f.value_and_derivative(e);
            value += v;
            stiffness = d;
        }
        if let Some(Some(f)) = self.viscous.get(i) {
            let (v, d) = f.value_and_derivative(rate);
            value += v;
            viscosity = d;
        }
        (value, stiffness, viscosity)
    }

    /// The same functions as components `offset .. offset + len` of a law of `dim`
    /// components (a hinge's 3-D law is the rotation block, 3..6, of a 6-D one).
    pub fn placed(&self, offset: usize, dim: usize) -> Self {
        let place = |v: &Vec<Option<ScalarFunction>>| {
            let mut out = vec![None; dim];
            for (i, f) in v.iter().enumerate() {
                out[offset + i] = f.clone();
            }
            out
        };
        LawFunctions { elastic: place(&self.elastic), viscous: place(&self.viscous) }
    }
}
