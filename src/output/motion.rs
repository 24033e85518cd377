//! Node histories in MBDyn's `.mov` layout: one line per node per output instant,
//!
//! ```text
//! label  x y z  o1 o2 o3  vx vy vz  wx wy wz
//! ```
//!
//! positions [m], orientation as Euler 1-2-3 angles [deg] (MBDyn's default) or as a
//! rotation vector [rad], velocities [m/s] and angular velocities [rad/s] in the global
//! frame; no header, so Octave's `load` reads it. The file is written to a temporary name
//! and renamed when the run finishes.

use std::path::Path;

use super::atomic::{AtomicFile, OutputError};
use crate::element::NodeKinematics;
use crate::kinematics::{euler123, rotation_vector};
use crate::model::Label;

/// How orientations are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrientationOutput {
    /// Euler 1-2-3 angles in degrees (MBDyn's default).
    Euler123Degrees,
    /// Rotation vector φ n in radians.
    RotationVector,
}

/// A `.mov` file being written step by step.
pub struct MotionWriter {
    file: AtomicFile,
    orientation: OrientationOutput,
}

impl MotionWriter {
    pub fn create(path: &Path, orientation: OrientationOutput) -> Result<Self, OutputError> {
        Ok(MotionWriter { file: AtomicFile::create(path)?, orientation })
    }

    /// Appends one output instant: a line per node.
    pub fn write_step(&mut self, nodes: &[(Label, NodeKinematics)]) -> Result<(), OutputError> {
        let orientation = self.orientation;
        self.file.write_with(|out| {
            for (label, k) in nodes {
                let o = match orientation {
                    OrientationOutput::Euler123Degrees => euler123(&k.r).map(f64::to_degrees),
                    OrientationOutput::RotationVector => rotation_vector(&k.r),
                };
                write!(out, "{label}")?;
                for v in [k.x, o, k.xdot, k.omega] {
                    for c in v.iter() {
                        write!(out, " {c:.12e}")?;
                    }
                }
                writeln!(out)?;
            }
            Ok(())
        })
    }

    /// Flushes and renames the file into place.
    /// The file, to be put in place with the rest of its set.
    pub fn into_file(self) -> AtomicFile {
        self.file
    }

    pub fn finish(self) -> Result<(), OutputError> {
        self.file.commit()
    }
}
