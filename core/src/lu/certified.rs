//! A fast LU with partial pivoting that is trusted only when it proves its matrix far from
//! singular; callers fall back to their full-pivoting (rank-revealing) path otherwise.
//!
//! Full pivoting is unblocked and memory-bound: on the 1712-equation pendulum chain its two
//! factorizations (the pencil's regularity check and the full model's static gain) took
//! half of `romdyn eig`'s time. Partial pivoting is blocked and parallel, but its pivots
//! alone do not reveal a near-singular matrix (a triangular `U` with moderate diagonal can
//! be arbitrarily ill-conditioned). So the fast path also runs three steps of inverse
//! iteration on `M Mᵀ` from a fixed vector (`y = M⁻¹ x`, then `M⁻ᵀ`, then `M⁻¹` of the
//! normalized result): each `‖x‖ / ‖M⁻¹ x‖` is an upper bound of `σ_min(M)`, which a
//! (near-)singular matrix drives to its rounding level for any start not orthogonal to
//! its null vectors (three solves, `O(n²)` each). The factorization is accepted when every pivot is above
//! `tolerance` times the largest and that bound is too; any doubt sends the caller to its
//! full-pivoting test, so refusals are decided as before.

use faer::linalg::solvers::{FullPivLu, PartialPivLu, Solve};
use faer::{Mat, MatRef};

/// Largest and smallest absolute diagonal entry of a triangular factor (its pivots).
fn pivot_range(u: MatRef<'_, f64>) -> (f64, f64) {
    (0..u.nrows().min(u.ncols())).map(|k| u[(k, k)].abs()).fold((0.0f64, f64::INFINITY), |(b, s), x| (b.max(x), s.min(x)))
}

/// The callers' fallback rank test: a full-pivoting (rank-revealing) LU's smallest pivot
/// above `tolerance` times its largest. `false` for NaN pivots.
pub(crate) fn full_pivots_nonsingular(lu: &FullPivLu<f64>, tolerance: f64) -> bool {
    let (big, small) = pivot_range(lu.U());
    small > tolerance * big
}

/// The partial-pivoting LU of `m` when it certifies `m` as numerically nonsingular:
/// smallest pivot and the inverse-iteration bound of `σ_min` both above `tolerance` times
/// `reference` or the largest pivot, whichever is larger. `None` means "not proven", not
/// "singular". `reference` is the size rounding is measured against when `m` is a block
/// of a larger matrix (a block at rounding level is well conditioned relative to itself);
/// 0 for a matrix on its own.
pub(crate) fn certified_partial_lu(m: MatRef<'_, f64>, tolerance: f64, reference: f64) -> Option<PartialPivLu<f64>> {
    let n = m.nrows();
    if n == 0 || m.ncols() != n {
        return None;
    }
    let lu = m.partial_piv_lu();
    let (big, small) = pivot_range(lu.U());
    let big = big.max(reference);
    if !(big.is_finite() && small > tolerance * big) {
        return None;
    }
    // A fixed start with no relation to the model's structure (a Weyl sequence in [-1, 1]),
    // then power steps on (M Mᵀ)⁻¹, alternating M⁻¹ and M⁻ᵀ: each `‖b‖/‖M⁻¹ b‖` (or with
    // M⁻ᵀ, as σ_min(Mᵀ) = σ_min(M)) is an upper bound of σ_min.
    let mut b = Mat::<f64>::from_fn(n, 1, |i, _| 2.0 * ((i as f64 + 1.0) * 0.618_033_988_749_894_9).fract() - 1.0);
    let mut sigma_bound = f64::INFINITY;
    for step in 0..3 {
        let b_norm = b.norm_l2();
        let y = if step % 2 == 0 { lu.solve(&b) } else { lu.solve_transpose(&b) };
        let y_norm = y.norm_l2();
        if !(y_norm.is_finite() && y_norm > 0.0) {
            return None;
        }
        sigma_bound = sigma_bound.min(b_norm / y_norm);
        b = y * faer::Scale(1.0 / y_norm);
    }
    (sigma_bound.is_finite() && sigma_bound > tolerance * big).then_some(lu)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unit upper triangular with −1 above the diagonal: every pivot is 1, so the pivots
    /// alone pass, yet `‖U⁻¹‖` grows as `2ⁿ⁻¹` (Higham, Accuracy and Stability of Numerical
    /// Algorithms, 2nd ed., §8.2): σ_min/σ_max is about 1e-18 at n = 60. The
    /// inverse-iteration bound must reject it.
    #[test]
    fn a_matrix_singular_behind_unit_pivots_is_not_certified() {
        let n = 60;
        let m = Mat::<f64>::from_fn(n, n, |i, j| if i == j { 1.0 } else if j > i { -1.0 } else { 0.0 });
        let sv = m.singular_values().unwrap();
        assert!(sv[n - 1] < 1e-12 * sv[0], "numerically singular: σ_min/σ_max = {:.1e}", sv[n - 1] / sv[0]);
        assert!(certified_partial_lu(m.as_ref(), 1e-12, 0.0).is_none());
    }

    /// A block at rounding level is not certified against the matrix it came from.
    #[test]
    fn a_block_at_rounding_level_is_measured_against_its_reference() {
        let tiny = Mat::<f64>::from_fn(1, 1, |_, _| 3e-16);
        assert!(certified_partial_lu(tiny.as_ref(), 1e-14, 0.0).is_some());
        assert!(certified_partial_lu(tiny.as_ref(), 1e-14, 3.0).is_none());
    }

    /// A well-conditioned matrix is certified and solves like any LU (residual 1e-14).
    #[test]
    fn a_well_conditioned_matrix_is_certified() {
        let n = 50;
        let m = Mat::<f64>::from_fn(n, n, |i, j| if i == j { 4.0 } else { 1.0 / (1.0 + (i as f64 - j as f64).abs()) });
        let lu = certified_partial_lu(m.as_ref(), 1e-12, 0.0).expect("certified");
        let b = Mat::<f64>::from_fn(n, 1, |i, _| i as f64);
        let x = lu.solve(&b);
        assert!((&m * &x - &b).norm_l2() < 1e-12 * b.norm_l2());
    }

    /// An exactly singular matrix (two equal rows) is not certified.
    #[test]
    fn an_exactly_singular_matrix_is_not_certified() {
        let n = 20;
        let m = Mat::<f64>::from_fn(n, n, |i, j| {
            let i = if i == n - 1 { 0 } else { i };
            1.0 / (1.0 + i as f64 + 2.0 * j as f64) + if i == j { 1.0 } else { 0.0 }
        });
        assert!(certified_partial_lu(m.as_ref(), 1e-12, 0.0).is_none());
    }
}
