//! Scalar node histories in MBDyn's files (node.cc, `ScalarDifferentialNode::Output`,
//! `ScalarAlgebraicNode::Output`; output.cc's extensions): abstract nodes in `.abs`,
//! electric nodes in `.ele`, hydraulic (pressure) nodes in `.prs`, one line per written node
//! per output instant,
//!
//! ```text
//! label  value  [derivative]
//! ```
//!
//! the derivative for differential nodes only (abstract nodes' values have the model's
//! units, electric nodes' are voltages [V] and their rates [V/s], hydraulic nodes'
//! pressures [Pa]); no header, so Octave's `load` reads it. Each file is written to a
//! temporary name and put in place with the rest of its set.

use std::path::Path;

use super::atomic::{AtomicFile, OutputError};
use crate::model::{Model, ScalarNodeKind};

/// MBDyn's extension of a scalar node kind's file.
pub fn extension(kind: ScalarNodeKind) -> &'static str {
    match kind {
        ScalarNodeKind::Abstract => "abs",
        ScalarNodeKind::Electric => "ele",
        ScalarNodeKind::Hydraulic => "prs",
    }
}

/// The `.abs`, `.ele`, `.prs` files of a run, one per kind with a written node.
pub struct ScalarNodeWriter {
    /// Per file: its kind, the file, and the (index in `Model::scalar_nodes`, differential)
    /// of its written nodes.
    files: Vec<(AtomicFile, Vec<(usize, bool)>)>,
    digits: usize,
}

impl ScalarNodeWriter {
    /// The files under `prefix` (`prefix.abs`, …) of the model's written scalar nodes;
    /// numbers with `digits` after the decimal point.
    pub fn create(prefix: &Path, model: &Model, digits: usize) -> Result<Self, OutputError> {
        let mut files = Vec::new();
        for kind in [ScalarNodeKind::Abstract, ScalarNodeKind::Electric, ScalarNodeKind::Hydraulic] {
            let written: Vec<(usize, bool)> = model.scalar_nodes.iter().enumerate().filter(|(_, n)| n.id.kind == kind && n.output).map(|(i, n)| (i, n.differential)).collect();
            if !written.is_empty() {
                files.push((AtomicFile::create(&super::prefixed_path(prefix, extension(kind)))?, written));
            }
        }
        Ok(ScalarNodeWriter { files, digits })
    }

    /// Appends one output instant: `y`, `yp` the state's unknowns and derivatives, `first`
    /// the unknown of the first scalar node.
    pub fn write_step(&mut self, model: &Model, y: &[f64], yp: &[f64], first: usize) -> Result<(), OutputError> {
        let d = self.digits;
        for (file, nodes) in &mut self.files {
            file.write_with(|out| {
                for &(i, differential) in nodes.iter() {
                    write!(out, "{} {:.d$e}", model.scalar_nodes[i].id.label, y[first + i])?;
                    if differential {
                        write!(out, " {:.d$e}", yp[first + i])?;
                    }
                    writeln!(out)?;
                }
                Ok(())
            })?;
        }
        Ok(())
    }

    /// The files, to be put in place with the rest of their set.
    pub fn into_files(self) -> Vec<AtomicFile> {
        self.files.into_iter().map(|(f, _)| f).collect()
    }
}
