//! Elimination, before factoring, of unknowns that enter their own equation alone with a
//! diagonal coefficient. A dynamic node's momenta `p = (β, γ)` appear in their definitions
//! (rows 0–5: `β − Σ …`, `γ − Σ …`) only as `c p` (no element reads a momentum), so
//! `δp = (r_M − J_Mq δq) / c` and the remaining unknowns solve the Schur complement
//! `(J_Rq − J_Rp J_Mq / c) δq = r_R − J_Rp r_M / c` (`M`: the definitions, `R`: the other
//! equations, `q`: the other unknowns): 6 fewer unknowns per dynamic node, and for chains
//! and beams a band half as wide. Exact algebra: the same Newton increment as the whole
//! system's, up to rounding.

use super::factored::{Factored, LuPath, SparseError, Triplets};
use crate::lu::prefetch;

/// How many triplets (and Schur products) ahead [`Eliminated::factor`]'s scatter asks the
/// caches for the storage it will add to ([`prefetch`]).
const SCATTER_AHEAD: usize = 32;

/// One eliminated unknown `p` and its equation `m`, with the pivot's entry.
#[derive(Clone, Copy, Debug)]
struct Pivot {
    row: usize,
    col: usize,
    entry: usize,
}

/// The reduced system of a pattern and how its values are formed from the Jacobian's.
pub(super) struct Eliminated {
    /// Where each triplet goes: below `storage_len`, the factorization's storage index (an
    /// entry of `J_Rq`); else `storage_len +` its entry in `entries` (pivots, `J_Mq`, `J_Rp`).
    /// One 32-bit index per triplet (4 bytes a triplet: the set-up refuses patterns whose
    /// indices would not fit, and the whole system is solved instead).
    target: Vec<u32>,
    storage_len: usize,
    entries: Vec<f64>,
    pivots: Vec<Pivot>,
    inverse: Vec<f64>,
    /// Original equation of each reduced equation, original unknown of each reduced unknown.
    kept_rows: Vec<usize>,
    kept_cols: Vec<usize>,
    /// `(storage index, entry (r, p), entry (m, q), pivot)`: terms of `J_Rp J_Mq / c`
    /// (32-bit, as `target`).
    products: Vec<[u32; 4]>,
    /// `(reduced equation, entry, pivot)`: entries of `J_Rp`, for the right-hand side.
    column: Vec<(usize, usize, usize)>,
    /// Entries of `J_Mq` by pivot: `row[row_start[k]..row_start[k + 1]]` holds
    /// `(reduced unknown, entry)`, for the back substitution.
    row_start: Vec<usize>,
    row: Vec<(usize, usize)>,
    inner: Factored,
    x: Vec<f64>,
}

/// Whether every triplet index and entry number of a pattern with `len` triplets fits the
/// set-up's 32-bit indices.
fn fits_u32(len: usize) -> bool {
    len < u32::MAX as usize
}

/// The distinct `(row, col)` pairs of an `n`x`n` pattern in order of first appearance, and
/// the distinct entry of each pair: a bucket sort by row and a column marker, no hashing.
/// The per-triplet arrays are 32-bit (the caller checks [`fits_u32`] on `rows.len()`): they
/// are the set-up's peak, 8 bytes a triplet instead of 16.
fn distinct(n: usize, rows: &[usize], cols: &[usize]) -> (Vec<u32>, Vec<(usize, usize)>) {
    debug_assert!(fits_u32(rows.len()));
    let mut start = vec![0usize; n + 1];
    for &r in rows {
        start[r + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut by_row = vec![0u32; rows.len()];
    for (k, &r) in rows.iter().enumerate() {
        by_row[fill[r]] = k as u32;
        fill[r] += 1;
    }
    drop(fill);
    // first[k]: the earliest triplet with k's pair (bucket order is triplet order).
    let mut first = vec![0u32; rows.len()];
    let mut seen = vec![u32::MAX; n];
    for i in 0..n {
        let bucket = &by_row[start[i]..start[i + 1]];
        for &k in bucket {
            let c = cols[k as usize];
            if seen[c] == u32::MAX {
                seen[c] = k;
            }
            first[k as usize] = seen[c];
        }
        for &k in bucket {
            seen[cols[k as usize]] = u32::MAX;
        }
    }
    drop(by_row);
    // Number the pairs in order of first appearance, in place: first[k] ≤ k is numbered
    // (the pairs counted first, so that their list is allocated once, exactly).
    let n_keys = first.iter().enumerate().filter(|&(k, &f)| f as usize == k).count();
    let mut keys = Vec::with_capacity(n_keys);
    for k in 0..rows.len() {
        first[k] = if first[k] as usize == k {
            keys.push((rows[k], cols[k]));
            (keys.len() - 1) as u32
        } else {
            first[first[k] as usize]
        };
    }
    let entry_of = first;
    (entry_of, keys)
}

impl Eliminated {
    /// The reduced pattern, or `None` when some equation `m` has an entry in another pair's
    /// unknown (the elimination would not be one diagonal step) or lacks its pivot.
    pub(super) fn new(j: &Triplets, pairs: &[(usize, usize)], path: LuPath) -> Result<Option<Self>, SparseError> {
        let n = j.n;
        if !fits_u32(j.rows.len()) || !fits_u32(n) {
            return Ok(None);
        }
        let mut pivot_of_row = vec![usize::MAX; n];
        let mut pivot_of_col = vec![usize::MAX; n];
        for (k, &(m, p)) in pairs.iter().enumerate() {
            if m >= n || p >= n || pivot_of_row[m] != usize::MAX || pivot_of_col[p] != usize::MAX {
                return Ok(None);
            }
            pivot_of_row[m] = k;
            pivot_of_col[p] = k;
        }
        let (entry_of, keys) = distinct(n, &j.rows, &j.cols);
        let reduced_index = |kept: &mut Vec<usize>, eliminated: &[usize]| {
            let mut map = vec![usize::MAX; n];
            for (i, m) in map.iter_mut().enumerate() {
                if eliminated[i] == usize::MAX {
                    *m = kept.len();
                    kept.push(i);
                }
            }
            map
        };
        let (mut kept_rows, mut kept_cols) = (Vec::new(), Vec::new());
        let row_map = reduced_index(&mut kept_rows, &pivot_of_row);
        let col_map = reduced_index(&mut kept_cols, &pivot_of_col);
        let mut pivots: Vec<Pivot> = pairs.iter().map(|&(row, col)| Pivot { row, col, entry: usize::MAX }).collect();
        // Entries of J_Rq by their number (their reduced row and column are read from
        // `keys` later), counted first and allocated exactly.
        let n_direct = keys.iter().filter(|&&(r, c)| pivot_of_row[r] == usize::MAX && pivot_of_col[c] == usize::MAX).count();
        let mut direct_entries: Vec<u32> = Vec::with_capacity(n_direct);
        let (mut column, mut row_entries) = (Vec::new(), Vec::new());
        // Entries other than J_Rq's, numbered compactly.
        let mut compact = vec![usize::MAX; keys.len()];
        let mut others = 0;
        for (e, &(r, c)) in keys.iter().enumerate() {
            let (k, l) = (pivot_of_row[r], pivot_of_col[c]);
            if k == usize::MAX && l == usize::MAX {
                direct_entries.push(e as u32);
                continue;
            }
            compact[e] = others;
            others += 1;
            match (k, l) {
                (k, l) if k != usize::MAX && l != usize::MAX => {
                    if k != l {
                        return Ok(None);
                    }
                    pivots[k].entry = compact[e];
                }
                (k, _) if k != usize::MAX => row_entries.push((k, col_map[c], compact[e])),
                (_, l) => column.push((row_map[r], compact[e], l)),
            }
        }
        if pivots.iter().any(|p| p.entry == usize::MAX) {
            return Ok(None);
        }
        row_entries.sort_by_key(|&(k, _, _)| k);
        let mut row_start = vec![0; pivots.len() + 1];
        for &(k, _, _) in &row_entries {
            row_start[k + 1] += 1;
        }
        for k in 0..pivots.len() {
            row_start[k + 1] += row_start[k];
        }
        let row: Vec<(usize, usize)> = row_entries.iter().map(|&(_, q, e)| (q, e)).collect();
        drop(row_entries);
        // Reduced entries: those of J_Rq, then the products' (r, q), duplicates shared. The
        // set-up's temporaries are sized exactly and freed as soon as they are read: they
        // set the run's peak memory on large models (1000-beam cantilever).
        let n_products: usize = column.iter().map(|&(_, _, k)| row_start[k + 1] - row_start[k]).sum();
        if !fits_u32(n_direct + n_products) {
            return Ok(None);
        }
        let mut red_keys_rows = Vec::with_capacity(n_direct + n_products);
        let mut red_keys_cols = Vec::with_capacity(n_direct + n_products);
        for &e in &direct_entries {
            let (r, c) = keys[e as usize];
            red_keys_rows.push(row_map[r]);
            red_keys_cols.push(col_map[c]);
        }
        // The products' storage indices (first component) are filled in once the reduced
        // pattern is factored, in place.
        let mut products: Vec<[u32; 4]> = Vec::with_capacity(n_products);
        for &(r, a, k) in &column {
            for &(q, b) in &row[row_start[k]..row_start[k + 1]] {
                red_keys_rows.push(r);
                red_keys_cols.push(q);
                products.push([0, a as u32, b as u32, k as u32]);
            }
        }
        drop(keys);
        let (reduced_of, reduced_keys) = distinct(kept_rows.len(), &red_keys_rows, &red_keys_cols);
        drop((red_keys_rows, red_keys_cols));
        let (red_rows, red_cols): (Vec<usize>, Vec<usize>) = reduced_keys.into_iter().unzip();
        let inner = Factored::new(kept_rows.len(), &red_rows, &red_cols, path)?;
        drop((red_rows, red_cols));
        let storage = inner.positions();
        let storage_len = storage.iter().max().map_or(0, |&m| m + 1);
        if !fits_u32(storage_len + others) {
            return Ok(None);
        }
        let mut storage_of = vec![usize::MAX; compact.len()];
        for (&e, &t) in direct_entries.iter().zip(&reduced_of) {
            storage_of[e as usize] = storage[t as usize];
        }
        for (p, &t) in products.iter_mut().zip(&reduced_of[direct_entries.len()..]) {
            p[0] = storage[t as usize] as u32;
        }
        drop(reduced_of);
        let target = entry_of
            .iter()
            .map(|&e| {
                let e = e as usize;
                (if compact[e] == usize::MAX { storage_of[e] } else { storage_len + compact[e] }) as u32
            })
            .collect();
        Ok(Some(Eliminated {
            target,
            storage_len,
            entries: vec![0.0; others],
            inverse: vec![0.0; pivots.len()],
            pivots,
            x: vec![0.0; n],
            kept_rows,
            kept_cols,
            products,
            column,
            row_start,
            row,
            inner,
        }))
    }

    pub(super) fn eliminated(&self) -> usize {
        self.pivots.len()
    }

    pub(super) fn is_banded(&self) -> bool {
        self.inner.is_banded()
    }

    /// Solves `J x = rhs` in place, `J`'s values given in the pattern's triplet order;
    /// `Err` for a zero pivot (the caller then solves the whole system).
    pub(super) fn solve(&mut self, values: &[f64], rhs: &mut [f64]) -> Result<(), SparseError> {
        self.factor(values)?;
        self.solve_factored(rhs);
        Ok(())
    }

    /// Forms the pivots and the Schur complement from `J`'s values (in the pattern's triplet
    /// order) and factors it; `Err` for a zero pivot.
    pub(super) fn factor(&mut self, values: &[f64]) -> Result<(), SparseError> {
        let len = self.storage_len;
        let (entries, inverse) = (&mut self.entries, &mut self.inverse);
        let (target, products, pivots) = (&self.target, &self.products, &self.pivots);
        let mut zero_pivot = false;
        // One pass over the triplets: J_Rq's values into the factorization's storage, the
        // others (pivots, J_Mq, J_Rp) into `entries`; then the products of J_Rp J_Mq / c.
        let factored = self.inner.factor_with(|storage| {
            entries.iter_mut().for_each(|v| *v = 0.0);
            for (k, (&t, &v)) in target.iter().zip(values).enumerate() {
                // The storage an entry [`SCATTER_AHEAD`] on adds to: its place is in `target`,
                // which the hardware cannot read ahead.
                if let Some(&ahead) = target.get(k + SCATTER_AHEAD) {
                    let ahead = ahead as usize;
                    if ahead < len {
                        prefetch::at(storage, ahead);
                    } else {
                        prefetch::at(entries, ahead - len);
                    }
                }
                let t = t as usize;
                if t < len {
                    storage[t] += v;
                } else {
                    entries[t - len] += v;
                }
            }
            for (inv, p) in inverse.iter_mut().zip(pivots) {
                let d = entries[p.entry];
                zero_pivot |= d == 0.0 || !d.is_finite();
                *inv = 1.0 / d;
            }
            if zero_pivot {
                // No Schur complement: what is factored is discarded below and the caller
                // solves the whole system (a rare case: one wasted factorization).
                return;
            }
            for (i, &[at, a, b, k]) in products.iter().enumerate() {
                if let Some(ahead) = products.get(i + SCATTER_AHEAD) {
                    prefetch::at(storage, ahead[0] as usize);
                }
                storage[at as usize] -= entries[a as usize] * entries[b as usize] * inverse[k as usize];
            }
        });
        if zero_pivot {
            return Err(SparseError::Singular);
        }
        factored
    }

    /// Solves `J x = rhs` in place with the entries and factors of the last successful
    /// [`Eliminated::factor`].
    pub(super) fn solve_factored(&mut self, rhs: &mut [f64]) {
        let (entries, inverse) = (&self.entries, &self.inverse);
        // Reduced right-hand side r_R − J_Rp r_M / c, in the reduced unknowns' storage.
        let nr = self.kept_rows.len();
        let (y, momenta) = self.x.split_at_mut(nr);
        for (yi, &i) in y.iter_mut().zip(&self.kept_rows) {
            *yi = rhs[i];
        }
        for &(r, e, k) in &self.column {
            y[r] -= entries[e] * rhs[self.pivots[k].row] * inverse[k];
        }
        self.inner.solve_factored(y);
        // Back substitution δp = (r_M − J_Mq δq) / c, before rhs is overwritten.
        for (k, p) in self.pivots.iter().enumerate() {
            let mut acc = rhs[p.row];
            for &(q, e) in &self.row[self.row_start[k]..self.row_start[k + 1]] {
                acc -= entries[e] * y[q];
            }
            momenta[k] = acc * inverse[k];
        }
        for (p, &v) in self.pivots.iter().zip(momenta.iter()) {
            rhs[p.col] = v;
        }
        for (&c, &v) in self.kept_cols.iter().zip(y.iter()) {
            rhs[c] = v;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::sparse::{LuPath, SparseLu, Triplets};

    /// A pseudo-random 5-block system shaped like dynamic nodes: unknowns `[q, p]` per block,
    /// equation `m` of a block reads `c p + J_mq q` (and nothing of other momenta), the rest
    /// reads anything of its own and the neighbouring blocks; duplicates included.
    fn system(c: f64, cross_momentum: bool) -> (Triplets, Vec<(usize, usize)>, Vec<f64>) {
        let (blocks, half) = (5, 2);
        let n = blocks * 2 * half;
        let mut seed = 7u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((seed >> 33) as f64 / (1u64 << 31) as f64) - 0.5
        };
        let mut j = Triplets::new(n);
        let mut pairs = Vec::new();
        for b in 0..blocks {
            let f = 2 * half * b;
            for k in 0..half {
                let (m, p) = (f + k, f + half + k);
                pairs.push((m, p));
                j.push(m, p, 0.5 * c);
                j.push(m, p, 0.5 * c);
                for q in 0..half {
                    j.push(m, f + q, next());
                }
                // Equilibrium rows: own momenta, own and neighbouring positions.
                let r = f + half + k;
                j.push(r, p, 1.0 + next());
                for q in 0..2 * half {
                    j.push(r, f + q, 2.0 * next() + if q == k { 3.0 } else { 0.0 });
                }
                if b + 1 < blocks {
                    j.push(r, f + 2 * half + k, next());
                    j.push(f + 2 * half + half + k, f + k, next());
                }
            }
        }
        if cross_momentum {
            j.push(0, 2 * half + half, 0.1);
        }
        let rhs = (0..n).map(|i| (i as f64 + 1.0).sin()).collect();
        (j, pairs, rhs)
    }

    fn solve(j: &Triplets, pairs: &[(usize, usize)], rhs: &[f64], path: LuPath) -> (Vec<f64>, usize) {
        let mut lu = SparseLu::with_path(path);
        lu.eliminating(pairs);
        let mut x = rhs.to_vec();
        lu.solve(j, &mut x).unwrap();
        (x, lu.eliminated())
    }

    #[test]
    fn eliminated_momenta_give_the_whole_systems_solution() {
        for path in [LuPath::Auto, LuPath::General] {
            for c in [1.0, 1e-4] {
                let (j, pairs, rhs) = system(c, false);
                let (x, eliminated) = solve(&j, &pairs, &rhs, path);
                assert_eq!(eliminated, pairs.len());
                let (reference, none) = solve(&j, &[], &rhs, path);
                assert_eq!(none, 0);
                // The same system solved two ways: agreement to rounding (condition ~1/c).
                for (a, b) in x.iter().zip(&reference) {
                    assert!((a - b).abs() <= 1e-9 * b.abs().max(1.0), "{a} vs {b} (c = {c})");
                }
                // And the residual of the eliminated solution itself.
                let d = j.to_dense();
                for i in 0..j.n {
                    let r: f64 = (0..j.n).map(|k| d[(i, k)] * x[k]).sum::<f64>() - rhs[i];
                    assert!(r.abs() < 1e-10, "residual {r} in row {i}");
                }
            }
        }
    }

    /// An equation that reads another pair's unknown is not eliminated: the whole system is
    /// solved instead, as is one with a zero pivot.
    #[test]
    fn elimination_falls_back_when_it_does_not_apply() {
        let (j, pairs, rhs) = system(1.0, true);
        let (x, eliminated) = solve(&j, &pairs, &rhs, LuPath::Auto);
        assert_eq!(eliminated, 0);
        assert_eq!(x, solve(&j, &[], &rhs, LuPath::Auto).0);
        let (j, pairs, rhs) = system(0.0, false);
        let mut lu = SparseLu::new();
        lu.eliminating(&pairs);
        let mut x = rhs.clone();
        lu.solve(&j, &mut x).unwrap();
        let d = j.to_dense();
        for i in 0..j.n {
            let r: f64 = (0..j.n).map(|k| d[(i, k)] * x[k]).sum::<f64>() - rhs[i];
            assert!(r.abs() < 1e-10, "residual {r} in row {i} (zero pivots: whole system)");
        }
    }
}
