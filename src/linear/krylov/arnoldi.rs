//! The Arnoldi expansion of a Krylov–Schur basis (see [`super::iteration`]): each new
//! direction is the operator applied to the last basis vector, orthogonalized against the
//! basis by classical Gram–Schmidt twice; for a real basis the second pass of a step is
//! delayed and done together with the next step's first (one sweep over the basis instead
//! of two), and a breakdown restarts from a fresh random direction.

use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{c64, Col, ColMut, ColRef, Mat};

use super::gram_schmidt::Sweeper;
use super::iteration::{columns, purified, Scalar};
use crate::linear::sparse::{contiguous, contiguous_mut};
use super::KrylovError;

/// The state of an Arnoldi expansion: the basis `v` (`n x (m + 1)`), the Hessenberg matrix
/// `h` (`(m + 1) x m`), the scratch of the Gram–Schmidt steps.
pub(super) struct Arnoldi<T: Scalar> {
    pub(super) n: usize,
    pub(super) m: usize,
    pub(super) v: Mat<T>,
    pub(super) h: Mat<T>,
    pub(super) coef: Col<T>,
    pub(super) scratch: Col<T>,
    pub(super) applications: usize,
    pub(super) seed: u64,
    pub(super) sweeper: Sweeper,
}

fn all_finite<T: Scalar>(w: ColRef<'_, T>) -> Result<(), KrylovError> {
    if w.iter().all(|x| x.to_c64().re.is_finite() && x.to_c64().im.is_finite()) {
        Ok(())
    } else {
        Err(KrylovError::Breakdown("the operator returned non-finite values".into()))
    }
}

/// `w ← T v_j` into column `j + 1`.
fn apply<T: Scalar>(a: &mut Arnoldi<T>, op: &mut dyn FnMut(ColRef<'_, T>, ColMut<'_, T>), j: usize) -> Result<(), KrylovError> {
    let (done, mut rest) = a.v.as_mut().split_at_col_mut(j + 1);
    op(done.rb().col(j), rest.rb_mut().col_mut(0));
    a.applications += 1;
    all_finite(rest.rb().col(0))
}

/// A fresh unit direction in column `col`, orthogonal to the columns before it: a random
/// vector purified like the start vector (coupling zero, an invariant subspace was
/// reached); `false` when the purified fresh vectors lie in the basis too (the finite
/// spectrum the operator reaches is exhausted).
fn fresh_direction<T: Scalar>(a: &mut Arnoldi<T>, op: &mut dyn FnMut(ColRef<'_, T>, ColMut<'_, T>), col: usize) -> bool {
    let j = col - 1;
    for attempt in 0..3u64 {
        let Some(mut f) = purified(op, a.n, a.seed + 1000 + 7 * j as u64 + attempt, &mut a.applications) else { continue };
        let nb = T::orthogonalize(a.sweeper, a.v.as_ref().subcols(0, col), f.as_mut(), a.coef.subrows_mut(0, col), a.scratch.subrows_mut(0, col));
        if nb > 1e-8 && nb.is_finite() {
            let mut w = a.v.col_mut(col);
            w.copy_from(&f);
            for x in w.iter_mut() {
                *x = x.times(1.0 / nb);
            }
            return true;
        }
    }
    false
}

/// Column `j + 1` holds `T v_j` (with `h[.., j]` already holding `add` of its coefficients
/// when `add`): orthogonalized against columns `0..=j` by classical Gram–Schmidt twice, its
/// coefficients added to `h[.., j]`, normalized; `Some(j + 1)` (the size reached) when the
/// finite spectrum is exhausted.
fn complete_step<T: Scalar>(a: &mut Arnoldi<T>, op: &mut dyn FnMut(ColRef<'_, T>, ColMut<'_, T>), j: usize, add: bool) -> Option<usize> {
    let zero = T::from_c64(c64::new(0.0, 0.0));
    let beta = {
        let (done, mut rest) = a.v.as_mut().split_at_col_mut(j + 1);
        T::orthogonalize(a.sweeper, done.rb(), rest.rb_mut().col_mut(0), a.coef.subrows_mut(0, j + 1), a.scratch.subrows_mut(0, j + 1))
    };
    for i in 0..=j {
        let before = if add { a.h[(i, j)] } else { zero };
        a.h[(i, j)] = before + a.coef[i];
    }
    let scale_c = (0..=j).map(|i| a.h[(i, j)].to_c64().norm_sqr()).sum::<f64>().sqrt().max(beta);
    if beta <= 1e-12 * scale_c {
        // Invariant subspace: continue with a fresh direction (coupling zero).
        a.h[(j + 1, j)] = zero;
        if !fresh_direction(a, op, j + 1) {
            return Some(j + 1);
        }
    } else {
        a.h[(j + 1, j)] = T::from_c64(c64::new(beta, 0.0));
        for x in a.v.col_mut(j + 1).iter_mut() {
            *x = x.times(1.0 / beta);
        }
    }
    None
}

/// Arnoldi with classical Gram–Schmidt twice at each step (three or four reads of the basis).
pub(super) fn expand_classic<T: Scalar>(a: &mut Arnoldi<T>, op: &mut dyn FnMut(ColRef<'_, T>, ColMut<'_, T>), kept: usize) -> Result<usize, KrylovError> {
    for j in kept..a.m {
        apply(a, op, j)?;
        if let Some(size) = complete_step(a, op, j, false) {
            return Ok(size);
        }
    }
    Ok(a.m)
}

/// Column `j` holds `u`, the once-orthogonalized unit vector of step `j − 1` (`T v_{j−1} =
/// V_j h + β₁ u`, `h` in `h[0..j, j − 1]`): orthogonalized again by classical Gram–Schmidt
/// twice, `u = V_j s + α v_j`, so `T v_{j−1} = V_j (h + β₁ s) + β₁ α v_j`; `Some(j)` (the
/// size reached) when the finite spectrum is exhausted.
fn finish_delayed(a: &mut Arnoldi<f64>, op: &mut dyn FnMut(ColRef<'_, f64>, ColMut<'_, f64>), j: usize, beta1: f64) -> Option<usize> {
    let alpha = {
        let (done, mut rest) = a.v.as_mut().split_at_col_mut(j);
        f64::orthogonalize(a.sweeper, done.rb(), rest.rb_mut().col_mut(0), a.coef.subrows_mut(0, j), a.scratch.subrows_mut(0, j))
    };
    for i in 0..j {
        a.h[(i, j - 1)] += beta1 * a.coef[i];
    }
    let beta = beta1 * alpha;
    let scale_c = (0..j).map(|i| a.h[(i, j - 1)] * a.h[(i, j - 1)]).sum::<f64>().sqrt().max(beta);
    if beta <= 1e-12 * scale_c {
        a.h[(j, j - 1)] = 0.0;
        if !fresh_direction(a, op, j) {
            return Some(j);
        }
    } else {
        a.h[(j, j - 1)] = beta;
        for x in a.v.col_mut(j).iter_mut() {
            *x /= alpha;
        }
    }
    None
}

/// Arnoldi on a real basis with the second Gram–Schmidt pass delayed by one step (DCGS2:
/// Świrydowicz, Langou, Ananthan, Yang, Thomas, "Low synchronization Gram–Schmidt and
/// generalized minimal residual algorithms", Numer. Linear Algebra Appl. 28, 2021; Bielich
/// et al., "Low-synch Gram–Schmidt with delayed reorthogonalization for Krylov solvers",
/// Parallel Comput. 112, 2022). At 10⁵ unknowns every pass over the basis is a read from
/// memory, and with classical Gram–Schmidt twice nearly every step takes its second pass
/// (118 of 118 on the hanging chain): three reads a step. Here the operator is applied to
/// `u`, the vector of the previous step orthogonalized once; one sweep then gives both
/// `s = V_jᵀ u` (the delayed second pass of `u`) and `z = V_jᵀ w` for `w = T u`, and a second
/// sweep writes `v_j = (u − V_j s)/α` and `w` orthogonalized once against `[V_j, v_j]`: two
/// reads a step. With `α² = uᵀu − sᵀs`, by linearity
/// `T v_j = (w − T V_j s)/α = (w − V_{j+1} H s)/α` (the Arnoldi relation of the earlier
/// columns, `H = h[0..=j, 0..j]` once column `j − 1` is corrected as in [`finish_delayed`]),
/// so with `g = [V_j, v_j]ᵀ w = [z; (uᵀw − sᵀz)/α]` the new column of `h` is `(g − H s)/α`
/// and `T v_j − V_{j+1} (g − H s)/α = (w − V_{j+1} g)/α`. When `u` was far from orthogonal
/// (`α² < uᵀu/2`, where the Pythagorean `α` would lose digits) or nearly in the basis,
/// column `j` is finished by the classical passes and `T` applied again.
pub(super) fn expand_delayed(a: &mut Arnoldi<f64>, op: &mut dyn FnMut(ColRef<'_, f64>, ColMut<'_, f64>), kept: usize) -> Result<usize, KrylovError> {
    let m = a.m;
    let sw = a.sweeper;
    let (mut s, mut z, mut g) = (vec![0.0; m + 1], vec![0.0; m + 1], vec![0.0; m + 1]);
    // β₁ of column j when it holds the once-orthogonalized u of the previous step.
    let mut pending: Option<f64> = None;
    let mut j = kept;
    while j < m {
        apply(a, op, j)?;
        let (beta1, add) = if let Some(b1) = pending {
            let (uu, uw) = {
                let cols = columns(a.v.as_ref(), j);
                sw.project_pair(&cols, contiguous(a.v.col(j)), contiguous(a.v.col(j + 1)), &mut s[..j], &mut z[..j])
            };
            let ss: f64 = s[..j].iter().map(|x| x * x).sum();
            let alpha2 = uu - ss;
            let corrected = (0..j).map(|i| (a.h[(i, j - 1)] + b1 * s[i]).powi(2)).sum::<f64>().sqrt();
            let alpha = alpha2.max(0.0).sqrt();
            if !(alpha2.is_finite() && uw.is_finite() && alpha2 >= 0.5 * uu && b1 * alpha > 1e-12 * corrected.max(b1 * alpha)) {
                if let Some(size) = finish_delayed(a, op, j, b1) {
                    return Ok(size);
                }
                pending = None;
                continue;
            }
            for i in 0..j {
                a.h[(i, j - 1)] += b1 * s[i];
            }
            a.h[(j, j - 1)] = b1 * alpha;
            g[..j].copy_from_slice(&z[..j]);
            g[j] = (uw - s[..j].iter().zip(&z[..j]).map(|(x, y)| x * y).sum::<f64>()) / alpha;
            for i in 0..=j {
                let hs: f64 = (0..j).map(|l| a.h[(i, l)] * s[l]).sum();
                a.h[(i, j)] = (g[i] - hs) / alpha;
            }
            let (done, mut rest) = a.v.as_mut().split_at_col_mut(j);
            let cols = columns(done.rb(), j);
            let (mut uc, mut wc) = rest.rb_mut().split_at_col_mut(1);
            (sw.update_pair(&cols, &s[..j], &g[..=j], alpha, contiguous_mut(uc.rb_mut().col_mut(0)), contiguous_mut(wc.rb_mut().col_mut(0))).sqrt(), true)
        } else {
            // Column j is orthonormal to the others: one pass, its second one delayed.
            let (done, mut rest) = a.v.as_mut().split_at_col_mut(j + 1);
            let cols = columns(done.rb(), j + 1);
            let w = contiguous_mut(rest.rb_mut().col_mut(0));
            if sw.project(&cols, w, &mut g[..=j]).is_finite() {
                for i in 0..=j {
                    a.h[(i, j)] = g[i];
                }
                (sw.subtract(&cols, &g[..=j], w).sqrt(), true)
            } else {
                (f64::NAN, false)
            }
        };
        if !beta1.is_finite() {
            // Overflow: the classical passes with faer's scaled norms (added to the
            // coefficients already in h[.., j] when a pass was made).
            pending = None;
            if let Some(size) = complete_step(a, op, j, add) {
                return Ok(size);
            }
            j += 1;
            continue;
        }
        let hn = (0..=j).map(|i| a.h[(i, j)] * a.h[(i, j)]).sum::<f64>().sqrt();
        if beta1 <= 1e-12 * hn.max(beta1) {
            // Invariant subspace (a second pass only makes the norm smaller).
            a.h[(j + 1, j)] = 0.0;
            pending = None;
            if !fresh_direction(a, op, j + 1) {
                return Ok(j + 1);
            }
        } else {
            for x in a.v.col_mut(j + 1).iter_mut() {
                *x /= beta1;
            }
            pending = Some(beta1);
        }
        j += 1;
    }
    if let Some(b1) = pending {
        if let Some(size) = finish_delayed(a, op, m, b1) {
            return Ok(size);
        }
    }
    Ok(m)
}
