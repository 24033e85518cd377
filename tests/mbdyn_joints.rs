//! Joints and deformable elements of issue 12, point 3 (axial rotation, …): each one's
//! analytic Jacobian against central finite differences of its residual (1e-6 relative to
//! the element's largest entry, as tests/multibody_jacobians.rs), and a test file of
//! `tests/mbdyn_files/` in MBDyn's style whose numbers are checked against a closed form
//! and against MBDyn 1.7.3's output on the same file (recorded here with the file's name;
//! MBDyn is never run by the tests).

mod common;

use std::path::{Path, PathBuf};

use common::fixtures::Noise;
use romdyn::analysis::run;
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::{Anchor, AxialRotation, Drive, Element};
use romdyn::input::mbdyn::{build, parse_text, read_model, MbdynModel};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::linear::ConstraintForm;
use romdyn::model::{Model, ModelBuilder};

fn path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files").join(name)
}

fn read(name: &str) -> MbdynModel {
    read_model(&path(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// The file's text with each `(old, new)` replaced (every `old` must occur).
fn rewritten(name: &str, replacements: &[(&str, &str)]) -> MbdynModel {
    let mut t = std::fs::read_to_string(path(name)).unwrap();
    for (old, new) in replacements {
        assert!(t.contains(old), "{name} does not contain {old:?}");
        t = t.replace(old, new);
    }
    parse_text(&t, &path(name)).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"))
}

fn node(label: u32, n: &mut Noise) -> Anchor {
    Anchor::Node { label, offset: n.vec(), orientation: n.rotation() }
}

fn ground(n: &mut Noise) -> Anchor {
    Anchor::Ground { position: n.vec(), orientation: n.rotation() }
}

/// Nodes 1 (static), 2 and 3 (dynamic) at random positions, orientations and velocities,
/// with the given elements.
fn model_with(form: ConstraintForm, elements: impl FnOnce(&mut Noise) -> Vec<Box<dyn Element>>) -> Model {
    let mut n = Noise(4242);
    let mut b = ModelBuilder::new();
    b.static_node(1, n.vec(), n.rotation()).dynamic_node(2, n.vec(), n.rotation(), n.vec(), n.vec()).dynamic_node(3, n.vec(), n.rotation(), n.vec(), n.vec());
    for e in elements(&mut n) {
        b.boxed_element(e);
    }
    b.constraint_form(form);
    b.build().unwrap()
}

/// Every element's worst Jacobian entry at a random state (unknowns, derivatives,
/// multipliers all perturbed), both constraint forms, below 1e-6.
fn assert_jacobians(elements: impl Fn(&mut Noise) -> Vec<Box<dyn Element>>) {
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let model = model_with(form, &elements);
        let asm = Assembler::new(&model);
        let mut st = State::initial(&model, &asm.dofs);
        let mut n = Noise(99);
        st.t = 0.3;
        for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
            *x += 0.5 * n.next();
        }
        for w in check_jacobians(&asm, &st, 0.37, form) {
            assert!(w.relative_error < 1e-6, "{form:?}: {} d({})/d({}): analytic {:e}, fd {:e} (error {:e})", w.element, w.equation, w.unknown, w.analytic, w.finite_difference, w.relative_error);
        }
    }
}

/// Rotation angle about global x of a frame that turned about x.
fn angle_about_x(r: &Mat3) -> f64 {
    r[(2, 1)].atan2(r[(1, 1)])
}

#[test]
fn axial_rotation_jacobian_matches_finite_differences() {
    assert_jacobians(|n| {
        let omega = Drive::Sine { t0: 0.0, omega: 2.0, amplitude: 1.5, cycles: None, v0: 0.2 };
        vec![
            Box::new(AxialRotation::new(1, node(2, n), node(3, n), omega.clone())),
            Box::new(AxialRotation::new(2, ground(n), node(2, n), omega.clone())),
            Box::new(AxialRotation::new(3, node(1, n), node(3, n), omega)),
        ]
    });
}

#[test]
fn axial_rotation_spins_a_rotor_up_as_the_closed_form_and_mbdyn() {
    // axial_rotation.mbd: Ω ramps at 2 rad/s² to 1 rad/s in 0.5 s, then holds: after 1 s the
    // rotor has turned 0.25 + 0.5 = 0.75 rad about x. MBDyn 1.7.3 (1727489e) on the same file:
    // node 2 Euler 123 angle 4.297183461665724e+01 deg at t = 1 s, ω_x = 1 rad/s.
    let m = read("axial_rotation.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, 1).kin;
    let mbdyn = 4.297183461665724e+01f64.to_radians();
    // ms integrates the orientation parameters, not the angle: 1e-9 rad of integration error
    // (MBDyn's own is 3e-10 rad); against MBDyn 1e-12 rad (the same discrete formulation).
    assert!((angle_about_x(&kin.r) - 0.75).abs() < 1e-9, "angle {}", angle_about_x(&kin.r));
    assert!((angle_about_x(&kin.r) - mbdyn).abs() < 1e-12, "angle {} against MBDyn {mbdyn}", angle_about_x(&kin.r));
    assert!((kin.omega - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-12, "ω = {}", kin.omega);
    // The motor moment after the ramp is 0 (MBDyn: 4.9e-13 N m).
    let motor = asm.dofs.element_first[1] + 5;
    assert!(report.final_state.y[motor].abs() < 1e-9, "motor moment {}", report.final_state.y[motor]);

    // During the ramp, J Ω̇ = 1 kg m² · 2 rad/s² = 2 N m (MBDyn at t = 0.25 s: 2.000000000000005
    // N m in its .jnt); romdyn's multiplier is the reaction's residual, −2 N m about x.
    let m = rewritten("axial_rotation.mbd", &[("final time: 1.;", "final time: .25;")]);
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    assert!((report.final_state.y[motor] + 2.0).abs() < 1e-9, "motor moment {}", report.final_state.y[motor]);
}
