//! `PREFIX.hyd`, MBDyn's hydraulic elements' output (output.cc's `.hyd` stream, written by
//! each hydraulic element's `Output` in hydr/*.cc): one line per written hydraulic element
//! and output instant, its label then its own columns ([`crate::element::Outputs::hydraulic_row`]:
//! an actuator's chamber flows, pressures, rates, volumes and densities; a minor loss's or
//! an orifice's velocity and flow; a pipe's velocity, flow and Reynolds number; …), in SI
//! units (kg/s, Pa, Pa/s, m³, kg/m³, m/s, m). No header, so Octave's `load` reads it (the
//! rows of different element types have different lengths: filter by label first);
//! written under a temporary name and put in place with the rest of its set.

use std::path::Path;

use super::atomic::{AtomicFile, OutputError};
use crate::model::Label;

/// The `.hyd` file of a run, written step by step.
pub struct HydraulicWriter {
    file: AtomicFile,
    digits: usize,
}

impl HydraulicWriter {
    /// The file at `path`; numbers with `digits` after the decimal point.
    pub fn create(path: &Path, digits: usize) -> Result<Self, OutputError> {
        Ok(HydraulicWriter { file: AtomicFile::create(path)?, digits })
    }

    /// Appends one output instant: a line per written hydraulic element.
    pub fn write_step(&mut self, rows: &[(Label, Vec<f64>)]) -> Result<(), OutputError> {
        let d = self.digits;
        self.file.write_with(|out| {
            rows.iter().try_for_each(|(label, row)| {
                write!(out, "{label}")?;
                for v in row {
                    write!(out, " {v:.d$e}")?;
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
