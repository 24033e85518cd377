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
    /// and entries that sum to zero are dropped. `None` when an index is out of range.
    pub fn from_triplets(nrows: usize, ncols: usize, entries: impl IntoIterator<Item = (usize, usize, f64)>) -> Option<Self> {
        let mut e: Vec<(usize, usize, f64)> = entries.into_iter().collect();
        if e.iter().any(|&(i, j, _)| i >= nrows || j >= ncols) {
            return None;
        }
        e.sort_unstable_by_key(|&(i, j, _)| (i, j));
        let mut start = vec![0; nrows + 1];
        let (mut col, mut val) = (Vec::with_capacity(e.len()), Vec::with_capacity(e.len()));
        let mut k = 0;
        for i in 0..nrows {
            while k < e.len() && e[k].0 == i {
                let j = e[k].1;
                let mut x = 0.0;
                while k < e.len() && e[k].0 == i && e[k].1 == j {
                    x += e[k].2;
                    k += 1;
                }
                if x != 0.0 {
                    col.push(j);
                    val.push(x);
                }
            }
            start[i + 1] = col.len();
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
