//! Banded LU with partial pivoting for Jacobians whose unknowns can be numbered so that
//! every entry lies near the diagonal (chains, beams: the common multibody case), after a
//! reverse Cuthill–McKee renumbering.
//!
//! Storage and algorithm follow LAPACK's `gbtf2`: column-major band of `2 kl + ku + 1`
//! rows, entry `(i, j)` at row `kl + ku + i − j` of column `j`; row interchanges within
//! the band widen `U` to `kl + ku` superdiagonals. Work is `n kl (kl + ku)` multiply–adds
//! in contiguous column segments, with no index chasing: for these matrices it is several
//! times faster than a general sparse LU whose work is dominated by its bookkeeping.

/// A symmetric renumbering of `n` unknowns and the band it gives.
#[derive(Clone, Debug)]
pub struct BandOrdering {
    /// `position[i]`: new index of unknown (and equation) `i`.
    pub position: Vec<usize>,
    /// Lower and upper bandwidth of the renumbered pattern.
    pub kl: usize,
    pub ku: usize,
}

impl BandOrdering {
    /// Reverse Cuthill–McKee on the pattern of `A + Aᵀ` given as `(row, col)` entries,
    /// each connected component started from a pseudo-peripheral unknown.
    pub fn reverse_cuthill_mckee(n: usize, rows: &[usize], cols: &[usize]) -> Self {
        let mut degree = vec![0usize; n + 1];
        for (&r, &c) in rows.iter().zip(cols) {
            if r != c {
                degree[r] += 1;
                degree[c] += 1;
            }
        }
        // Adjacency in compressed form (duplicates kept: harmless for a BFS).
        let mut start = vec![0usize; n + 1];
        for i in 0..n {
            start[i + 1] = start[i] + degree[i];
        }
        let mut fill = start.clone();
        let mut adjacent = vec![0usize; start[n]];
        for (&r, &c) in rows.iter().zip(cols) {
            if r != c {
                adjacent[fill[r]] = c;
                fill[r] += 1;
                adjacent[fill[c]] = r;
                fill[c] += 1;
            }
        }
        let neighbours = |v: usize| &adjacent[start[v]..start[v + 1]];
        let mut order = Vec::with_capacity(n);
        let mut level = vec![usize::MAX; n];
        let mut placed = vec![false; n];
        // Breadth-first search from `root` over unplaced unknowns: the last unknown reached
        // and the number of levels.
        let bfs = |root: usize, level: &mut Vec<usize>, placed: &[bool], visited: &mut Vec<usize>| -> (usize, usize) {
            visited.clear();
            visited.push(root);
            level[root] = 0;
            let mut head = 0;
            while head < visited.len() {
                let v = visited[head];
                head += 1;
                for &w in neighbours(v) {
                    if !placed[w] && level[w] == usize::MAX {
                        level[w] = level[v] + 1;
                        visited.push(w);
                    }
                }
            }
            let last = *visited.iter().max_by_key(|&&v| (level[v], usize::MAX - degree[v])).unwrap_or(&root);
            let depth = level[last];
            for &v in visited.iter() {
                level[v] = usize::MAX;
            }
            (last, depth)
        };
        let mut visited = Vec::new();
        let mut candidates: Vec<usize> = (0..n).collect();
        candidates.sort_by_key(|&v| degree[v]);
        for &seed in &candidates {
            if placed[seed] {
                continue;
            }
            // Pseudo-peripheral root: move to the farthest unknown while the depth grows.
            let (mut root, mut depth) = (seed, bfs(seed, &mut level, &placed, &mut visited).1);
            for _ in 0..8 {
                let (far, _) = bfs(root, &mut level, &placed, &mut visited);
                let (_, d) = bfs(far, &mut level, &placed, &mut visited);
                if d <= depth {
                    break;
                }
                (root, depth) = (far, d);
            }
            // Cuthill–McKee: breadth first, neighbours by increasing degree.
            let first = order.len();
            order.push(root);
            placed[root] = true;
            let mut head = first;
            let mut next = Vec::new();
            while head < order.len() {
                let v = order[head];
                head += 1;
                next.clear();
                next.extend(neighbours(v).iter().copied().filter(|&w| !placed[w]));
                next.sort_unstable_by_key(|&w| (degree[w], w));
                next.dedup();
                for &w in &next {
                    if !placed[w] {
                        placed[w] = true;
                        order.push(w);
                    }
                }
            }
        }
        order.reverse();
        let mut position = vec![0; n];
        for (k, &v) in order.iter().enumerate() {
            position[v] = k;
        }
        let (mut kl, mut ku) = (0, 0);
        for (&r, &c) in rows.iter().zip(cols) {
            let (i, j) = (position[r], position[c]);
            if i > j {
                kl = kl.max(i - j);
            } else {
                ku = ku.max(j - i);
            }
        }
        BandOrdering { position, kl, ku }
    }

    /// Multiply–adds of a banded LU in this ordering (upper bound, `n kl (kl + ku)`).
    pub fn factorization_work(&self) -> usize {
        self.position.len() * self.kl * (self.kl + self.ku)
    }
}

/// The banded LU factors of a matrix in a [`BandOrdering`], and the storage it is
/// assembled into.
#[derive(Clone, Debug)]
pub struct BandLu {
    n: usize,
    kl: usize,
    ku: usize,
    /// Rows of the band storage, `2 kl + ku + 1`.
    ld: usize,
    band: Vec<f64>,
    pivot: Vec<usize>,
    /// Rows of `L` below the diagonal in each column up to its last nonzero.
    lower: Vec<usize>,
    /// The last column each row of the matrix can hold a nonzero in: the band's edge
    /// `i + ku`, or the pattern's ([`BandLu::with_pattern`]).
    row_end: Vec<usize>,
    /// `row_end` as the factorization goes: rows swapped, rows updated by a pivot row reach
    /// its last column.
    fill_end: Vec<usize>,
    /// The last row each column can hold a nonzero in: the band's edge `j + kl`, or the
    /// last row of the pattern whose first entry is at or left of column `j` (a row's
    /// first nonzero never moves left: updates fill to the right, and a row swapped at
    /// step `k` goes to a row that held a nonzero in column `k`).
    col_end: Vec<usize>,
    /// The first row each column of `U` holds a nonzero in after the last factorization
    /// (`min { i : fill_end[i] ≥ j }`; before any, the band's edge `j − kl − ku`): where
    /// [`BandLu::clear`] and the back substitution start.
    upper_top: Vec<usize>,
}

/// How many columns ahead [`BandLu::solve_in_place`] asks the caches for.
const SOLVE_AHEAD: usize = 16;

/// A zero pivot: the matrix is singular.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ZeroPivot;

impl BandLu {
    pub fn new(n: usize, kl: usize, ku: usize) -> Self {
        let ld = 2 * kl + ku + 1;
        let last = n.saturating_sub(1);
        let row_end: Vec<usize> = (0..n).map(|i| (i + ku).min(last)).collect();
        let col_end = (0..n).map(|j| (j + kl).min(last)).collect();
        let upper_top = (0..n).map(|j| j.saturating_sub(kl + ku)).collect();
        BandLu { n, kl, ku, ld, band: vec![0.0; ld * n], pivot: vec![0; n], lower: vec![0; n], fill_end: row_end.clone(), row_end, col_end, upper_top }
    }

    /// A band LU for matrices whose nonzeros all lie at the renumbered `(i, j)` of
    /// `entries`: each row's elimination then stops at its last entry and its fill's, and
    /// each column's pivot search at its last possible row, instead of the band's edges
    /// (the same operations on the same nonzeros, fewer zeros visited).
    pub fn with_pattern(n: usize, kl: usize, ku: usize, entries: impl Iterator<Item = (usize, usize)>) -> Self {
        let mut lu = BandLu::new(n, kl, ku);
        let mut row_start: Vec<usize> = (0..n).collect();
        lu.row_end.iter_mut().enumerate().for_each(|(i, e)| *e = i);
        for (i, j) in entries {
            lu.row_end[i] = lu.row_end[i].max(j);
            row_start[i] = row_start[i].min(j);
        }
        // col_end[j] = max { i : row_start[i] ≤ j }, at least j: the rows by their first
        // column, then a running maximum.
        lu.col_end.iter_mut().enumerate().for_each(|(j, e)| *e = j);
        for (i, &s) in row_start.iter().enumerate() {
            lu.col_end[s] = lu.col_end[s].max(i);
        }
        for j in 1..n {
            lu.col_end[j] = lu.col_end[j].max(lu.col_end[j - 1]);
        }
        lu
    }

    /// Index in the band storage of entry `(i, j)` of the renumbered matrix
    /// (`j − ku ≤ i ≤ j + kl`).
    pub fn index(&self, i: usize, j: usize) -> usize {
        debug_assert!(i + self.ku >= j && i <= j + self.kl);
        j * self.ld + self.kl + self.ku + i - j
    }

    /// Zeroes the storage for a new matrix: in each column, the rows the last factorization
    /// can have left a nonzero in (`U` from [`BandLu::upper_top`], `L` to the column's last
    /// possible row); the rest of the band is zero already.
    pub fn clear(&mut self) {
        let (ld, kv) = (self.ld, self.kl + self.ku);
        for (j, (&top, &end)) in self.upper_top.iter().zip(&self.col_end).enumerate() {
            let col = j * ld + kv - j;
            self.band[col + top..=col + end].iter_mut().for_each(|v| *v = 0.0);
        }
    }

    /// The storage, indexed by [`BandLu::index`].
    pub fn storage_mut(&mut self) -> &mut [f64] {
        &mut self.band
    }

    /// Adds `v` at storage index `k` (from [`BandLu::index`]).
    #[cfg(test)]
    pub fn add(&mut self, k: usize, v: f64) {
        self.band[k] += v;
    }

    /// Factors the assembled matrix in place: `P A = L U`.
    pub fn factorize(&mut self) -> Result<(), ZeroPivot> {
        let done = self.eliminate();
        // Where U's columns start, from how far each row reached (a failed factorization's
        // rows too: `clear` must reach every nonzero it left).
        let mut next = 0;
        for (j, top) in self.upper_top.iter_mut().enumerate() {
            *top = j;
        }
        for (i, &end) in self.fill_end.iter().enumerate() {
            for top in self.upper_top.iter_mut().take(end + 1).skip(next.max(i)) {
                *top = i;
            }
            next = next.max(end + 1);
        }
        done
    }

    /// The elimination of [`BandLu::factorize`].
    fn eliminate(&mut self) -> Result<(), ZeroPivot> {
        let (n, kl, ld) = (self.n, self.kl, self.ld);
        let kv = self.kl + self.ku;
        // Loops over `a..b + 1` rather than `a..=b`: the inclusive range's iterator keeps an
        // extra flag that the optimizer does not remove from these inner loops.
        // The fill rows above the original band start as zero (done by `clear`). Entries of
        // row i right of `fill_end[i]` are zero: the row's own, and those its updates by
        // pivot rows brought in (LAPACK's `gbtf2` goes to the furthest column any row
        // reached; the same nonzeros, fewer zeros visited).
        self.fill_end.copy_from_slice(&self.row_end);
        for j in 0..n {
            let km = kl.min(self.col_end[j] - j);
            let col = j * ld + kv; // index of (j, j)
            let mut p = 0;
            let mut best = self.band[col].abs();
            for i in 1..km + 1 {
                let a = self.band[col + i].abs();
                if a > best || best.is_nan() {
                    (p, best) = (i, a);
                }
            }
            self.pivot[j] = j + p;
            if best == 0.0 || !best.is_finite() {
                return Err(ZeroPivot);
            }
            if p != 0 {
                // Swap rows j and j + p in columns j up to the later of their last nonzeros.
                let end = self.fill_end[j].max(self.fill_end[j + p]);
                for c in j..end + 1 {
                    let row_j = c * ld + kv + j - c;
                    self.band.swap(row_j, row_j + p);
                }
                self.fill_end.swap(j, j + p);
            }
            // Rows below the last nonzero of column j take no update: skip them (the
            // renumbered band is far from full, so this is most of the work saved).
            let km = (1..km + 1).rev().find(|&i| self.band[col + i] != 0.0).unwrap_or(0);
            self.lower[j] = km;
            let inv = 1.0 / self.band[col];
            for v in &mut self.band[col + 1..=col + km] {
                *v *= inv;
            }
            if km == 0 {
                continue;
            }
            let end = self.fill_end[j];
            for e in &mut self.fill_end[j + 1..=j + km] {
                *e = (*e).max(end);
            }
            let (head, tail) = self.band.split_at_mut((j + 1) * ld);
            let l = &head[col + 1..=col + km];
            // (j, c) in `tail` for c = j + 1: then one column (ld rows) right and one row up.
            let mut row_j = kv - 1;
            for _ in j + 1..end + 1 {
                let t = tail[row_j];
                if t != 0.0 {
                    for (x, &li) in tail[row_j + 1..=row_j + km].iter_mut().zip(l) {
                        *x -= t * li;
                    }
                }
                row_j += ld - 1;
            }
        }
        Ok(())
    }

    /// Solves `A x = b` in place with the factors (in the renumbered ordering). Each sweep
    /// asks for the factors' column [`SOLVE_AHEAD`] columns on ([`super::prefetch`]): the
    /// columns' segments are too short and far apart for the hardware to follow.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let (n, ld) = (self.n, self.ld);
        let kv = self.kl + self.ku;
        for j in 0..n {
            if j + SOLVE_AHEAD < n {
                let ahead = (j + SOLVE_AHEAD) * ld + kv;
                super::prefetch::lines(self.band.as_ptr().wrapping_add(ahead), 8 * (self.lower[j + SOLVE_AHEAD] + 1));
            }
            let p = self.pivot[j];
            if p != j {
                b.swap(j, p);
            }
            let km = self.lower[j];
            let bj = b[j];
            if bj != 0.0 {
                let col = j * ld + kv;
                for (x, &l) in b[j + 1..=j + km].iter_mut().zip(&self.band[col + 1..=col + km]) {
                    *x -= bj * l;
                }
            }
        }
        for j in (0..n).rev() {
            if j >= SOLVE_AHEAD {
                let ahead = j - SOLVE_AHEAD;
                let top = self.upper_top[ahead];
                super::prefetch::lines(self.band.as_ptr().wrapping_add(ahead * ld + kv - (ahead - top)), 8 * (ahead - top + 1));
            }
            let col = j * ld + kv;
            b[j] /= self.band[col];
            let bj = b[j];
            let top = self.upper_top[j];
            if bj != 0.0 {
                // Column j of U above the diagonal: rows top..j at col − (j − i).
                for (i, x) in b[top..j].iter_mut().enumerate() {
                    *x -= bj * self.band[col - (j - top - i)];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random-ish banded matrix (pivoting needed: zero diagonal entries) against a dense
    /// solve by faer's partial-pivoting LU.
    #[test]
    fn band_lu_solves_like_dense_lu_with_pivoting() {
        let n = 40;
        let (kl, ku) = (3, 2);
        let mut dense = faer::Mat::<f64>::zeros(n, n);
        let mut lu = BandLu::new(n, kl, ku);
        let mut seed = 1u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 33) as f64 / (1u64 << 31) as f64) - 0.5
        };
        for j in 0..n {
            for i in j.saturating_sub(ku)..(j + kl + 1).min(n) {
                // Zero diagonal every third row: a pivot must come from below.
                let v = if i == j && i % 3 == 0 { 0.0 } else { next() };
                dense[(i, j)] = v;
                lu.add(lu.index(i, j), v);
            }
        }
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut x = b.clone();
        lu.factorize().unwrap();
        lu.solve_in_place(&mut x);
        let reference = faer::linalg::solvers::Solve::solve(&dense.partial_piv_lu(), faer::Mat::from_fn(n, 1, |i, _| b[i]));
        for i in 0..n {
            // Same system solved two ways: agreement to rounding (condition ~1e2-1e3).
            assert!((x[i] - reference[(i, 0)]).abs() < 1e-10, "x[{i}] = {} vs {}", x[i], reference[(i, 0)]);
        }
        // Residual of the banded solution itself.
        for i in 0..n {
            let r: f64 = (0..n).map(|j| dense[(i, j)] * x[j]).sum::<f64>() - b[i];
            assert!(r.abs() < 1e-12, "residual {r} in row {i}");
        }
    }

    /// Stopping each row at its pattern's last entry and its fill's visits only zeros less:
    /// the same factors and solution, bit for bit, as sweeping to the band's edge (a pattern
    /// sparse inside its band, pivoting needed).
    #[test]
    fn a_pattern_inside_the_band_gives_the_same_factors_as_the_whole_band() {
        let (n, kl, ku): (usize, usize, usize) = (60, 4, 3);
        let mut seed = 5u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 33) as f64 / (1u64 << 31) as f64) - 0.5
        };
        let mut entries = Vec::new();
        for j in 0..n {
            for i in j.saturating_sub(ku)..(j + kl + 1).min(n) {
                // About a third of the band; no diagonal in rows 4, 8, 16, … (a multiple of
                // 4 and not of 3), whose row and column meet their neighbour's instead
                // (structurally nonsingular, a pivot from below needed).
                let swapped = |k: usize| k % 4 == 0 && k + 1 < n;
                let diagonal = i == j && (!swapped(i) || i % 3 == 0);
                let pair = (swapped(j) && i == j + 1) || (swapped(i) && j == i + 1);
                if diagonal || pair || (i * 7 + j * 3) % 3 == 0 && i != j {
                    entries.push((i, j, next()));
                }
            }
        }
        let mut whole = BandLu::new(n, kl, ku);
        let mut patterned = BandLu::with_pattern(n, kl, ku, entries.iter().map(|&(i, j, _)| (i, j)));
        for &(i, j, v) in &entries {
            whole.add(whole.index(i, j), v);
            patterned.add(patterned.index(i, j), v);
        }
        whole.factorize().unwrap();
        patterned.factorize().unwrap();
        assert!(whole.pivot.iter().enumerate().any(|(j, &p)| p != j), "no row interchange: the test would not cover them");
        assert_eq!(whole.band, patterned.band);
        let mut x: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
        let mut y = x.clone();
        whole.solve_in_place(&mut x);
        patterned.solve_in_place(&mut y);
        assert_eq!(x, y);
        // `clear` after a factorization leaves no fill behind: other values on the same
        // pattern factor as in fresh storage.
        let mut fresh = BandLu::with_pattern(n, kl, ku, entries.iter().map(|&(i, j, _)| (i, j)));
        patterned.clear();
        for &(i, j, v) in &entries {
            let w = v * v - 0.1;
            patterned.add(patterned.index(i, j), w);
            fresh.add(fresh.index(i, j), w);
        }
        patterned.factorize().unwrap();
        fresh.factorize().unwrap();
        assert_eq!(patterned.band, fresh.band);
    }

    #[test]
    fn singular_band_is_reported() {
        let mut lu = BandLu::new(3, 1, 1);
        for (i, j) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            lu.add(lu.index(i, j), 1.0);
        }
        lu.add(lu.index(2, 2), 1.0);
        assert_eq!(lu.factorize(), Err(ZeroPivot));
    }

    /// A path graph numbered out of order comes back with bandwidth 1.
    #[test]
    fn reverse_cuthill_mckee_finds_the_path() {
        let order = [4, 0, 3, 1, 5, 2];
        let (mut rows, mut cols) = (Vec::new(), Vec::new());
        for k in 0..order.len() {
            rows.push(order[k]);
            cols.push(order[k]);
            if k + 1 < order.len() {
                rows.push(order[k]);
                cols.push(order[k + 1]);
            }
        }
        let o = BandOrdering::reverse_cuthill_mckee(6, &rows, &cols);
        assert_eq!((o.kl, o.ku), (0, 1));
        let mut seen = o.position.clone();
        seen.sort();
        assert_eq!(seen, (0..6).collect::<Vec<_>>());
    }
}
