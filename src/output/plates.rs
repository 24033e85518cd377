//! `PREFIX.pla`, MBDyn's plate output (shelleas.cc, shelleasans.cc, membraneeas.cc,
//! `Output`): one line per plate element and output instant, `label` then the stress
//! resultants of each of its four Gauss points: a shell's 12 (n₁₁, n₁₂, n₁₃, n₂₁, n₂₂, n₂₃
//! [N/m], m₁₁, …, m₂₃ [N]) in the points' frames, a membrane's 3 (n₁₁, n₂₂, n₁₂ [N/m],
//! second Piola–Kirchhoff, in the initial points' frames). No header,
//! so Octave's `load` reads it; written under a temporary name and renamed when the run
//! finishes.

use std::path::Path;

use super::atomic::{AtomicFile, OutputError};
use crate::model::Label;

/// The `.pla` file of a run, written step by step.
pub struct PlateWriter {
    file: AtomicFile,
}

impl PlateWriter {
    pub fn create(path: &Path) -> Result<Self, OutputError> {
        Ok(PlateWriter { file: AtomicFile::create(path)? })
    }

    /// Appends one output instant: a line per shell.
    pub fn write_step(&mut self, plates: &[(Label, Vec<f64>)]) -> Result<(), OutputError> {
        self.file.write_with(|out| {
            plates.iter().try_for_each(|(label, points)| {
                write!(out, "{label}")?;
                for v in points {
                    write!(out, " {v:.16e}")?;
                }
                writeln!(out)
            })
        })
    }

    /// The file, to be put in place with the rest of its set.
    pub fn into_file(self) -> AtomicFile {
        self.file
    }
}
