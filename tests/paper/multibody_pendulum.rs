//! CASES C2 and C3: the simple and the inverted pendulum (paper §7.2, eqs. 82 and 87).

use crate::common;

use common::models::{pendulum, G, J, L, M};
use romdyn::c64;
use romdyn::dae::{linearize, Assembler, State};
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::model::ConstraintForm;
use romdyn::model::Summary;
use romdyn::rom::{select_modes, DescriptorRom, ModeSelection};
use romdyn::solve::{static_solution, NewtonSettings};

/// ω² = (g/L)/(1 + J/(m L²)) (eq. 82): 3.130527 rad/s.
fn omega() -> f64 {
    ((G / L) / (1.0 + J / (M * L * L))).sqrt()
}

#[test]
fn pendulum_has_29_equations() {
    // Paper §7.2: 6 (ground node) + 12 (pendulum node) + 6 (clamp) + 5 (revolute hinge).
    let s = Summary::of(&pendulum(0.0, false, ConstraintForm::Scaled));
    assert_eq!((s.static_nodes, s.dynamic_nodes, s.node_equations, s.constraint_equations), (1, 1, 18, 11));
    assert_eq!(s.equations(), 29);
}

fn equilibrium(upright: bool, form: ConstraintForm) -> (romdyn::model::Model, State) {
    let model = pendulum(0.0, upright, form);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    drop(asm);
    (model, st)
}

#[test]
fn hanging_pendulum_eigenvalues_in_both_forms_and_routes() {
    assert!((omega() - 3.130527).abs() < 5e-7, "CASES C2 value");
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let (model, st) = equilibrium(false, form);
        for dcoef in [None, Some(1e-3)] {
            let dae = linearize(&model, &st, &[], &[], dcoef).unwrap();
            for route in [EigenRoute::Direct, EigenRoute::Lambda] {
                let modal = ModalAnalysis::compute(&dae.jacobians, route).unwrap();
                let ctx = format!("{form:?} dcoef={dcoef:?} {route:?}");
                assert_eq!(modal.count(ModeKind::Dynamic), 2, "{ctx}");
                // Eq. 82, 1e-6 relative (CASES C2).
                let l = modal.modes[0].lambda;
                assert!((l - c64::new(0.0, omega())).norm() / omega() < 1e-6, "{ctx}: {l}");
            }
        }
    }
}

#[test]
fn inverted_pendulum_eigenvalues_are_real() {
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let (model, st) = equilibrium(true, form);
        let dae = linearize(&model, &st, &[], &[], None).unwrap();
        let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Direct).unwrap();
        assert_eq!(modal.count(ModeKind::Dynamic), 2);
        // Eq. 87: ±3.130527 real, one unstable (1e-6 relative, CASES C3).
        let mut re: Vec<f64> = modal.modes[..2].iter().map(|m| m.lambda.re).collect();
        re.sort_by(f64::total_cmp);
        assert!((re[0] + omega()).abs() / omega() < 1e-6 && (re[1] - omega()).abs() / omega() < 1e-6, "{re:?}");
        assert!(modal.modes[..2].iter().all(|m| m.lambda.im == 0.0));
    }
}

#[test]
fn torque_to_angle_rom_and_mode_shape() {
    let (model, st) = equilibrium(false, ConstraintForm::Scaled);
    let dae = linearize(&model, &st, &["2:Mz".parse().unwrap()], &["2:rz".parse().unwrap(), "2:x".parse().unwrap()], None).unwrap();
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Direct).unwrap();
    let sel = select_modes(&modal, &ModeSelection::Lowest(1)).unwrap();
    let rom = DescriptorRom::project(&dae, &modal, &sel, false).unwrap().to_ordinary().unwrap();
    // Static gain 1/(m g L) rad/(N m) (CASES C2), 1e-9 relative; x/M = L/(m g L).
    let g = rom.static_gain().unwrap();
    assert!((g[(0, 0)] * M * G * L - 1.0).abs() < 1e-9, "{}", g[(0, 0)]);
    assert!((g[(1, 0)] * M * G - 1.0).abs() < 1e-9, "{}", g[(1, 0)]);
    let ev = rom.a.eigenvalues().unwrap();
    assert!(ev.iter().all(|l| (l.norm() - omega()).abs() / omega() < 1e-6), "{ev:?}");
    // Mode shape: displacement x of node 2 over its rotation rz equals L (paper §7.2).
    let v = modal.modes[0].right.as_ref().unwrap();
    let names = &dae.unknown_names;
    let (ix, ig) = (names.iter().position(|n| n == "node 2 x").unwrap(), names.iter().position(|n| n == "node 2 gz").unwrap());
    let ratio = v[ix] / v[ig];
    assert!((ratio - c64::new(L, 0.0)).norm() < 1e-9, "{ratio}");
}

#[test]
fn pendulum_mode_is_labelled_by_its_kinetic_energy() {
    use romdyn::eigen::{describe, kinetic_energy_shares};
    let (model, st) = equilibrium(false, ConstraintForm::Scaled);
    let dae = linearize(&model, &st, &[], &[], None).unwrap();
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Direct).unwrap();
    let shares = kinetic_energy_shares(&model, &dae, &modal.modes[0]);
    // Swing about the hinge: node 2 moves along x (m L² θ̇²/2) and rotates about z
    // (J θ̇²/2): shares m L²/(m L² + J) = 0.999 and J/(m L² + J) = 0.000999 (closed form).
    assert_eq!((shares[0].node, shares[0].component), (2, "x"));
    assert!((shares[0].share - M * L * L / (M * L * L + J)).abs() < 1e-9, "{shares:?}");
    assert_eq!((shares[1].node, shares[1].component), (2, "rz"));
    assert_eq!(describe(&shares), "node 2 x 100 %");
}

#[test]
fn newton_failure_names_time_residual_and_worst_equation() {
    // Two iterations are not enough from the horizontal position (a nonlinear static problem).
    let model = pendulum(1.2, false, ConstraintForm::Plain);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    st.t = 0.25;
    let settings = NewtonSettings { max_iterations: 1, ..Default::default() };
    let e = static_solution(&asm, &mut st, 1, &settings).unwrap_err();
    let text = e.to_string();
    assert!(text.starts_with("Newton failed at t = 0.25 s, iteration 1: residual norm"), "{text}");
    let worst = text.split("worst equation: ").nth(1).unwrap_or("");
    assert!(["node 1 ", "node 2 ", "clamp 1 ", "revolute hinge 2 "].iter().any(|p| worst.starts_with(p)), "{text}");
    assert_eq!(e.iteration, 1);
    assert!(e.residual_norm > settings.tolerance);
}

#[test]
fn static_solution_from_far_reaches_the_hanging_equilibrium() {
    // Released at 1.2 rad, the static solver must bring the pendulum down (x = 0, y = −L).
    let model = pendulum(1.2, false, ConstraintForm::Plain);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    let settings = NewtonSettings { max_iterations: 100, ..Default::default() };
    static_solution(&asm, &mut st, 1, &settings).unwrap();
    let f = asm.dofs.node_first[1];
    assert!(st.y[f].abs() < 1e-9 && (st.y[f + 1] + L).abs() < 1e-9, "{:?}", &st.y[f..f + 3]);
}

#[test]
fn both_linearization_routes_agree_to_1e_12() {
    // METHOD §2: F_yd, F_y assembled directly and recovered from J(±c) (eqs. 15–16).
    use romdyn::linear::Jacobians;
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let (model, st) = equilibrium(false, form);
        let direct = linearize(&model, &st, &[], &[], None).unwrap();
        let via_j = linearize(&model, &st, &[], &[], Some(1e-3)).unwrap();
        assert!(matches!(via_j.jacobians, Jacobians::Coefficient { .. }));
        let ((a, b), (c, d)) = (direct.jacobians.derivatives(), via_j.jacobians.derivatives());
        let rel = |x: &faer::Mat<f64>, y: &faer::Mat<f64>| (x - y).norm_max() / x.norm_max();
        assert!(rel(&a, &c) < 1e-12 && rel(&b, &d) < 1e-12, "{form:?}: {:e} {:e}", rel(&a, &c), rel(&b, &d));
    }
}

#[test]
fn static_load_ramp_reaches_the_same_equilibrium() {
    // Ten load steps from the horizontal position end where one step from the bottom does.
    let model = pendulum(1.2, false, ConstraintForm::Plain);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 10, &NewtonSettings { max_iterations: 100, ..Default::default() }).unwrap();
    let f = asm.dofs.node_first[1];
    assert!(st.y[f].abs() < 1e-9 && (st.y[f + 1] + L).abs() < 1e-9);
    // The hinge carries the weight: reaction m g (plain form: multiplier = force, N).
    let lambda: Vec<f64> = st.y[asm.dofs.element_first[1]..asm.dofs.element_first[1] + 3].to_vec();
    assert!((lambda[1].abs() - M * G).abs() < 1e-9, "{lambda:?}");
}

#[test]
fn linearization_at_a_time_step_of_a_resting_pendulum() {
    // Released at its equilibrium the pendulum stays put; linearized after 100 steps it has
    // the eigenvalues of eq. 82 (1e-6 relative).
    use romdyn::solve::{initial_derivatives, Integrator, Method};
    let (model, mut st) = equilibrium(false, ConstraintForm::Scaled);
    let asm = Assembler::new(&model);
    initial_derivatives(&asm, &mut st, &NewtonSettings::default()).unwrap();
    let mut int = Integrator::new(&asm, st, Method::Ms { rho: 0.6 }, 1e-2, NewtonSettings::default());
    for _ in 0..100 {
        int.step().unwrap();
    }
    let dae = linearize(&model, &int.state, &[], &[], Some(0.5 * 1e-2)).unwrap();
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Lambda).unwrap();
    assert!((modal.modes[0].lambda - c64::new(0.0, omega())).norm() / omega() < 1e-6, "{}", modal.modes[0].lambda);
}

/// A first-order mode of a viscous element on a static node moves no mass: its kinetic
/// energy is rounding, and the table must not attribute it to a node that happens to hold
/// that rounding. tests/mbdyn_files/time_variant_laws.mbd at t = 0.5 s: node 3 (static) on
/// a rod of EA = 400 N and C = 40 N s scaled by s_C = 1 + t, so λ = −EA/(C s_C) =
/// −400/(40 · 1.5) = −6.6667 rad/s (closed form), whose vector holds node 4's components at
/// rounding; it was listed "node 4 x 100 %". The other modes keep their descriptions.
#[test]
fn a_massless_first_order_mode_claims_no_kinetic_energy() {
    use common::cli::romdyn;
    let (ok, out, err) = romdyn(&["eig", "tests/mbdyn_files/time_variant_laws.mbd", "--at", "0.5"]);
    assert!(ok, "{err}");
    let rows: Vec<&str> = out.lines().filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit()) && l.contains(" dynamic ")).collect();
    let first_order: Vec<&&str> = rows.iter().filter(|l| l.split_whitespace().nth(1).and_then(|r| r.parse::<f64>().ok()).is_some_and(|re| (re + 400.0 / 60.0).abs() < 1e-6)).collect();
    assert_eq!(first_order.len(), 1, "{out}");
    assert!(!first_order[0].contains("node "), "a massless mode claims kinetic energy: {}", first_order[0]);
    assert!(rows.iter().filter(|l| l.contains("node ")).count() == rows.len() - 1, "the massive modes keep their descriptions: {out}");
}
