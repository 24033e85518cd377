//! Classical Gram–Schmidt twice (CGS2; Giraud, Langou, Rozložník, "The loss of
//! orthogonality in the Gram–Schmidt orthogonalization process", Comput. Math. Appl. 50,
//! 2005: two classical passes keep `w` orthogonal to the basis to working accuracy) for a
//! real Krylov basis, as row-blocked kernels over the basis's columns.
//!
//! At 10⁵ unknowns the basis (up to ~100 columns, 80 MB) is far larger than the caches, so
//! every pass over it is a read from memory: `h = Vᵀ w`, `w ← w − V h`, `c = Vᵀ w`,
//! `w ← w − V c` were four reads. Here the first subtraction and the second projection go
//! together, one block of rows at a time (the block of `V`, 512 rows, is still in the cache
//! when it is read the second time): three reads. The norms are accumulated in the same
//! sweeps. The kernels use AVX2 with FMA when the processor has them (four basis columns per
//! load of `w` when projecting, four columns per load and store of `w` when subtracting), plain loops
//! otherwise.

/// Rows per block of the fused sweep: 512 rows of a 97-column basis are 388 KiB (the
/// second-level cache holds 1 MiB here).
const ROWS: usize = 512;
/// Rows per block of the single passes (the block of `w`, 32 KiB, stays in the cache while
/// the columns stream past it).
const LONG_ROWS: usize = 4096;
/// `w` with its components along the orthonormal columns `cols` removed; the coefficients
/// removed are written to `h`, `c` is scratch of the same length; returns the norm left.
/// A second pass only when the first removed more than `1 − 1/√2` of `w` (Kahan–Parlett
/// "twice is enough"), as the general code in `iteration.rs` does. `None` (and `w`, `h`
/// untouched) when `‖w‖²` overflows: the caller then takes faer's scaled norms.
pub(super) fn orthogonalize_real(cols: &[&[f64]], w: &mut [f64], h: &mut [f64], c: &mut [f64]) -> Option<f64> {
    let n = w.len();
    let k = cols.len();
    let (h, c) = (&mut h[..k], &mut c[..k]);
    let kernels = Kernels::detect();
    let before2 = kernels.dot(w, w);
    if !before2.is_finite() {
        return None;
    }
    h.fill(0.0);
    for r0 in (0..n).step_by(LONG_ROWS) {
        kernels.project(cols, w, h, r0, (r0 + LONG_ROWS).min(n));
    }
    // w ← w − V h and c = Vᵀ w, block by block.
    c.fill(0.0);
    let mut after2 = 0.0;
    for r0 in (0..n).step_by(ROWS) {
        let r1 = (r0 + ROWS).min(n);
        kernels.subtract(cols, h, w, r0, r1);
        kernels.project(cols, w, c, r0, r1);
        after2 += kernels.dot(&w[r0..r1], &w[r0..r1]);
    }
    if after2 > 0.5 * before2 {
        return Some(after2.sqrt());
    }
    let mut left2 = 0.0;
    for r0 in (0..n).step_by(LONG_ROWS) {
        let r1 = (r0 + LONG_ROWS).min(n);
        kernels.subtract(cols, c, w, r0, r1);
        left2 += kernels.dot(&w[r0..r1], &w[r0..r1]);
    }
    for (a, b) in h.iter_mut().zip(c.iter()) {
        *a += b;
    }
    Some(left2.sqrt())
}

/// The kernels this processor runs.
#[derive(Clone, Copy)]
struct Kernels {
    #[cfg(target_arch = "x86_64")]
    avx2: bool,
}

impl Kernels {
    fn detect() -> Self {
        Kernels {
            #[cfg(target_arch = "x86_64")]
            avx2: std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma"),
        }
    }

    fn dot(self, a: &[f64], b: &[f64]) -> f64 {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: the processor has AVX2 and FMA (checked in `detect`).
            return unsafe { avx2::dot(a, b) };
        }
        portable::dot(a, b)
    }

    /// `out[j] += Σ_{r0 ≤ i < r1} cols[j][i] w[i]`.
    fn project(self, cols: &[&[f64]], w: &[f64], out: &mut [f64], r0: usize, r1: usize) {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: as in `dot`; the slices are bounds-checked inside.
            return unsafe { avx2::project(cols, w, out, r0, r1) };
        }
        portable::project(cols, w, out, r0, r1)
    }

    /// `w[i] −= Σ_j cols[j][i] coef[j]` for `r0 ≤ i < r1`.
    fn subtract(self, cols: &[&[f64]], coef: &[f64], w: &mut [f64], r0: usize, r1: usize) {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: as in `dot`.
            return unsafe { avx2::subtract(cols, coef, w, r0, r1) };
        }
        portable::subtract(cols, coef, w, r0, r1)
    }
}

mod portable {
    pub fn dot(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }

    pub fn project(cols: &[&[f64]], w: &[f64], out: &mut [f64], r0: usize, r1: usize) {
        let w = &w[r0..r1];
        for (o, col) in out.iter_mut().zip(cols) {
            *o += dot(&col[r0..r1], w);
        }
    }

    pub fn subtract(cols: &[&[f64]], coef: &[f64], w: &mut [f64], r0: usize, r1: usize) {
        for (col, &f) in cols.iter().zip(coef) {
            for (x, v) in w[r0..r1].iter_mut().zip(&col[r0..r1]) {
                *x -= v * f;
            }
        }
    }
}

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use std::arch::x86_64::*;

    #[target_feature(enable = "avx2,fma")]
    fn hsum(x: __m256d) -> f64 {
        let lo = _mm256_castpd256_pd128(x);
        let hi = _mm256_extractf128_pd::<1>(x);
        let s = _mm_add_pd(lo, hi);
        _mm_cvtsd_f64(_mm_add_sd(s, _mm_unpackhi_pd(s, s)))
    }

    /// # Safety
    /// The processor has AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    pub unsafe fn dot(a: &[f64], b: &[f64]) -> f64 {
        let n = a.len().min(b.len());
        let (pa, pb) = (a.as_ptr(), b.as_ptr());
        let mut acc = [_mm256_setzero_pd(); 4];
        let mut i = 0;
        // SAFETY: every load reads a[i..i + 16], b[i..i + 16] with i + 16 ≤ n.
        unsafe {
            while i + 16 <= n {
                for (l, a_l) in acc.iter_mut().enumerate() {
                    *a_l = _mm256_fmadd_pd(_mm256_loadu_pd(pa.add(i + 4 * l)), _mm256_loadu_pd(pb.add(i + 4 * l)), *a_l);
                }
                i += 16;
            }
        }
        let mut s = hsum(_mm256_add_pd(_mm256_add_pd(acc[0], acc[1]), _mm256_add_pd(acc[2], acc[3])));
        for j in i..n {
            s += a[j] * b[j];
        }
        s
    }

    /// # Safety
    /// The processor has AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    pub unsafe fn project(cols: &[&[f64]], w: &[f64], out: &mut [f64], r0: usize, r1: usize) {
        assert!(r1 <= w.len() && cols.iter().all(|c| c.len() >= r1) && out.len() >= cols.len());
        let pw = w.as_ptr();
        let mut j = 0;
        while j + 4 <= cols.len() {
            let p = [cols[j].as_ptr(), cols[j + 1].as_ptr(), cols[j + 2].as_ptr(), cols[j + 3].as_ptr()];
            let mut acc = [_mm256_setzero_pd(); 4];
            let mut i = r0;
            // SAFETY: i + 4 ≤ r1 ≤ the length of w and of every column (asserted).
            unsafe {
                while i + 4 <= r1 {
                    let x = _mm256_loadu_pd(pw.add(i));
                    for l in 0..4 {
                        acc[l] = _mm256_fmadd_pd(_mm256_loadu_pd(p[l].add(i)), x, acc[l]);
                    }
                    i += 4;
                }
            }
            for l in 0..4 {
                let mut s = hsum(acc[l]);
                for r in i..r1 {
                    s += cols[j + l][r] * w[r];
                }
                out[j + l] += s;
            }
            j += 4;
        }
        for jj in j..cols.len() {
            // SAFETY: the caller's guarantee.
            out[jj] += unsafe { dot(&cols[jj][r0..r1], &w[r0..r1]) };
        }
    }

    /// # Safety
    /// The processor has AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    pub unsafe fn subtract(cols: &[&[f64]], coef: &[f64], w: &mut [f64], r0: usize, r1: usize) {
        assert!(r1 <= w.len() && cols.iter().all(|c| c.len() >= r1) && coef.len() >= cols.len());
        let pw = w.as_mut_ptr();
        // Four columns at a time down the block: four sequential streams of the basis, the
        // block of w in the first-level cache.
        let mut j = 0;
        while j + 4 <= cols.len() {
            let p = [cols[j].as_ptr(), cols[j + 1].as_ptr(), cols[j + 2].as_ptr(), cols[j + 3].as_ptr()];
            let f = [_mm256_set1_pd(coef[j]), _mm256_set1_pd(coef[j + 1]), _mm256_set1_pd(coef[j + 2]), _mm256_set1_pd(coef[j + 3])];
            let mut i = r0;
            // SAFETY: every access is to rows i..i + 4 ≤ r1 (asserted in bounds).
            unsafe {
                while i + 4 <= r1 {
                    let mut x = _mm256_loadu_pd(pw.add(i));
                    for l in 0..4 {
                        x = _mm256_fnmadd_pd(_mm256_loadu_pd(p[l].add(i)), f[l], x);
                    }
                    _mm256_storeu_pd(pw.add(i), x);
                    i += 4;
                }
            }
            for r in i..r1 {
                w[r] -= cols[j][r] * coef[j] + cols[j + 1][r] * coef[j + 1] + cols[j + 2][r] * coef[j + 2] + cols[j + 3][r] * coef[j + 3];
            }
            j += 4;
        }
        for jj in j..cols.len() {
            let f = coef[jj];
            for (x, v) in w[r0..r1].iter_mut().zip(&cols[jj][r0..r1]) {
                *x -= v * f;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn random(len: usize, seed: u64) -> Vec<f64> {
        let mut x = 0x2545_F491_4F6C_DD1Du64 ^ seed;
        (0..len)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect()
    }

    /// Against faer's QR (independent code): the coefficients are `Qᵀ w` and what is left
    /// is orthogonal to `Q`, to rounding, for sizes that exercise every remainder path.
    #[test]
    fn removes_the_span_of_an_orthonormal_basis() {
        for (n, k) in [(1, 1), (37, 5), (300, 13), (1000, 97)] {
            let a = faer::Mat::<f64>::from_fn(n, k, |i, j| random(1, (i * 131 + j) as u64)[0]);
            let q = a.qr().compute_thin_Q();
            let cols: Vec<Vec<f64>> = (0..k).map(|j| (0..n).map(|i| q[(i, j)]).collect()).collect();
            let refs: Vec<&[f64]> = cols.iter().map(|c| c.as_slice()).collect();
            let w0 = random(n, 7);
            let mut w = w0.clone();
            let (mut h, mut c) = (vec![0.0; k + 3], vec![0.0; k + 3]);
            let left = orthogonalize_real(&refs, &mut w, &mut h, &mut c).unwrap_or(f64::NAN);
            let norm = w.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!((left - norm).abs() <= 1e-12 * (1.0 + norm), "n = {n}, k = {k}");
            for j in 0..k {
                let qw0: f64 = (0..n).map(|i| q[(i, j)] * w0[i]).sum();
                let qw: f64 = (0..n).map(|i| q[(i, j)] * w[i]).sum();
                assert!((h[j] - qw0).abs() < 1e-12, "coefficient {j}: {} vs {qw0}", h[j]);
                assert!(qw.abs() < 1e-13, "left part not orthogonal to column {j}: {qw:e}");
            }
            // w0 = Q h + w.
            for i in 0..n {
                let back: f64 = (0..k).map(|j| q[(i, j)] * h[j]).sum::<f64>() + w[i];
                assert!((back - w0[i]).abs() < 1e-12);
            }
        }
    }
}
