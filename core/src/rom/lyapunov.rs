//! The matrix sign function by Newton's iteration and what it solves for balanced
//! reduction: the stable/unstable splitting of a state matrix (its spectral projector) and
//! Lyapunov equations `A X + X Aᵀ + Q = 0` (Roberts, "Linear model reduction and solution of
//! the algebraic Riccati equation by use of the sign function", Int. J. Control 32, 1980;
//! Benner and Quintana-Ortí, "Solving stable generalized Lyapunov equations with the matrix
//! sign function", Numer. Algorithms 20, 1999). Dense, O(n³) per step and quadratically
//! convergent; unlike an eigendecomposition it needs no diagonalizable matrix (a rigid-body
//! mode is a Jordan block).

use faer::Mat;

use super::dense::solve_nonsingular;
use super::RomError;

const MAX_STEPS: usize = 100;

fn frobenius(m: &Mat<f64>) -> f64 {
    m.norm_l2()
}

/// One Newton step's inverse, or an error naming what was singular.
fn inverse(z: &Mat<f64>, what: &str) -> Result<Mat<f64>, RomError> {
    let n = z.nrows();
    solve_nonsingular(z, &Mat::identity(n, n)).ok_or_else(|| RomError::Balanced(format!("{what}: an eigenvalue on the imaginary axis (the sign iteration met a singular matrix)")))
}

/// The scale `c` of a Newton step, `sqrt(‖Z⁻¹‖/‖Z‖)` (Frobenius) far from convergence, 1 near it.
fn step_scale(z: &Mat<f64>, zinv: &Mat<f64>, converging: bool) -> f64 {
    if converging { 1.0 } else { (frobenius(zinv) / frobenius(z)).sqrt() }
}

/// `sign(Z)`: `Z_{k+1} = (c Z_k + Z_k⁻¹/c)/2` until it stops changing; `Z` may have no
/// eigenvalue on the imaginary axis.
pub(crate) fn sign(z0: &Mat<f64>) -> Result<Mat<f64>, RomError> {
    let mut z = z0.clone();
    let mut change = f64::INFINITY;
    for _ in 0..MAX_STEPS {
        let zinv = inverse(&z, "the stable/unstable splitting")?;
        let c = step_scale(&z, &zinv, change < 1e-2);
        let next = (&z * faer::Scale(c) + &zinv * faer::Scale(1.0 / c)) * faer::Scale(0.5);
        change = frobenius(&(&next - &z)) / frobenius(&next);
        z = next;
        if change < 1e-13 {
            return Ok(z);
        }
    }
    Err(RomError::Balanced(format!("the sign iteration of the stable/unstable splitting did not converge in {MAX_STEPS} steps (an eigenvalue too close to the splitting line)")))
}

/// `X` with `A X + X Aᵀ + Q = 0` for a stable `A` (every eigenvalue with Re λ < 0) and
/// symmetric `Q`: `A_{k+1} = (c A_k + A_k⁻¹/c)/2`, `Q_{k+1} = (c Q_k + A_k⁻¹ Q_k A_k⁻ᵀ/c)/2`
/// converge to `−I` and `2 X`. The residual is checked.
pub(crate) fn lyapunov(a: &Mat<f64>, q: &Mat<f64>) -> Result<Mat<f64>, RomError> {
    let n = a.nrows();
    let (mut ak, mut qk) = (a.clone(), q.clone());
    let id = Mat::<f64>::identity(n, n);
    let mut converged = false;
    for _ in 0..MAX_STEPS {
        let inv = inverse(&ak, "a Lyapunov equation")?;
        let near = frobenius(&(&ak + &id)) < 1e-2 * (n as f64).sqrt();
        let c = step_scale(&ak, &inv, near);
        let qnext = (&qk * faer::Scale(c) + &inv * &qk * inv.transpose() * faer::Scale(1.0 / c)) * faer::Scale(0.5);
        ak = (&ak * faer::Scale(c) + &inv * faer::Scale(1.0 / c)) * faer::Scale(0.5);
        let change = frobenius(&(&qnext - &qk)) / frobenius(&qnext).max(f64::MIN_POSITIVE);
        qk = qnext;
        if frobenius(&(&ak + &id)) < 1e-12 * (n as f64).sqrt() && change < 1e-13 {
            converged = true;
            break;
        }
    }
    if !converged {
        return Err(RomError::Balanced(format!("a Lyapunov equation's sign iteration did not converge in {MAX_STEPS} steps (an eigenvalue too close to the imaginary axis)")));
    }
    let x = Mat::from_fn(n, n, |i, j| 0.25 * (qk[(i, j)] + qk[(j, i)]));
    let residual = frobenius(&(a * &x + &x * a.transpose() + q));
    let scale = 2.0 * frobenius(a) * frobenius(&x) + frobenius(q);
    if !(residual <= 1e-8 * scale) {
        return Err(RomError::Balanced(format!("a Lyapunov equation was solved to a relative residual of {:.1e} only (an eigenvalue too close to the imaginary axis)", residual / scale)));
    }
    Ok(x)
}

/// A similarity `T` (with `T⁻¹`) that makes `T⁻¹ A T = diag(A_s, A_r)`: `A_s` of the
/// eigenvalues for which `stable(λ)` holds, `A_r` of the others; `ns` the size of `A_s`.
/// The splitting line is halfway between the two groups' real parts; the bases are the
/// ranges of the spectral projectors `(I ∓ sign(A − σ I))/2`.
pub(crate) struct Split {
    pub t: Mat<f64>,
    pub tinv: Mat<f64>,
    pub ns: usize,
}

pub(crate) fn split(a: &Mat<f64>, stable: &[bool], eigenvalues: &[faer::c64]) -> Result<Split, RomError> {
    let n = a.nrows();
    let ns = stable.iter().filter(|s| **s).count();
    if ns == 0 || ns == n {
        return Ok(Split { t: Mat::identity(n, n), tinv: Mat::identity(n, n), ns });
    }
    let re_stable = eigenvalues.iter().zip(stable).filter(|p| *p.1).map(|p| p.0.re).fold(f64::NEG_INFINITY, f64::max);
    let re_rest = eigenvalues.iter().zip(stable).filter(|p| !*p.1).map(|p| p.0.re).fold(f64::INFINITY, f64::min);
    let sigma = 0.5 * (re_stable + re_rest);
    let s = sign(&(a - Mat::<f64>::identity(n, n) * faer::Scale(sigma)))?;
    let id = Mat::<f64>::identity(n, n);
    let basis = |p: Mat<f64>, k: usize| -> Result<Mat<f64>, RomError> {
        let svd = p.svd().map_err(|_| RomError::Balanced("the SVD of a spectral projector did not converge".into()))?;
        Ok(svd.U().get(.., ..k).to_owned())
    };
    let vs = basis((&id - &s) * faer::Scale(0.5), ns)?;
    let vr = basis((&id + &s) * faer::Scale(0.5), n - ns)?;
    let t = Mat::from_fn(n, n, |i, j| if j < ns { vs[(i, j)] } else { vr[(i, j - ns)] });
    let tinv = solve_nonsingular(&t, &id).ok_or_else(|| RomError::Balanced("the stable and the other invariant subspaces are not independent".into()))?;
    let blocks = &tinv * a * &t;
    let off = (0..n).flat_map(|i| (0..n).map(move |j| (i, j))).filter(|&(i, j)| (i < ns) != (j < ns)).map(|(i, j)| blocks[(i, j)].abs()).fold(0.0, f64::max);
    if !(off <= 1e-8 * a.norm_max()) {
        return Err(RomError::Balanced(format!("the stable part could not be split off (coupling {:.1e} of the largest entry of A): eigenvalues too close to the splitting line Re λ = {sigma:.6e} rad/s", off / a.norm_max())));
    }
    Ok(Split { t, tinv, ns })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2x2 with a Jordan block at −1: X of A X + X Aᵀ + B Bᵀ = 0 for A = [[−1, 1], [0, −1]],
    /// B = (0, 1)ᵀ is [[1/4, 1/4], [1/4, 1/2]] (solved by hand, elementwise).
    #[test]
    fn lyapunov_of_a_jordan_block() {
        let a = Mat::from_fn(2, 2, |i, j| [[-1.0, 1.0], [0.0, -1.0]][i][j]);
        let q = Mat::from_fn(2, 2, |i, j| if i == 1 && j == 1 { 1.0 } else { 0.0 });
        let x = lyapunov(&a, &q).unwrap();
        let exact = [[0.25, 0.25], [0.25, 0.5]];
        for i in 0..2 {
            for j in 0..2 {
                assert!((x[(i, j)] - exact[i][j]).abs() < 1e-14, "{x:?}");
            }
        }
    }

    /// A rigid-body Jordan block [[0, 1], [0, 0]] beside a damped mode: the split is
    /// block diagonal and keeps both spectra.
    #[test]
    fn split_keeps_a_rigid_body_block_apart() {
        let a = Mat::from_fn(4, 4, |i, j| [[0.0, 1.0, 0.3, 0.0], [0.0, 0.0, 0.0, 0.2], [0.0, 0.0, -0.5, 10.0], [0.0, 0.0, -10.0, -0.5]][i][j]);
        let ev = a.as_ref().eigenvalues().unwrap();
        let stable: Vec<bool> = ev.iter().map(|l| l.re < -0.1).collect();
        let sp = split(&a, &stable, &ev).unwrap();
        assert_eq!(sp.ns, 2);
        let blocks = &sp.tinv * &a * &sp.t;
        let s = blocks.get(..2, ..2).to_owned();
        // The stable block's trace and determinant are those of −0.5 ± 10j.
        assert!((s[(0, 0)] + s[(1, 1)] + 1.0).abs() < 1e-12);
        assert!((s[(0, 0)] * s[(1, 1)] - s[(0, 1)] * s[(1, 0)] - 100.25).abs() < 1e-10);
        assert!(blocks.get(2.., 2..).norm_max() > 0.1 && blocks.get(..2, 2..).norm_max() < 1e-12);
    }
}
