//! Size budgets: the largest sizes romdyn accepts from its inputs, checked before anything
//! is allocated, so a declared size that cannot fit in memory gives a clear error instead
//! of an allocation failure (an abort) or a run without end. The book's Limits chapter (docs/src/limits.md) lists them.

/// Largest input text file read [bytes] (256 MiB): an MBDyn file with its includes, a
/// pencil, a Matrix Market or an Octave file each.
pub const MAX_INPUT_BYTES: u64 = 256 << 20;

/// Largest dense matrix built from a file [entries] (5e7 doubles, 400 MB: a 7064 x 7064
/// matrix). Dense eigenanalysis of such a pencil already takes hours.
pub const MAX_DENSE_ENTRIES: usize = 50_000_000;

/// Largest row or column count of a sparse matrix read from a file (5e7: its row
/// pointers alone take 400 MB).
pub const MAX_SPARSE_DIMENSION: usize = 50_000_000;

/// Most time steps of one run (1e8): `(final time − initial time) / time step`.
pub const MAX_TIME_STEPS: f64 = 1e8;

/// Most points of a frequency grid (1e6).
pub const MAX_FREQUENCY_POINTS: usize = 1_000_000;

/// Lowest and highest frequency of a response [Hz] (1e-30 and 1e30 Hz): beyond, `ω²`
/// times a pencil's entries leaves the range of doubles for ordinary models (responses of
/// NaN or 0), and a plot's log axis cannot span the decades (the plotting library looped
/// without end on 1e-160 to 1e160 Hz).
pub const FREQUENCY_RANGE_HZ: (f64, f64) = (1e-30, 1e30);

/// Most load increments of a static solution (1e5).
pub const MAX_LOAD_STEPS: usize = 100_000;

/// Deepest chain of `include:` files (a file including a file including …): 100. Each
/// level holds a file open in the reader; real inputs nest two or three.
pub const MAX_INCLUDE_DEPTH: usize = 100;

/// Deepest nesting of evaluations one drive or scalar function makes (64): drive callers
/// inside drive callers, references to `drive caller:` cards, `model::drive` and
/// `model::sf` calls of a `string` drive, operands of `sum`/`sub`/`mul`/`div` scalar
/// functions. Each level takes stack; without a bound a chain of 2000 string drives, each
/// calling the previous one, overflowed the stack (issue 32).
pub const MAX_EVALUATION_DEPTH: usize = 64;

/// Most evaluations one call of a drive or scalar function makes, repetitions counted
/// (1e5): a `sum` of a function with itself doubles them, so 25 such cards would make 3e7
/// per call, at every residual.
pub const MAX_EVALUATION_TERMS: u64 = 100_000;

/// A number for a message: plain when it reads well, else in exponent form (`1e308`,
/// `1e-320`); an overflowed count reads "more than 1.8e308".
pub fn readable(x: f64) -> String {
    if x.is_infinite() && x > 0.0 {
        "more than 1.8e308".into()
    } else if x == 0.0 || (1e-4..1e15).contains(&x.abs()) || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Why a size is refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{what} is {rows} x {cols} = {entries} entries, more than romdyn's budget of {max} entries for a dense matrix ({mb} MB; rows count in multiples of 8)", entries = *rows as u128 * *cols as u128, max = MAX_DENSE_ENTRIES, mb = MAX_DENSE_ENTRIES * 8 / 1_000_000)]
pub struct TooLarge {
    pub what: String,
    pub rows: usize,
    pub cols: usize,
}

/// Rows are stored in multiples of this in a faer matrix (columns aligned for SIMD): a
/// 1 x n matrix takes the memory of 8 x n entries (measured: a 1 x 3.9e7 matrix took
/// over 2 GB under cargo-fuzz).
const FAER_ROW_PADDING: usize = 8;

/// Errors unless a dense `rows x cols` matrix, as faer stores it (rows padded to a
/// multiple of 8), fits in [`MAX_DENSE_ENTRIES`]. An empty dimension counts as one: a
/// 0 x 3.9e18 matrix holds no entry but every column still costs work (cargo-fuzz found
/// it hanging the Matrix Market reader for 27 minutes).
pub fn check_dense(rows: usize, cols: usize, what: impl FnOnce() -> String) -> Result<(), TooLarge> {
    let cols = cols.max(1);
    match rows.max(1).div_ceil(FAER_ROW_PADDING).saturating_mul(FAER_ROW_PADDING).checked_mul(cols) {
        Some(n) if n <= MAX_DENSE_ENTRIES => Ok(()),
        _ => Err(TooLarge { what: what(), rows, cols }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_well() {
        assert_eq!(readable(1e308), "1e308");
        assert_eq!(readable(1e-320), "1e-320");
        assert_eq!(readable(0.001), "0.001");
        assert_eq!(readable(f64::INFINITY), "more than 1.8e308");
    }

    #[test]
    fn dense_budget_is_exact() {
        assert!(check_dense(MAX_DENSE_ENTRIES, 1, String::new).is_ok());
        assert!(check_dense(MAX_DENSE_ENTRIES + 1, 1, String::new).is_err());
        // A single row is stored as 8.
        assert!(check_dense(1, MAX_DENSE_ENTRIES / 8, String::new).is_ok());
        assert!(check_dense(1, MAX_DENSE_ENTRIES / 8 + 1, String::new).is_err());
        assert!(check_dense(usize::MAX, 2, String::new).is_err());
        // Empty in one dimension, enormous in the other: refused (work per row or column).
        assert!(check_dense(0, usize::MAX, String::new).is_err());
        assert!(check_dense(usize::MAX, 0, String::new).is_err());
        assert!(check_dense(0, 10, String::new).is_ok());
    }
}
