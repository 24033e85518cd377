//! The inner kernels of the Gram–Schmidt sweeps ([`super::gram_schmidt`]): dot products of
//! basis columns with a block of rows of one or two vectors, and subtractions of their
//! multiples, with AVX2 and FMA when the processor has them (four basis columns per load of
//! the vector), plain loops otherwise. The choice is made once, at [`Kernels::detect`].

/// The kernels this processor runs. Each takes a block of rows `r0..r0 + len` of the
/// columns and the same rows of the vectors (`len` their length).
#[derive(Clone, Copy)]
pub(super) struct Kernels {
    #[cfg(target_arch = "x86_64")]
    avx2: bool,
}

impl Kernels {
    pub(super) fn detect() -> Self {
        Kernels {
            #[cfg(target_arch = "x86_64")]
            avx2: std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma"),
        }
    }

    pub(super) fn dot(self, a: &[f64], b: &[f64]) -> f64 {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: the processor has AVX2 and FMA (checked in `detect`).
            return unsafe { avx2::dot(a, b) };
        }
        portable::dot(a, b)
    }

    /// `out[j] += Σ_i cols[j][r0 + i] w[i]`.
    pub(super) fn project(self, cols: &[&[f64]], w: &[f64], out: &mut [f64], r0: usize) {
        let cols = &cols[..out.len().min(cols.len())];
        assert!(cols.iter().all(|c| c.len() >= r0 + w.len()), "project: column shorter than the block");
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: the processor has AVX2 and FMA (checked in `detect`); every column
            // holds the rows r0..r0 + w.len() (asserted) and `out` one entry per column.
            return unsafe { avx2::project(cols, w, out, r0) };
        }
        portable::project(cols, w, out, r0)
    }

    /// `w[i] −= Σ_j cols[j][r0 + i] coef[j]`.
    pub(super) fn subtract(self, cols: &[&[f64]], coef: &[f64], w: &mut [f64], r0: usize) {
        let cols = &cols[..coef.len().min(cols.len())];
        assert!(cols.iter().all(|c| c.len() >= r0 + w.len()), "subtract: column shorter than the block");
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: as in `project` (`coef` has an entry per column of `cols`).
            return unsafe { avx2::subtract(cols, coef, w, r0) };
        }
        portable::subtract(cols, coef, w, r0)
    }

    /// `s[j] += Σ_i cols[j][r0 + i] u[i]`, `z[j] += Σ_i cols[j][r0 + i] w[i]`.
    pub(super) fn project_pair(self, cols: &[&[f64]], u: &[f64], w: &[f64], s: &mut [f64], z: &mut [f64], r0: usize) {
        let k = cols.len().min(s.len()).min(z.len());
        let cols = &cols[..k];
        assert!(u.len() == w.len() && cols.iter().all(|c| c.len() >= r0 + w.len()), "project_pair: sizes");
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: as in `project`, for both vectors (of one length, asserted).
            return unsafe { avx2::project_pair(cols, u, w, s, z, r0) };
        }
        portable::project(cols, u, s, r0);
        portable::project(cols, w, z, r0);
    }

    /// `u[i] −= Σ_j cols[j][r0 + i] s[j]`, `w[i] −= Σ_j cols[j][r0 + i] g[j]`.
    pub(super) fn subtract_pair(self, cols: &[&[f64]], s: &[f64], g: &[f64], u: &mut [f64], w: &mut [f64], r0: usize) {
        let k = cols.len().min(s.len()).min(g.len());
        let cols = &cols[..k];
        assert!(u.len() == w.len() && cols.iter().all(|c| c.len() >= r0 + w.len()), "subtract_pair: sizes");
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: as in `project_pair`.
            return unsafe { avx2::subtract_pair(cols, s, g, u, w, r0) };
        }
        portable::subtract(cols, s, u, r0);
        portable::subtract(cols, g, w, r0);
    }
}

mod portable {
    pub fn dot(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }

    pub fn project(cols: &[&[f64]], w: &[f64], out: &mut [f64], r0: usize) {
        for (o, col) in out.iter_mut().zip(cols) {
            *o += dot(&col[r0..r0 + w.len()], w);
        }
    }

    pub fn subtract(cols: &[&[f64]], coef: &[f64], w: &mut [f64], r0: usize) {
        let len = w.len();
        for (col, &f) in cols.iter().zip(coef) {
            for (x, v) in w.iter_mut().zip(&col[r0..r0 + len]) {
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

    /// Pointers to rows `r0..` of four columns `j..j + 4`.
    fn four(cols: &[&[f64]], j: usize, r0: usize) -> [*const f64; 4] {
        [cols[j][r0..].as_ptr(), cols[j + 1][r0..].as_ptr(), cols[j + 2][r0..].as_ptr(), cols[j + 3][r0..].as_ptr()]
    }

    /// # Safety
    /// The processor has AVX2 and FMA; every column holds rows `r0..r0 + w.len()`, `out` an
    /// entry per column.
    #[target_feature(enable = "avx2,fma")]
    pub unsafe fn project(cols: &[&[f64]], w: &[f64], out: &mut [f64], r0: usize) {
        let len = w.len();
        let pw = w.as_ptr();
        let mut j = 0;
        while j + 4 <= cols.len() {
            let p = four(cols, j, r0);
            let mut acc = [_mm256_setzero_pd(); 4];
            let mut i = 0;
            // SAFETY: i + 4 ≤ len, the rows r0 + i.. r0 + i + 4 of every column exist (the
            // caller's guarantee) and w[i..i + 4] too.
            unsafe {
                while i + 4 <= len {
                    let x = _mm256_loadu_pd(pw.add(i));
                    for l in 0..4 {
                        acc[l] = _mm256_fmadd_pd(_mm256_loadu_pd(p[l].add(i)), x, acc[l]);
                    }
                    i += 4;
                }
            }
            for l in 0..4 {
                let mut s = hsum(acc[l]);
                for r in i..len {
                    s += cols[j + l][r0 + r] * w[r];
                }
                out[j + l] += s;
            }
            j += 4;
        }
        for jj in j..cols.len() {
            // SAFETY: the caller's guarantee.
            out[jj] += unsafe { dot(&cols[jj][r0..r0 + len], w) };
        }
    }

    /// # Safety
    /// As [`project`], `u` as long as `w`, `s` and `z` an entry per column.
    #[target_feature(enable = "avx2,fma")]
    pub unsafe fn project_pair(cols: &[&[f64]], u: &[f64], w: &[f64], s: &mut [f64], z: &mut [f64], r0: usize) {
        let len = w.len();
        let (pu, pw) = (u.as_ptr(), w.as_ptr());
        let mut j = 0;
        while j + 4 <= cols.len() {
            let p = four(cols, j, r0);
            let (mut a, mut b) = ([_mm256_setzero_pd(); 4], [_mm256_setzero_pd(); 4]);
            let mut i = 0;
            // SAFETY: as in `project`, u[i..i + 4] exists as w[i..i + 4] does.
            unsafe {
                while i + 4 <= len {
                    let (x, y) = (_mm256_loadu_pd(pu.add(i)), _mm256_loadu_pd(pw.add(i)));
                    for l in 0..4 {
                        let v = _mm256_loadu_pd(p[l].add(i));
                        a[l] = _mm256_fmadd_pd(v, x, a[l]);
                        b[l] = _mm256_fmadd_pd(v, y, b[l]);
                    }
                    i += 4;
                }
            }
            for l in 0..4 {
                let (mut sa, mut sb) = (hsum(a[l]), hsum(b[l]));
                for r in i..len {
                    sa += cols[j + l][r0 + r] * u[r];
                    sb += cols[j + l][r0 + r] * w[r];
                }
                s[j + l] += sa;
                z[j + l] += sb;
            }
            j += 4;
        }
        for jj in j..cols.len() {
            let c = &cols[jj][r0..r0 + len];
            // SAFETY: the caller's guarantee.
            unsafe {
                s[jj] += dot(c, u);
                z[jj] += dot(c, w);
            }
        }
    }

    /// # Safety
    /// As [`project`], `coef` an entry per column.
    #[target_feature(enable = "avx2,fma")]
    pub unsafe fn subtract(cols: &[&[f64]], coef: &[f64], w: &mut [f64], r0: usize) {
        let len = w.len();
        let pw = w.as_mut_ptr();
        // Four columns at a time down the block: four sequential streams of the basis, the
        // block of w in the first-level cache.
        let mut j = 0;
        while j + 4 <= cols.len() {
            let p = four(cols, j, r0);
            let f = [_mm256_set1_pd(coef[j]), _mm256_set1_pd(coef[j + 1]), _mm256_set1_pd(coef[j + 2]), _mm256_set1_pd(coef[j + 3])];
            let mut i = 0;
            // SAFETY: every access is to rows i..i + 4 ≤ len of w and r0 + i.. of the columns.
            unsafe {
                while i + 4 <= len {
                    let mut x = _mm256_loadu_pd(pw.add(i));
                    for l in 0..4 {
                        x = _mm256_fnmadd_pd(_mm256_loadu_pd(p[l].add(i)), f[l], x);
                    }
                    _mm256_storeu_pd(pw.add(i), x);
                    i += 4;
                }
            }
            for r in i..len {
                let q = r0 + r;
                w[r] -= cols[j][q] * coef[j] + cols[j + 1][q] * coef[j + 1] + cols[j + 2][q] * coef[j + 2] + cols[j + 3][q] * coef[j + 3];
            }
            j += 4;
        }
        for jj in j..cols.len() {
            let f = coef[jj];
            for (x, v) in w.iter_mut().zip(&cols[jj][r0..r0 + len]) {
                *x -= v * f;
            }
        }
    }

    /// # Safety
    /// As [`project_pair`], `s` and `g` an entry per column.
    #[target_feature(enable = "avx2,fma")]
    pub unsafe fn subtract_pair(cols: &[&[f64]], s: &[f64], g: &[f64], u: &mut [f64], w: &mut [f64], r0: usize) {
        let len = w.len();
        let (pu, pw) = (u.as_mut_ptr(), w.as_mut_ptr());
        let mut j = 0;
        while j + 4 <= cols.len() {
            let p = four(cols, j, r0);
            let fs = [_mm256_set1_pd(s[j]), _mm256_set1_pd(s[j + 1]), _mm256_set1_pd(s[j + 2]), _mm256_set1_pd(s[j + 3])];
            let fg = [_mm256_set1_pd(g[j]), _mm256_set1_pd(g[j + 1]), _mm256_set1_pd(g[j + 2]), _mm256_set1_pd(g[j + 3])];
            let mut i = 0;
            // SAFETY: as in `subtract`, for u as for w (one length).
            unsafe {
                while i + 4 <= len {
                    let (mut x, mut y) = (_mm256_loadu_pd(pu.add(i)), _mm256_loadu_pd(pw.add(i)));
                    for l in 0..4 {
                        let v = _mm256_loadu_pd(p[l].add(i));
                        x = _mm256_fnmadd_pd(v, fs[l], x);
                        y = _mm256_fnmadd_pd(v, fg[l], y);
                    }
                    _mm256_storeu_pd(pu.add(i), x);
                    _mm256_storeu_pd(pw.add(i), y);
                    i += 4;
                }
            }
            for r in i..len {
                let q = r0 + r;
                u[r] -= cols[j][q] * s[j] + cols[j + 1][q] * s[j + 1] + cols[j + 2][q] * s[j + 2] + cols[j + 3][q] * s[j + 3];
                w[r] -= cols[j][q] * g[j] + cols[j + 1][q] * g[j + 1] + cols[j + 2][q] * g[j + 2] + cols[j + 3][q] * g[j + 3];
            }
            j += 4;
        }
        for jj in j..cols.len() {
            let c = &cols[jj][r0..r0 + len];
            for ((x, y), v) in u.iter_mut().zip(w.iter_mut()).zip(c) {
                *x -= v * s[jj];
                *y -= v * g[jj];
            }
        }
    }
}
