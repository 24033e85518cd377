//! Node histories in MBDyn's `.mov` layout: one line per node per step,
//!
//! ```text
//! label  x y z  o1 o2 o3  vx vy vz  wx wy wz
//! ```
//!
//! positions [m], orientation as Euler 1-2-3 angles [deg] (MBDyn's default) or as a
//! rotation vector [rad], velocities [m/s] and angular velocities [rad/s] in the global
//! frame; no header, so Octave's `load` reads it. The file is written to a temporary name
//! and renamed when the run finishes.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use super::atomic::OutputError;
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
    path: PathBuf,
    tmp: PathBuf,
    out: Option<BufWriter<File>>,
    orientation: OrientationOutput,
}

impl MotionWriter {
    pub fn create(path: &Path, orientation: OrientationOutput) -> Result<Self, OutputError> {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let tmp = path.with_file_name(format!(".{name}.tmp-{}", std::process::id()));
        let file = File::create(&tmp).map_err(|source| OutputError::Io { path: path.to_path_buf(), operation: "create a temporary file", source })?;
        Ok(MotionWriter { path: path.to_path_buf(), tmp, out: Some(BufWriter::new(file)), orientation })
    }

    /// Appends one step: a line per node.
    pub fn write_step(&mut self, nodes: &[(Label, NodeKinematics)]) -> Result<(), OutputError> {
        let Some(out) = self.out.as_mut() else { return Ok(()) };
        for (label, k) in nodes {
            let o = match self.orientation {
                OrientationOutput::Euler123Degrees => euler123(&k.r).map(f64::to_degrees),
                OrientationOutput::RotationVector => rotation_vector(&k.r),
            };
            let mut line = format!("{label}");
            for v in [k.x, o, k.xdot, k.omega] {
                for c in v.iter() {
                    line += &format!(" {c:.12e}");
                }
            }
            writeln!(out, "{line}").map_err(|source| OutputError::Io { path: self.path.clone(), operation: "write", source })?;
        }
        Ok(())
    }

    /// Flushes and renames the file into place.
    pub fn finish(mut self) -> Result<(), OutputError> {
        let io = |operation, source| OutputError::Io { path: self.path.clone(), operation, source };
        if let Some(out) = self.out.take() {
            let file = out.into_inner().map_err(|e| io("write", e.into_error()))?;
            file.sync_all().map_err(|e| io("sync", e))?;
            std::fs::rename(&self.tmp, &self.path).map_err(|e| io("rename the temporary file onto it", e))?;
        }
        Ok(())
    }
}

impl Drop for MotionWriter {
    fn drop(&mut self) {
        if self.out.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}
