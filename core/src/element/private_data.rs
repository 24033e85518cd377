//! Element private data (MBDyn's `Elem::dGetPrivData`; the "Private data" paragraphs of
//! the input manual's element sections): named scalars of an element's state that MBDyn's
//! `element` drive caller and `bind` (to a parameter node read by a `dof` drive caller)
//! read during the run.
//!
//! A datum is a function of the model's state, read through
//! [`ElementState::structural_node`] from the state the reading drive is evaluated in (the
//! current Newton iterate, as MBDyn's `GetXCurr`, see [`super::drive::TimeFunction`]).

use std::sync::Arc;

use super::anchor::{Anchor, Pair};
use super::contract::{ElementState, Label, NodeKinematics};
use super::joint::{Joint, JointKind};
use super::drive::{RotationRead, StepDrive, StepKind, Turns};
use crate::kinematics::{rotation_vector, Vec3};

pub use super::contract::PrivateDatum;

/// The nodes an element connects, copied by label from the state a drive reads, in the
/// element's slot order: the element's own kinematics helpers then apply unchanged.
struct ByLabel {
    nodes: Vec<NodeKinematics>,
    t: f64,
}

impl ByLabel {
    fn read(labels: &[Label], st: &dyn ElementState) -> Option<Self> {
        let nodes = labels.iter().map(|&l| st.structural_node(l).cloned()).collect::<Option<Vec<_>>>()?;
        Some(ByLabel { nodes, t: st.time() })
    }
}

impl ElementState for ByLabel {
    fn node(&self, slot: usize) -> &NodeKinematics {
        &self.nodes[slot]
    }
    fn multiplier(&self, _k: usize) -> f64 {
        0.0
    }
    fn time(&self) -> f64 {
        self.t
    }
    fn gravity(&self) -> Vec3 {
        Vec3::zeros()
    }
    fn load_factor(&self) -> f64 {
        1.0
    }
}

/// What a joint's datum measures between its frames A and B.
#[derive(Clone, Copy)]
enum JointDatum {
    /// `(Q_aᵀ (p_b − p_a))_k` [m] (totalj.cc "px", "py", "pz").
    Position(usize),
    /// `rotvec(Q_aᵀ Q_b)_k` [rad] (planej.cc, totalj.cc "rx" … "rz").
    Rotation(usize),
    /// `(Q_aᵀ (ω_b − ω_a))_k` [rad/s] (totalj.cc "wx" … "wz").
    AngularVelocityInA(usize),
    /// `(Q_bᵀ (ω_b − ω_a))_3` [rad/s] (planej.cc "wz": in the hinge frame of node 2).
    AngularVelocityInB,
}

/// The private datum `name` of a joint, if romdyn computes it: a revolute hinge's (or
/// revolute rotation's) `rz`, `wz` (planej.cc, `PlaneHingeJoint::dGetPrivData`), a total
/// joint's `p*`, `r*`, `w*` (totalj.cc). The rotations `rz`/`r*` are counted across the
/// turns of the accepted steps, as MBDyn's `NTheta` and `Unwrap`: the datum carries that
/// memory ([`PrivateDatum::memory`], a [`StepKind::Turns`]).
impl Joint {
    pub fn private_datum(&self, name: &str) -> Option<PrivateDatum> {
        joint_private_datum(self, name)
    }
}

/// [`Joint::private_datum`].

fn joint_private_datum(joint: &Joint, name: &str) -> Option<PrivateDatum> {
    let axis = |c: u8| match c {
        b'x' => Some(0),
        b'y' => Some(1),
        b'z' => Some(2),
        _ => None,
    };
    let bytes = name.as_bytes();
    let datum = match (joint.kind, bytes) {
        (JointKind::RevoluteHinge | JointKind::RevoluteRotation, b"rz") => JointDatum::Rotation(2),
        (JointKind::RevoluteHinge | JointKind::RevoluteRotation, b"wz") => JointDatum::AngularVelocityInB,
        (JointKind::TotalJoint, [b'p', c]) => JointDatum::Position(axis(*c)?),
        (JointKind::TotalJoint, [b'r', c]) => JointDatum::Rotation(axis(*c)?),
        (JointKind::TotalJoint, [b'w', c]) => JointDatum::AngularVelocityInA(axis(*c)?),
        _ => return None,
    };
    let vector = move |p: &Pair| match datum {
        JointDatum::Position(_) => p.q_a.transpose() * p.d,
        JointDatum::Rotation(_) => rotation_vector(&(p.q_a.transpose() * p.q_b)),
        JointDatum::AngularVelocityInA(_) => p.q_a.transpose() * (p.omega_b - p.omega_a),
        JointDatum::AngularVelocityInB => p.q_b.transpose() * (p.omega_b - p.omega_a),
    };
    Some(match datum {
        // Counted across turns, as MBDyn: a revolute hinge's angle (planej.cc `NTheta`), a
        // total joint's rotation vector (totalj.cc `Unwrap`).
        JointDatum::Rotation(k) => {
            let counting = if joint.kind == JointKind::TotalJoint { Turns::Vector(k) } else { Turns::Hinge };
            let rotation = RotationRead(Arc::new(pair_reader(&joint.a, &joint.b, vector)));
            PrivateDatum::remembering(StepDrive::new(StepKind::Turns { rotation, counting }))
        }
        JointDatum::Position(k) | JointDatum::AngularVelocityInA(k) => of_pair(&joint.a, &joint.b, move |p| vector(p)[k]),
        JointDatum::AngularVelocityInB => of_pair(&joint.a, &joint.b, move |p| vector(p)[2]),
    })
}

/// `f` of the pair of anchors `a`, `b` (a joint's or a rod's two sides), read from the state
/// by node label; `None` where the state lacks one of the nodes.
fn pair_reader<T>(a: &Anchor, b: &Anchor, f: impl Fn(&Pair) -> T + Send + Sync + 'static) -> impl Fn(&dyn ElementState) -> Option<T> + Send + Sync + 'static {
    let (a, b) = (a.clone(), b.clone());
    let labels: Vec<Label> = [&a, &b].into_iter().filter_map(|x| if let Anchor::Node { label, .. } = x { Some(*label) } else { None }).collect();
    move |st: &dyn ElementState| {
        let nodes = ByLabel::read(&labels, st)?;
        Some(f(&Pair::new(&a, &b, &nodes)))
    }
}

/// A datum `f` of the pair of anchors `a`, `b` ([`pair_reader`]).
pub(super) fn of_pair(a: &Anchor, b: &Anchor, f: impl Fn(&Pair) -> f64 + Send + Sync + 'static) -> PrivateDatum {
    PrivateDatum::new(pair_reader(a, b, f))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::Mat3;

    struct Nodes(Vec<(Label, NodeKinematics)>);
    impl ElementState for Nodes {
        fn node(&self, slot: usize) -> &NodeKinematics {
            &self.0[slot].1
        }
        fn multiplier(&self, _k: usize) -> f64 {
            0.0
        }
        fn time(&self) -> f64 {
            0.0
        }
        fn gravity(&self) -> Vec3 {
            Vec3::zeros()
        }
        fn load_factor(&self) -> f64 {
            1.0
        }
        fn structural_node(&self, label: Label) -> Option<&NodeKinematics> {
            self.0.iter().find(|(l, _)| *l == label).map(|(_, k)| k)
        }
    }

    fn about_z(phi: f64) -> Mat3 {
        let (s, c) = phi.sin_cos();
        Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
    }

    /// A hinge whose frame A is node 1 turned by 0.3 rad about z, B node 2 turned by 1 rad:
    /// the relative rotation is 0.7 rad about the common axis, the relative spin 2 − 0.5
    /// rad/s; node 2 sits 1 m along global x, 1 m along A's x turned by −0.3 rad.
    #[test]
    fn hinge_and_total_joint_data_are_the_relative_rotation_and_spin() -> Result<(), String> {
        let node = |label, offset| Anchor::Node { label, offset, orientation: about_z(0.3 * f64::from(u8::from(label == 1))) };
        let hinge = Joint::revolute_hinge(9, node(1, Vec3::zeros()), node(2, Vec3::zeros()));
        let total = Joint::total(9, node(1, Vec3::zeros()), node(2, Vec3::zeros()), [true; 3], [true; 3]);
        let w = |z| NodeKinematics { x: Vec3::zeros(), r: Mat3::identity(), xdot: Vec3::zeros(), omega: Vec3::new(0.0, 0.0, z) };
        let n2 = NodeKinematics { x: Vec3::new(1.0, 0.0, 0.0), r: about_z(1.0), ..w(2.0) };
        let st = Nodes(vec![(1, w(0.5)), (2, n2)]);
        let read = |j: &Joint, name: &str| joint_private_datum(j, name).and_then(|d| d.value(&st)).ok_or(format!("no datum {name}"));
        assert!((read(&hinge, "rz")? - 0.7).abs() < 1e-15);
        assert!((read(&hinge, "wz")? - 1.5).abs() < 1e-15);
        assert!((read(&total, "px")? - 0.3f64.cos()).abs() < 1e-15 && (read(&total, "py")? + 0.3f64.sin()).abs() < 1e-15);
        assert!((read(&total, "rz")? - 0.7).abs() < 1e-15 && read(&total, "rx")?.abs() < 1e-15);
        assert!((read(&total, "wz")? - 1.5).abs() < 1e-15);
        assert!(joint_private_datum(&hinge, "Fx").is_none() && joint_private_datum(&total, "vx").is_none());
        // A state without node 2 (a unit test of one element) has no value.
        assert!(joint_private_datum(&hinge, "rz").and_then(|d| d.value(&Nodes(vec![(1, w(0.0))]))).is_none());
        Ok(())
    }
}
