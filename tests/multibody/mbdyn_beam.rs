//! `beam3` as MBDyn's input manual writes it (§Three-node beam element): node offsets and
//! orientations, section frames given in any reference or `from nodes`, `same`, and the 6-D
//! laws `linear elastic generic` (`sym`), `linear elastic isotropic` and `linear
//! viscoelastic generic` (`diag`). Each file's residual equals that of the same beam built
//! through the Rust API, at random states (1e-12 relative).

use crate::common;

use common::mbdyn::{assert_same_physics, file};
use nalgebra::{Matrix6, Vector6};
use romdyn::element::{Beam3, BeamNode, SectionLaw, SectionOrientation};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::model::{Model, ModelBuilder};

/// `R_x(a) R_y(b) R_z(c)` (MBDyn's euler123, radians).
fn euler123(a: f64, b: f64, c: f64) -> Mat3 {
    let r = |axis: Vec3, angle: f64| *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle).matrix();
    r(Vec3::x(), a) * r(Vec3::y(), b) * r(Vec3::z(), c)
}

const NODES: &str = "structural: 1, dynamic, 0., 0., 0., eye, null, null;
structural: 2, dynamic, 0.5, 0.1, 0., euler123, 0., 0., 0.2, null, null;
structural: 3, dynamic, 1., 0.15, 0.05, euler123, 0.1, 0., 0.3, null, null;";

fn nodes() -> [(Vec3, Mat3); 3] {
    [(Vec3::zeros(), Mat3::identity()), (Vec3::new(0.5, 0.1, 0.0), euler123(0.0, 0.0, 0.2)), (Vec3::new(1.0, 0.15, 0.05), euler123(0.1, 0.0, 0.3))]
}

fn model(beam: Beam3) -> Model {
    let mut b = ModelBuilder::new();
    for (i, (x, r)) in nodes().into_iter().enumerate() {
        b.dynamic_node(i as u32 + 1, x, r, Vec3::zeros(), Vec3::zeros());
    }
    b.element(beam);
    b.build().unwrap()
}

fn beam_node(i: usize, offset: Vec3, orientation: Mat3) -> BeamNode {
    let (x, r) = nodes()[i];
    BeamNode::new(i as u32 + 1, x, r, offset).with_orientation(orientation)
}

#[test]
fn offsets_a_global_section_frame_and_a_symmetric_generic_law_with_same() {
    let text = file(
        "structural nodes: 3; beams: 1;",
        NODES,
        "beam3: 7,
            1, position, reference, node, 0., 0.02, 0.,
            2, reference, node, 0., 0.02, 0.,
            3, 0., 0.02, 0.01,
            reference, global, euler123, 0., 0., 0.25,
            linear elastic generic, sym,
                1.e6, 0., 0., 0., 1.e3, 0.,
                     4.e5, 0., 0., 0., 0.,
                          4.e5, 0., 0., 0.,
                               2.e3, 0., 0.,
                                    3.e3, 0.,
                                         5.e3,
            same, same;",
    );
    let mut k = Matrix6::from_diagonal(&Vector6::new(1e6, 4e5, 4e5, 2e3, 3e3, 5e3));
    (k[(0, 4)], k[(4, 0)]) = (1e3, 1e3);
    let law = SectionLaw::elastic(k);
    let offsets = [Vec3::new(0.0, 0.02, 0.0), Vec3::new(0.0, 0.02, 0.0), Vec3::new(0.0, 0.02, 0.01)];
    let bn = [0, 1, 2].map(|i| beam_node(i, offsets[i], Mat3::identity()));
    let frame = SectionOrientation::Given(euler123(0.0, 0.0, 0.25));
    assert_same_physics(&text, model(Beam3::new(7, bn, [frame.clone(), frame], [law.clone(), law]).unwrap()));
}

#[test]
fn node_orientations_frames_from_nodes_and_viscoelastic_and_isotropic_laws() {
    let text = file(
        "structural nodes: 3; beams: 1;",
        NODES,
        "beam3: 8,
            1, null, orientation, reference, node, euler123, 0., 0., 0.1,
            2, null, orientation, reference, node, euler123, 0., 0.05, 0.,
            3, null, orientation, eye,
            from nodes,
            linear viscoelastic generic,
                diag, 1.e6, 4.e5, 4.e5, 2.e3, 3.e3, 5.e3,
                diag, 10., 4., 4., 0.2, 0.3, 0.5,
            from nodes,
            linear elastic isotropic, 5.e4;",
    );
    let k = Matrix6::from_diagonal(&Vector6::new(1e6, 4e5, 4e5, 2e3, 3e3, 5e3));
    let v = Matrix6::from_diagonal(&Vector6::new(10.0, 4.0, 4.0, 0.2, 0.3, 0.5));
    let rel = [euler123(0.0, 0.0, 0.1), euler123(0.0, 0.05, 0.0), Mat3::identity()];
    let bn = [0, 1, 2].map(|i| beam_node(i, Vec3::zeros(), rel[i]));
    let laws = [SectionLaw::viscoelastic(k, v), SectionLaw::elastic(5e4 * Matrix6::identity())];
    assert_same_physics(&text, model(Beam3::new(8, bn, [SectionOrientation::FromNodes, SectionOrientation::FromNodes], laws).unwrap()));
}
