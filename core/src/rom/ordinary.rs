//! SVD residualization of a descriptor ROM into `ẋ = A x + B u`, `z = C x + D u`
//! (eqs. 51–63).

use faer::{c64, Mat};

use super::dense::{solve_nonsingular, transfer};
use super::{DescriptorRom, RomError};
use crate::linear::rad_per_s;

/// Ordinary state-space ROM with a direct transmission term.
#[derive(Clone, Debug)]
pub struct OrdinaryRom {
    pub a: Mat<f64>,
    pub b: Mat<f64>,
    pub c: Mat<f64>,
    pub d: Mat<f64>,
    pub eigenvalues: Vec<c64>,
    pub input_names: Vec<String>,
    pub output_names: Vec<String>,
}

impl DescriptorRom {
    /// `E = U Σ Vᵀ` (eq. 51); singular values above `s ε σ_max` are dynamic, the rest static.
    /// The static coordinates are eliminated with `(U_sᵀ A V_s)⁻¹` (eqs. 57–63).
    pub fn to_ordinary(&self) -> Result<OrdinaryRom, RomError> {
        let s = self.e.nrows();
        let svd = self.e.svd().map_err(|_| RomError::SingularStatic("E (its SVD did not converge)"))?;
        let (u, sv, v) = (svd.U().to_owned(), svd.S(), svd.V().to_owned());
        let sigma: Vec<f64> = (0..s).map(|i| sv[i]).collect();
        let smax = sigma.iter().copied().fold(0.0, f64::max);
        let rank = sigma.iter().filter(|&&x| x > smax * s as f64 * f64::EPSILON).count();
        let ud = u.get(.., ..rank).to_owned();
        let us = u.get(.., rank..).to_owned();
        let vd = v.get(.., ..rank).to_owned();
        let vs = v.get(.., rank..).to_owned();
        let sinv = Mat::from_fn(rank, rank, |i, j| if i == j { 1.0 / sigma[i] } else { 0.0 });

        // M = U_sᵀ A V_s; X = M⁻¹ U_sᵀ [A V_d, B]  (eq. 57).
        let m = us.transpose() * &self.a * &vs;
        let rhs_a = us.transpose() * &self.a * &vd;
        let rhs_b = us.transpose() * &self.b;
        let xa = solve_nonsingular(&m, &rhs_a).ok_or(RomError::SingularStatic("U_sᵀ A V_s"))?;
        let xb = solve_nonsingular(&m, &rhs_b).ok_or(RomError::SingularStatic("U_sᵀ A V_s"))?;
        let av_s = &self.a * &vs;
        // Eqs. 60–63.
        let a = &sinv * ud.transpose() * (&self.a * &vd - &av_s * &xa);
        let b = &sinv * ud.transpose() * (&self.b - &av_s * &xb);
        let mut c = &self.c * (&vd - &vs * &xa);
        let mut d = -(&self.c * &vs * &xb);
        if let Some(cv) = &self.c_rate {
            // Rate outputs: z = C_v ẋ_desc with ẋ_desc = (V_d − V_s X_a) ẋ − V_s X_b u̇;
            // the ordinary form has no u̇, so its term must vanish (no static states).
            let d_udot = -(cv * &vs * &xb);
            let scale = (cv * &vs).norm_max().max(f64::MIN_POSITIVE) * xb.norm_max().max(1.0);
            if d_udot.norm_max() > 1e-9 * scale {
                return Err(RomError::ImproperRate);
            }
            let cr = cv * (&vd - &vs * &xa);
            c += &cr * &a;
            d += &cr * &b;
        }
        // The SVD's V_d is any orthonormal basis of E's range: on a kept block E ≈ I it
        // permuted and flipped the modal coordinates (examples/mass_on_springs.mbd, 4 modes:
        // state 1 named 'mode 1 re' was mode 7's). The kept descriptor states are
        // x_k = P x with P = (V_d − V_s X_a) on their rows (eq. 58); back in them, the
        // ordinary states are the kept modes' coordinates their names say.
        let kept = s - self.static_states;
        let (a, b, c) = match (rank == kept).then(|| (&vd - &vs * &xa).get(..kept, ..).to_owned()) {
            Some(p) => {
                // A' = P A P⁻¹, C' = C P⁻¹ by solving with Pᵀ: A'ᵀ = P⁻ᵀ (P A)ᵀ, C'ᵀ = P⁻ᵀ Cᵀ.
                let pt = p.transpose().to_owned();
                match (solve_nonsingular(&pt, &(&p * &a).transpose().to_owned()), solve_nonsingular(&pt, &c.transpose().to_owned())) {
                    (Some(at), Some(ct)) => (at.transpose().to_owned(), &p * &b, ct.transpose().to_owned()),
                    _ => (a, b, c),
                }
            }
            None => (a, b, c),
        };
        Ok(OrdinaryRom {
            a,
            b,
            c,
            d,
            eigenvalues: self.eigenvalues.clone(),
            input_names: self.input_names.clone(),
            output_names: self.output_names.clone(),
        })
    }
}

impl OrdinaryRom {
    /// `C (jω I − A)⁻¹ B + D` at each frequency [Hz].
    pub fn frequency_response(&self, freq_hz: &[f64]) -> Vec<Mat<c64>> {
        let n = self.a.nrows();
        let id = Mat::<f64>::identity(n, n);
        let minus_a = -&self.a;
        freq_hz.iter().map(|f| transfer(rad_per_s(*f), &id, &minus_a, &self.b, &self.c, Some(&self.d))).collect()
    }

    /// Static gain `D − C A⁻¹ B`.
    pub fn static_gain(&self) -> Result<Mat<f64>, RomError> {
        let x = solve_nonsingular(&self.a, &self.b).ok_or(RomError::SingularStatic("A of the ROM"))?;
        Ok(&self.d - &self.c * &x)
    }
}
