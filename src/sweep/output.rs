//! A sweep's results as files: stacked arrays (MATLAB ss-array layout, `A(:,:,k)` is design
//! point k, every point's ROM in the tracked modes' consistent basis) in `.mat` or `.npz`, a
//! CSV table of the tracked modes against the parameters, and a plot of their frequency and
//! damping against one parameter.

use std::io::Write;
use std::path::Path;

use faer::{c64, Mat};

use crate::output::atomic::{write_atomic, OutputError};
use crate::output::mat5::MatFile;
use crate::output::npz::NpzWriter;
use crate::output::sweep_plot::{write_sweep_plot, ModeCurve, SweepPlot};
use crate::output::rom_file::RomExport;

use super::track::Tracking;
use super::SweepResults;
use crate::linear::hz;

/// Why a sweep's results cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum StackError {
    #[error("no design point succeeded: nothing to write")]
    NoPoint,
    #[error("the ROMs do not have the same size at every design point ({0}); stacked arrays need one size: choose the modes with --count or --modes so every point keeps as many")]
    Sizes(String),
    #[error("interpolation: {0}")]
    Interpolation(String),
    #[error("--against {0}: not a swept parameter (swept: {1})")]
    UnknownParameter(String, String),
    #[error("the output file must end in .mat or .npz, got {0}")]
    Extension(String),
    #[error(transparent)]
    Output(#[from] OutputError),
}

/// One named real array, data column-major.
pub struct Array {
    pub name: &'static str,
    pub dims: Vec<usize>,
    pub data: Vec<f64>,
}

/// The stacked results: numeric arrays and string lists.
pub struct Stacked {
    pub arrays: Vec<Array>,
    pub strings: Vec<(&'static str, Vec<String>)>,
    pub kind: &'static str,
}

/// MBDyn's frequency `|Im λ|/2π` [Hz].
fn freq_hz(l: c64) -> f64 {
    hz(l.im.abs())
}

/// Damping ratio `−Re λ/|λ|` (0 for λ = 0).
fn damping(l: c64) -> f64 {
    if l.norm() > 0.0 { -l.re / l.norm() } else { 0.0 }
}

fn dims(m: &Mat<f64>) -> (usize, usize) {
    (m.nrows(), m.ncols())
}

/// `X(:,:,k)` for every point: `get` gives point k's matrix (`None`: NaN slice).
fn stack(name: &'static str, (r, c): (usize, usize), k: usize, get: impl Fn(usize) -> Option<Mat<f64>>) -> Array {
    let mut data = Vec::with_capacity(r * c * k);
    for p in 0..k {
        match get(p) {
            Some(m) => data.extend((0..c).flat_map(|j| (0..r).map(move |i| (i, j))).map(|(i, j)| m[(i, j)])),
            None => data.extend(std::iter::repeat_n(f64::NAN, r * c)),
        }
    }
    Array { name, dims: vec![r, c, k], data }
}

/// A K × m table (column-major) from `f(point, mode)`, NaN where absent.
fn table(name: &'static str, k: usize, m: usize, f: impl Fn(usize, usize) -> Option<f64>) -> Array {
    Array { name, dims: vec![k, m], data: (0..m).flat_map(|j| (0..k).map(move |p| (p, j))).map(|(p, j)| f(p, j).unwrap_or(f64::NAN)).collect() }
}

impl SweepResults {
    /// The eigenvalue of tracked mode `j` at point `p` (`None`: failed point, mode not found).
    fn tracked(&self, tracking: &Tracking, p: usize, j: usize) -> Option<c64> {
        let m = tracking.matches[p].as_ref()?.get(j)?.as_ref()?;
        Some(self.results[p].as_ref().ok()?.modes[m.candidate].lambda)
    }

    /// "modes 1 and 2 cross; mode 3 ambiguous (MAC 0.55)" for point `p` ("" when nothing).
    fn flags(tracking: &Tracking, p: usize) -> String {
        let Some(row) = &tracking.matches[p] else { return String::new() };
        let crossing: Vec<String> = row.iter().enumerate().filter(|(_, m)| m.as_ref().is_some_and(|m| m.crossing)).map(|(j, _)| (j + 1).to_string()).collect();
        let mut out = Vec::new();
        if !crossing.is_empty() {
            out.push(format!("modes {} crossed", crossing.join(", ")));
        }
        for (j, m) in row.iter().enumerate() {
            match m {
                Some(m) if m.ambiguous() => out.push(format!("mode {} ambiguous (MAC {:.2}: a veering, or points too far apart)", j + 1, m.mac)),
                None => out.push(format!("mode {} not found", j + 1)),
                _ => {}
            }
        }
        out.join("; ")
    }

    /// Stacks the ROMs in the consistent basis of the tracked modes: every successful point
    /// must have the same sizes; a failed point's slices are NaN and `point_ok` is 0 there,
    /// `point_errors` says why.
    pub fn stacked(&self) -> Result<Stacked, StackError> {
        let k = self.points.len();
        let tracking = self.tracking();
        let roms = self.consistent_roms();
        let rom = |p: usize| roms[p].as_ref().map(|r| &r.rom);
        let first_k = (0..k).find(|&p| rom(p).is_some()).ok_or(StackError::NoPoint)?;
        let first = &roms[first_k].as_ref().ok_or(StackError::NoPoint)?.rom;
        let shape = |r: &RomExport| (dims(&r.e), dims(&r.a), dims(&r.b), dims(&r.c), dims(&r.d));
        let differ: Vec<String> = (0..k).filter_map(|p| rom(p).filter(|r| shape(r) != shape(first)).map(|r| format!("point {} ({}): {} states, first point: {}", p + 1, self.describe_point(p), r.a.nrows(), first.a.nrows()))).collect();
        if !differ.is_empty() {
            return Err(StackError::Sizes(differ.join("; ")));
        }
        let (ni, no, ns) = (first.b.ncols(), first.c.nrows(), first.a.nrows());
        let mut arrays = vec![
            stack("E", dims(&first.e), k, |p| rom(p).map(|r| r.e.clone())),
            stack("A", dims(&first.a), k, |p| rom(p).map(|r| r.a.clone())),
            stack("B", dims(&first.b), k, |p| rom(p).map(|r| r.b.clone())),
            stack("C", dims(&first.c), k, |p| rom(p).map(|r| r.c.clone())),
            stack("D", dims(&first.d), k, |p| rom(p).map(|r| r.d.clone())),
            stack("full_static_gain", (no, ni), k, |p| rom(p).and_then(|r| r.full_static_gain.clone())),
            stack("rom_static_gain", (no, ni), k, |p| rom(p).and_then(|r| r.rom_static_gain.clone())),
            // Each state's tracked mode (1-based; 0: a mode not tracked or a static state).
            stack("state_tracks", (ns, 1), k, |p| roms[p].as_ref().map(|r| Mat::from_fn(ns, 1, |i, _| r.state_tracks[i] as f64))),
        ];
        let np = self.names.len();
        arrays.push(table("parameters", k, np, |p, j| Some(self.points[p][j])));
        arrays.push(table("point_ok", k, 1, |p, _| Some(if self.results[p].is_ok() { 1.0 } else { 0.0 })));
        arrays.push(table("reference_time", k, 1, |p, _| rom(p).and_then(|r| r.reference_time)));
        arrays.push(table("dcoef", k, 1, |p, _| rom(p).map(|r| r.dcoef)));
        let mode = |p: usize, j: usize| self.tracked(&tracking, p, j);
        // --lowest columns, NaN beyond the modes the first point has.
        let m = self.modes.max(tracking.labels.len());
        arrays.push(table("mode_re", k, m, |p, j| mode(p, j).map(|l| l.re)));
        arrays.push(table("mode_im", k, m, |p, j| mode(p, j).map(|l| l.im)));
        arrays.push(table("mode_freq_hz", k, m, |p, j| mode(p, j).map(freq_hz)));
        arrays.push(table("mode_undamped_hz", k, m, |p, j| mode(p, j).map(|l| hz(l.norm()))));
        arrays.push(table("mode_damping", k, m, |p, j| mode(p, j).map(damping)));
        let matched = |p: usize, j: usize| tracking.matches[p].as_ref().and_then(|r| r.get(j).cloned().flatten());
        arrays.push(table("mode_mac", k, m, |p, j| matched(p, j).map(|mt| mt.mac)));
        arrays.push(table("mode_crossing", k, m, |p, j| matched(p, j).map(|mt| if mt.crossing { 1.0 } else { 0.0 })));
        let errors = self.results.iter().map(|r| r.as_ref().err().map_or(String::new(), |e| e.message.clone())).collect();
        let strings = vec![
            ("parameter_names", self.names.clone()),
            ("point_errors", errors),
            ("mode_labels", (0..m).map(|j| tracking.labels.get(j).cloned().unwrap_or_default()).collect()),
            ("mode_flags", (0..k).map(|p| Self::flags(&tracking, p)).collect()),
            ("inputs", first.inputs.clone()),
            ("outputs", first.outputs.clone()),
            ("states", first.states.clone()),
            ("input_units", first.input_units.clone()),
            ("output_units", first.output_units.clone()),
        ];
        Ok(Stacked { arrays, strings, kind: first.kind })
    }

    /// Writes the stacked arrays to `path` (.mat or .npz).
    pub fn write_arrays(&self, path: &Path) -> Result<(), StackError> {
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        let s = self.stacked()?;
        match ext.as_deref() {
            Some("mat") => {
                let mut f = MatFile::new();
                for a in &s.arrays {
                    f.add_array(a.name, &a.dims, &a.data)?;
                }
                for (name, list) in &s.strings {
                    f.add_string_list(name, list)?;
                }
                f.add_string("kind", s.kind)?;
                f.write(path)?;
            }
            Some("npz") => {
                let mut f = NpzWriter::new();
                for a in &s.arrays {
                    f.add_array(a.name, &a.dims, &a.data)?;
                }
                for (name, list) in &s.strings {
                    f.add_string_list(name, list)?;
                }
                f.add_string_list("kind", &[s.kind.to_string()])?;
                f.write(path)?;
            }
            _ => return Err(StackError::Extension(path.display().to_string())),
        }
        Ok(())
    }

    /// The table of the tracked modes against the parameters, as CSV text: one row per
    /// design point; per mode its eigenvalue, frequency, damping and the MAC of its match
    /// (the header names each mode by its label at the first point); the flags (crossings,
    /// ambiguous matches); a failed point has empty mode columns and its error.
    pub fn modes_csv(&self) -> String {
        let tracking = self.tracking();
        let quote = |s: String| if s.contains([',', '"']) { format!("\"{}\"", s.replace('"', "'")) } else { s };
        let mut s = String::from("point");
        for n in &self.names {
            s += &format!(",{n}");
        }
        let m = self.modes.max(tracking.labels.len());
        for j in 0..m {
            let label = tracking.labels.get(j).map_or("", |l| l.as_str());
            let head = if label.is_empty() { format!("mode {}", j + 1) } else { format!("mode {} ({label})", j + 1) };
            for col in ["Re λ [rad/s]", "Im λ [rad/s]", "freq [Hz]", "damping [-]", "MAC [-]"] {
                s += &format!(",{}", quote(format!("{head} {col}")));
            }
        }
        s += ",flags,error\n";
        for (p, r) in self.results.iter().enumerate() {
            s += &(p + 1).to_string();
            for v in &self.points[p] {
                s += &format!(",{v:e}");
            }
            for j in 0..m {
                let mac = tracking.matches[p].as_ref().and_then(|r| r.get(j)?.as_ref()).map(|m| m.mac);
                match (self.tracked(&tracking, p, j), mac) {
                    (Some(l), Some(mac)) => s += &format!(",{:.12e},{:.12e},{:.12e},{:.6e},{mac:.4}", l.re, l.im, freq_hz(l), damping(l)),
                    _ => s += ",,,,,",
                }
            }
            let e = r.as_ref().err().map_or(String::new(), |e| e.message.lines().next().unwrap_or("").replace('"', "'"));
            s += &format!(",\"{}\",\"{e}\"\n", Self::flags(&tracking, p));
        }
        s
    }

    /// Writes [`SweepResults::modes_csv`] atomically.
    pub fn write_modes_csv(&self, path: &Path) -> Result<(), StackError> {
        let text = self.modes_csv();
        write_atomic(path, |w: &mut dyn Write| w.write_all(text.as_bytes()))?;
        Ok(())
    }

    /// Frequency and damping of the tracked modes against parameter `against` (default the
    /// first), each labelled by its number and its label at the first point; with several
    /// parameters, one curve per mode and combination of the others.
    pub fn plot(&self, against: Option<&str>) -> Result<SweepPlot, StackError> {
        let tracking = self.tracking();
        let x = match against {
            None => 0,
            Some(a) => self.names.iter().position(|n| n == a).ok_or_else(|| StackError::UnknownParameter(a.to_string(), self.names.join(", ")))?,
        };
        // Points grouped by the values of the other parameters, in order of appearance.
        let mut groups: Vec<(Vec<f64>, Vec<usize>)> = Vec::new();
        for (p, v) in self.points.iter().enumerate() {
            let others: Vec<f64> = v.iter().enumerate().filter(|(j, _)| *j != x).map(|(_, v)| *v).collect();
            match groups.iter_mut().find(|(o, _)| o.iter().zip(&others).all(|(a, b)| a.to_bits() == b.to_bits())) {
                Some((_, list)) => list.push(p),
                None => groups.push((others, vec![p])),
            }
        }
        let other_names: Vec<&String> = self.names.iter().enumerate().filter(|(j, _)| *j != x).map(|(_, n)| n).collect();
        let mut curves = Vec::new();
        for (others, list) in groups.iter_mut() {
            // Along increasing parameter (a list may be given in any order); a failed point
            // keeps its place and breaks the line.
            list.sort_by(|a, b| self.points[*a][x].total_cmp(&self.points[*b][x]));
            let tag = other_names.iter().zip(others).map(|(n, v)| format!("{n} = {v}")).collect::<Vec<_>>().join(", ");
            for (j, name) in tracking.labels.iter().enumerate() {
                let lam = |p: &usize| self.tracked(&tracking, *p, j);
                let head = if name.is_empty() { format!("{}", j + 1) } else { format!("{}: {name}", j + 1) };
                let label = if tag.is_empty() { head } else { format!("{head}, {tag}") };
                let ambiguous = |p: &usize| tracking.matches[*p].as_ref().and_then(|r| r[j].as_ref()).is_some_and(|m| m.ambiguous());
                curves.push(ModeCurve {
                    label,
                    parameter: list.iter().map(|p| self.points[*p][x]).collect(),
                    freq_hz: list.iter().map(|p| lam(p).map_or(f64::NAN, freq_hz)).collect(),
                    damping: list.iter().map(|p| lam(p).map_or(f64::NAN, damping)).collect(),
                    ambiguous: list.iter().map(ambiguous).collect(),
                });
            }
        }
        let file = self.file.file_name().map_or(String::new(), |f| f.to_string_lossy().into_owned());
        let failed: Vec<String> = self.failures().map(|(k, _, _)| self.describe_point(k)).collect();
        let note = match failed.len() {
            0 => String::new(),
            1..=2 => format!(" ({} failed, not drawn: {})", failed.len(), failed.join("; ")),
            n => format!(" ({n} failed points, not drawn)"),
        };
        Ok(SweepPlot { title: format!("{file}: modes tracked against {}{note}", self.names[x]), parameter: format!("{} (the file's set: variable, its SI units)", self.names[x]), curves })
    }

    /// Writes the plot as `PREFIX.svg` and `PREFIX.png`.
    pub fn write_plot(&self, prefix: &Path, against: Option<&str>) -> Result<[std::path::PathBuf; 2], StackError> {
        let plot = self.plot(against)?;
        let (svg, png) = (crate::output::prefixed_path(prefix, "svg"), crate::output::prefixed_path(prefix, "png"));
        write_sweep_plot(&plot, &svg, &png)?;
        Ok([svg, png])
    }
}
