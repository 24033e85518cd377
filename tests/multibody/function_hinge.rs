//! The deformable hinge with a `scalar function elastic isotropic | orthotropic` law (issue
//! 12, point 3): its analytic Jacobian against central finite differences of its residual,
//! its rest against the closed form, its swing against energy conservation and MBDyn 1.7.3.

use crate::common;

use std::path::Path;

use common::fixtures::Noise;
use romdyn::analysis::{reference_state, run, Reference};
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::drive::ScalarFunction;
use romdyn::element::{Anchor, FunctionHinge};
use romdyn::input::mbdyn::read_model;
use romdyn::kinematics::euler123;
use romdyn::model::ConstraintForm;
use romdyn::model::ModelBuilder;

/// `F(x) = 10 x + x³`.
fn stiffening() -> ScalarFunction {
    ScalarFunction::Sum(std::sync::Arc::new(ScalarFunction::Multilinear { points: vec![(0.0, 0.0), (1.0, 10.0)], extrapolate: true }), std::sync::Arc::new(ScalarFunction::Pow(3.0)))
}

#[test]
fn function_hinge_jacobians_match_finite_differences() {
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let mut n = Noise(4242);
        let mut b = ModelBuilder::new();
        b.static_node(1, n.vec(), n.rotation()).dynamic_node(2, n.vec(), n.rotation(), n.vec(), n.vec()).dynamic_node(3, n.vec(), n.rotation(), n.vec(), n.vec());
        let node = |label: u32, n: &mut Noise| Anchor::Node { label, offset: n.vec(), orientation: n.rotation() };
        let exp = ScalarFunction::Exp { multiplier: 2.0, base: std::f64::consts::E, coefficient: 0.7 };
        b.element(FunctionHinge { label: 1, a: node(2, &mut n), b: node(3, &mut n), functions: [Some(stiffening()), Some(stiffening()), Some(stiffening())] });
        b.element(FunctionHinge { label: 2, a: node(1, &mut n), b: node(3, &mut n), functions: [Some(exp), None, Some(stiffening())] });
        b.element(FunctionHinge { label: 3, a: Anchor::Ground { position: n.vec(), orientation: n.rotation() }, b: node(2, &mut n), functions: [None, Some(ScalarFunction::Pow(3.0)), None] });
        b.constraint_form(form);
        let model = b.build().unwrap();
        let asm = Assembler::new(&model);
        let mut st = State::initial(&model, &asm.dofs);
        let mut n = Noise(99);
        for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
            *x += 0.5 * n.next();
        }
        for w in check_jacobians(&asm, &st, 0.37, form) {
            assert!(w.relative_error < 1e-6, "{form:?}: {} d({})/d({}): analytic {:e}, fd {:e} (error {:e})", w.element, w.equation, w.unknown, w.analytic, w.finite_difference, w.relative_error);
        }
    }
}

#[test]
fn function_hinge_rests_and_swings_as_the_closed_form_and_mbdyn() {
    let m = read_model(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/function_hinge.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let f = stiffening();
    // Rest: F(θ) = M = 5 N m about z, θ = .488 rad (Newton's tolerance, 1e-10).
    let st = reference_state(&m.model, &m.problem, Reference::Static { load_steps: 10 }).unwrap();
    let theta = euler123(&st.node_frame(&asm.dofs, 1).kin.r).z;
    assert!((f.value(theta) - 5.0).abs() < 1e-9 && (theta - 0.488).abs() < 1e-3, "rest at {theta} rad: F = {}", f.value(theta));

    // The swing from rest at t = 1 s: J ω²/2 + V(θ) − M θ = 0 with V = 5 θ² + θ⁴/4, to
    // Crank–Nicolson's O(h²) error (1e-6 N m allowed). MBDyn 1.7.3 (1727489e, the same
    // file), .mov: Euler z 5.445815339058564e+01 deg, ω_z −2.503269811612361e-01 rad/s.
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let kin = report.final_state.node_frame(&asm.dofs, 1).kin;
    let (theta, w) = (euler123(&kin.r).z, kin.omega.z);
    let energy = w * w / 2.0 + 5.0 * theta * theta + theta.powi(4) / 4.0 - 5.0 * theta;
    assert!(energy.abs() < 1e-6, "energy {energy} at θ = {theta}, ω = {w}");
    assert!((theta.to_degrees() - 5.445815339058564e+01).abs() < 1e-7, "θ = {} deg against MBDyn", theta.to_degrees());
    assert!((w + 2.503269811612361e-01).abs() < 1e-7, "ω = {w} against MBDyn");
}
