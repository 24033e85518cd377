//! MBDyn's FEM file for the `modal` joint (input manual, appendix "Modal Element Data",
//! §FEM File Format): a component's reduced finite-element model, as `femgen` writes it
//! from NASTRAN output or Code_Aster's CMS scripts do, read as MBDyn 1.7.3 reads it.
//!
//! The file is a sequence of records, each opened by a line `** RECORD GROUP N, …`; lines
//! outside records are comments, and `** END OF FILE` ends it. Record 1 (the header: a
//! revision, then the counts of FEM nodes and of normal, attached, constraint and rejected
//! modes) comes first; the others follow in any order, each at most once: 2 node labels,
//! 3–4 initial modal displacements and velocities (optional, zero), 5–7 node coordinates
//! in the FEM frame, 8 mode shapes (six components per node, one `**` comment line before
//! each mode, rejected modes first), 9–10 modal mass and stiffness, 11 lumped nodal
//! inertia and 12 rigid-body inertia (both optional), 13 modal damping (optional). Modes
//! in use: `normal + attached + constraint − rejected`. Records 1, 2 and 5–10 are required.
//!
//! Where MBDyn reads whitespace-separated values with C++ streams and silently misreads a
//! record whose size does not match the header, this reader counts every record against
//! the header and names the file, line and column of what does not fit. Sizes announced
//! by the header are checked against the file's length before anything is allocated.

use std::path::{Path, PathBuf};

use faer::Mat;

use super::text_file::{read_text_file, TextFileError};

/// A FEM file that cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum FemError {
    #[error(transparent)]
    Read(#[from] TextFileError),
    #[error("{file}:{line}:{column}: {message}")]
    Syntax { file: PathBuf, line: usize, column: usize, message: String },
}

/// Rigid-body inertia of the component (record 12): mass [kg], centre of mass in the FEM
/// frame [m], inertia about the centre of mass [kg m²].
#[derive(Clone, Debug, PartialEq)]
pub struct RigidInertia {
    pub mass: f64,
    pub centre_of_mass: [f64; 3],
    pub inertia: [[f64; 3]; 3],
}

/// The contents of a FEM file, with the rejected modes dropped.
#[derive(Clone, Debug)]
pub struct FemFile {
    /// FEM node labels (record 2), in file order.
    pub node_labels: Vec<String>,
    /// Initial modal displacements and velocities (records 3, 4; zero when absent).
    pub modal_displacements: Vec<f64>,
    pub modal_velocities: Vec<f64>,
    /// Node positions in the FEM frame [m] (records 5–7).
    pub positions: Vec<[f64; 3]>,
    /// Mode shapes (record 8): `shapes[mode][node]` = displacement x, y, z [m] and linearized
    /// rotation x, y, z [rad] per unit modal coordinate.
    pub shapes: Vec<Vec<[f64; 6]>>,
    /// Modal mass, stiffness and (record 13) damping matrices, `modes × modes`, entry
    /// `(j, k)` the `k`-th value of the `j`-th group of `modes` values, as MBDyn puts them.
    pub mass: Mat<f64>,
    pub stiffness: Mat<f64>,
    pub damping: Option<Mat<f64>>,
    /// Lumped nodal inertia (record 11): per node the masses along x, y, z [kg] and the
    /// rotational inertias about x, y, z [kg m²].
    pub lumped_inertia: Option<Vec<[f64; 6]>>,
    /// Rigid-body inertia (record 12).
    pub rigid_inertia: Option<RigidInertia>,
    /// What MBDyn 1.7.3 warns about too (a lumped node mass whose y or z component differs
    /// from x), with its place in the file.
    pub warnings: Vec<String>,
}

impl FemFile {
    pub fn modes(&self) -> usize {
        self.mass.nrows()
    }

    pub fn nodes(&self) -> usize {
        self.node_labels.len()
    }

    /// The component's rigid-body inertia: record 12 when given, otherwise from the lumped
    /// nodal inertia of record 11 (point masses at the node positions plus the nodes' own
    /// rotational inertias, about the centre of mass); `None` when the file has neither.
    pub fn rigid_body_inertia(&self) -> Option<RigidInertia> {
        if let Some(r) = &self.rigid_inertia {
            return Some(r.clone());
        }
        let lumped = self.lumped_inertia.as_ref()?;
        let mass: f64 = lumped.iter().map(|m| m[0]).sum();
        let mut first = [0.0; 3];
        for (m, p) in lumped.iter().zip(&self.positions) {
            for i in 0..3 {
                first[i] += m[0] * p[i];
            }
        }
        let centre_of_mass = if mass != 0.0 { first.map(|s| s / mass) } else { [0.0; 3] };
        let mut inertia = [[0.0; 3]; 3];
        for (m, p) in lumped.iter().zip(&self.positions) {
            let r = [p[0] - centre_of_mass[0], p[1] - centre_of_mass[1], p[2] - centre_of_mass[2]];
            let r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
            for i in 0..3 {
                for j in 0..3 {
                    inertia[i][j] += m[0] * (if i == j { r2 } else { 0.0 } - r[i] * r[j]);
                }
                inertia[i][i] += m[3 + i];
            }
        }
        Some(RigidInertia { mass, centre_of_mass, inertia })
    }
}

/// Reads the FEM file `path`.
pub fn read_fem(path: &Path) -> Result<FemFile, FemError> {
    let text = read_text_file(path)?;
    parse_fem(&text, path)
}

/// The header's counts (record 1).
#[derive(Clone, Copy)]
struct Header {
    nodes: usize,
    modes: usize,
    rejected: usize,
}

/// One whitespace-separated value and where it starts (1-based line and column).
struct Token<'a> {
    text: &'a str,
    line: usize,
    column: usize,
}

/// Parses the text of a FEM file (`file` names it in errors).
pub fn parse_fem(text: &str, file: &Path) -> Result<FemFile, FemError> {
    let err = |line: usize, column: usize, message: String| FemError::Syntax { file: file.to_path_buf(), line, column, message };
    let lines: Vec<&str> = text.lines().collect();
    // Record starts: (index of the header line, record number).
    const PREFIX: &str = "** RECORD GROUP ";
    let mut records: Vec<(usize, usize)> = Vec::new();
    let mut end = lines.len();
    for (i, l) in lines.iter().enumerate() {
        if l.starts_with("** END OF FILE") {
            end = i;
            break;
        }
        if let Some(rest) = l.strip_prefix(PREFIX) {
            let digits: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
            let n = digits.parse::<usize>().ok().filter(|n| (1..=13).contains(n));
            let Some(n) = n else {
                return Err(err(i + 1, PREFIX.len() + 1, format!("expected a record group number from 1 to 13 after '{}', found '{}'", PREFIX.trim_end(), rest.trim())));
            };
            if records.is_empty() && n != 1 {
                return Err(err(i + 1, 1, format!("record group {n} comes before record group 1 (the header), which must come first")));
            }
            if let Some(&(prev, _)) = records.iter().find(|r| r.1 == n) {
                return Err(err(i + 1, 1, format!("record group {n} appears twice (first at line {})", prev + 1)));
            }
            records.push((i, n));
        }
    }
    let Some(&(header_line, _)) = records.first() else {
        return Err(err(1, 1, "no '** RECORD GROUP 1' line: not a FEM file of MBDyn's modal element (input manual, §FEM File Format)".into()));
    };
    // The values of record k: the tokens of its lines up to the next record or the end.
    let body = |k: usize| -> (usize, usize) {
        let start = records[k].0 + 1;
        let stop = records.get(k + 1).map_or(end, |r| r.0);
        (start, stop)
    };
    let tokens = |start: usize, stop: usize, skip_comments: bool| -> Vec<Token> {
        let mut out = Vec::new();
        for (i, l) in lines.iter().enumerate().take(stop).skip(start) {
            if skip_comments && l.trim_start().starts_with("**") {
                continue;
            }
            let mut rest = *l;
            let mut offset = 0;
            while let Some(s) = rest.find(|c: char| !c.is_whitespace()) {
                let len = rest[s..].find(char::is_whitespace).unwrap_or(rest.len() - s);
                out.push(Token { text: &rest[s..s + len], line: i + 1, column: l[..offset + s].chars().count() + 1 });
                offset += s + len;
                rest = &rest[s + len..];
            }
        }
        out
    };
    // Record 1: MBDyn skips the line after the record's own (the column titles), then reads
    // the revision and five counts.
    let (start, stop) = body(0);
    let header_tokens = tokens((start + 1).min(stop), stop, false);
    if header_tokens.len() < 6 {
        return Err(err(header_line + 1, 1, format!("record group 1 (the header) needs the revision and five counts (nodes, normal, attached, constraint, rejected modes) on the line after its title line; found {} value(s)", header_tokens.len())));
    }
    let count = |t: &Token, what: &str| -> Result<usize, FemError> { t.text.parse::<usize>().map_err(|_| err(t.line, t.column, format!("expected the number of {what} (a non-negative integer), found '{}'", t.text))) };
    let nodes = count(&header_tokens[1], "FEM nodes")?;
    let normal = count(&header_tokens[2], "normal modes")?;
    let attached = count(&header_tokens[3], "attached modes")?;
    let constraint = count(&header_tokens[4], "constraint modes")?;
    let rejected = count(&header_tokens[5], "rejected modes")?;
    let listed = normal.checked_add(attached).and_then(|s| s.checked_add(constraint));
    let Some(modes) = listed.and_then(|l| l.checked_sub(rejected)) else {
        return Err(err(header_tokens[5].line, header_tokens[5].column, format!("{rejected} rejected modes, more than the {} normal, attached and constraint modes listed", listed.map_or("too many".to_string(), |l| l.to_string()))));
    };
    if nodes == 0 {
        return Err(err(header_tokens[1].line, header_tokens[1].column, "a FEM file needs at least one node".into()));
    }
    check_sizes(nodes, modes, rejected, text.len()).map_err(|m| err(header_tokens[1].line, header_tokens[1].column, m))?;
    if let Some(t) = header_tokens.get(6).filter(|t| t.text.parse::<f64>().is_ok()) {
        return Err(err(t.line, t.column, format!("unexpected value '{}' after the header's five counts", t.text)));
    }
    let h = Header { nodes, modes, rejected };
    let mut fem = FemFile {
        node_labels: Vec::new(),
        modal_displacements: vec![0.0; modes],
        modal_velocities: vec![0.0; modes],
        positions: vec![[0.0; 3]; nodes],
        shapes: Vec::new(),
        mass: Mat::zeros(modes, modes),
        stiffness: Mat::zeros(modes, modes),
        damping: None,
        lumped_inertia: None,
        rigid_inertia: None,
        warnings: Vec::new(),
    };
    for k in 1..records.len() {
        let (line, n) = records[k];
        let (start, stop) = body(k);
        let toks = tokens(start, stop, true);
        let place = RecordPlace { file, record: n, line: line + 1, stop_line: stop, warnings: Default::default() };
        match n {
            2 => {
                let labels = place.take(&toks, h.nodes, "FEM node labels", |t| Ok(t.text.to_string()))?;
                let mut seen = std::collections::HashMap::new();
                for (t, label) in toks.iter().zip(&labels) {
                    if let Some(first) = seen.insert(label.as_str(), t.line) {
                        return Err(err(t.line, t.column, format!("FEM node label '{label}' appears twice in record group 2 (first at line {first})")));
                    }
                }
                fem.node_labels = labels;
            }
            3 => fem.modal_displacements = place.reals(&toks, h.modes, "initial modal displacements")?,
            4 => fem.modal_velocities = place.reals(&toks, h.modes, "initial modal velocities")?,
            5..=7 => {
                let values = place.reals(&toks, h.nodes, ["node x coordinates [m]", "node y coordinates [m]", "node z coordinates [m]"][n - 5])?;
                for (p, v) in fem.positions.iter_mut().zip(values) {
                    p[n - 5] = v;
                }
            }
            8 => {
                let values = place.reals(&toks, 6 * h.nodes * (h.modes + h.rejected), "mode shape components (six per node and mode, rejected modes first)")?;
                fem.shapes = values.chunks_exact(6 * h.nodes).skip(h.rejected).map(|m| m.chunks_exact(6).map(|c| [c[0], c[1], c[2], c[3], c[4], c[5]]).collect()).collect();
            }
            9 | 10 | 13 => {
                let what = ["modal mass matrix entries", "modal stiffness matrix entries", "modal damping matrix entries"][[9, 10, 13].iter().position(|&r| r == n).unwrap_or(0)];
                let values = place.reals(&toks, h.modes * h.modes, what)?;
                let m = Mat::from_fn(h.modes, h.modes, |j, k| values[j * h.modes + k]);
                match n {
                    9 => fem.mass = m,
                    10 => fem.stiffness = m,
                    _ => fem.damping = Some(m),
                }
            }
            11 => {
                let values = place.reals(&toks, 6 * h.nodes, "lumped inertia components (six per node)")?;
                let lumped: Vec<[f64; 6]> = values.chunks_exact(6).map(|c| [c[0], c[1], c[2], c[3], c[4], c[5]]).collect();
                for (i, m) in lumped.iter().enumerate() {
                    if m[1] != m[0] || m[2] != m[0] {
                        let t = &toks[6 * i];
                        fem.warnings.push(format!("{}:{}:{}: FEM node {} has lumped masses {}, {}, {} along x, y, z; romdyn, as MBDyn 1.7.3, uses the x one", file.display(), t.line, t.column, i + 1, m[0], m[1], m[2]));
                    }
                }
                fem.lumped_inertia = Some(lumped);
            }
            12 => {
                let v = place.reals(&toks, 13, "rigid-body inertia values (mass, centre of mass, 3 x 3 inertia)")?;
                fem.rigid_inertia = Some(RigidInertia { mass: v[0], centre_of_mass: [v[1], v[2], v[3]], inertia: [[v[4], v[5], v[6]], [v[7], v[8], v[9]], [v[10], v[11], v[12]]] });
            }
            _ => unreachable!("record 1 is first, numbers are 1..=13"),
        }
        fem.warnings.extend(place.warnings.into_inner());
    }
    let missing: Vec<String> = [2, 5, 6, 7, 8, 9, 10].iter().filter(|n| !records.iter().any(|r| r.1 == **n)).map(|n| n.to_string()).collect();
    if !missing.is_empty() {
        let at = end.min(lines.len()).max(1);
        return Err(err(at, 1, format!("record group(s) {} missing: a FEM file needs records 1, 2 and 5 to 10 (each opened by a line '** RECORD GROUP N, …')", missing.join(", "))));
    }
    Ok(fem)
}

/// Where a record is, for its errors.
struct RecordPlace<'a> {
    file: &'a Path,
    record: usize,
    /// Line of the record's title (1-based) and index of the line that ends it.
    line: usize,
    stop_line: usize,
    /// Zeros after the announced values, which MBDyn skips (femgen writes a row of zeros
    /// after record 11's in MBDyn's own tests/joints/modal/beam/beam.fem).
    warnings: std::cell::RefCell<Vec<String>>,
}

impl RecordPlace<'_> {
    fn err(&self, line: usize, column: usize, message: String) -> FemError {
        FemError::Syntax { file: self.file.to_path_buf(), line, column, message }
    }

    /// The first `n` values of the record, each parsed by `parse`; fewer, or more numbers
    /// after them (but zeros, a warning), is an error naming the record and the header's
    /// count.
    fn take<T>(&self, toks: &[Token], n: usize, what: &str, parse: impl Fn(&Token) -> Result<T, FemError>) -> Result<Vec<T>, FemError> {
        if toks.len() < n {
            let (line, column) = toks.last().map_or((self.line, 1), |t| (t.line, t.column));
            let end = if self.stop_line > self.line { format!(" before line {}", self.stop_line + 1) } else { String::new() };
            return Err(self.err(line, column, format!("record group {} (line {}) holds {} of the {n} {what} the header announces{end}", self.record, self.line, toks.len())));
        }
        if let Some(t) = toks.get(n).filter(|t| t.text.parse::<f64>().is_ok()) {
            let extra: Vec<&Token> = toks[n..].iter().take_while(|t| t.text.parse::<f64>().is_ok()).collect();
            if !extra.iter().all(|t| t.text.parse::<f64>() == Ok(0.0)) {
                return Err(self.err(t.line, t.column, format!("record group {} (line {}) holds more than the {n} {what} the header announces: '{}' is one too many (do the header's counts match the data?)", self.record, self.line, t.text)));
            }
            self.warnings.borrow_mut().push(format!("{}:{}:{}: record group {} holds {} zero(s) after the {n} {what} the header announces; romdyn, as MBDyn 1.7.3, skips them", self.file.display(), t.line, t.column, self.record, extra.len()));
        }
        toks[..n].iter().map(parse).collect()
    }

    fn reals(&self, toks: &[Token], n: usize, what: &str) -> Result<Vec<f64>, FemError> {
        self.take(toks, n, what, |t| real(t).map_err(|m| self.err(t.line, t.column, format!("record group {}: {m}", self.record))))
    }
}

/// A finite real number as C++ streams read it (`1`, `-2.5e-3`, `1.E+03`).
fn real(t: &Token) -> Result<f64, String> {
    match t.text.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(format!("expected a finite real number, found '{}'", t.text)),
        Err(_) if t.text.contains(['D', 'd']) && t.text.replace(['D', 'd'], "E").parse::<f64>().is_ok() => Err(format!("expected a real number, found '{}' (a Fortran exponent: write E instead of D)", t.text)),
        Err(_) => Err(format!("expected a real number, found '{}'", t.text)),
    }
}

/// The header's sizes against the file's length, before anything is allocated: every
/// value takes at least two bytes (a digit and a separator), and records 5–10 are
/// required.
fn check_sizes(nodes: usize, modes: usize, rejected: usize, bytes: usize) -> Result<(), String> {
    let values = (|| {
        let coordinates = nodes.checked_mul(3)?;
        let shapes = nodes.checked_mul(6)?.checked_mul(modes.checked_add(rejected)?)?;
        let matrices = modes.checked_mul(modes)?.checked_mul(2)?;
        coordinates.checked_add(shapes)?.checked_add(matrices)
    })();
    match values {
        Some(v) if v <= bytes / 2 + 1 => Ok(()),
        _ => Err(format!(
            "the header announces {nodes} nodes and {} modes: records 5 to 10 need at least {} values, more than this file of {bytes} bytes can hold",
            modes + rejected,
            values.map_or("more than 2^64".to_string(), |v| v.to_string())
        )),
    }
}
