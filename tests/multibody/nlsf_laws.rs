//! MBDyn's 1-D `nlsf` constitutive laws (input manual, §nlsf viscoelastic; constltp_nlsf.cc):
//! `f = k (ε − ε_p) + f′(ε − ε_p) + c ε̇ + f″(ε̇) + f_p` with scalar functions, on deformable
//! axial joints (`tests/mbdyn_files/nlsf_axial.mbd`). The joint's Jacobian with both terms is
//! checked against finite differences in `tests/multibody/multibody_jacobians.rs`.

use crate::common;

use std::path::Path;

use common::mbdyn::file;
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{read_model_text, SetOverrides};
use romdyn::kinematics::rotation_vector;

#[test]
fn an_nlsf_spring_rests_at_its_closed_form_and_an_nlsf_brake_follows_its_ode() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/nlsf_axial.mbd");
    let text = std::fs::read_to_string(&path).unwrap();
    let m = read_model_text(&text, &path, &SetOverrides::default()).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let node = |slot: usize| report.final_state.node_frame(&asm.dofs, slot).kin;
    // Node 2: θ + θ³ = 2 N m, θ = 1 rad (Newton's tolerance 1e-10 N m bounds it).
    let theta = rotation_vector(&node(1).r).z;
    assert!((theta - 1.0).abs() < 1e-9, "spring at {theta} rad");
    // Node 3: sinh(ω/ω₀) = sinh(2/ω₀) exp(−F t/(J ω₀)), ω(1 s) = 1.00875406443987 rad/s; ms ρ∞ =
    // 0.6 at h = 1 ms measured 1.2e-8 from it, 1e-7 bounds it.
    let w = node(2).omega.z;
    let exact = 0.5 * ((4.0_f64).sinh() * (-2.0_f64).exp()).asinh();
    assert!((w - exact).abs() < 1e-7, "brake at {w} rad/s against {exact}");
    // MBDyn 1.7.3 on the same file (`mbdyn -f nlsf_axial.mbd`, the .mov at t = 1 s): node 2 at
    // 57.295779513082046 deg, node 3 at 32.961816248290560 deg, 1.0087540760317331 rad/s.
    // romdyn measured 32.96181624831 deg and 1.008754076032 rad/s: the same integrator,
    // agreement to 1e-9 bounds it.
    assert!((theta.to_degrees() - 57.295779513082046).abs() < 1e-7);
    let angle = rotation_vector(&node(2).r).z.to_degrees();
    assert!((angle - 32.961816248290560).abs() < 1e-9, "brake angle {angle} deg against MBDyn's");
    assert!((w - 1.0087540760317331).abs() < 1e-9, "brake {w} rad/s against MBDyn's");
}

/// An `nlsf` law on an element that takes linear laws only (an invariant deformable hinge),
/// or on a rod with a prestrain that changes in time, is refused naming it (3-D and 6-D laws: `tests/multibody/nonlinear_laws.rs`); so are bistop
/// laws off rods and symbolic laws, with the reason.
#[test]
fn nlsf_laws_elsewhere_or_in_3d_are_refused_by_name() {
    let nodes = "structural: 1, static, null, eye, null, null; structural: 2, dynamic, 1., 0., 0., eye, null, null;";
    let cases = [
        ("joint: 2, rod, 1, 2, from nodes, nlsf viscoelastic, 1., null, 0., \"f\", prestrain, ramp, 1., 0., 1., 0.;", "prestrain that changes in time on an 'nlsf viscoelastic' law"),
        ("joint: 2, invariant deformable hinge, 1, 2, nlsf viscous, null, null, null, \"f\";", "'nlsf viscous' is supported by romdyn on the deformable displacement joint"),
        // Refused with the reason (constltp_impl.h's BiStopCLWrapper; MBDyn 1.7.3 here has no GiNaC).
        // A bistop law on a rod only (tests/mbdyn/mbdyn_events.rs).
        ("joint: 2, deformable hinge, 1, null, 2, null, linear viscoelastic bistop, 1.e3, 1.e2, initial status, inactive, const, 1., const, 0.;", "in 1-D only (a rod)"),
        ("joint: 2, rod, 1, 2, from nodes, symbolic viscous, epsilon prime, \"w\", expression, \"w\";", "GiNaC"),
    ];
    for (element, message) in cases {
        let text = file("structural nodes: 2; joints: 1;", nodes, element).replace("begin: elements;", "scalar function: \"f\", pow, 3.;\nbegin: elements;");
        let err = read_model_text(&text, Path::new("m.mbd"), &SetOverrides::default()).err().expect("refused").to_string();
        assert!(err.contains(message) && err.starts_with("m.mbd:"), "{err}");
    }
}
