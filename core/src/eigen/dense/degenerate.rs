//! Pencils the eigenanalysis cannot answer honestly, found before QZ, and the exact
//! rescaling that lets extreme but regular pencils through.
//!
//! - Non-finite entries (NaN, ±∞, or `F_y = (J − J*)/(2c)` overflowing for a tiny `c`,
//!   eq. 16) are refused, naming the matrix and the entry.
//! - Extreme magnitudes (largest entry 1e308, or 1e-300): both matrices are multiplied by
//!   the same power of two so the exponents of their nonzero entries centre on 1; this is exact and leaves every
//!   eigenvalue and right vector unchanged (left vectors are scaled back by [`finish`]).
//!   Rows and columns of very different sizes (1e-200 next to 1e200) are then equilibrated
//!   by the balancing before QZ.
//! - A singular pencil, `det(λ F_yd + F_y) ≡ 0` (every λ is an "eigenvalue"; e.g. an
//!   all-zero pencil, or an unknown with no entry in either matrix: a common null vector),
//!   has no eigenvalues to label. A regular pencil has at most n values of `s` where
//!   `F_y + s F_yd` is singular, so the pencil is declared singular when, after
//!   balancing, this matrix is numerically rank deficient (smallest pivot of a
//!   full-pivoting LU below `10 n ε` of the largest) at two unrelated shifts `s` (a partial-pivoting LU that
//!   proves the matrix nonsingular, [`crate::lu::certified_partial_lu`], settles it faster). An
//!   unknown or equation without any entry is named.

use faer::Mat;

use super::balance::balance_pencil;
use crate::eigen::EigenError;
use crate::linear::Jacobians;

/// The largest absolute entry of a matrix (NaN if any entry is NaN).
fn max_abs(m: &Mat<f64>) -> f64 {
    let mut x = 0.0f64;
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            let v = m[(i, j)].abs();
            if !(v <= x) {
                x = v;
            }
        }
    }
    x
}

/// The smallest nonzero absolute entry (∞ for a zero matrix).
fn min_nonzero_abs(m: &Mat<f64>) -> f64 {
    let mut x = f64::INFINITY;
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            let v = m[(i, j)].abs();
            if v > 0.0 && v < x {
                x = v;
            }
        }
    }
    x
}

fn first_non_finite(m: &Mat<f64>) -> Option<(usize, usize, f64)> {
    (0..m.ncols()).flat_map(|j| (0..m.nrows()).map(move |i| (i, j))).find(|&(i, j)| !m[(i, j)].is_finite()).map(|(i, j)| (i, j, m[(i, j)]))
}

/// Jacobians rescaled for the eigenanalysis, and the factor `s` they were multiplied by.
pub(crate) struct Prepared {
    pub jacobians: Jacobians,
    pub scale: f64,
}

/// Checks a pencil before QZ (see the module doc) and rescales it by a power of two;
/// `dcoef` is the coefficient of the Λ form requested for a pencil given as F_yd, F_y.
pub(crate) fn prepare(jacobians: &Jacobians, dcoef: Option<f64>) -> Result<Prepared, EigenError> {
    let prepared = prepare_unchecked(jacobians, dcoef)?;
    let (fyd, fy) = prepared.jacobians.derivatives();
    check_regular(&fyd, &fy)?;
    Ok(prepared)
}

/// [`prepare`] without the check for a singular pencil.
fn prepare_unchecked(jacobians: &Jacobians, dcoef: Option<f64>) -> Result<Prepared, EigenError> {
    let scale = pencil_scale(jacobians, dcoef)?;
    let scaled = |m: &Mat<f64>| m * faer::Scale(scale);
    let jacobians = match jacobians {
        Jacobians::Derivatives { fyd, fy } => Jacobians::Derivatives { fyd: scaled(fyd), fy: scaled(fy) },
        Jacobians::Coefficient { j, jstar, dcoef } => Jacobians::Coefficient { j: scaled(j), jstar: scaled(jstar), dcoef: *dcoef },
    };
    Ok(Prepared { jacobians, scale })
}

/// The checks of [`prepare`] but the singular pencil's, and the power of two it scales the
/// pencil by (1 for ordinary magnitudes), without copying the matrices (for a caller that
/// proves regularity otherwise: the deflation of `super::deflate`).
pub(crate) fn pencil_scale(jacobians: &Jacobians, dcoef: Option<f64>) -> Result<f64, EigenError> {
    let non_finite = |what: &str, m: &Mat<f64>| first_non_finite(m).map(|(i, j, x)| EigenError::NonFinite(format!("{what} entry ({}, {}) is {x}", i + 1, j + 1)));
    let (a, b, names) = match jacobians {
        Jacobians::Derivatives { fyd, fy } => (fyd, fy, ["F_yd", "F_y"]),
        Jacobians::Coefficient { j, jstar, .. } => (j, jstar, ["J(+c)", "J(-c)"]),
    };
    if let Some(e) = non_finite(names[0], a).or_else(|| non_finite(names[1], b)) {
        return Err(e);
    }
    let dcoef_ok = |c: f64| c.is_normal() && c > 0.0;
    if let Some(c) = dcoef.filter(|c| !dcoef_ok(*c)) {
        return Err(EigenError::InvalidDcoef(c));
    }
    // A power of two that centres the exponents of the nonzero entries on 1: the product is
    // exact, and entries spanning more than the double range's half (1e-151 next to 1e180)
    // neither overflow nor underflow.
    let (largest, smallest) = (max_abs(a).max(max_abs(b)), min_nonzero_abs(a).min(min_nonzero_abs(b)));
    // Pencils of ordinary magnitudes are left exactly as they are.
    let ordinary = largest <= 2f64.powi(400) && smallest >= 2f64.powi(-400);
    let scale = if largest > 0.0 && !ordinary { (-((largest.log2() + smallest.log2()) / 2.0).round()).exp2() } else { 1.0 };
    match jacobians {
        Jacobians::Coefficient { j, jstar, dcoef } => {
            if !dcoef_ok(*dcoef) {
                return Err(EigenError::InvalidDcoef(*dcoef));
            }
            // F_y = (J − J*)/(2 dCoef) of the scaled matrices, checked entry by entry.
            let c = *dcoef;
            let overflow = (0..j.ncols()).flat_map(|col| (0..j.nrows()).map(move |row| (row, col))).find(|&(row, col)| !((j[(row, col)] * scale - jstar[(row, col)] * scale) * (0.5 / c)).is_finite());
            if let Some((row, col)) = overflow {
                let x = (j[(row, col)] * scale - jstar[(row, col)] * scale) * (0.5 / c);
                return Err(EigenError::NonFinite(format!("F_y = (J(+c) - J(-c))/(2 dCoef) (eq. 16; dCoef too small for these matrices) entry ({}, {}) is {x}", row + 1, col + 1)));
            }
        }
        Jacobians::Derivatives { fyd, fy } => {
            if let Some(c) = dcoef {
                if !(max_abs(fyd) * scale + c * max_abs(fy) * scale).is_finite() {
                    return Err(EigenError::NonFinite(format!("J = F_yd + dCoef F_y overflows with dCoef = {c} s")));
                }
            }
        }
    }
    Ok(scale)
}

/// Errors when an unknown or an equation has no entry in `F_yd` nor `F_y`: the pencil is
/// then singular for every λ. Cheap (one pass over the entries), so it comes before any
/// factorization: a 2000 x 2000 pencil of zeros was refused only after 18 s and 690 MB.
pub(crate) fn check_no_empty_lines(fyd: &Mat<f64>, fy: &Mat<f64>) -> Result<(), EigenError> {
    let n = fyd.nrows();
    let empty_col = (0..n).find(|&j| (0..n).all(|i| fyd[(i, j)] == 0.0 && fy[(i, j)] == 0.0));
    let empty_row = (0..n).find(|&i| (0..n).all(|j| fyd[(i, j)] == 0.0 && fy[(i, j)] == 0.0));
    if empty_col.is_some() || empty_row.is_some() {
        let mut what = Vec::new();
        if let Some(j) = empty_col {
            what.push(format!("unknown {} has no entry in F_yd or F_y", j + 1));
        }
        if let Some(i) = empty_row {
            what.push(format!("equation {} has no entry in F_yd or F_y", i + 1));
        }
        return Err(EigenError::Singular { detail: what.join(", "), unknowns: empty_col.into_iter().collect(), unknown_names: Vec::new() });
    }
    Ok(())
}

/// Errors when `λ F_yd + F_y` is singular for every λ (see the module doc).
fn check_regular(fyd: &Mat<f64>, fy: &Mat<f64>) -> Result<(), EigenError> {
    check_no_empty_lines(fyd, fy)?;
    let n = fyd.nrows();
    let balanced = balance_pencil(fy, fyd);
    let (a, b) = (&balanced.a, &balanced.b);
    let ratio = {
        let (na, nb) = (max_abs(a), max_abs(b));
        if na > 0.0 && nb > 0.0 { na / nb } else { 1.0 }
    };
    let tolerance = 10.0 * n as f64 * f64::EPSILON;
    // Two shifts with no relation to each other or to simple eigenvalues (0, ±1, ±2, …).
    for s in [0.734_918_251_3, -1.618_033_988_7] {
        let m = a + b * faer::Scale(s * ratio);
        // The fast partial-pivoting LU decides only when it proves `m` nonsingular.
        if crate::lu::certified_partial_lu(m.as_ref(), tolerance, 0.0).is_some() {
            return Ok(());
        }
        if crate::lu::full_pivots_nonsingular(&m.full_piv_lu(), tolerance) {
            return Ok(());
        }
    }
    Err(EigenError::Singular {
        detail: format!("F_y + s F_yd is rank deficient at two unrelated shifts s (smallest LU pivot below {tolerance:.1e} of the largest, after balancing)"),
        unknowns: common_null_vector(a, b),
        unknown_names: Vec::new(),
    })
}

/// Largest system whose common null vector is looked for (dense SVD of `[A; B]`).
const NULL_VECTOR_LIMIT: usize = 2000;

/// The unknowns of a common null vector `A v = B v = 0` (entries within a tenth of the
/// largest, largest first), when `[A; B]` is rank deficient; empty otherwise.
fn common_null_vector(a: &Mat<f64>, b: &Mat<f64>) -> Vec<usize> {
    let n = a.ncols();
    if n == 0 || n > NULL_VECTOR_LIMIT {
        return Vec::new();
    }
    let stacked = Mat::<f64>::from_fn(2 * n, n, |i, j| if i < n { a[(i, j)] } else { b[(i - n, j)] });
    let Ok(svd) = stacked.thin_svd() else { return Vec::new() };
    let s = svd.S();
    if !(s[n - 1] <= 10.0 * n as f64 * f64::EPSILON * s[0]) {
        return Vec::new();
    }
    let v = svd.V();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&x, &y| v[(y, n - 1)].abs().total_cmp(&v[(x, n - 1)].abs()));
    let top = v[(order[0], n - 1)].abs();
    order.into_iter().take_while(|&i| v[(i, n - 1)].abs() >= 0.1 * top).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn derivatives(fyd: Mat<f64>, fy: Mat<f64>) -> Jacobians {
        Jacobians::Derivatives { fyd, fy }
    }

    #[test]
    fn zero_and_common_null_vector_pencils_are_singular() {
        let zero = derivatives(Mat::zeros(3, 3), Mat::zeros(3, 3));
        assert!(matches!(prepare(&zero, None), Err(EigenError::Singular { detail: m, .. }) if m.contains("unknown 1")));
        // A common null vector that is not a coordinate: v = (1, 1) with F_yd v = F_y v = 0.
        let fyd = Mat::from_fn(2, 2, |i, j| if j == 0 { 1.0 + i as f64 } else { -1.0 - i as f64 });
        let fy = Mat::from_fn(2, 2, |_, j| if j == 0 { 3.0 } else { -3.0 });
        assert!(matches!(prepare(&derivatives(fyd, fy), None), Err(EigenError::Singular { detail: m, unknowns, .. }) if m.contains("rank deficient") && unknowns.len() == 2));
        // Regular: the two-mass system's kind of pencil.
        let ok = derivatives(Mat::<f64>::identity(2, 2), Mat::from_fn(2, 2, |i, j| [[0.0, -1.0], [4.0, 0.1]][i][j]));
        assert!(prepare(&ok, None).is_ok());
    }

    #[test]
    fn non_finite_entries_and_tiny_dcoef_are_refused() {
        let mut fy = Mat::<f64>::identity(2, 2);
        fy[(1, 0)] = f64::NAN;
        assert!(matches!(prepare(&derivatives(Mat::identity(2, 2), fy), None), Err(EigenError::NonFinite(m)) if m.contains("F_y entry (2, 1)")));
        let j = Mat::<f64>::identity(2, 2);
        let jstar = Mat::<f64>::identity(2, 2) * faer::Scale(-1.0);
        let tiny = Jacobians::Coefficient { j: j.clone(), jstar: jstar.clone(), dcoef: 1e-320 };
        assert!(matches!(prepare(&tiny, None), Err(EigenError::InvalidDcoef(_))));
        // The smallest normal dCoef still gives a finite F_y once J is scaled to entries of 1.
        let small = Jacobians::Coefficient { j: j * faer::Scale(1e300), jstar: jstar * faer::Scale(1e300), dcoef: 2.3e-308 };
        assert!(prepare(&small, None).is_ok());
    }
}
