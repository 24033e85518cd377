//! Beam internal forces and deformations per output instant, one line per beam:
//!
//! - `PREFIX.act`, MBDyn's layout for beams: `label  F_I  M_I  F_II  M_II`, forces [N] and
//!   moments [N m] at evaluation points I and II in the section frames (axis 1 along the
//!   beam: axial force, two shear forces; torsional moment, two bending moments);
//! - `PREFIX.bst` (romdyn's): `label  ε_I  κ_I  ε_II  κ_II`, axial and shear strains [-] and
//!   torsional and bending curvatures [1/m] in the same frames.
//!
//! No header, so Octave's `load` reads both; written under temporary names and renamed
//! when the run finishes.

use std::io::Write;
use std::path::Path;

use super::atomic::{AtomicFile, OutputError};
use super::scientific::{push_scientific, push_unsigned};
use crate::element::SectionState;
use crate::kinematics::Vec3;
use crate::model::Label;

/// The `.act` and `.bst` files of a run, written step by step.
pub struct BeamSectionWriter {
    forces: AtomicFile,
    strains: AtomicFile,
    /// One output instant's text.
    text: Vec<u8>,
}

/// Every beam's line of one output instant, formed in `text` (cleared first; kept between
/// instants so that its storage is reused) and written at once.
fn lines(out: &mut dyn Write, text: &mut Vec<u8>, beams: &[(Label, Vec<SectionState>)], pick: impl Fn(&SectionState) -> [Vec3; 2]) -> std::io::Result<()> {
    text.clear();
    for (label, sections) in beams {
        push_unsigned(text, u64::from(*label));
        for s in sections {
            for v in pick(s) {
                for &c in v.iter() {
                    text.push(b' ');
                    push_scientific(text, c, 12);
                }
            }
        }
        text.push(b'\n');
    }
    out.write_all(text)
}

impl BeamSectionWriter {
    pub fn create(forces: &Path, strains: &Path) -> Result<Self, OutputError> {
        Ok(BeamSectionWriter { forces: AtomicFile::create(forces)?, strains: AtomicFile::create(strains)?, text: Vec::new() })
    }

    /// Appends one output instant: a line per beam in each file.
    pub fn write_step(&mut self, beams: &[(Label, Vec<SectionState>)]) -> Result<(), OutputError> {
        let text = &mut self.text;
        self.forces.write_with(|out| lines(out, text, beams, |x| [x.force, x.moment]))?;
        self.strains.write_with(|out| lines(out, text, beams, |x| [x.strain, x.curvature]))
    }

    /// Flushes and renames both files into place.
    /// The `.act` and `.bst` files, to be put in place with the rest of their set.
    pub fn into_files(self) -> [AtomicFile; 2] {
        [self.forces, self.strains]
    }

    pub fn finish(self) -> Result<(), OutputError> {
        self.forces.commit()?;
        self.strains.commit()
    }

    pub fn paths(&self) -> [&Path; 2] {
        [self.forces.path(), self.strains.path()]
    }
}
