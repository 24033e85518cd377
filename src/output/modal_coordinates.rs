//! Modal coordinates per output instant in MBDyn's `.mod` layout (input manual §Modal,
//! "Output"; modal.cc, `Modal::Output`): one line per mode of every modal joint,
//!
//! ```text
//! LABEL.MODE  q  q̇  q̈
//! ```
//!
//! the joint's label and the mode's number in the FEM file, the modal coordinate (its unit
//! is the mode shapes' normalization: metres of displacement per unit `q`), its first [1/s]
//! and second [1/s²] time derivatives. No header; written under a temporary name and
//! renamed when the run finishes.

use std::path::Path;

use super::atomic::{AtomicFile, OutputError};
use crate::dae::ModalRow;

/// A `.mod` file being written step by step.
pub struct ModalCoordinateWriter {
    file: AtomicFile,
    /// Digits after the decimal point.
    digits: usize,
}

impl ModalCoordinateWriter {
    pub fn create(path: &Path, digits: usize) -> Result<Self, OutputError> {
        Ok(ModalCoordinateWriter { file: AtomicFile::create(path)?, digits })
    }

    /// Appends one output instant.
    pub fn write_step(&mut self, rows: &[ModalRow]) -> Result<(), OutputError> {
        let d = self.digits;
        self.file.write_with(|out| {
            for r in rows {
                writeln!(out, "{:>8}.{} {:.d$e} {:.d$e} {:.d$e}", r.element, r.mode, r.q, r.rate, r.acceleration)?;
            }
            Ok(())
        })
    }

    /// The file, to be put in place with the rest of its set.
    pub fn into_file(self) -> AtomicFile {
        self.file
    }
}
