//! Node histories in MBDyn's `.mov` layout: one line per node per output instant,
//!
//! ```text
//! label  x y z  o1 o2 o3  vx vy vz  wx wy wz  [ax ay az  dwx dwy dwz]
//! ```
//!
//! positions [m], orientation as Euler 1-2-3 angles [deg] (MBDyn's default), Euler 3-1-3 or
//! 3-2-1 angles [deg], a rotation vector [rad] or the nine entries of R by rows (MBDyn's
//! `orientation description`, strnode.cc `StructNode::Output`), velocities [m/s] and angular
//! velocities [rad/s] in the global frame, for nodes that ask for them (MBDyn's `accelerations,
//! yes`) the accelerations [m/s²] and angular accelerations [rad/s²]; no header, so Octave's `load` reads it. Dummy
//! nodes are rows computed from their base node, as MBDyn writes them. The file is written to a temporary name
//! and renamed when the run finishes.

use std::collections::HashMap;
use std::path::Path;

use super::atomic::{AtomicFile, OutputError};
use super::scientific::{push_scientific, push_unsigned};
use crate::element::NodeKinematics;
use crate::kinematics::{euler123, rotation_vector, Mat3, Vec3};
pub use crate::model::OrientationOutput;
use crate::model::{Label, MotionOutput, NodeSource};

/// A `.mov` file being written step by step.
pub struct MotionWriter {
    file: AtomicFile,
    orientation: OrientationOutput,
    /// Digits after the decimal point ([`MotionOutput::digits`]).
    digits: usize,
    /// One output instant's text.
    text: Vec<u8>,
}

/// Euler angles `[a, b, c]` of `R = R_i(a) R_j(b) R_k(c)` for the axis sequences 3-1-3 and
/// 3-2-1 (input manual, "Orientation Matrix"), in radians.
fn euler313(r: &Mat3) -> Vec3 {
    let b = r[(2, 2)].clamp(-1.0, 1.0).acos();
    if b.sin().abs() < 1e-12 {
        return Vec3::new(r[(1, 0)].atan2(r[(0, 0)]), b, 0.0);
    }
    Vec3::new(r[(0, 2)].atan2(-r[(1, 2)]), b, r[(2, 0)].atan2(r[(2, 1)]))
}

fn euler321(r: &Mat3) -> Vec3 {
    let b = (-r[(2, 0)]).clamp(-1.0, 1.0).asin();
    Vec3::new(r[(1, 0)].atan2(r[(0, 0)]), b, r[(2, 1)].atan2(r[(2, 2)]))
}

/// The numbers a row writes for orientation `r`: the first `len` of the array.
fn orientation_values(r: &Mat3, how: OrientationOutput) -> ([f64; 9], usize) {
    let three = |v: Vec3| ([v[0], v[1], v[2], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], 3);
    match how {
        OrientationOutput::Euler123Degrees => three(euler123(r).map(f64::to_degrees)),
        OrientationOutput::Euler313Degrees => three(euler313(r).map(f64::to_degrees)),
        OrientationOutput::Euler321Degrees => three(euler321(r).map(f64::to_degrees)),
        OrientationOutput::RotationVector => three(rotation_vector(r)),
        OrientationOutput::Matrix => (std::array::from_fn(|k| r[(k / 3, k % 3)]), 9),
        OrientationOutput::Unwritten => ([0.0; 9], 0),
    }
}

/// Linear and angular acceleration [m/s², rad/s²], global frame.
pub type Accelerations = (Vec3, Vec3);

/// One row of the motion file: label, kinematics, orientation form and, for a node that
/// asks for them, its accelerations.
pub type MotionRow = (Label, NodeKinematics, OrientationOutput, Option<Accelerations>);

/// The rows `output` asks for, from the kinematics (and, where known, accelerations) of
/// the model's nodes: each written entry's label, kinematics, orientation form and
/// accelerations, dummy nodes computed from their bases (strnode.cc, the dummy nodes'
/// `Update_int`: the offset point's `a_b + ω̇ × f + ω × (ω × f)`, and the relative frame's
/// derivatives of its velocities).
pub fn motion_rows(output: &MotionOutput, nodes: &[(Label, NodeKinematics)], accelerations: &[(Label, Accelerations)]) -> Vec<MotionRow> {
    let mut all: Vec<(NodeKinematics, Option<Accelerations>)> = Vec::with_capacity(output.nodes.len());
    // By label, once per call: a search per written node made each output step O(n²)
    // (50 s for a 1e5-node model's one step; issue 32's reader benchmark timed the run).
    // The first entry of a label, as the search took.
    let mut kinematics: HashMap<Label, &NodeKinematics> = HashMap::with_capacity(nodes.len());
    nodes.iter().rev().for_each(|(l, k)| _ = kinematics.insert(*l, k));
    let mut by_label: HashMap<Label, Accelerations> = HashMap::with_capacity(accelerations.len());
    accelerations.iter().rev().for_each(|(l, a)| _ = by_label.insert(*l, *a));
    let accelerations = by_label;
    for n in &output.nodes {
        let k = match &n.source {
            NodeSource::Node(label) => kinematics.get(label).map(|k| ((*k).clone(), accelerations.get(label).copied())),
            NodeSource::Offset { base, offset, orientation } => all.get(*base).map(|(b, ba)| {
                let arm = b.r * offset;
                let k = NodeKinematics { x: b.x + arm, r: b.r * orientation, xdot: b.xdot + b.omega.cross(&arm), omega: b.omega };
                (k, ba.map(|(a, wd)| (a + wd.cross(&arm) + b.omega.cross(&b.omega.cross(&arm)), wd)))
            }),
            NodeSource::RelativeFrame { base, reference } => all.get(*base).zip(all.get(*reference)).map(|((b, ba), (f, fa))| {
                let (rt, d, w) = (f.r.transpose(), b.x - f.x, f.omega);
                let k = NodeKinematics { x: rt * d, r: rt * b.r, xdot: rt * (b.xdot - f.xdot - w.cross(&d)), omega: rt * (b.omega - w) };
                // d/dt of R_fᵀ (ḋ − ω_f × d) and R_fᵀ (ω_b − ω_f).
                let acc = ba.zip(*fa).map(|((ab, wdb), (af, wdf))| {
                    let dd = b.xdot - f.xdot;
                    (rt * (ab - af - wdf.cross(&d) - 2.0 * w.cross(&dd) + w.cross(&w.cross(&d))), rt * (wdb - wdf - w.cross(&b.omega)))
                });
                (k, acc)
            }),
        };
        // A source that is missing (a bug upstream) writes nothing rather than a wrong row.
        all.push(k.unwrap_or((NodeKinematics { x: Vec3::repeat(f64::NAN), r: Mat3::repeat(f64::NAN), xdot: Vec3::repeat(f64::NAN), omega: Vec3::repeat(f64::NAN) }, None)));
    }
    output
        .nodes
        .iter()
        .zip(all)
        .filter(|(n, (k, _))| n.written && k.x[0].is_finite())
        .map(|(n, (k, a))| (n.label, k, n.orientation, a.filter(|_| n.accelerations)))
        .collect()
}

impl MotionWriter {
    /// Numbers in scientific notation with `digits` after the decimal point.
    pub fn create(path: &Path, orientation: OrientationOutput, digits: usize) -> Result<Self, OutputError> {
        Ok(MotionWriter { file: AtomicFile::create(path)?, orientation, digits, text: Vec::new() })
    }

    /// Appends one output instant: a line per node, orientations in the writer's form.
    pub fn write_step(&mut self, nodes: &[(Label, NodeKinematics)]) -> Result<(), OutputError> {
        let rows: Vec<_> = nodes.iter().map(|(l, k)| (*l, k.clone(), self.orientation, None)).collect();
        self.write_rows(&rows)
    }

    /// Appends one output instant: a line per row, each with its own orientation form
    /// (formed in the writer's buffer, then written at once).
    pub fn write_rows(&mut self, rows: &[MotionRow]) -> Result<(), OutputError> {
        let (d, text) = (self.digits, &mut self.text);
        text.clear();
        for (label, k, how, acc) in rows {
            push_unsigned(text, u64::from(*label));
            let acc = acc.iter().flat_map(|(a, wd)| [*a, *wd]);
            let vectors = [k.xdot, k.omega].into_iter().chain(acc).flat_map(|v| [v[0], v[1], v[2]]);
            let (angles, len) = orientation_values(&k.r, *how);
            for c in k.x.iter().copied().chain(angles[..len].iter().copied()).chain(vectors) {
                text.push(b' ');
                push_scientific(text, c, d);
            }
            text.push(b'\n');
        }
        self.file.write_with(|out| out.write_all(text))
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
