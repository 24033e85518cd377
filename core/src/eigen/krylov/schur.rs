//! Complex Schur form `H = Z T Zᴴ` of the small Rayleigh-quotient matrices of the
//! Krylov–Schur iteration, and the reordering of `T`'s diagonal by Givens swaps
//! (Golub & Van Loan, *Matrix Computations*, 4th ed., §7.4–7.6: Householder reduction to
//! Hessenberg form, shifted QR with Wilkinson shifts, §7.6.2 swapping adjacent eigenvalues).
//! The matrices are at most a few hundred wide, so plain unblocked code is enough.

use faer::{c64, Mat};

/// `(T, Z)` with `H = Z T Zᴴ`, `T` upper triangular, `Z` unitary; `None` when the QR
/// iteration does not converge within `30 n` sweeps per eigenvalue.
// Out of line (here and `sort_schur`) so that profiles show the small dense work apart.
#[inline(never)]
pub(super) fn schur(h: &Mat<c64>) -> Option<(Mat<c64>, Mat<c64>)> {
    let n = h.nrows();
    let mut t = h.clone();
    let mut z = Mat::<c64>::identity(n, n);
    hessenberg(&mut t, &mut z);
    let zero = c64::new(0.0, 0.0);
    let mut hi = n;
    let mut iterations = 0usize;
    while hi > 1 {
        // Deflate negligible subdiagonal entries of the active block [lo, hi).
        let mut lo = hi - 1;
        while lo > 0 {
            let s = t[(lo, lo)].norm() + t[(lo - 1, lo - 1)].norm();
            let s = if s == 0.0 { t.norm_l2() } else { s };
            if t[(lo, lo - 1)].norm() <= f64::EPSILON * s {
                t[(lo, lo - 1)] = zero;
                break;
            }
            lo -= 1;
        }
        if lo == hi - 1 {
            hi -= 1;
            iterations = 0;
            continue;
        }
        iterations += 1;
        if iterations > 30 * n.max(10) {
            return None;
        }
        // Wilkinson shift (eigenvalue of the trailing 2x2 nearer its last entry), an
        // exceptional shift every 11 sweeps.
        let (a, b, c, d) = (t[(hi - 2, hi - 2)], t[(hi - 2, hi - 1)], t[(hi - 1, hi - 2)], t[(hi - 1, hi - 1)]);
        let mu = if iterations % 11 == 0 {
            d + c64::new(0.75 * t[(hi - 1, hi - 2)].norm(), 0.0)
        } else {
            let half = (a - d) * 0.5;
            let root = (half * half + b * c).sqrt();
            // (a + d)/2 ± root, written around d.
            let (m1, m2) = (d + half + root, d + half - root);
            if (m1 - d).norm() <= (m2 - d).norm() { m1 } else { m2 }
        };
        qr_sweep(&mut t, &mut z, lo, hi, mu);
    }
    for j in 0..n {
        for i in j + 1..n {
            t[(i, j)] = zero;
        }
    }
    Some((t, z))
}

/// The plane rotation `G = [[c, s], [−s̄, c]]` (c real, stored as `(c, s)`) with
/// `G [x; y] = [r; 0]`; applied to rows `(p, q)` as `[x; y] ← [c x + s y; −s̄ x + c y]`.
fn rotation(x: c64, y: c64) -> (f64, c64) {
    let (nx, ny) = (x.norm(), y.norm());
    if ny == 0.0 {
        return (1.0, c64::new(0.0, 0.0));
    }
    if nx == 0.0 {
        return (0.0, y.conj() / ny);
    }
    let r = (nx * nx + ny * ny).sqrt();
    let phase = x / nx;
    (nx / r, phase * y.conj() / r)
}

fn rotate_rows(t: &mut Mat<c64>, p: usize, q: usize, (c, s): (f64, c64), cols: std::ops::Range<usize>) {
    for j in cols {
        let (x, y) = (t[(p, j)], t[(q, j)]);
        t[(p, j)] = x * c + s * y;
        t[(q, j)] = -s.conj() * x + y * c;
    }
}

/// `M ← M Gᴴ` on columns `(p, q)` (the right half of the similarity `G M Gᴴ`).
fn rotate_cols(t: &mut Mat<c64>, p: usize, q: usize, (c, s): (f64, c64), rows: std::ops::Range<usize>) {
    for i in rows {
        let (x, y) = (t[(i, p)], t[(i, q)]);
        t[(i, p)] = x * c + y * s.conj();
        t[(i, q)] = -s * x + y * c;
    }
}

/// One explicitly shifted QR sweep on the Hessenberg block `[lo, hi)`, applied to the whole
/// of `t` (so that it stays similar to the input) and accumulated into `z`.
fn qr_sweep(t: &mut Mat<c64>, z: &mut Mat<c64>, lo: usize, hi: usize, mu: c64) {
    let n = t.nrows();
    for k in lo..hi {
        t[(k, k)] -= mu;
    }
    let mut rots = Vec::with_capacity(hi - lo);
    for k in lo..hi - 1 {
        let g = rotation(t[(k, k)], t[(k + 1, k)]);
        rotate_rows(t, k, k + 1, g, k..n);
        t[(k + 1, k)] = c64::new(0.0, 0.0);
        rots.push(g);
    }
    for (k, &g) in (lo..hi - 1).zip(rots.iter()) {
        rotate_cols(t, k, k + 1, g, 0..(k + 2).min(hi));
        rotate_cols(z, k, k + 1, g, 0..n);
    }
    for k in lo..hi {
        t[(k, k)] += mu;
    }
}

/// Householder reduction to upper Hessenberg form, `H ← Qᴴ H Q`, `z ← z Q`.
fn hessenberg(t: &mut Mat<c64>, z: &mut Mat<c64>) {
    let n = t.nrows();
    for k in 0..n.saturating_sub(2) {
        let x: Vec<c64> = (k + 1..n).map(|i| t[(i, k)]).collect();
        let nx = x.iter().map(|a| a.norm_sqr()).sum::<f64>().sqrt();
        if nx == 0.0 {
            continue;
        }
        let phase = if x[0].norm() > 0.0 { x[0] / x[0].norm() } else { c64::new(1.0, 0.0) };
        let mut v = x.clone();
        v[0] += phase * nx;
        let nv2 = v.iter().map(|a| a.norm_sqr()).sum::<f64>();
        if nv2 == 0.0 {
            continue;
        }
        // P = I − 2 v vᴴ / (vᴴ v), applied on the left (rows k+1..; columns before k are
        // already zero there) and the right.
        for j in k..n {
            let s = v.iter().enumerate().fold(c64::new(0.0, 0.0), |s, (i, vi)| s + vi.conj() * t[(k + 1 + i, j)]) * (2.0 / nv2);
            for (i, vi) in v.iter().enumerate() {
                t[(k + 1 + i, j)] -= *vi * s;
            }
        }
        for m in [&mut *t, &mut *z] {
            for i in 0..n {
                let s = v.iter().enumerate().fold(c64::new(0.0, 0.0), |s, (l, vl)| s + m[(i, k + 1 + l)] * *vl) * (2.0 / nv2);
                for (l, vl) in v.iter().enumerate() {
                    m[(i, k + 1 + l)] -= s * vl.conj();
                }
            }
        }
        for i in k + 2..n {
            t[(i, k)] = c64::new(0.0, 0.0);
        }
    }
}

/// Swaps the diagonal entries `k`, `k+1` of the upper triangular `t` by a rotation
/// (`t ← G t Gᴴ`, `z ← z Gᴴ`).
fn swap(t: &mut Mat<c64>, z: &mut Mat<c64>, k: usize) {
    let n = t.nrows();
    let (a, b, d) = (t[(k, k)], t[(k, k + 1)], t[(k + 1, k + 1)]);
    if a == d {
        return;
    }
    // The eigenvector [b; d − a] of d becomes the first coordinate vector.
    let g = rotation(b, d - a);
    rotate_rows(t, k, k + 1, g, k..n);
    rotate_cols(t, k, k + 1, g, 0..k + 2);
    rotate_cols(z, k, k + 1, g, 0..n);
    t[(k + 1, k)] = c64::new(0.0, 0.0);
}

/// Reorders the Schur form so that the diagonal entries come in decreasing `key`
/// (a stable bubble sort of adjacent swaps).
#[inline(never)]
pub(super) fn sort_schur(t: &mut Mat<c64>, z: &mut Mat<c64>, key: impl Fn(c64) -> f64) {
    let n = t.nrows();
    for i in 1..n {
        let mut k = i;
        while k > 0 && key(t[(k, k)]) > key(t[(k - 1, k - 1)]) {
            swap(t, z, k - 1);
            k -= 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn random(n: usize, seed: u64) -> Mat<c64> {
        let mut x = 0x2545_F491_4F6C_DD1Du64 ^ seed;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        Mat::from_fn(n, n, |_, _| c64::new(next(), next()))
    }

    /// `Z T Zᴴ = H`, `Zᴴ Z = I` and the diagonal in the requested order, to rounding.
    #[test]
    fn schur_form_reconstructs_and_sorts() {
        for (n, seed) in [(1, 1), (2, 2), (7, 3), (40, 4), (80, 5)] {
            let h = random(n, seed);
            let (mut t, mut z) = schur(&h).unwrap();
            sort_schur(&mut t, &mut z, |x| x.norm());
            let back = &z * &t * z.adjoint();
            assert!((&back - &h).norm_l2() < 1e-12 * h.norm_l2() * n as f64, "n = {n}");
            assert!((z.adjoint() * &z - Mat::<c64>::identity(n, n)).norm_l2() < 1e-12 * n as f64);
            for k in 1..n {
                assert!(t[(k, k)].norm() <= t[(k - 1, k - 1)].norm());
                assert!(t[(k, k - 1)] == c64::new(0.0, 0.0));
            }
            // Same eigenvalues as faer's dense complex eigensolver (independent code).
            let ev = h.eigenvalues().unwrap();
            for e in ev {
                let d = (0..n).map(|k| (t[(k, k)] - e).norm()).fold(f64::INFINITY, f64::min);
                assert!(d < 1e-10 * h.norm_l2(), "n = {n}: {e:?} missing ({d:e})");
            }
        }
    }
}
