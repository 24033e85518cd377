//! romdyn's JSON of one eigenanalysis: the content of the `.m` file (see `eigen_m`) plus the
//! modal table (labels, error estimates, kinetic-energy shares) and the unknowns' names.
//! Matrices are arrays of rows; complex numbers `{"re", "im"}`; missing eigenvectors and
//! non-finite numbers are `null`.
//!
//! Written as it is serialized, never held whole: the large parts (every mode's energy
//! shares, the sparse pencil's entries, the eigenvectors' rows) are produced item by item
//! straight into the writer. On the 96,024-equation spring chain's 40 modes the document
//! built as one `serde_json::Value` and then printed to a string took 1.4 GB at its peak
//! for a 112 MB file (issue 36, point 3). The bytes are those `serde_json`'s pretty printer
//! gives the same document as a `Value`: every object's keys in sorted order, the small
//! pieces (a mode's row, an energy share) serialized through `Value`, which sorts them.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::io::Write;

use faer::c64;
use serde::ser::{SerializeMap, SerializeSeq};
use serde::{Serialize, Serializer};
use serde_json::{json, Value};

use super::eigen_file::{mbdyn_alpha, EigenFile, MatrixLayout};
use super::modal::ModalReport;
use crate::eigen::EnergyShare;

fn number(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

/// A sequence serialized from an iterator, item by item (once: the iterator is consumed).
struct Stream<I>(RefCell<Option<I>>);

fn stream<I>(items: I) -> Stream<I> {
    Stream(RefCell::new(Some(items)))
}

impl<I: Iterator<Item = T>, T: Serialize> Serialize for Stream<I> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let items = self.0.borrow_mut().take().ok_or_else(|| serde::ser::Error::custom("a streamed sequence serialized twice"))?;
        let mut seq = s.serialize_seq(None)?;
        for item in items {
            seq.serialize_element(&item)?;
        }
        seq.end()
    }
}

/// `T` serialized as `serde_json::Value` serializes it: an object's keys sorted (the
/// reference [`SortedShare`] is tested against).
#[cfg(test)]
struct Sorted<'a, T>(&'a T);

#[cfg(test)]
impl<T: Serialize> Serialize for Sorted<'_, T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serde_json::to_value(self.0).map_err(serde::ser::Error::custom)?.serialize(s)
    }
}

/// An energy share as [`Sorted`] writes it (its keys in sorted order, the options left out
/// when `None`), written straight: `Sorted` built a `serde_json::Value` map per share,
/// 960,000 of them for the 96,024-equation string's 40 modes (a tenth of its run's samples).
struct SortedShare<'a>(&'a EnergyShare);

impl Serialize for SortedShare<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let e = self.0;
        let mut map = s.serialize_map(None)?;
        map.serialize_entry("component", e.component)?;
        if let Some(element) = &e.element {
            map.serialize_entry("element", element)?;
        }
        if let Some(mode) = e.mode {
            map.serialize_entry("mode", &(mode as u64))?;
        }
        map.serialize_entry("node", &u64::from(e.node))?;
        map.serialize_entry("share", &number(e.share))?;
        if let Some(state) = &e.state {
            map.serialize_entry("state", state)?;
        }
        map.end()
    }
}

/// A complex number as `{"im": …, "re": …}` (the sorted keys), `null` for a missing vector.
struct Complex(Option<c64>);

impl Serialize for Complex {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let Some(z) = self.0 else { return s.serialize_none() };
        let mut map = s.serialize_map(Some(2))?;
        map.serialize_entry("im", &number(z.im))?;
        map.serialize_entry("re", &number(z.re))?;
        map.end()
    }
}

/// One mode's row of the modal table with its energy shares (borrowed, streamed).
struct Row<'a> {
    fields: serde_json::Map<String, Value>,
    energy: &'a [EnergyShare],
}

impl Serialize for Row<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let energy = (!self.energy.is_empty()).then_some(("energy", self.energy));
        let mut map = s.serialize_map(None)?;
        let mut pending = energy;
        for (key, value) in &self.fields {
            if let Some((name, shares)) = pending.filter(|(name, _)| *name < key.as_str()) {
                map.serialize_entry(name, &stream(shares.iter().map(SortedShare)))?;
                pending = None;
            }
            map.serialize_entry(key, value)?;
        }
        if let Some((name, shares)) = pending {
            map.serialize_entry(name, &stream(shares.iter().map(SortedShare)))?;
        }
        map.end()
    }
}

/// A sparse `Aplus`/`Aminus`: `{"entries": [[i, j, v], …], "indices": …, "size": [n, n]}`.
struct SparseEntries {
    entries: Vec<(usize, usize, f64)>,
    n: usize,
}

impl Serialize for SparseEntries {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(3))?;
        map.serialize_entry("entries", &stream(self.entries.iter().map(|&(i, j, v)| (i + 1, j + 1, number(v)))))?;
        map.serialize_entry("indices", "1-based [row, column, value], as the .m file's spconvert")?;
        map.serialize_entry("size", &[self.n, self.n])?;
        map.end()
    }
}

/// A top-level entry of the document.
enum Part<'a> {
    Plain(Value),
    Rows(Vec<Row<'a>>),
    /// The sparse `Aplus`/`Aminus` (`plus`): `{"entries": [[i, j, v], …], "indices": …,
    /// "size": [n, n]}`.
    Sparse(bool),
    /// The dense `Aplus`/`Aminus` as rows (`plus`).
    Full(bool),
    /// `VR` (`right`) or `VL`: n rows, one complex entry per written mode.
    Vectors(bool),
}

/// The error when the document asks for `Aplus`/`Aminus` that were not assembled.
fn unassembled<E: serde::ser::Error>() -> E {
    E::custom(super::eigen_file::UNASSEMBLED)
}

/// The document's parts, serialized with the file they come from.
struct Document<'a, 'f> {
    file: &'a EigenFile<'f>,
    parts: BTreeMap<&'static str, Part<'a>>,
}

impl Serialize for Document<'_, '_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let e = self.file;
        let n = e.pencil.dim();
        let mut map = s.serialize_map(Some(self.parts.len()))?;
        for (key, part) in &self.parts {
            match part {
                Part::Plain(v) => map.serialize_entry(key, v)?,
                Part::Rows(rows) => map.serialize_entry(key, rows)?,
                Part::Sparse(plus) => map.serialize_entry(key, &SparseEntries { entries: e.pencil.nonzeros(*plus).ok_or_else(unassembled::<S::Error>)?, n })?,
                Part::Full(plus) => {
                    let full = e.pencil.full(*plus).ok_or_else(unassembled::<S::Error>)?;
                    let m: &faer::Mat<f64> = &full;
                    map.serialize_entry(key, &stream((0..m.nrows()).map(|i| stream((0..m.ncols()).map(move |j| number(m[(i, j)]))))))?
                }
                Part::Vectors(right) => {
                    let modes: Vec<_> = e.written.iter().map(|&k| &e.modal.modes[k]).map(|m| if *right { m.right.as_ref() } else { m.left.as_ref() }).collect();
                    map.serialize_entry(key, &stream((0..n).map(|i| stream(modes.iter().map(move |c| Complex(c.map(|v| v[i])))))))?
                }
            }
        }
        map.end()
    }
}

/// Writes the JSON document of one eigenanalysis (pretty-printed, a final newline) to `w`
/// (buffered by the caller: `output::atomic`'s files are).
pub fn write_eigen_json(w: &mut dyn Write, input: &str, e: &EigenFile) -> serde_json::Result<()> {
    let n = e.pencil.dim();
    let table = ModalReport::new(e.modal, n).with_descriptions(e.energy);
    let rows = e
        .written
        .iter()
        .map(|&k| {
            let fields = match serde_json::to_value(&table.eigenvalues[k])? {
                Value::Object(fields) => fields,
                _ => unreachable!("a mode's row serializes as an object"),
            };
            Ok(Row { fields, energy: e.energy.get(k).map_or(&[][..], Vec::as_slice) })
        })
        .collect::<serde_json::Result<Vec<_>>>()?;
    let mut parts: BTreeMap<&'static str, Part> = BTreeMap::new();
    let mut plain = |key, value| parts.insert(key, Part::Plain(value));
    plain("input", json!(input));
    plain("analysis", json!(e.index));
    plain("units", json!("time and dcoef in s; eigenvalues in rad/s; frequencies in Hz; positions in m; rotation vectors in rad"));
    plain("dTime", json!(e.time));
    plain("dCoef", json!(e.dcoef));
    plain("equations", json!(n));
    plain("route", serde_json::to_value(e.modal.route)?);
    plain("solver", json!(e.solver));
    plain("counts", serde_json::to_value(&table.counts)?);
    plain("alpha", Value::Array(e.written.iter().map(|&k| Value::Array(mbdyn_alpha(&e.modal.modes[k], e.modal.route, e.dcoef).map(number).to_vec())).collect()));
    plain("unknowns", json!(e.unknown_names));
    if let Some(g) = e.geometry {
        plain("labels", json!(g.labels));
        plain("idx", json!(g.first_index));
        plain("X0", Value::Array(g.position.iter().zip(&g.rotation_vector).flat_map(|(x, p)| [x.x, x.y, x.z, p.x, p.y, p.z]).map(number).collect()));
    }
    parts.insert("eigenvalues", Part::Rows(rows));
    for (plus, name) in [(true, "Aplus"), (false, "Aminus")] {
        match e.matrices {
            None => {}
            Some(MatrixLayout::Full) => {
                parts.insert(name, Part::Full(plus));
            }
            Some(MatrixLayout::Sparse) => {
                parts.insert(name, Part::Sparse(plus));
            }
        }
    }
    if e.eigenvectors {
        parts.insert("VR", Part::Vectors(true));
        parts.insert("VL", Part::Vectors(false));
    }
    let mut gathered = gathered(w);
    serde_json::to_writer_pretty(&mut gathered, &Document { file: e, parts })?;
    gathered.write_all(b"\n").and_then(|()| gathered.flush()).map_err(serde_json::Error::io)
}

/// Bytes gathered before they are handed to the caller's writer.
const GATHERED_BYTES: usize = 1 << 20;

/// The caller's writer behind a buffer of [`GATHERED_BYTES`] whose type serde_json sees:
/// its pretty printer writes each key, colon, indentation and number on its own (about
/// twenty writes per energy share, 960,000 shares on the 96,024-equation string), which
/// through `dyn Write` were each a dynamic call and took most of the `.json`'s time; into
/// a `BufWriter` each is a copy, handed on a megabyte at a time. The bytes are the same.
fn gathered(w: &mut dyn Write) -> std::io::BufWriter<&mut dyn Write> {
    std::io::BufWriter::with_capacity(GATHERED_BYTES, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A document of about 3 MB written through [`gathered`] (three hand-overs of a
    /// megabyte and the rest) is, byte for byte, what serde_json's pretty printer writes
    /// straight into a `Vec`, and reaches the writer in megabyte pieces, not item by item.
    #[test]
    fn gathered_bytes_are_the_pretty_printers() {
        struct Counting(Vec<u8>, usize);
        impl Write for Counting {
            fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
                self.0.extend_from_slice(b);
                self.1 += 1;
                Ok(b.len())
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        let doc = json!({"shares": (0..120_000).map(|k| json!({"node": k, "share": 1.0 / (k as f64 + 3.0), "component": "x"})).collect::<Vec<_>>()});
        let want = serde_json::to_vec_pretty(&doc).unwrap();
        assert!(want.len() > 3 * GATHERED_BYTES, "{} bytes", want.len());
        let mut out = Counting(Vec::new(), 0);
        let mut gathered = gathered(&mut out);
        serde_json::to_writer_pretty(&mut gathered, &doc).unwrap();
        gathered.flush().unwrap();
        drop(gathered);
        assert_eq!(out.0, want);
        assert!(out.1 <= want.len() / GATHERED_BYTES + 1, "{} writes", out.1);
    }

    /// Each kind of energy share (a node component's; an element's own unknown with its
    /// state, with a modal joint's mode; a share that is not finite) written straight
    /// equals, byte for byte, what serde_json's own `Value` map writes of it (its keys
    /// sorted), compact and pretty.
    #[test]
    fn energy_shares_are_written_as_serde_json_sorts_them() {
        let share = |component, share, element: Option<&str>, state: Option<&str>, mode| EnergyShare { node: 4_000_000_001, component, share, element: element.map(str::to_string), state: state.map(str::to_string), mode };
        let shares = [
            share("x", 0.1 + 0.2, None, None, None),
            share("rz", 1e-300, None, None, None),
            share("element", 1.0, Some("motor"), Some("current \"i\""), None),
            share("element", 0.5, Some("modal joint"), Some("mode 3"), Some(3)),
            share("abstract", f64::NAN, None, None, None),
        ];
        for e in &shares {
            assert_eq!(serde_json::to_string(&SortedShare(e)).unwrap(), serde_json::to_string(&Sorted(e)).unwrap());
            assert_eq!(serde_json::to_string_pretty(&SortedShare(e)).unwrap(), serde_json::to_string_pretty(&Sorted(e)).unwrap());
        }
        let all = |f: &dyn Fn(&EnergyShare) -> String| shares.iter().map(f).collect::<Vec<_>>();
        assert_eq!(all(&|e| serde_json::to_string(&SortedShare(e)).unwrap()), all(&|e| serde_json::to_string(&Sorted(e)).unwrap()));
    }
}
