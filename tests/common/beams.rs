//! Beam models of CASES C4/C5 built through the Rust API: 3-node finite-volume beams along
//! x with masses lumped on the nodes by finite volumes.

use romdyn::element::drive::Drive;

use romdyn::element::{Anchor, Beam3, BeamNode, Force, ForceFrame, Joint, RigidBody, SectionLaw, SectionOrientation};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::model::{Label, Model, ModelBuilder};

/// Section and mass data of a uniform beam (SI).
#[derive(Clone, Copy, Debug)]
pub struct BeamData {
    pub length: f64,
    pub ea: f64,
    pub ga: f64,
    pub gj: f64,
    pub ej: f64,
    /// Mass per unit length [kg/m].
    pub rho_a: f64,
}

/// Paper Table 3 (CASES C4).
pub const TABLE3: BeamData = BeamData { length: 1.0, ea: 1e6, ga: 1e6, gj: 1e3, ej: 1e3, rho_a: 1.0 };

/// Node labels 1..=2n+1 along x from 0 to L; beam labels 1..=n; bodies 101..; joints 201..;
/// forces 301...
pub fn node_label(i: usize) -> Label {
    i as Label + 1
}

/// A straight beam of `elements` 3-node elements along x, all nodes dynamic. The beam has no
/// inertia of its own; each node carries the beam between the midpoints to its neighbours,
/// a segment of length ℓ (the node spacing inside, half of it at the ends): mass ρA ℓ and,
/// about the two bending axes, the rotary inertia of that segment as a slender rod,
/// ρA ℓ³/12 (none about the beam axis).
pub fn straight_beam(b: &mut ModelBuilder, d: &BeamData, elements: usize) {
    let n = 2 * elements + 1;
    let h = d.length / (n - 1) as f64;
    for i in 0..n {
        b.dynamic_node(node_label(i), Vec3::new(i as f64 * h, 0.0, 0.0), Mat3::identity(), Vec3::zeros(), Vec3::zeros());
    }
    let law = SectionLaw::diagonal(d.ea, d.ga, d.ga, d.gj, d.ej, d.ej);
    let sections = [SectionOrientation::Given(Mat3::identity()), SectionOrientation::Given(Mat3::identity())];
    for e in 0..elements {
        let nodes = [0, 1, 2].map(|k| {
            let m = &b.nodes()[2 * e + k];
            BeamNode::new(m.label, m.position, m.orientation, Vec3::zeros())
        });
        b.element(Beam3::new(e as Label + 1, nodes, sections.clone(), [law.clone(), law.clone()]).expect("valid beam"));
    }
    for i in 0..n {
        let l = if i == 0 || i == n - 1 { h / 2.0 } else { h };
        let (m, j) = (d.rho_a * l, d.rho_a * l.powi(3) / 12.0);
        b.element(RigidBody::new(101 + i as Label, node_label(i), m, Vec3::zeros(), Mat3::from_diagonal(&Vec3::new(0.0, j, j))));
    }
}

fn ground() -> Anchor {
    Anchor::Ground { position: Vec3::zeros(), orientation: Mat3::identity() }
}

fn at_node(label: Label) -> Anchor {
    Anchor::Node { label, offset: Vec3::zeros(), orientation: Mat3::identity() }
}

/// The simply supported beam of paper §6.2 bending in the x–y plane: every node kept in
/// the plane (z, rx, ry locked), node 1 pinned (x, y also locked), the last node pinned and
/// free to slide along x (y locked); torsion is restrained by the plane constraints. An
/// axial compression `n_axial` [N] acts on the sliding end, a force `f_mid` [N] along y at
/// mid-span.
pub fn simply_supported(d: &BeamData, elements: usize, n_axial: f64, f_mid: f64) -> Model {
    let mut b = ModelBuilder::new();
    straight_beam(&mut b, d, elements);
    let last = 2 * elements;
    for i in 0..=last {
        let (x, y) = (i == 0, i == 0 || i == last);
        b.element(Joint::total(201 + i as Label, ground(), at_node(node_label(i)), [x, y, true], [true, true, false]));
    }
    force(&mut b, 301, node_label(last), Vec3::new(-n_axial, 0.0, 0.0));
    force(&mut b, 302, node_label(elements), Vec3::new(0.0, f_mid, 0.0));
    b.build().expect("valid simply supported beam")
}

/// A constant absolute force [N] on a node (nothing when zero).
fn force(b: &mut ModelBuilder, label: Label, node: Label, f: Vec3) {
    if f != Vec3::zeros() {
        b.element(Force::new(label, node, ForceFrame::Absolute, f, Vec3::zeros(), Drive::Const(1.0)));
    }
}

/// The cantilever of CASES C5 along x, clamped at node 1, a force `tip` [N] on the free
/// end; bending in the x-y plane (every node's z and rotations about x and y locked).
pub fn cantilever(d: &BeamData, elements: usize, tip: Vec3) -> Model {
    let mut b = ModelBuilder::new();
    straight_beam(&mut b, d, elements);
    let last = 2 * elements;
    b.element(Joint::clamp(200, node_label(0), Vec3::zeros(), Mat3::identity()));
    for i in 1..=last {
        b.element(Joint::total(201 + i as Label, ground(), at_node(node_label(i)), [false, false, true], [true, true, false]));
    }
    force(&mut b, 301, node_label(last), tip);
    b.build().expect("valid cantilever")
}
