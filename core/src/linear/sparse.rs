//! Compressed-row sparse real matrices: the products that eigenvector lifts, residuals and
//! normalizations need, in time proportional to the non-zeros.

use faer::{c64, Col, ColMut, ColRef, Mat};

/// The entries of the vectors a [`SparseMatrix`] multiplies: `f64` or `c64`.
pub trait SparseScalar: faer::traits::ComplexField + Copy + Default + std::ops::Add<Output = Self> + std::ops::Mul<f64, Output = Self> {}
impl SparseScalar for f64 {}
impl SparseScalar for c64 {}

/// The entries of a column stored contiguously (every owned `Col`, every column of a `Mat`).
pub(crate) fn contiguous<T>(v: ColRef<'_, T>) -> &[T] {
    match v.try_as_col_major() {
        Some(c) => c.as_slice(),
        None => unreachable!("owned columns and the columns of owned matrices are contiguous"),
    }
}

/// [`contiguous`] of a mutable column.
pub(crate) fn contiguous_mut<T>(v: ColMut<'_, T>) -> &mut [T] {
    match v.try_as_col_major_mut() {
        Some(c) => c.as_slice_mut(),
        None => unreachable!("owned columns and the columns of owned matrices are contiguous"),
    }
}

/// A real sparse matrix in compressed-row form (exact zeros are not stored).
#[derive(Clone, Debug)]
pub struct SparseMatrix {
    nrows: usize,
    ncols: usize,
    start: Vec<usize>,
    col: Vec<usize>,
    val: Vec<f64>,
}

impl SparseMatrix {
    /// The non-zeros of a dense matrix.
    pub fn from_dense(m: &Mat<f64>) -> Self {
        let rows: Vec<usize> = (0..m.nrows()).collect();
        let cols: Vec<usize> = (0..m.ncols()).collect();
        Self::from_dense_part(m, &rows, &cols)
    }

    /// An `nrows x ncols` matrix from `(row, col, value)` entries; duplicates are summed
    /// in the order given and entries that sum to zero are dropped. `None` when an index is
    /// out of range. See [`Self::from_triplet_parts`].
    pub fn from_triplets(nrows: usize, ncols: usize, entries: impl IntoIterator<Item = (usize, usize, f64)>) -> Option<Self> {
        let entries = entries.into_iter();
        let capacity = entries.size_hint().0;
        let (mut rows, mut cols, mut values) = (Vec::with_capacity(capacity), Vec::with_capacity(capacity), Vec::with_capacity(capacity));
        for (i, j, v) in entries {
            rows.push(i);
            cols.push(j);
            values.push(v);
        }
        Self::from_triplet_parts(nrows, ncols, &rows, &cols, &values)
    }

    /// [`Self::from_triplets`] of the entries `(rows[k], cols[k], values[k])`, in time linear
    /// in their number (sorting them by comparison took O(entries log entries): 4–6 % of a
    /// sparse eigenanalysis' samples): a stable counting sort by row, then each row's
    /// entries sorted by column stably (a row holds a few dozen), so the duplicates of a
    /// position are summed from 0 in the order given — each sum the one a dense
    /// accumulation `m[(i, j)] += v` over the entries in order gives
    /// ([`crate::dae::Triplets::to_dense`], the dense linearization's). One temporary of
    /// 16 bytes an entry (the comparison sort's copy took 24); the result's arrays are
    /// written only as far as the sums kept (the memory beyond them is never touched, so not
    /// resident: `F_/ẏ` keeps about a third of the assembler's entries).
    pub fn from_triplet_parts(nrows: usize, ncols: usize, rows: &[usize], cols: &[usize], values: &[f64]) -> Option<Self> {
        assert!(rows.len() == values.len() && cols.len() == values.len(), "from_triplet_parts: one row and one column per value");
        if rows.iter().any(|&i| i >= nrows) || cols.iter().any(|&j| j >= ncols) {
            return None;
        }
        let nnz = values.len();
        // next[i]: where row i's next entry goes (row pointers, moved along by the scatter).
        let mut next = vec![0usize; nrows + 1];
        for &i in rows {
            next[i + 1] += 1;
        }
        for i in 0..nrows {
            next[i + 1] += next[i];
        }
        let row_start = next.clone();
        let mut by_row = vec![(0usize, 0.0f64); nnz];
        for k in 0..nnz {
            let p = &mut next[rows[k]];
            by_row[*p] = (cols[k], values[k]);
            *p += 1;
        }
        drop(next);
        // Each row by column (stable: a position's duplicates keep their order), each run of
        // one position summed, zero sums dropped.
        let mut start = Vec::with_capacity(nrows + 1);
        start.push(0);
        let (mut col, mut val) = (Vec::with_capacity(nnz), Vec::with_capacity(nnz));
        for i in 0..nrows {
            let row = &mut by_row[row_start[i]..row_start[i + 1]];
            row.sort_by_key(|&(j, _)| j);
            let mut k = 0;
            while k < row.len() {
                let j = row[k].0;
                let mut x = 0.0;
                while k < row.len() && row[k].0 == j {
                    x += row[k].1;
                    k += 1;
                }
                if x != 0.0 {
                    col.push(j);
                    val.push(x);
                }
            }
            start.push(col.len());
        }
        Some(SparseMatrix { nrows, ncols, start, col, val })
    }

    /// The non-zeros of the submatrix `m[rows, cols]` (indices in the given order).
    pub fn from_dense_part(m: &Mat<f64>, rows: &[usize], cols: &[usize]) -> Self {
        let mut start = Vec::with_capacity(rows.len() + 1);
        let (mut col, mut val) = (Vec::new(), Vec::new());
        start.push(0);
        for &i in rows {
            for (jj, &j) in cols.iter().enumerate() {
                let x = m[(i, j)];
                if x != 0.0 {
                    col.push(jj);
                    val.push(x);
                }
            }
            start.push(col.len());
        }
        SparseMatrix { nrows: rows.len(), ncols: cols.len(), start, col, val }
    }

    pub fn nrows(&self) -> usize {
        self.nrows
    }
    pub fn ncols(&self) -> usize {
        self.ncols
    }
    /// Number of stored non-zeros.
    pub fn nnz(&self) -> usize {
        self.val.len()
    }

    /// Frobenius norm.
    pub fn norm_l2(&self) -> f64 {
        self.val.iter().map(|x| x * x).sum::<f64>().sqrt()
    }

    /// `out = M v` (slices of the matrix's column and row counts), for real or complex
    /// vectors, without allocating.
    pub fn mul_into<T: SparseScalar>(&self, v: &[T], out: &mut [T]) {
        assert!(v.len() == self.ncols && out.len() == self.nrows, "M v: sizes");
        for (i, o) in out.iter_mut().enumerate() {
            let mut s = T::default();
            for k in self.start[i]..self.start[i + 1] {
                s = s + v[self.col[k]] * self.val[k];
            }
            *o = s;
        }
    }

    /// `out = Mᵀ v`, without allocating.
    pub fn mul_t_into<T: SparseScalar>(&self, v: &[T], out: &mut [T]) {
        assert!(v.len() == self.nrows && out.len() == self.ncols, "Mᵀ v: sizes");
        out.fill(T::default());
        for (i, &x) in v.iter().enumerate() {
            for k in self.start[i]..self.start[i + 1] {
                out[self.col[k]] = out[self.col[k]] + x * self.val[k];
            }
        }
    }

    /// `|M| x` (or `|M|ᵀ x`): the moduli of the entries times `x` (the bound of the
    /// rounding of `M x`, entry by entry).
    pub fn abs_mul(&self, x: &[f64], transpose: bool) -> Vec<f64> {
        let mut out = vec![0.0; if transpose { self.ncols } else { self.nrows }];
        for i in 0..self.nrows {
            for k in self.start[i]..self.start[i + 1] {
                let (j, a) = (self.col[k], self.val[k].abs());
                if transpose {
                    out[j] += a * x[i];
                } else {
                    out[i] += a * x[j];
                }
            }
        }
        out
    }

    /// The largest number of stored entries in a row.
    pub fn max_row_len(&self) -> usize {
        (0..self.nrows).map(|i| self.start[i + 1] - self.start[i]).max().unwrap_or(0)
    }

    /// `(M v_a, M v_b)` (or with `Mᵀ`) for `v = v_a + v_b`, `v_b` the entries of `v` where
    /// `split` is true: both in one pass over the matrix.
    pub fn mul_split(&self, v: &Col<c64>, split: &[bool], transpose: bool) -> (Col<c64>, Col<c64>) {
        let len = if transpose { self.ncols } else { self.nrows };
        let (mut a, mut b) = (Col::<c64>::zeros(len), Col::<c64>::zeros(len));
        let (x, pa, pb) = (contiguous(v.as_ref()), contiguous_mut(a.as_mut()), contiguous_mut(b.as_mut()));
        assert!(x.len() == if transpose { self.nrows } else { self.ncols } && split.len() == x.len(), "split product: sizes");
        for i in 0..self.nrows {
            for k in self.start[i]..self.start[i + 1] {
                let j = self.col[k];
                if transpose {
                    let out = if split[i] { &mut *pb } else { &mut *pa };
                    out[j] += x[i] * self.val[k];
                } else {
                    let out = if split[j] { &mut *pb } else { &mut *pa };
                    out[i] += x[j] * self.val[k];
                }
            }
        }
        (a, b)
    }

    /// Row `i` of `M v_a` and of `M v_b` for `v = v_a + v_b`, `v_b` the entries of `v` where
    /// `split` is true (the sums of [`Self::mul_split`] without the transpose, in its order).
    #[inline]
    pub fn row_split(&self, i: usize, v: &[c64], split: &[bool]) -> (c64, c64) {
        let (mut a, mut b) = (c64::new(0.0, 0.0), c64::new(0.0, 0.0));
        for k in self.start[i]..self.start[i + 1] {
            let j = self.col[k];
            if split[j] {
                b += v[j] * self.val[k];
            } else {
                a += v[j] * self.val[k];
            }
        }
        (a, b)
    }

    /// `a(self) + b(other)` entrywise, in faer's compressed-column layout: column pointers,
    /// row indices (ascending in each column) and values, on the union of the two patterns
    /// with explicit zeros kept and the entries present in both combined by
    /// `add(a(self), b(other))`: what faer's `try_new_from_triplets` makes of the triplets
    /// of `self` then `other` (each position has at most one term from each, so the sum is
    /// the same either way), by two counting passes instead of a sort.
    pub fn csc_sum<T: Copy>(&self, other: &SparseMatrix, a: impl Fn(f64) -> T, b: impl Fn(f64) -> T, add: impl Fn(T, T) -> T) -> (Vec<usize>, Vec<usize>, Vec<T>) {
        assert!(self.nrows == other.nrows && self.ncols == other.ncols, "csc_sum: sizes");
        let (m, n) = (self.nrows, self.ncols);
        // Pass 1: entries per column of the union (a column seen in row i is marked i + 1).
        let mut mark = vec![0usize; n];
        let mut count = vec![0usize; n + 1];
        for i in 0..m {
            for mat in [self, other] {
                for &j in &mat.col[mat.start[i]..mat.start[i + 1]] {
                    if mark[j] != i + 1 {
                        mark[j] = i + 1;
                        count[j + 1] += 1;
                    }
                }
            }
        }
        for j in 0..n {
            count[j + 1] += count[j];
        }
        let col_ptr = count.clone();
        let nnz = col_ptr[n];
        // Pass 2: rows in order, so each column's row indices come ascending.
        let (mut row_idx, mut val): (Vec<usize>, Vec<Option<T>>) = (vec![0; nnz], vec![None; nnz]);
        let mut next = count;
        let mut slot = vec![usize::MAX; n];
        mark.fill(0);
        for i in 0..m {
            for k in self.start[i]..self.start[i + 1] {
                let j = self.col[k];
                let p = next[j];
                next[j] += 1;
                row_idx[p] = i;
                val[p] = Some(a(self.val[k]));
                mark[j] = i + 1;
                slot[j] = p;
            }
            for k in other.start[i]..other.start[i + 1] {
                let j = other.col[k];
                let x = b(other.val[k]);
                if mark[j] == i + 1 {
                    let p = slot[j];
                    val[p] = Some(match val[p] {
                        Some(y) => add(y, x),
                        None => x,
                    });
                } else {
                    let p = next[j];
                    next[j] += 1;
                    row_idx[p] = i;
                    val[p] = Some(x);
                    mark[j] = i + 1;
                    slot[j] = p;
                }
            }
        }
        let val = val.into_iter().map(|x| x.unwrap_or_else(|| unreachable!("every counted place is filled"))).collect();
        (col_ptr, row_idx, val)
    }

    /// The matrix whose row `i` is row `order[i]` of this one (`order` a permutation).
    pub fn rows_in_order(&self, order: &[usize]) -> SparseMatrix {
        assert!(order.len() == self.nrows, "rows_in_order: a row each");
        let mut start = Vec::with_capacity(self.nrows + 1);
        let (mut col, mut val) = (Vec::with_capacity(self.val.len()), Vec::with_capacity(self.val.len()));
        start.push(0);
        for &r in order {
            col.extend_from_slice(&self.col[self.start[r]..self.start[r + 1]]);
            val.extend_from_slice(&self.val[self.start[r]..self.start[r + 1]]);
            start.push(col.len());
        }
        SparseMatrix { nrows: self.nrows, ncols: self.ncols, start, col, val }
    }

    /// The matrix whose row `i` is column `order[i]` of this one, its entries by increasing
    /// row of this one: [`Self::mul_into`] with it sums as [`Self::mul_t_into`] does.
    pub fn transpose_rows_in_order(&self, order: &[usize]) -> SparseMatrix {
        assert!(order.len() == self.ncols, "transpose_rows_in_order: a column each");
        let mut place = vec![0usize; self.ncols];
        for (i, &c) in order.iter().enumerate() {
            place[c] = i;
        }
        let mut start = vec![0usize; self.ncols + 1];
        for &c in &self.col {
            start[place[c] + 1] += 1;
        }
        for i in 0..self.ncols {
            start[i + 1] += start[i];
        }
        let mut next = start.clone();
        let (mut col, mut val) = (vec![0usize; self.val.len()], vec![0.0; self.val.len()]);
        for r in 0..self.nrows {
            for k in self.start[r]..self.start[r + 1] {
                let p = next[place[self.col[k]]];
                next[place[self.col[k]]] += 1;
                col[p] = r;
                val[p] = self.val[k];
            }
        }
        SparseMatrix { nrows: self.ncols, ncols: self.nrows, start, col, val }
    }

    /// `uᵀ M v` (no conjugation), without forming `M v`.
    pub fn bilinear(&self, u: &Col<c64>, v: &Col<c64>) -> c64 {
        let (u, v) = (contiguous(u.as_ref()), contiguous(v.as_ref()));
        assert!(u.len() == self.nrows && v.len() == self.ncols, "uᵀ M v: sizes");
        (0..self.nrows).fold(c64::new(0.0, 0.0), |acc, i| {
            let mv = (self.start[i]..self.start[i + 1]).fold(c64::new(0.0, 0.0), |s, k| s + v[self.col[k]] * self.val[k]);
            acc + u[i] * mv
        })
    }

    /// `uᵀ M v` in twice the working precision ([`super::Compensated`]): each row's `M v`
    /// and the outer sum carry their cancellation exactly.
    pub fn bilinear_compensated(&self, u: &Col<c64>, v: &Col<c64>) -> c64 {
        use super::CompensatedComplex;
        let (u, v) = (contiguous(u.as_ref()), contiguous(v.as_ref()));
        assert!(u.len() == self.nrows && v.len() == self.ncols, "uᵀ M v: sizes");
        let mut acc = CompensatedComplex::default();
        for i in 0..self.nrows {
            let mut mv = CompensatedComplex::default();
            (self.start[i]..self.start[i + 1]).for_each(|k| mv.add_real_times(self.val[k], v[self.col[k]]));
            acc.add_times(u[i], mv);
        }
        acc.value()
    }

    /// The two-sided Rayleigh quotient `λ = −uᵀ K v / uᵀ E v` of the pencil `λ E + K`
    /// (`self` = `K`), its sums compensated ([`Self::bilinear_compensated`]): a stiff beam's
    /// `uᵀ K v` cancels its axial stiffness down to the bending value, which plain sums lose.
    /// `None` when it is not finite (`uᵀ E v` vanishes).
    pub fn two_sided_quotient(&self, e: &SparseMatrix, u: &Col<c64>, v: &Col<c64>) -> Option<c64> {
        let q = -self.bilinear_compensated(u, v) / e.bilinear_compensated(u, v);
        (q.re.is_finite() && q.im.is_finite()).then_some(q)
    }

    /// `|u|ᵀ |M| |v|`: the magnitude of the terms of `uᵀ M v`, whose rounding error is a few
    /// ε times this.
    pub fn abs_bilinear(&self, u: &Col<c64>, v: &Col<c64>) -> f64 {
        let (u, v) = (contiguous(u.as_ref()), contiguous(v.as_ref()));
        assert!(u.len() == self.nrows && v.len() == self.ncols, "|u|ᵀ |M| |v|: sizes");
        (0..self.nrows).map(|i| u[i].norm() * (self.start[i]..self.start[i + 1]).map(|k| v[self.col[k]].norm() * self.val[k].abs()).sum::<f64>()).sum()
    }

    /// `M v`.
    pub fn mul_complex(&self, v: &Col<c64>) -> Col<c64> {
        self.mul_col(v, false)
    }

    /// `Mᵀ v`.
    pub fn mul_t_complex(&self, v: &Col<c64>) -> Col<c64> {
        self.mul_col(v, true)
    }

    /// `M v` of a real `v`.
    pub fn mul_real(&self, v: &Col<f64>) -> Col<f64> {
        self.mul_col(v, false)
    }

    /// `Mᵀ v` of a real `v`.
    pub fn mul_t_real(&self, v: &Col<f64>) -> Col<f64> {
        self.mul_col(v, true)
    }

    fn mul_col<T: SparseScalar>(&self, v: &Col<T>, transpose: bool) -> Col<T> {
        let mut out = Col::<T>::zeros(if transpose { self.ncols } else { self.nrows });
        let x = contiguous(v.as_ref());
        if transpose {
            self.mul_t_into(x, contiguous_mut(out.as_mut()));
        } else {
            self.mul_into(x, contiguous_mut(out.as_mut()));
        }
        out
    }

    /// `M X` for a dense `X`.
    pub fn mul_dense(&self, x: &Mat<f64>) -> Mat<f64> {
        let mut out = Mat::<f64>::zeros(self.nrows, x.ncols());
        for c in 0..x.ncols() {
            for i in 0..self.nrows {
                out[(i, c)] = (self.start[i]..self.start[i + 1]).map(|k| self.val[k] * x[(self.col[k], c)]).sum();
            }
        }
        out
    }

    /// `M X` for a complex `X`.
    pub fn mul_complex_mat(&self, x: &Mat<c64>) -> Mat<c64> {
        let mut out = Mat::<c64>::zeros(self.nrows, x.ncols());
        for c in 0..x.ncols() {
            for i in 0..self.nrows {
                out[(i, c)] = (self.start[i]..self.start[i + 1]).fold(c64::new(0.0, 0.0), |s, k| s + x[(self.col[k], c)] * self.val[k]);
            }
        }
        out
    }

    /// `Mᵀ X` for a complex `X`.
    pub fn mul_t_complex_mat(&self, x: &Mat<c64>) -> Mat<c64> {
        let mut out = Mat::<c64>::zeros(self.ncols, x.ncols());
        for c in 0..x.ncols() {
            for i in 0..self.nrows {
                for k in self.start[i]..self.start[i + 1] {
                    out[(self.col[k], c)] += x[(i, c)] * self.val[k];
                }
            }
        }
        out
    }

    /// `(row, col, value)` of every stored entry, row by row.
    pub fn triplets(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        (0..self.nrows).flat_map(move |i| (self.start[i]..self.start[i + 1]).map(move |k| (i, self.col[k], self.val[k])))
    }

    /// Dense copy.
    pub fn to_dense(&self) -> Mat<f64> {
        let mut m = Mat::zeros(self.nrows, self.ncols);
        for i in 0..self.nrows {
            for k in self.start[i]..self.start[i + 1] {
                m[(i, self.col[k])] = self.val[k];
            }
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::{SparseColMat, Triplet};

    /// `csc_sum` is what faer's `try_new_from_triplets` makes of the triplets of both
    /// matrices (independent code): same column pointers, row indices and values, with a
    /// position in both, positions in one only, an explicit zero from a zero factor and an
    /// empty row and column.
    #[test]
    fn csc_sum_matches_faers_triplets() {
        let k = SparseMatrix::from_triplets(4, 4, [(0, 0, 2.0), (0, 3, -1.0), (2, 1, 5.0), (3, 3, 4.0), (3, 0, 1.5)]).unwrap();
        let e = SparseMatrix::from_triplets(4, 4, [(0, 0, 0.5), (2, 2, 3.0), (3, 0, -2.0), (1, 3, 7.0)]).unwrap();
        for sigma in [0.0, -0.25] {
            let (col_ptr, row_idx, val) = k.csc_sum(&e, |v| v, |v| sigma * v, |x, y| x + y);
            let t: Vec<Triplet<usize, usize, f64>> = k.triplets().map(|(i, j, v)| Triplet::new(i, j, v)).chain(e.triplets().map(|(i, j, v)| Triplet::new(i, j, sigma * v))).collect();
            let a = SparseColMat::<usize, f64>::try_new_from_triplets(4, 4, &t).unwrap();
            assert_eq!(col_ptr, a.symbolic().col_ptr());
            assert_eq!(row_idx, a.symbolic().row_idx());
            assert_eq!(val, a.val());
        }
    }

    /// `from_triplets` against a dense accumulation of the same entries in the order given
    /// (`m[(i, j)] += v`, independent code): every stored value bit for bit, columns
    /// ascending in each row, every non-zero of the dense sum stored and no zero. The
    /// entries are duplicates of few positions with magnitudes from 1e-3 to 1e16, so that
    /// summing a position's duplicates in another order changes its last bits (checked: the
    /// reversed order differs somewhere), a position whose entries cancel exactly, an empty
    /// row and column, non-square shapes; rows of about 600 entries and of about 27.
    #[test]
    fn from_triplets_sums_duplicates_in_the_order_given() {
        for (nrows, ncols, count) in [(7, 5, 4000), (300, 40, 8000)] {
            check_against_dense_sum(nrows, ncols, count);
        }
        assert!(SparseMatrix::from_triplets(3, 2, [(3, 0, 1.0)]).is_none());
        assert!(SparseMatrix::from_triplets(3, 2, [(0, 2, 1.0)]).is_none());
        assert_eq!(SparseMatrix::from_triplets(0, 0, []).unwrap().nnz(), 0);
    }

    fn check_against_dense_sum(nrows: usize, ncols: usize, count: usize) {
        // A small linear congruential generator: reproducible, no dependency.
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            seed >> 33
        };
        let mut entries = Vec::new();
        for _ in 0..count {
            let (i, j) = ((next() % nrows as u64) as usize, (next() % ncols as u64) as usize);
            if i == 3 || j == 2 || (i, j) == (6, 4) {
                continue; // row 3 and column 2 stay empty, (6, 4) is set below
            }
            let scale = [1e-3, 0.1, 1.0, 7.0, 1e8, 1e16][(next() % 6) as usize];
            let sign = if next() % 2 == 0 { 1.0 } else { -1.0 };
            entries.push((i, j, sign * scale * (1.0 + (next() % 1000) as f64 / 997.0)));
        }
        // A position whose entries cancel exactly (dropped).
        entries.extend([(6, 4, 0.25), (6, 4, 0.5), (6, 4, -0.75)]);
        let dense_sum = |order: &mut dyn Iterator<Item = &(usize, usize, f64)>| {
            let mut m = Mat::<f64>::zeros(nrows, ncols);
            order.for_each(|&(i, j, v)| m[(i, j)] += v);
            m
        };
        let forward = dense_sum(&mut entries.iter());
        let reversed = dense_sum(&mut entries.iter().rev());
        assert!((0..nrows).any(|i| (0..ncols).any(|j| forward[(i, j)].to_bits() != reversed[(i, j)].to_bits())), "the entries do not depend on the order of summation");
        let m = SparseMatrix::from_triplets(nrows, ncols, entries.iter().copied()).unwrap();
        assert_eq!((m.nrows(), m.ncols()), (nrows, ncols));
        let mut stored = 0;
        for i in 0..nrows {
            let row = &m.col[m.start[i]..m.start[i + 1]];
            assert!(row.windows(2).all(|w| w[0] < w[1]), "row {i}: columns {row:?} not ascending");
            for j in 0..ncols {
                let want = forward[(i, j)];
                match row.iter().position(|&c| c == j) {
                    Some(p) => assert_eq!(m.val[m.start[i] + p].to_bits(), want.to_bits(), "({i}, {j})"),
                    None => assert!(want == 0.0, "({i}, {j}): {want} not stored"),
                }
                stored += usize::from(want != 0.0);
            }
        }
        assert_eq!(m.nnz(), stored);
        assert!(m.triplets().all(|(i, j, v)| i != 3 && j != 2 && v != 0.0 && (i, j) != (6, 4)));
        // The same from the parts.
        let (rows, cols, values): (Vec<usize>, Vec<usize>, Vec<f64>) = (entries.iter().map(|e| e.0).collect(), entries.iter().map(|e| e.1).collect(), entries.iter().map(|e| e.2).collect());
        let parts = SparseMatrix::from_triplet_parts(nrows, ncols, &rows, &cols, &values).unwrap();
        assert_eq!((parts.start, parts.col, parts.val.iter().map(|v| v.to_bits()).collect::<Vec<_>>()), (m.start.clone(), m.col.clone(), m.val.iter().map(|v| v.to_bits()).collect::<Vec<_>>()));
    }

    /// The reordered rows, and the transpose's, multiply as the matrix and its transpose do
    /// (bit for bit: the same sums in the same order).
    #[test]
    fn reordered_rows_multiply_as_the_matrix() {
        let m = SparseMatrix::from_triplets(4, 3, [(0, 0, 2.0), (0, 2, -1.0), (1, 1, 0.3), (2, 1, 5.0), (3, 2, 4.0), (3, 0, 1.5), (2, 2, 0.7)]).unwrap();
        let (x3, x4) = ([0.1, -0.7, 1.3], [0.5, 2.0, -1.1, 0.9]);
        let (mut y, mut yt) = ([0.0; 4], [0.0; 3]);
        m.mul_into(&x3, &mut y);
        m.mul_t_into(&x4, &mut yt);
        let (rows, cols) = ([2, 0, 3, 1], [1, 2, 0]);
        let (mut p, mut pt) = ([0.0; 4], [0.0; 3]);
        m.rows_in_order(&rows).mul_into(&x3, &mut p);
        m.transpose_rows_in_order(&cols).mul_into(&x4, &mut pt);
        for i in 0..4 {
            assert_eq!(p[i].to_bits(), y[rows[i]].to_bits());
        }
        for i in 0..3 {
            assert_eq!(pt[i].to_bits(), yt[cols[i]].to_bits());
        }
    }
}
