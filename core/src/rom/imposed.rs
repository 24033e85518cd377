//! Imposed motion and transmissibility (paper eqs. 96–100).
//!
//! The motion `z_e` of an excitation point is imposed by the collocated forces `u_e` that
//! produce it: with `H(s)` the transfer matrix from `[u, u_e]` to `[z, z_e]`,
//! `z_e = H_ee u_e` (eq. 98), `u_e = H_ee⁻¹ z_e` (eq. 99) and
//! `z = H_ze H_ee⁻¹ z_e` (eq. 100). The excitation ports are the last `n` inputs and the last
//! `n` outputs of the system (forces conjugate to the imposed displacements).

use faer::linalg::solvers::Solve;
use faer::{c64, Mat};

use super::dense::solve_nonsingular;
use super::{OrdinaryRom, RomError};

/// Eq. 100 at one frequency: `H_ze H_ee⁻¹` from a transfer matrix whose last `n` inputs and
/// outputs are the excitation's (the result is regular outputs × imposed components).
/// `None` when `H_ee` is singular there (the imposed motion cannot be produced).
pub fn transmissibility(h: &Mat<c64>, n: usize) -> Option<Mat<c64>> {
    let (no, ni) = (h.nrows() - n, h.ncols() - n);
    let hze = h.get(..no, ni..).to_owned();
    let hee = h.get(no.., ni..).to_owned();
    let lu = hee.full_piv_lu();
    let u = lu.U();
    let (big, small) = (0..n).map(|i| u[(i, i)].norm()).fold((0.0f64, f64::INFINITY), |(b, s), x| (b.max(x), s.min(x)));
    if !(small > big * 1e3 * n as f64 * f64::EPSILON) {
        return None;
    }
    // T H_ee = H_ze  ⇔  H_eeᵀ Tᵀ = H_zeᵀ.
    let x = hee.transpose().to_owned().full_piv_lu().solve(hze.transpose().to_owned());
    Some(x.transpose().to_owned())
}

/// The imposed-motion state-space model and the feedthrough of `ż_e` it dropped
/// (`|C P| / (|C| |P|)`, Frobenius norms; at most 1e-8, else it is an error).
#[derive(Clone, Debug)]
pub struct ImposedModel {
    /// `ẋ = A x + B z_e`, `z = C x + D z_e`.
    pub rom: OrdinaryRom,
    pub dropped_rate_feedthrough: f64,
}

fn null_space(l: &Mat<f64>) -> Result<Mat<f64>, RomError> {
    let n = l.ncols();
    let svd = l.svd().map_err(|_| RomError::SingularStatic("[C_e; C_e A] (its SVD did not converge)"))?;
    let (s, v) = (svd.S(), svd.V());
    let r = l.nrows().min(n);
    let smax = (0..r).map(|i| s[i]).fold(0.0, f64::max);
    if (0..r).any(|i| !(s[i] > smax * 1e-10)) || l.nrows() > n {
        return Err(RomError::SingularStatic("[C_e; C_e A] (the imposed components are not independent)"));
    }
    Ok(v.get(.., l.nrows()..).to_owned())
}

impl OrdinaryRom {
    /// A proper state-space model from the imposed displacements `z_e` (the last `n` outputs,
    /// driven by the last `n` inputs) to the other outputs, equivalent to eq. 100.
    ///
    /// With `C_e B_e = 0` (displacements respond to forces through at least two integrations)
    /// `u_e = (C_e A B_e)⁻¹ (z̈_e − C_e A² x)` keeps `C_e x = z_e`; the constrained dynamics
    /// `A_c = A − P C_e A²`, `P = B_e (C_e A B_e)⁻¹`, in the coordinates
    /// `ξ = x − A_c P z_e − P ż_e` read `ξ̇ = A_c ξ + A_c² P z_e`, `z = C ξ + C A_c P z_e`
    /// (`C P` must vanish). `ξ` stays in the kernel of `[C_e; C_e A]`, invariant under `A_c`;
    /// restricted to it the model is minimal in those directions (the double integrators of
    /// the imposed motion are gone).
    pub fn imposed_motion(&self, n: usize) -> Result<ImposedModel, RomError> {
        let (no, ni) = (self.c.nrows() - n, self.b.ncols() - n);
        let be = self.b.get(.., ni..).to_owned();
        let ce = self.c.get(no.., ..).to_owned();
        let c = self.c.get(..no, ..).to_owned();
        let scale = |m: &Mat<f64>| m.norm_max().max(f64::MIN_POSITIVE);
        let de = self.d.get(.., ni..).to_owned();
        if de.norm_max() > 1e-9 * scale(&self.c) * scale(&be) {
            return Err(RomError::Imposed("the ROM has a direct feedthrough from the excitation forces (statically residualized states): build it without residualization".into()));
        }
        // C_e B_e = 0 (relative degree 2): exact for a full set of modes of a mechanical
        // system, approximate for a truncated damped ROM.
        let ceb = (&ce * &be).norm_l2() / (ce.norm_l2() * be.norm_l2()).max(f64::MIN_POSITIVE);
        if ceb > 1e-8 {
            return Err(RomError::Imposed(format!("C_e B_e is {ceb:.1e} of |C_e| |B_e|, not zero: the ROM lets the imposed displacements jump under their forces (its modes do not carry the excitation point's inertia); keep more modes (or all), and impose displacements or rotations")));
        }
        let a = &self.a;
        let ceab = &ce * a * &be;
        let p_t = solve_nonsingular(&ceab.transpose().to_owned(), &be.transpose().to_owned()).ok_or(RomError::SingularStatic("C_e A B_e"))?;
        let p = p_t.transpose().to_owned();
        let ac = a - &p * &ce * a * a;
        let cea = &ce * a;
        let l = Mat::from_fn(2 * n, a.nrows(), |i, j| if i < n { ce[(i, j)] } else { cea[(i - n, j)] });
        let q = null_space(&l)?;
        let acp = &ac * &p;
        let cp = &c * &p;
        let d = &c * &acp;
        let dropped = cp.norm_l2() / (c.norm_l2() * p.norm_l2()).max(f64::MIN_POSITIVE);
        if dropped > 1e-8 {
            return Err(RomError::Imposed(format!("an output responds to the excitation forces directly (|C P| = {dropped:.1e} of |C| |P|): imposed-motion models take displacement and rotation outputs away from the excitation point")));
        }
        let rom = OrdinaryRom {
            a: q.transpose() * &ac * &q,
            b: q.transpose() * &ac * &acp,
            c: &c * &q,
            d,
            eigenvalues: Vec::new(),
            input_names: self.output_names[no..].to_vec(),
            output_names: self.output_names[..no].to_vec(),
        };
        let mut eig = rom.a.eigenvalues().map_err(|_| RomError::SingularStatic("A of the imposed-motion model (eigenvalues did not converge)"))?;
        eig.sort_by(|x, y| x.norm().total_cmp(&y.norm()).then(y.im.total_cmp(&x.im)));
        Ok(ImposedModel { rom: OrdinaryRom { eigenvalues: eig, ..rom }, dropped_rate_feedthrough: dropped })
    }
}
