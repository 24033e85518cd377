//! Matrix Market files (`coordinate` or `array`; `real`, `integer` or `pattern`;
//! `general`, `symmetric` or `skew-symmetric`) read into dense or sparse matrices.

use std::path::{Path, PathBuf};

use faer::Mat;

use super::text_file::{read_text_file, TextFileError};
use crate::limits::{check_dense, MAX_SPARSE_DIMENSION};
use crate::linear::SparseMatrix;

/// A malformed Matrix Market file.
#[derive(Debug, thiserror::Error)]
pub enum MatrixMarketError {
    #[error(transparent)]
    Read(#[from] TextFileError),
    #[error("{file}:{line}:{column}: {message}")]
    Syntax { file: PathBuf, line: usize, column: usize, message: String },
}

#[derive(Clone, Copy, PartialEq)]
enum Symmetry {
    General,
    Symmetric,
    Skew,
}

/// Reads a Matrix Market file into a dense matrix.
pub fn read_matrix(file: &Path) -> Result<Mat<f64>, MatrixMarketError> {
    let text = read_text_file(file)?;
    parse_matrix(&text, file)
}

/// Parses the text of a Matrix Market file (`file` names it in errors).
pub fn parse_matrix(text: &str, file: &Path) -> Result<Mat<f64>, MatrixMarketError> {
    struct Dense(Mat<f64>);
    impl Entries for Dense {
        fn start(&mut self, nrows: usize, ncols: usize, _: usize, _: usize) -> Result<(), String> {
            check_dense(nrows, ncols, || "the matrix".into()).map_err(|e| e.to_string())?;
            self.0 = Mat::zeros(nrows, ncols);
            Ok(())
        }
        fn add(&mut self, i: usize, j: usize, v: f64) {
            self.0[(i, j)] += v;
        }
    }
    let mut m = Dense(Mat::zeros(0, 0));
    parse_entries(text, file, &mut m)?;
    Ok(m.0)
}

/// Reads a Matrix Market file into a sparse matrix (duplicates summed, as for a dense one).
pub fn read_sparse_matrix(file: &Path) -> Result<SparseMatrix, MatrixMarketError> {
    let text = read_text_file(file)?;
    parse_sparse_matrix(&text, file)
}

/// Parses the text of a Matrix Market file into a sparse matrix: memory in proportion to
/// the entries present and the row count, which must be at most
/// [`MAX_SPARSE_DIMENSION`] (checked before anything is allocated).
pub fn parse_sparse_matrix(text: &str, file: &Path) -> Result<SparseMatrix, MatrixMarketError> {
    struct Sparse<'a> {
        text: &'a str,
        size: (usize, usize),
        entries: Vec<(usize, usize, f64)>,
    }
    impl Entries for Sparse<'_> {
        fn start(&mut self, nrows: usize, ncols: usize, expected: usize, _: usize) -> Result<(), String> {
            if nrows.max(ncols) > MAX_SPARSE_DIMENSION {
                return Err(format!("the matrix is {nrows} x {ncols}, more than romdyn's budget of {MAX_SPARSE_DIMENSION} rows or columns for a sparse matrix"));
            }
            self.size = (nrows, ncols);
            // Each entry takes a line of at least 4 bytes: the declared count is not
            // trusted beyond the text.
            self.entries.reserve(expected.min(self.text.len() / 4));
            Ok(())
        }
        fn add(&mut self, i: usize, j: usize, v: f64) {
            self.entries.push((i, j, v));
        }
    }
    let mut m = Sparse { text, size: (0, 0), entries: Vec::new() };
    parse_entries(text, file, &mut m)?;
    SparseMatrix::from_triplets(m.size.0, m.size.1, m.entries).ok_or_else(|| unreachable!("indices are checked against the size line"))
}

/// Where the entries of a Matrix Market file go: `start(rows, cols, entries, size line)`
/// once the size line is read (an error message for the size line), then `add(i, j, v)`
/// per entry (0-based, symmetric storage expanded).
trait Entries {
    fn start(&mut self, nrows: usize, ncols: usize, expected: usize, line: usize) -> Result<(), String>;
    fn add(&mut self, i: usize, j: usize, v: f64);
}

fn parse_entries(text: &str, file: &Path, sink: &mut dyn Entries) -> Result<(), MatrixMarketError> {
    let err = |line: usize, column: usize, message: String| MatrixMarketError::Syntax { file: file.to_path_buf(), line, column, message };
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let (_, header) = lines.next().ok_or_else(|| err(1, 1, "empty file: expected a '%%MatrixMarket matrix ...' header".into()))?;
    let words: Vec<String> = header.split_whitespace().map(str::to_ascii_lowercase).collect();
    if words.len() != 5 || words[0] != "%%matrixmarket" || words[1] != "matrix" {
        return Err(err(1, 1, "expected '%%MatrixMarket matrix <coordinate|array> <real|integer|pattern> <general|symmetric|skew-symmetric>'".into()));
    }
    let coordinate = match words[2].as_str() {
        "coordinate" => true,
        "array" => false,
        f => return Err(err(1, column_of(header, 3), format!("format '{f}' is not supported: expected coordinate or array"))),
    };
    let pattern = match words[3].as_str() {
        "real" | "integer" | "double" => false,
        "pattern" if coordinate => true,
        f => return Err(err(1, column_of(header, 4), format!("field '{f}' is not supported: expected real, integer or pattern"))),
    };
    let symmetry = match words[4].as_str() {
        "general" => Symmetry::General,
        "symmetric" => Symmetry::Symmetric,
        "skew-symmetric" => Symmetry::Skew,
        s => return Err(err(1, column_of(header, 5), format!("symmetry '{s}' is not supported: expected general, symmetric or skew-symmetric"))),
    };
    let mut data = lines.filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('%'));
    let (size_line, size_text) = data.next().ok_or_else(|| err(2, 1, "missing the size line".into()))?;
    let size = numbers::<usize>(size_text, size_line, file)?;
    let want = if coordinate { 3 } else { 2 };
    if size.len() != want {
        return Err(err(size_line, 1, format!("size line: expected {want} integers, found {}", size.len())));
    }
    let (nrows, ncols) = (size[0], size[1]);
    if symmetry != Symmetry::General && nrows != ncols {
        return Err(err(size_line, 1, format!("a {} matrix must be square, the size line declares {nrows} x {ncols}", words[4])));
    }
    let expected = if coordinate {
        Some(size[2])
    } else if symmetry == Symmetry::General {
        nrows.checked_mul(ncols)
    } else {
        ncols.checked_mul(ncols + 1).map(|x| x / 2 - if symmetry == Symmetry::Skew { ncols } else { 0 })
    };
    let expected = expected.ok_or_else(|| err(size_line, 1, format!("an array of {nrows} x {ncols} entries is too large")))?;
    sink.start(nrows, ncols, expected, size_line).map_err(|e| err(size_line, 1, e))?;
    let mut count = 0;
    // Column-major; symmetric storage lists the lower triangle, skew-symmetric the strict one.
    let (mut i_arr, mut j_arr) = (usize::from(symmetry == Symmetry::Skew), 0usize);
    for (line, text) in data {
        if count == expected {
            return Err(err(line, 1, format!("more entries than the {expected} declared")));
        }
        let (i, j, v) = if coordinate {
            let fields: Vec<&str> = text.split_whitespace().collect();
            let need = if pattern { 2 } else { 3 };
            if fields.len() != need {
                return Err(err(line, 1, format!("expected {need} fields (row, column{}), found {}", if pattern { "" } else { ", value" }, fields.len())));
            }
            let idx = |k: usize, n: usize, what: &str| -> Result<usize, MatrixMarketError> {
                let x: usize = fields[k].parse().map_err(|_| err(line, column_of(text, k + 1), format!("{what} index '{}' is not a positive integer", fields[k])))?;
                if x == 0 || x > n {
                    return Err(err(line, column_of(text, k + 1), format!("{what} index {x} is out of range 1..={n}")));
                }
                Ok(x - 1)
            };
            let (i, j) = (idx(0, nrows, "row")?, idx(1, ncols, "column")?);
            if symmetry == Symmetry::Skew && i == j {
                return Err(err(line, 1, format!("entry ({}, {}) is on the diagonal of a skew-symmetric matrix (it must be zero and is not stored)", i + 1, j + 1)));
            }
            let v = if pattern { 1.0 } else { value(fields[2], line, column_of(text, 3), file)? };
            (i, j, v)
        } else {
            let v = value(text.trim(), line, column_of(text, 1), file)?;
            let (i, j) = (i_arr, j_arr);
            // Column-major; symmetric storage lists the lower triangle only.
            i_arr += 1;
            if i_arr >= nrows {
                j_arr += 1;
                i_arr = match symmetry {
                    Symmetry::General => 0,
                    Symmetry::Symmetric => j_arr,
                    Symmetry::Skew => j_arr + 1,
                };
            }
            (i, j, v)
        };
        sink.add(i, j, v);
        if i != j {
            match symmetry {
                Symmetry::General => {}
                Symmetry::Symmetric => sink.add(j, i, v),
                Symmetry::Skew => sink.add(j, i, -v),
            }
        }
        count += 1;
    }
    if count != expected {
        let last = text.lines().count();
        return Err(err(last, 1, format!("found {count} entries, the size line declares {expected}")));
    }
    Ok(())
}

/// 1-based column of the `k`-th (1-based) whitespace-separated field of `line`.
fn column_of(line: &str, k: usize) -> usize {
    let mut seen = 0;
    let mut in_word = false;
    for (c, ch) in line.char_indices() {
        if !ch.is_whitespace() && !in_word {
            seen += 1;
            if seen == k {
                return c + 1;
            }
        }
        in_word = !ch.is_whitespace();
    }
    line.len() + 1
}

fn numbers<T: std::str::FromStr>(text: &str, line: usize, file: &Path) -> Result<Vec<T>, MatrixMarketError> {
    text.split_whitespace()
        .enumerate()
        .map(|(k, w)| {
            w.parse().map_err(|_| MatrixMarketError::Syntax {
                file: file.to_path_buf(),
                line,
                column: column_of(text, k + 1),
                message: format!("'{w}' is not a non-negative integer"),
            })
        })
        .collect()
}

fn value(w: &str, line: usize, column: usize, file: &Path) -> Result<f64, MatrixMarketError> {
    w.parse::<f64>().ok().filter(|x| x.is_finite()).ok_or_else(|| MatrixMarketError::Syntax {
        file: file.to_path_buf(),
        line,
        column,
        message: format!("'{w}' is not a finite number"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(t: &str) -> Result<Mat<f64>, String> {
        parse_matrix(t, Path::new("m.mtx")).map_err(|e| e.to_string())
    }

    #[test]
    fn coordinate_symmetric_and_array_forms() -> Result<(), String> {
        let m = parse("%%MatrixMarket matrix coordinate real symmetric\n% comment\n2 2 2\n1 1 4\n2 1 -1\n")?;
        assert_eq!((m[(0, 0)], m[(0, 1)], m[(1, 0)], m[(1, 1)]), (4.0, -1.0, -1.0, 0.0));
        let m = parse("%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n")?;
        assert_eq!((m[(0, 0)], m[(1, 0)], m[(0, 1)], m[(1, 1)]), (1.0, 2.0, 3.0, 4.0));
        let m = parse("%%MatrixMarket matrix coordinate pattern general\n2 3 1\n2 3\n")?;
        assert_eq!(m[(1, 2)], 1.0);
        let m = parse("%%MatrixMarket matrix coordinate real skew-symmetric\n2 2 1\n2 1 5\n")?;
        assert_eq!((m[(1, 0)], m[(0, 1)]), (5.0, -5.0));
        Ok(())
    }

    #[test]
    fn errors_name_line_and_column() {
        let cases = [
            ("", "m.mtx:1:1: empty file"),
            ("%%MatrixMarket vector coordinate real general\n", "m.mtx:1:1: expected '%%MatrixMarket matrix"),
            ("%%MatrixMarket matrix coordinate complex general\n1 1 1\n1 1 1\n", "m.mtx:1:34: field 'complex' is not supported"),
            ("%%MatrixMarket matrix coordinate real general\n2 2\n", "m.mtx:2:1: size line: expected 3 integers, found 2"),
            ("%%MatrixMarket matrix coordinate real general\n2 2 1\n3 1 1.0\n", "m.mtx:3:1: row index 3 is out of range 1..=2"),
            ("%%MatrixMarket matrix coordinate real general\n2 2 1\n1 2 abc\n", "m.mtx:3:5: 'abc' is not a finite number"),
            ("%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n", "m.mtx:3:1: found 1 entries, the size line declares 2"),
            ("%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 1.0\n2 2 1.0\n", "m.mtx:4:1: more entries than the 1 declared"),
            ("%%MatrixMarket matrix coordinate real general\n2 x 1\n", "m.mtx:2:3: 'x' is not a non-negative integer"),
            ("%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1\n", "m.mtx:3:1: expected 3 fields"),
        ];
        for (text, want) in cases {
            let got = parse(text).err().unwrap_or_default();
            assert!(got.starts_with(want), "{text:?}\n got: {got}\nwant: {want}");
            // The sparse reader gives the same errors.
            let got = parse_sparse_matrix(text, Path::new("m.mtx")).err().map(|e| e.to_string()).unwrap_or_default();
            assert!(got.starts_with(want), "sparse {text:?}\n got: {got}\nwant: {want}");
        }
    }

    /// The sparse reader gives the dense reader's matrix (duplicates summed, symmetric
    /// storage expanded), and refuses a size it could not hold before allocating.
    #[test]
    fn sparse_reader_matches_the_dense_one_and_checks_sizes() -> Result<(), String> {
        for text in [
            "%%MatrixMarket matrix coordinate real symmetric\n% comment\n3 3 3\n1 1 4\n2 1 -1\n3 2 2.5\n",
            "%%MatrixMarket matrix coordinate real general\n2 3 3\n1 3 1\n1 3 2\n2 1 -7e-3\n",
            "%%MatrixMarket matrix coordinate real skew-symmetric\n2 2 1\n2 1 5\n",
            "%%MatrixMarket matrix array real general\n2 2\n1\n0\n3\n4\n",
        ] {
            let sparse = parse_sparse_matrix(text, Path::new("m.mtx")).map_err(|e| e.to_string())?;
            assert_eq!(sparse.to_dense(), parse(text)?, "{text:?}");
        }
        let huge = parse_sparse_matrix("%%MatrixMarket matrix coordinate real general\n50000001 1 0\n", Path::new("m.mtx")).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(huge.starts_with("m.mtx:2:1: the matrix is 50000001 x 1, more than romdyn's budget of 50000000 rows"), "{huge}");
        let ok = parse_sparse_matrix("%%MatrixMarket matrix coordinate real general\n50000000 1 0\n", Path::new("m.mtx")).map_err(|e| e.to_string())?;
        assert_eq!((ok.nrows(), ok.nnz()), (50_000_000, 0));
        // A declared entry count far beyond the text is not reserved.
        let lie = parse_sparse_matrix("%%MatrixMarket matrix coordinate real general\n2 2 4000000000000\n1 1 1\n", Path::new("m.mtx")).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(lie.starts_with("m.mtx:3:1: found 1 entries, the size line declares 4000000000000"), "{lie}");
        Ok(())
    }

}
