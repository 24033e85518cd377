//! Why a Newton matrix is singular, in the model's words: the unknowns that no equation
//! determines and the equations that involve no unknown (structural rank: a maximum
//! matching of equations to unknowns over the nonzero entries of J, Duff, "On algorithms
//! for obtaining a maximum transversal", ACM TOMS 7, 1981), or, when every unknown is
//! matched but J is numerically singular, the unknowns with the largest entries in J's
//! null vector (the right singular vector of its smallest singular value; models up to
//! [`DENSE_NULL_VECTOR_LIMIT`] unknowns). An unconnected node, a massless free node, a
//! clamp twice on one node or a body without rotary inertia on a spherical hinge are
//! named this way instead of by the multiplier whose residual happens to be largest.

use std::collections::HashMap;

use crate::dae::{Assembler, Triplets};

/// Largest system whose null vector is computed with a dense SVD.
pub const DENSE_NULL_VECTOR_LIMIT: usize = 2000;

/// Names shown per list.
const SHOWN: usize = 6;

/// A sentence naming why `j` (the Newton matrix of `asm`'s model) is singular, when it
/// can be told.
pub fn explain_singular_matrix(asm: &Assembler, j: &Triplets) -> Option<String> {
    let n = j.n;
    let mut entries: HashMap<(usize, usize), f64> = HashMap::new();
    for k in 0..j.values.len() {
        *entries.entry((j.rows[k], j.cols[k])).or_insert(0.0) += j.values[k];
    }
    let mut by_row: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (&(r, c), &v) in &entries {
        if v != 0.0 && r < n && c < n {
            by_row[r].push(c);
        }
    }
    let (row_of_col, col_of_row) = maximum_matching(n, &by_row);
    let names = |idx: Vec<usize>, name: &dyn Fn(usize) -> String| {
        let more = idx.len().saturating_sub(SHOWN);
        let mut s: Vec<String> = idx.into_iter().take(SHOWN).map(name).collect();
        if more > 0 {
            s.push(format!("… {more} more"));
        }
        s.join(", ")
    };
    let unknown = |i: usize| asm.dofs.unknown_name(asm.model, i);
    let equation = |i: usize| asm.dofs.equation_name(asm.model, i);
    let free: Vec<usize> = (0..n).filter(|&c| row_of_col[c].is_none()).collect();
    if !free.is_empty() {
        let empty: Vec<usize> = (0..n).filter(|&r| col_of_row[r].is_none()).collect();
        return Some(format!(
            "the matrix is singular: structural rank {} of {n}; unknowns no equation determines: {}; equations left without an unknown: {}",
            n - free.len(),
            names(free, &unknown),
            names(empty, &equation)
        ));
    }
    if n > DENSE_NULL_VECTOR_LIMIT {
        return None;
    }
    let dense = j.to_dense();
    let svd = dense.svd().ok()?;
    let s = svd.S();
    let (largest, smallest) = (s[0], s[n - 1]);
    if !(smallest <= 1e-12 * largest) {
        return None;
    }
    let v = svd.V();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| v[(b, n - 1)].abs().total_cmp(&v[(a, n - 1)].abs()));
    let top = v[(order[0], n - 1)].abs();
    let shown: Vec<usize> = order.into_iter().take_while(|&i| v[(i, n - 1)].abs() >= 0.1 * top).collect();
    Some(format!(
        "the matrix is singular (smallest singular value {smallest:.1e} of the largest {largest:.1e}); the unknowns it leaves undetermined (largest entries of its null vector): {}",
        names(shown, &|i| format!("{} ({:.2})", unknown(i), v[(i, n - 1)]))
    ))
}

/// Maximum matching of rows to columns by augmenting paths (iterative depth-first search);
/// returns the row matched to each column and the column matched to each row.
fn maximum_matching(n: usize, by_row: &[Vec<usize>]) -> (Vec<Option<usize>>, Vec<Option<usize>>) {
    let mut row_of_col: Vec<Option<usize>> = vec![None; n];
    let mut col_of_row: Vec<Option<usize>> = vec![None; n];
    let mut seen = vec![usize::MAX; n];
    for start in 0..n {
        // Cheap assignment first.
        if let Some(&c) = by_row[start].iter().find(|&&c| row_of_col[c].is_none()) {
            row_of_col[c] = Some(start);
            col_of_row[start] = Some(c);
            continue;
        }
        // Depth-first search for an augmenting path: stack of (row, next edge index).
        let mut stack: Vec<(usize, usize)> = vec![(start, 0)];
        let mut path_cols: Vec<usize> = Vec::new();
        let mut found = false;
        while let Some(&mut (r, ref mut k)) = stack.last_mut() {
            if *k >= by_row[r].len() {
                stack.pop();
                path_cols.pop();
                continue;
            }
            let c = by_row[r][*k];
            *k += 1;
            if seen[c] == start {
                continue;
            }
            seen[c] = start;
            path_cols.push(c);
            match row_of_col[c] {
                None => {
                    found = true;
                    break;
                }
                Some(next) => stack.push((next, 0)),
            }
        }
        if found {
            // Rows on the stack are matched, in order, to the columns on the path.
            for (&(r, _), &c) in stack.iter().zip(path_cols.iter()) {
                row_of_col[c] = Some(r);
                col_of_row[r] = Some(c);
            }
        }
    }
    (row_of_col, col_of_row)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matching_finds_the_structural_rank() {
        // Rows 0 and 1 both only touch column 0; column 2 is touched by row 2 alone.
        let by_row = vec![vec![0], vec![0, 1], vec![1, 2], vec![]];
        let (row_of_col, col_of_row) = maximum_matching(4, &by_row);
        assert_eq!(row_of_col.iter().filter(|r| r.is_some()).count(), 3);
        assert_eq!(col_of_row[3], None);
        assert_eq!(row_of_col[3], None);
        // A path that must re-route two earlier assignments: full rank 3.
        let by_row = vec![vec![0, 1], vec![0], vec![1, 2]];
        let (row_of_col, _) = maximum_matching(3, &by_row);
        assert!(row_of_col.iter().all(Option::is_some), "{row_of_col:?}");
    }
}
