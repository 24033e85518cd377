//! The linearized DAE `F_yd Δẏ + F_y Δy = B̃ u`, `z = C̃ Δy` (eqs. 38–40).

use faer::{Col, Mat};

use crate::model::ConstraintForm;

/// How the Jacobians of the DAE residual were supplied.
///
/// Both carry the same information: `J(c) = F_yd + c F_y` is affine in `c`, so
/// `F_yd = (J + J*)/2` and `F_y = (J − J*)/(2c)` (eqs. 13–16) are exact.
#[derive(Clone, Debug)]
pub enum Jacobians {
    /// `F_/ẏ` and `F_/y` directly.
    Derivatives { fyd: Mat<f64>, fy: Mat<f64> },
    /// `J = F_yd + c F_y` and `J* = F_yd − c F_y` for a coefficient `c = dCoef` (eqs. 13–14).
    Coefficient { j: Mat<f64>, jstar: Mat<f64>, dcoef: f64 },
}

/// A linear DAE with its input and output maps.
#[derive(Clone, Debug)]
pub struct LinearDae {
    pub jacobians: Jacobians,
    /// `B̃`: rows = equations, columns = inputs (`−ΔF = B̃ u`, eq. 38).
    pub b: Mat<f64>,
    /// `C̃`: rows = outputs, columns = unknowns (`z = C̃ Δy`, eq. 39).
    pub c: Mat<f64>,
    pub unknown_names: Vec<String>,
    pub input_names: Vec<String>,
    pub output_names: Vec<String>,
    /// Layout of the constraint equations, when known (multibody models report it).
    pub constraint_form: Option<ConstraintForm>,
    /// Indices of the Lagrange multipliers (each also the index of its constraint
    /// equation), when known.
    pub multipliers: Vec<usize>,
    /// `C̃_v` of rate outputs (velocity sensors): `z = C̃ Δy + C̃_v Δẏ`; rows = outputs,
    /// columns = unknowns. `None` when every output is a displacement or rotation.
    pub c_rate: Option<Mat<f64>>,
}

/// `F_yd = (J + J*)/2`, `F_y = (J − J*)/(2c)` (eqs. 15–16).
pub fn derivatives_from_coefficient(j: &Mat<f64>, jstar: &Mat<f64>, dcoef: f64) -> (Mat<f64>, Mat<f64>) {
    let fyd = (j + jstar) * faer::Scale(0.5);
    let fy = (j - jstar) * faer::Scale(0.5 / dcoef);
    (fyd, fy)
}

/// `J = F_yd + c F_y`, `J* = F_yd − c F_y` (eqs. 13–14).
pub fn coefficient_from_derivatives(fyd: &Mat<f64>, fy: &Mat<f64>, dcoef: f64) -> (Mat<f64>, Mat<f64>) {
    let j = fyd + fy * faer::Scale(dcoef);
    let jstar = fyd - fy * faer::Scale(dcoef);
    (j, jstar)
}

impl Jacobians {
    /// Number of equations (= unknowns).
    pub fn dim(&self) -> usize {
        match self {
            Jacobians::Derivatives { fyd, .. } => fyd.nrows(),
            Jacobians::Coefficient { j, .. } => j.nrows(),
        }
    }

    /// `(F_yd, F_y)`, computed by eqs. 15–16 when J and J* were given.
    pub fn derivatives(&self) -> (Mat<f64>, Mat<f64>) {
        match self {
            Jacobians::Derivatives { fyd, fy } => (fyd.clone(), fy.clone()),
            Jacobians::Coefficient { j, jstar, dcoef } => derivatives_from_coefficient(j, jstar, *dcoef),
        }
    }

    /// The given dCoef, or `‖F_yd‖_F / ‖F_y‖_F`. The eigenanalysis uses the latter only when it
    /// cannot centre the Λ form on the spectrum (`ModalAnalysis::of_dae` takes the geometric
    /// mean of the dynamic part's |λ|, the undeflated route the balanced pencil's norms): the
    /// stiffest entry decides it, 8.2e-11 s on a 32-element beam (issue 30).
    pub fn dcoef(&self) -> f64 {
        match self {
            Jacobians::Coefficient { dcoef, .. } => *dcoef,
            Jacobians::Derivatives { fyd, fy } => {
                let (a, b) = (fyd.norm_l2(), fy.norm_l2());
                if a > 0.0 && b > 0.0 && (a / b).is_finite() { a / b } else { 1.0 }
            }
        }
    }
}

impl LinearDae {
    /// The matrix of the static response `S Δy = B̃ u` (`ẏ = 0`): [`Self::plain_derivatives`]'s
    /// `F_y` (eq. 29's), which in the form of eq. 30 takes the constraint rows and multiplier
    /// columns from `F_yd` (multipliers as derivatives, constraint rows scaled by 1/c).
    pub fn static_matrix(&self) -> Mat<f64> {
        self.plain_derivatives().1
    }

    /// `F_yd` and `F_y` in the form of eq. 29 (plain constraints): in the form of eq. 30 the
    /// constraint rows and multiplier columns sit in `F_yd` (`jω F_yd + F_y` is then eq. 29's
    /// with those rows and columns multiplied by `jω`), so they move to `F_y`. Responses of
    /// ports off those rows and columns (forces on equilibrium rows, motions and modal
    /// coordinates read) are the same for `ω ≠ 0`, and at `ω = 0` this pencil is the static
    /// matrix, where eq. 30's loses the constraints (NaN at f = 0 before).
    pub fn plain_derivatives(&self) -> (Mat<f64>, Mat<f64>) {
        let (mut fyd, mut fy) = self.jacobians.derivatives();
        if self.constraint_form == Some(ConstraintForm::Scaled) {
            for &k in &self.multipliers {
                for i in 0..fy.nrows() {
                    fy[(i, k)] = fyd[(i, k)];
                    fyd[(i, k)] = 0.0;
                }
                for j in 0..fy.ncols() {
                    fy[(k, j)] = fyd[(k, j)];
                    fyd[(k, j)] = 0.0;
                }
            }
        }
        (fyd, fy)
    }

    /// The real eigenvalue of `(λ F_yd + F_y) v = 0` nearest `lambda` [rad/s] and its right
    /// vector (unit norm), by inverse iteration: `(σ F_yd + F_y)⁻¹ F_yd v = v / (σ − λ)`
    /// with the shift `σ = lambda` (one LU, a few solves). `None` when the shifted matrix is
    /// exactly singular or the relative residual `‖(λ F_yd + F_y) v‖ / (|λ| ‖F_yd‖ + ‖F_y‖)`
    /// is not below 1e-8 after 30 iterations (no real eigenvalue near the shift); the
    /// iteration stops earlier at 1e-14.
    pub fn real_mode_near(&self, lambda: f64) -> Option<(f64, Col<f64>)> {
        use faer::linalg::solvers::Solve;
        let (fyd, fy) = self.jacobians.derivatives();
        let n = fyd.nrows();
        let lu = (&fyd * faer::Scale(lambda) + &fy).partial_piv_lu();
        let mut x = Col::<f64>::from_fn(n, |i| 1.0 + (i % 7) as f64 * 0.1);
        let mut estimate = lambda;
        let mut residual = f64::INFINITY;
        for _ in 0..30 {
            let y = lu.solve(&fyd * &x);
            let (xy, yy) = (x.transpose() * &y, y.norm_l2());
            if !(yy.is_finite() && yy > 0.0) {
                return None;
            }
            // x ≈ v, y ≈ v / (σ − λ): λ ≈ σ − (xᵀ x)/(xᵀ y).
            if xy != 0.0 {
                estimate = lambda - (x.norm_l2().powi(2)) / xy;
            }
            x = y * faer::Scale(1.0 / yy);
            residual = (&fyd * &x * faer::Scale(estimate) + &fy * &x).norm_l2() / (estimate.abs() * fyd.norm_l2() + fy.norm_l2());
            if residual < 1e-14 {
                break;
            }
        }
        (residual < 1e-8).then_some((estimate, x))
    }

    /// Number of equations (= unknowns).
    pub fn dim(&self) -> usize {
        self.jacobians.dim()
    }
    pub fn num_inputs(&self) -> usize {
        self.b.ncols()
    }
    pub fn num_outputs(&self) -> usize {
        self.c.nrows()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `λ v₁ − v₂ = 0`, `λ v₂ − a² v₁ = 0` (an inverted pendulum, λ = ±a): inverse
    /// iteration from a shift 10 % off finds each real eigenvalue to 1e-10 and its vector.
    #[test]
    fn real_mode_near_finds_the_nearest_real_eigenvalue() {
        let a = 3.130527;
        let fy = Mat::from_fn(2, 2, |i, j| [[0.0, -1.0], [-a * a, 0.0]][i][j]);
        let dae = LinearDae {
            jacobians: Jacobians::Derivatives { fyd: Mat::identity(2, 2), fy },
            b: Mat::zeros(2, 0),
            c: Mat::zeros(0, 2),
            unknown_names: vec!["q".into(), "p".into()],
            input_names: Vec::new(),
            output_names: Vec::new(),
            constraint_form: None,
            multipliers: Vec::new(),
            c_rate: None,
        };
        for sign in [1.0, -1.0] {
            let (l, v) = dae.real_mode_near(sign * 0.9 * a).unwrap();
            assert!((l - sign * a).abs() < 1e-10 * a, "{l}");
            // v ∝ (1, λ).
            assert!((v[1] / v[0] - l).abs() < 1e-8 * a, "{v:?}");
        }
    }

    /// Eqs. 13–16 are exact inverses of each other (J is affine in c).
    #[test]
    fn linearization_algebra_round_trips() {
        let fyd = Mat::from_fn(4, 4, |i, j| (i * 4 + j) as f64 * 0.3 - 1.0);
        let fy = Mat::from_fn(4, 4, |i, j| ((i + 2 * j) % 5) as f64 + 0.5);
        let c = 1e-3;
        let (j, jstar) = coefficient_from_derivatives(&fyd, &fy, c);
        let (fyd2, fy2) = derivatives_from_coefficient(&j, &jstar, c);
        // Rounding only: entries are O(1) to O(10), F_y recovered through a 1/(2c) factor.
        assert!((&fyd2 - &fyd).norm_max() < 1e-14);
        assert!((&fy2 - &fy).norm_max() < 1e-10);
    }
}
