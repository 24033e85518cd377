//! An eigenanalysis as the Octave/MATLAB script MBDyn writes (MBDyn manual, "Eigenanalysis",
//! output; DataManager::OutputEig*): in this order
//!
//! ```text
//! dTime = t;  dCoef = c;                              always
//! Aplus = [...]; Aminus = [...];                      output full matrices
//! Aplus = [i j v; ...]; Aplus = spconvert(Aplus);     output sparse matrices
//! labels = [...]; idx = [...]; X0 = [...];            output geometry
//! alpha = [αr αi β; ...];                             always (MBDyn: with eigenvectors)
//! VL = [...]; VR = [...];                             output eigenvectors
//! ```
//!
//! Complex entries are written `re+i*im`, a complex pair as two adjacent columns. Numbers
//! carry 17 significant digits, so the matrices round-trip exactly. Departures from MBDyn,
//! all additive: `alpha` is written even without eigenvectors; columns of eigenvalues
//! labelled infinite (no eigenvector) are NaN; a sparse matrix gets an explicit `n n 0`
//! entry when its last diagonal entry is zero, so `spconvert` gives it its full size.

use std::io::Write;

use faer::{c64, Col, Mat};

use super::eigen_file::{mbdyn_alpha, EigenFile, MatrixLayout};

fn num(x: f64) -> String {
    format!("{x:.16e}")
}

fn complex(z: c64) -> String {
    if z.im == 0.0 {
        num(z.re)
    } else {
        format!("{}{}i*{}", num(z.re), if z.im < 0.0 { '-' } else { '+' }, num(z.im.abs()))
    }
}

fn full(w: &mut dyn Write, name: &str, m: &Mat<f64>) -> std::io::Result<()> {
    write!(w, "{name} = [")?;
    for i in 0..m.nrows() {
        for j in 0..m.ncols() {
            write!(w, "{} ", num(m[(i, j)]))?;
        }
        writeln!(w, "{}", if i + 1 == m.nrows() { "];" } else { ";" })?;
    }
    if m.nrows() == 0 {
        writeln!(w, "];")?;
    }
    Ok(())
}

fn sparse(w: &mut dyn Write, name: &str, n: usize, entries: &[(usize, usize, f64)]) -> std::io::Result<()> {
    writeln!(w, "{name} = [")?;
    for &(i, j, v) in entries {
        writeln!(w, "{} {} {};", i + 1, j + 1, num(v))?;
    }
    if n > 0 && !entries.iter().any(|&(i, j, _)| i == n - 1 && j == n - 1) {
        writeln!(w, "{n} {n} 0;")?;
    }
    writeln!(w, "];")?;
    writeln!(w, "{name} = spconvert({name});")
}

fn column(w: &mut dyn Write, name: &str, values: impl Iterator<Item = String>) -> std::io::Result<()> {
    writeln!(w, "{name} = [")?;
    for v in values {
        writeln!(w, "{v};")?;
    }
    writeln!(w, "];")
}

fn vectors(w: &mut dyn Write, name: &str, n: usize, cols: &[Option<&Col<c64>>]) -> std::io::Result<()> {
    if cols.is_empty() {
        return writeln!(w, "{name} = zeros({n}, 0);");
    }
    writeln!(w, "{name} = [")?;
    for i in 0..n {
        for c in cols {
            write!(w, "{} ", c.map_or("NaN".to_string(), |v| complex(v[i])))?;
        }
        writeln!(w, "{}", if i + 1 == n { "];" } else { ";" })?;
    }
    Ok(())
}

/// The error when the file asks for `Aplus`/`Aminus` that were not assembled.
fn unassembled() -> std::io::Error {
    std::io::Error::other(super::eigen_file::UNASSEMBLED)
}

/// Writes the `.m` script of one eigenanalysis to `w`; `input` names the model file.
pub fn write_eigen_m(w: &mut dyn Write, input: &str, e: &EigenFile) -> std::io::Result<()> {
    let n = e.pencil.dim();
    {
        writeln!(w, "% romdyn {} eigenanalysis {} of {input} (MBDyn .m layout; SI units: time and dCoef in s)", env!("CARGO_PKG_VERSION"), e.index)?;
        writeln!(w, "% time: {}", e.time)?;
        writeln!(w, "dTime = {};", num(e.time))?;
        writeln!(w, "% coefficient")?;
        writeln!(w, "dCoef = {};", num(e.dcoef))?;
        writeln!(w, "% modes: {}", e.solver)?;
        for (plus, name, comment) in [(true, "Aplus", "% F/xPrime + dCoef * F/x"), (false, "Aminus", "% F/xPrime - dCoef * F/x")] {
            match e.matrices {
                None => break,
                Some(MatrixLayout::Full) => {
                    writeln!(w, "{comment}")?;
                    full(w, name, &*e.pencil.full(plus).ok_or_else(unassembled)?)?
                }
                Some(MatrixLayout::Sparse) => {
                    writeln!(w, "{comment}")?;
                    sparse(w, name, n, &e.pencil.nonzeros(plus).ok_or_else(unassembled)?)?
                }
            }
        }
        if let Some(g) = e.geometry {
            writeln!(w, "% structural nodes labels")?;
            column(w, "labels", g.labels.iter().map(|l| l.to_string()))?;
            writeln!(w, "% structural nodes base index")?;
            column(w, "idx", g.first_index.iter().map(|i| i.to_string()))?;
            writeln!(w, "% structural nodes reference configuration (X, Phi)")?;
            column(w, "X0", g.position.iter().zip(&g.rotation_vector).flat_map(|(x, p)| [x.x, x.y, x.z, p.x, p.y, p.z]).map(num))?;
        }
        writeln!(w, "% alphar, alphai, beta")?;
        if e.written.is_empty() {
            writeln!(w, "alpha = zeros(0, 3);")?;
        } else {
            writeln!(w, "alpha = [")?;
            for &k in e.written {
                let [ar, ai, b] = mbdyn_alpha(&e.modal.modes[k], e.modal.route, e.dcoef);
                writeln!(w, "{} {} {};", num(ar), num(ai), num(b))?;
            }
            writeln!(w, "];")?;
        }
        if e.eigenvectors {
            let modes = || e.written.iter().map(|&k| &e.modal.modes[k]);
            writeln!(w, "% left eigenvectors")?;
            vectors(w, "VL", n, &modes().map(|m| m.left.as_ref()).collect::<Vec<_>>())?;
            writeln!(w, "% right eigenvectors")?;
            vectors(w, "VR", n, &modes().map(|m| m.right.as_ref()).collect::<Vec<_>>())?;
        }
        Ok(())
    }
}
