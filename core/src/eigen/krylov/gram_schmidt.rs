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

use super::sweep_kernels::Kernels;

/// Rows per block of the fused sweeps: 512 rows of a 97-column basis are 388 KiB (the
/// second-level cache holds 2 MiB here), the blocks of the one or two vectors 4 KiB each.
const ROWS: usize = 512;
/// Rows per block of the plain projections (the block of `w`, 16 KiB, or of `u` and `w`,
/// stays in the first-level cache while the columns stream past it).
const LONG_ROWS: usize = 2048;

/// The sweeps over a real basis, each one read of the basis. The rows go in two fixed
/// halves (split at [`Sweeper::mid`]), on two rayon threads when `parallel` (one Krylov run
/// alone: at 10⁵ unknowns the sweeps wait on memory, and one core draws about half of what
/// two draw here, 12 against 24 GB/s), else one after the other; the partial sums of the
/// halves are always added in the same order, so the results are the same bits either way.
#[derive(Clone, Copy)]
pub(super) struct Sweeper {
    kernels: Kernels,
    parallel: bool,
}

impl Sweeper {
    pub fn new(parallel: bool) -> Self {
        Sweeper { kernels: Kernels::detect(), parallel }
    }

    /// The first row of the second half.
    pub fn mid(n: usize) -> usize {
        (n / 2) & !7
    }

    /// Both halves' work, on two threads when `parallel` ([`both`]).
    fn both<A: Send, B: Send>(self, a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
        both(self.parallel, a, b)
    }

    /// `out = Vᵀ w` (`cols` the columns of `V`); returns `wᵀw`.
    pub fn project(self, cols: &[&[f64]], w: &[f64], out: &mut [f64]) -> f64 {
        let (n, k) = (w.len(), cols.len());
        let mid = Self::mid(n);
        let half = |r0: usize, r1: usize| {
            let mut o = vec![0.0; k];
            let mut ww = 0.0;
            for b0 in (r0..r1).step_by(LONG_ROWS) {
                let b1 = (b0 + LONG_ROWS).min(r1);
                self.kernels.project(cols, &w[b0..b1], &mut o, b0);
                ww += self.kernels.dot(&w[b0..b1], &w[b0..b1]);
            }
            (o, ww)
        };
        let ((o0, w0), (o1, w1)) = self.both(|| half(0, mid), || half(mid, n));
        for (j, o) in out[..k].iter_mut().enumerate() {
            *o = o0[j] + o1[j];
        }
        w0 + w1
    }

    /// `w ← w − V coef`; returns the new `wᵀw`.
    pub fn subtract(self, cols: &[&[f64]], coef: &[f64], w: &mut [f64]) -> f64 {
        let mid = Self::mid(w.len());
        let half = |r0: usize, w: &mut [f64]| {
            let mut ww = 0.0;
            let len = w.len();
            for b in (0..len).step_by(LONG_ROWS) {
                let blk = &mut w[b..(b + LONG_ROWS).min(len)];
                self.kernels.subtract(cols, coef, blk, r0 + b);
                ww += self.kernels.dot(blk, blk);
            }
            ww
        };
        let (w0, w1) = w.split_at_mut(mid);
        let (a, b) = self.both(|| half(0, w0), || half(mid, w1));
        a + b
    }

    /// `s = Vᵀ u`, `z = Vᵀ w` in one read of `V`; returns `(uᵀu, uᵀw)`.
    pub fn project_pair(self, cols: &[&[f64]], u: &[f64], w: &[f64], s: &mut [f64], z: &mut [f64]) -> (f64, f64) {
        let (n, k) = (w.len(), cols.len());
        let mid = Self::mid(n);
        let half = |r0: usize, r1: usize| {
            let (mut sp, mut zp) = (vec![0.0; k], vec![0.0; k]);
            let (mut uu, mut uw) = (0.0, 0.0);
            for b0 in (r0..r1).step_by(LONG_ROWS) {
                let b1 = (b0 + LONG_ROWS).min(r1);
                self.kernels.project_pair(cols, &u[b0..b1], &w[b0..b1], &mut sp, &mut zp, b0);
                uu += self.kernels.dot(&u[b0..b1], &u[b0..b1]);
                uw += self.kernels.dot(&u[b0..b1], &w[b0..b1]);
            }
            (sp, zp, uu, uw)
        };
        let ((s0, z0, uu0, uw0), (s1, z1, uu1, uw1)) = self.both(|| half(0, mid), || half(mid, n));
        for j in 0..k {
            s[j] = s0[j] + s1[j];
            z[j] = z0[j] + z1[j];
        }
        (uu0 + uu1, uw0 + uw1)
    }

    /// `u ← (u − V s)/α` and then `w ← (w − V g[..k] − u g[k])/α` (`k` the columns of `V`),
    /// row block by row block in one read of `V`; returns the new `wᵀw`.
    pub fn update_pair(self, cols: &[&[f64]], s: &[f64], g: &[f64], alpha: f64, u: &mut [f64], w: &mut [f64]) -> f64 {
        let k = cols.len();
        let (gk, inv) = (g[k], 1.0 / alpha);
        let mid = Self::mid(w.len());
        let half = |r0: usize, u: &mut [f64], w: &mut [f64]| {
            let mut ww = 0.0;
            for b in (0..w.len()).step_by(ROWS) {
                let e = (b + ROWS).min(w.len());
                let (ub, wb) = (&mut u[b..e], &mut w[b..e]);
                self.kernels.subtract_pair(cols, &s[..k], &g[..k], ub, wb, r0 + b);
                for (x, y) in ub.iter_mut().zip(wb.iter_mut()) {
                    *x *= inv;
                    *y = (*y - *x * gk) * inv;
                }
                ww += self.kernels.dot(wb, wb);
            }
            ww
        };
        let ((u0, u1), (w0, w1)) = (u.split_at_mut(mid), w.split_at_mut(mid));
        let (a, b) = self.both(|| half(0, u0, w0), || half(mid, u1, w1));
        a + b
    }

    /// `w` with its components along the orthonormal columns `cols` removed; the
    /// coefficients removed are written to `h`, `c` is scratch of the same length; returns
    /// the norm left. Classical Gram–Schmidt twice, the first pass's subtraction and the
    /// second pass's projection fused block by block (three reads of the basis, not four);
    /// the second pass only when the first removed more than `1 − 1/√2` of `w`
    /// (Kahan–Parlett "twice is enough"), as the general code in `iteration.rs` does. `None`
    /// (and `w`, `h` untouched) when `‖w‖²` overflows: the caller then takes faer's scaled
    /// norms.
    pub fn orthogonalize(self, cols: &[&[f64]], w: &mut [f64], h: &mut [f64], c: &mut [f64]) -> Option<f64> {
        let k = cols.len();
        let (h, c) = (&mut h[..k], &mut c[..k]);
        let before2 = self.kernels.dot(w, w);
        if !before2.is_finite() {
            return None;
        }
        self.project(cols, w, h);
        // w ← w − V h and c = Vᵀ w, block by block.
        let mid = Self::mid(w.len());
        let hh: &[f64] = h;
        let half = |r0: usize, w: &mut [f64]| {
            let mut cp = vec![0.0; k];
            let mut ww = 0.0;
            let len = w.len();
            for b in (0..len).step_by(ROWS) {
                let blk = &mut w[b..(b + ROWS).min(len)];
                self.kernels.subtract(cols, hh, blk, r0 + b);
                self.kernels.project(cols, blk, &mut cp, r0 + b);
                ww += self.kernels.dot(blk, blk);
            }
            (cp, ww)
        };
        let (w0, w1) = w.split_at_mut(mid);
        let ((c0, a0), (c1, a1)) = self.both(|| half(0, w0), || half(mid, w1));
        for j in 0..k {
            c[j] = c0[j] + c1[j];
        }
        let after2 = a0 + a1;
        if after2 > 0.5 * before2 {
            return Some(after2.sqrt());
        }
        let left2 = self.subtract(cols, c, w);
        for (a, b) in h.iter_mut().zip(c.iter()) {
            *a += b;
        }
        Some(left2.sqrt())
    }
}

/// `(a(), b())`, with `b` on another thread of the rayon pool when `parallel`: the calling
/// thread runs `a` itself and then waits for `b` (`rayon::in_place_scope`). Outside the pool
/// that wait blocks this thread only, and no worker waits on it; on a worker (a sweep's
/// point) the wait runs other work of the pool meanwhile, so no worker blocks (the
/// deadlock of `tests/eigen/sparse_eigen.rs`' rayon-workers test cannot form). `rayon::join`
/// from outside the pool hands both halves to the workers, and when the second worker is
/// asleep the first one often runs both (measured: one worker had 2.6 times the other's
/// samples).
pub(super) fn both<A: Send, B: Send>(parallel: bool, a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    if !parallel {
        return (a(), b());
    }
    let mut rb = None;
    let ra = rayon::in_place_scope(|s| {
        s.spawn(|_| rb = Some(b()));
        a()
    });
    (ra, rb.unwrap_or_else(|| unreachable!("the scope waits for its spawned half")))
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

    fn orthonormal(n: usize, k: usize) -> (faer::Mat<f64>, Vec<Vec<f64>>) {
        let a = faer::Mat::<f64>::from_fn(n, k, |i, j| random(1, (i * 131 + j) as u64)[0]);
        let q = a.qr().compute_thin_Q();
        let cols: Vec<Vec<f64>> = (0..k).map(|j| (0..n).map(|i| q[(i, j)]).collect()).collect();
        (q, cols)
    }

    /// Against faer's QR (independent code): the coefficients are `Qᵀ w` and what is left
    /// is orthogonal to `Q`, to rounding, for sizes that exercise every remainder path, on
    /// one thread and on two (the same bits).
    #[test]
    fn removes_the_span_of_an_orthonormal_basis() {
        for (n, k) in [(1, 1), (37, 5), (300, 13), (1000, 97), (5000, 30)] {
            let (q, cols) = orthonormal(n, k);
            let refs: Vec<&[f64]> = cols.iter().map(|c| c.as_slice()).collect();
            let w0 = random(n, 7);
            let mut runs = Vec::new();
            for parallel in [false, true] {
                let mut w = w0.clone();
                let (mut h, mut c) = (vec![0.0; k + 3], vec![0.0; k + 3]);
                let left = Sweeper::new(parallel).orthogonalize(&refs, &mut w, &mut h, &mut c).unwrap_or(f64::NAN);
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
                runs.push((w, h, left));
            }
            assert!(runs[0] == runs[1], "n = {n}, k = {k}: one thread and two differ");
        }
    }

    /// The sweeps of the delayed reorthogonalization against plain loops: `s = Vᵀ u`,
    /// `z = Vᵀ w`, `uᵀu`, `uᵀw`, then `u ← (u − V s)/α`, `w ← (w − V g[..k] − u g[k])/α` and
    /// the new `wᵀw`; one thread and two give the same bits.
    #[test]
    fn pair_sweeps_match_plain_loops() {
        for (n, k) in [(3, 1), (37, 5), (1000, 13), (5000, 30)] {
            let (_, cols) = orthonormal(n, k);
            let refs: Vec<&[f64]> = cols.iter().map(|c| c.as_slice()).collect();
            let (u0, w0) = (random(n, 11), random(n, 12));
            let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
            let s_ref: Vec<f64> = refs.iter().map(|c| dot(c, &u0)).collect();
            let z_ref: Vec<f64> = refs.iter().map(|c| dot(c, &w0)).collect();
            let g: Vec<f64> = (0..=k).map(|j| 0.3 + 0.1 * j as f64).collect();
            let alpha = 0.9;
            let u_ref: Vec<f64> = (0..n).map(|i| (u0[i] - (0..k).map(|j| refs[j][i] * s_ref[j]).sum::<f64>()) / alpha).collect();
            let w_ref: Vec<f64> = (0..n).map(|i| (w0[i] - (0..k).map(|j| refs[j][i] * g[j]).sum::<f64>() - u_ref[i] * g[k]) / alpha).collect();
            let mut runs = Vec::new();
            for parallel in [false, true] {
                let sw = Sweeper::new(parallel);
                let (mut s, mut z) = (vec![0.0; k], vec![0.0; k]);
                let (uu, uw) = sw.project_pair(&refs, &u0, &w0, &mut s, &mut z);
                assert!((uu - dot(&u0, &u0)).abs() < 1e-10 && (uw - dot(&u0, &w0)).abs() < 1e-10);
                for j in 0..k {
                    assert!((s[j] - s_ref[j]).abs() < 1e-12 && (z[j] - z_ref[j]).abs() < 1e-12, "n = {n}, column {j}");
                }
                let (mut u, mut w) = (u0.clone(), w0.clone());
                let ww = sw.update_pair(&refs, &s, &g, alpha, &mut u, &mut w);
                assert!((ww - dot(&w, &w)).abs() <= 1e-12 * ww.max(1.0));
                for i in 0..n {
                    assert!((u[i] - u_ref[i]).abs() < 1e-12 && (w[i] - w_ref[i]).abs() < 1e-12, "n = {n}, row {i}");
                }
                let mut g2 = vec![0.0; k];
                let w2 = sw.project(&refs, &w0, &mut g2);
                assert!((w2 - dot(&w0, &w0)).abs() < 1e-10 && g2.iter().zip(&z_ref).all(|(a, b)| (a - b).abs() < 1e-12));
                let mut w3 = w0.clone();
                let left = sw.subtract(&refs, &g2, &mut w3);
                assert!((left - dot(&w3, &w3)).abs() <= 1e-12 * left.max(1.0) && refs.iter().all(|c| dot(c, &w3).abs() < 1e-12));
                runs.push((s, z, u, w, ww, w3));
            }
            assert!(runs[0] == runs[1], "n = {n}, k = {k}: one thread and two differ");
        }
    }
}
