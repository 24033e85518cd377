//! Hydraulic fluids and elements (issue 34): MBDyn's `actuator`, `minor loss`, `control
//! valve` and `pipe` with `linear compressible` and `incompressible` fluids, on
//! tests/mbdyn_files/hydraulic_actuator_mass.mbd (a mass on the hydraulic spring of two
//! closed chambers), hydraulic_minor_loss.mbd and hydraulic_pipe.mbd (chamber 1 fed from a
//! supply through a minor loss, a pipe) and hydraulic_control_valve.mbd (a four-way valve
//! between supply, chambers and tank): Jacobians against finite differences, the hydraulic
//! stiffness `k = β (A₁²/V₁ + A₂²/V₂)` (its eigenvalue and step response), MBDyn 1.7.3's
//! numbers on the same files; and the clean refusals of bad values and of the cards romdyn
//! does not build (electric ones too).

use crate::common;
use common::mbdyn::{assert_refused, test_file};
use faer::c64;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::read_model;
use romdyn::study::{Study, StudySource};

/// hydraulic_actuator_mass.mbd's numbers: M, A, L0, D0, BETA, P0, F0.
const M: f64 = 10.0;
const A: f64 = 1e-3;
const L0: f64 = 0.2;
const D0: f64 = 0.1;
const BETA: f64 = 1e9;
const P0: f64 = 1e6;
const F0: f64 = 200.0;

/// The chambers' volumes and the hydraulic stiffness `β (A²/V₁ + A²/V₂)` [N/m] at the
/// reference pressure (where ρ = ρ₀: MBDyn's dρ/dp = ρ₀/β makes the chamber's stiffness
/// `β ρ/ρ₀ A²/V`).
fn stiffness() -> (f64, f64, f64) {
    let (v1, v2) = (A * D0, A * (L0 - D0));
    (v1, v2, BETA * (A * A / v1 + A * A / v2))
}

fn jacobians_of(name: &'static str) -> impl Fn(romdyn::model::ConstraintForm) -> romdyn::model::Model {
    move |form| {
        let mut model = read_model(&test_file(name)).unwrap_or_else(|e| panic!("{e}")).model;
        model.constraint_form = form;
        model
    }
}

#[test]
fn hydraulic_element_jacobians_match_finite_differences() {
    // Central differences at states moved by noise (rotations, velocities, pressure rates;
    // pressures 1e6 Pa apart, so the minor loss is off its square root's kink): 1e-7.
    assert_eq!(common::mbdyn::assert_model_jacobians(jacobians_of("hydraulic_actuator_mass.mbd"), 43, 1e-7), 6);
    assert_eq!(common::mbdyn::assert_model_jacobians(jacobians_of("hydraulic_minor_loss.mbd"), 44, 1e-7), 8);
    assert_eq!(common::mbdyn::assert_model_jacobians(jacobians_of("hydraulic_control_valve.mbd"), 45, 1e-7), 9);
    assert_eq!(common::mbdyn::assert_model_jacobians(jacobians_of("hydraulic_pipe.mbd"), 46, 1e-7), 8);
}

#[test]
fn actuator_eigenvalue_is_its_hydraulic_stiffness_and_mbdyns() {
    let m = read_model(&test_file("hydraulic_actuator_mass.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let study = Study::builder(StudySource::model(m.model, m.problem)).node_ports(vec!["2:Fz".parse().unwrap()], vec!["1:hydraulic".parse().unwrap()]).build().unwrap_or_else(|e| panic!("{e}"));
    let dynamic: Vec<&romdyn::eigen::Mode> = study.modal().modes.iter().filter(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).collect();
    let (_, _, k) = stiffness();
    let omega = (k / M).sqrt();
    // Source: the closed form ±j √(k/M) = ±1414.2135… rad/s (k = 2e7 N/m), 1e-10 relative.
    assert_eq!(dynamic.len(), 2);
    for mode in &dynamic {
        assert!((mode.lambda - c64::new(0.0, omega * mode.lambda.im.signum())).norm() < 1e-10 * omega, "{} vs ±{omega}j", mode.lambda);
    }
    // MBDyn 1.7.3 on the same file (`eigenanalysis: 0., parameter, 1.e-4, use lapack`,
    // `output precision: 16`; λ = (Λ − 1)/(dCoef (Λ + 1)) of its .m file): 4.3e-6 ±
    // 1414.2135618404807j, within 4e-10 of the closed form (its real part is the Cayley
    // transform's rounding: 4.3e-6 dCoef = 2e-10).
    let mbdyn = 1414.2135618404807;
    assert!((dynamic[0].lambda.im.abs() - mbdyn).abs() < 5e-10 * mbdyn);
    // Its error estimate (componentwise, independent of units): the pencil mixes pascals
    // and metres 1e10 apart, and the normwise estimate said 2.2e-2 rad/s for a pair right to
    // 1e-10 relative; the closed form above is the reference, tolerance 1e-8 rad/s.
    for mode in &dynamic {
        assert!(mode.error < 1e-8, "error estimate {} rad/s of {}", mode.error, mode.lambda);
    }
    // The mode's energy (issue 34): the piston's kinetic energy ½ M ω² |z|² and the
    // chambers' compression energies ½ (Vₖ/β) |pₖ|² with pₖ = ∓β A z/Vₖ, which add up to
    // ½ k |z|² = ½ M ω² |z|²: half the piston's, a quarter each chamber's (V₁ = V₂), though
    // the vector's largest entries are the pressures (1e10 Pa per metre). 1e-8.
    let energy = study.energy();
    let index = study.modal().modes.iter().position(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).unwrap();
    let share = |who: &str| energy[index].iter().find(|s| s.who() == who).map_or(0.0, |s| s.share);
    let (v1, v2, k) = stiffness();
    let want = [("node 2 z", 0.5), ("actuator 1 chamber 1 pressure", 0.5 * BETA * A * A / v1 / k), ("actuator 1 chamber 2 pressure", 0.5 * BETA * A * A / v2 / k)];
    for (who, w) in want {
        assert!((share(who) - w).abs() < 1e-8, "{who}: {} against {w} ({:?})", share(who), energy[index]);
    }
    let table = study.modal_report().with_energy(energy.clone()).to_text();
    assert!(table.contains("node 2 z 50 %, actuator 1 chamber 1 pressure 25 %, actuator 1 chamber 2 pressure 25 %"), "{table}");
}

#[test]
fn actuator_step_response_follows_the_hydraulic_spring_and_mbdyn() {
    let m = read_model(&test_file("hydraulic_actuator_mass.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let (st, first, piston) = (&report.final_state, asm.dofs.scalar_first, asm.dofs.node_first[1] + 2);
    let (v1, v2, k) = stiffness();
    let omega = (k / M).sqrt();
    let t = st.t;
    assert!((t - 0.02001).abs() < 1e-12);
    // The linear closed form: z − D0 = F0/k (1 − cos ωt), p₁ − P0 = −β A (z − D0)/V₁,
    // p₂ − P0 = β A (z − D0)/V₂. Tolerance 2e-3 of the amplitude 2F0/k: the model's
    // nonlinearity (amplitude/stroke 2e-4, ρ(p) 2e-4) and the ms method's phase error at
    // ω h = 0.014 over 28 rad.
    let x = F0 / k * (1.0 - (omega * t).cos());
    let amplitude = 2.0 * F0 / k;
    assert!((st.y[piston] - D0 - x).abs() < 2e-3 * amplitude, "z − D0 = {:e}, closed form {x:e}", st.y[piston] - D0);
    let dp = [-BETA * A * x / v1, BETA * A * x / v2];
    for (j, want) in dp.into_iter().enumerate() {
        let got = st.y[first + j] - P0;
        assert!((got - want).abs() < 2e-3 * BETA * A * amplitude / v1, "p{} − P0 = {got:e}, closed form {want:e}", j + 1);
    }
    // MBDyn 1.7.3 on the same file (`output precision: 16`), its .prs and .mov rows at t =
    // 0.02001 s: romdyn's pressures agree to 3.5e-7 Pa over the whole run (changes of 2e5
    // Pa), the piston's z to 5.3e-16 m and its velocity to 6.7e-16 m/s; here 1e-12 relative
    // (pressures, position) and 1e-9 (the velocity, 1/40 of its peak here).
    for (j, want) in [8.0006767449167080e+05, 1.2000123033643658e+06].into_iter().enumerate() {
        assert!((st.y[first + j] - want).abs() < 1e-12 * want, "p{} = {}, MBDyn {want}", j + 1, st.y[first + j]);
    }
    assert!((st.y[piston] - 1.0001999723065294e-01).abs() < 1e-12 * D0, "z = {}", st.y[piston]);
    assert!((st.yp[piston] - -3.3259263545890104e-04).abs() < 1e-9 * 3.3259263545890104e-04, "vz = {}", st.yp[piston]);
}

/// Runs the test file `name` and checks its final time, its hydraulic nodes' pressures (to
/// `tolerance` relative), the piston's z (to `tolerance` of D0) and its velocity (to 1e-8
/// relative) against MBDyn 1.7.3's rows of the same file.
fn assert_final_state_is_mbdyns(name: &str, t: f64, pressures: &[f64], z: f64, vz: f64, tolerance: f64) {
    let m = read_model(&test_file(name)).unwrap_or_else(|e| panic!("{e}"));
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let (st, first, piston) = (&report.final_state, asm.dofs.scalar_first, asm.dofs.node_first[1] + 2);
    assert!((st.t - t).abs() < 1e-12, "{name}: t = {}", st.t);
    for (j, &want) in pressures.iter().enumerate() {
        assert!((st.y[first + j] - want).abs() < tolerance * want, "{name}: p{} = {}, MBDyn {want}", j + 1, st.y[first + j]);
    }
    assert!((st.y[piston] - z).abs() < tolerance * D0, "{name}: z = {}, MBDyn {z}", st.y[piston]);
    assert!((st.yp[piston] - vz).abs() < 1e-8 * vz.abs(), "{name}: vz = {}, MBDyn {vz}", st.yp[piston]);
}

#[test]
fn minor_loss_control_valve_and_pipe_runs_follow_mbdyn() {
    // MBDyn 1.7.3 on the same files (`output precision: 16`), its .prs and .mov rows at the
    // final time. hydraulic_minor_loss.mbd (the supply fills chamber 1 through the loss and
    // pushes the piston): romdyn's pressures agree to 5.7e-5 Pa over the run (changes of 1e6
    // Pa), z to 5.6e-15 m, the velocity to 3.4e-12 m/s (peak 0.03 m/s).
    assert_final_state_is_mbdyns("hydraulic_minor_loss.mbd", 0.01001, &[2.0005974698474233e+06, 1.9328393051030464e+06, 2.0e6], 1.0009319699269739e-01, 5.7571524140725700e-04, 1e-10);
    // hydraulic_control_valve.mbd (a 20 Hz valve command between supply and tank): pressures
    // to 3.2e-8 Pa over the run (changes of 5.7e4 Pa), z to 6.8e-16 m, the velocity to
    // 5.3e-15 m/s (peak 0.016 m/s).
    assert_final_state_is_mbdyns("hydraulic_control_valve.mbd", 0.05, &[1.0562427353670713e+06, 1.0366721380225067e+06, 2.0e6, 1.0e5], 1.0001343574233700e-01, -5.2324394282223586e-05, 1e-12);
    // hydraulic_pipe.mbd (chamber 1 fed through a pipe from a ramped supply; MBDyn's .hyd
    // rows: Reynolds numbers up to 15117, 158 steps laminar, 196 in the transition, 648
    // turbulent, 5 crossings of the transition): pressures to 5.1e-8 Pa over the run
    // (changes of 1.2e6 Pa), z to 4.2e-16 m, the velocity to 3.9e-15 m/s (peak 0.036 m/s).
    // With `tolerance: 1.e-11` MBDyn 1.7.3 stopped at 4.66 ms (its pipe's residual, in Pa,
    // cannot reach it) where romdyn ran on; the file asks 1e-8.
    assert_final_state_is_mbdyns("hydraulic_pipe.mbd", 0.01001, &[1.9965588002626917e+06, 1.8830499392000588e+06, 2.0e6], 1.0008822708494713e-01, 1.3772927429884710e-02, 1e-12);
}

/// `text` with `old` (which it must hold) replaced by `new`.
fn changed(text: &str, old: &str, new: &str) -> String {
    assert!(text.contains(old), "{old}");
    text.replace(old, new)
}

#[test]
fn bad_hydraulic_and_electric_cards_are_refused_by_name_and_place() {
    let name = "hydraulic_minor_loss.mbd";
    let original = std::fs::read_to_string(test_file(name)).unwrap();
    let change = |old: &str, new: &str| changed(&original, old, new);
    let actuator = "hydraulic: 1, actuator, 1, 2, 1, null, 2, null, direction, 0., 0., 1., A, A, L0,";
    let loss = "hydraulic: 2, minor loss, 3, 1, 2., 3., AL,";
    let fluid = "hydraulic fluid: 1, linear compressible, density, RHO, BETA, P0, viscosity, 1.e-2;";
    let cases = [
        (change(fluid, "hydraulic fluid: 1, linear compressible, density, RHO, -BETA, P0, viscosity, 1.e-2;"), "bulk modulus [Pa] must be positive, found -1000000000"),
        (change(fluid, "hydraulic fluid: 1, linear compressible, density, RHO, BETA, P0;"), "'viscosity' (MBDyn 1.7.3 requires a positive viscosity)"),
        (change(fluid, "hydraulic fluid: 1, super, density, RHO, BETA, P0, viscosity, 1.e-2;"), "the fluid type 'super' is not supported by romdyn (MBDyn 1.7.3 runs it)"),
        (change(actuator, "hydraulic: 1, actuator, 1, 2, 1, null, 2, null, direction, 0., 0., 1., 0., A, L0,"), "area 1 [m^2] must be positive, found 0"),
        (change(actuator, "hydraulic: 1, actuator, 1, 2, 1, null, 2, null, direction, 0., 0., 0., A, A, L0,"), "the direction is null"),
        (change("fluid, reference, 1, same;", "fluid, reference, 2, same;"), "hydraulic fluid 2 is not defined above this element"),
        (change(loss, "hydraulic: 2, minor loss, 3, 1, 0., 3., AL,"), "loss coefficient K12 must be positive, found 0"),
        (change(loss, "hydraulic: 2, minor loss, 3, 4, 2., 3., AL,"), "hydraulic node 4 is not defined"),
        (change(loss, "hydraulic: 2, pressure valve, 3, 1, 2., 3., AL,"), "hydraulic element type 'pressure valve' is not supported by romdyn (MBDyn 1.7.3 runs it)"),
        (change(loss, "hydraulic: 2, accumulator, 3, 0.1, start, 0.2, AL,"), "the initial stroke 0.2 m exceeds the stroke 0.1 m (MBDyn 1.7.3: \"stroke less then initial position\")"),
        (change(loss, "hydraulic: 2, orifice, 3, 1, 2.e-3, 3.5e-6,"), "against the pipe's 0.00000314 m^2 gives no discharge coefficient (1 - (Cc Ao/Ap)^2 <= 0; MBDyn 1.7.3: \"error computing Cd\")"),
        (change(loss, "hydraulic: 2, tank, 3, 1, 1.e5, AL, -1.,"), "tank area [m^2] must be positive, found -1"),
        (change(loss, "hydraulic: 2, pipe, 3, 1, 4.e-3, -1.,"), "length [m] must be positive, found -1"),
        (change(loss, "hydraulic: 2, dynamic control valve, 3, 1, 2., 3., AL,"), "hydraulic element type 'dynamic control valve' is not supported by romdyn (MBDyn 1.7.3 runs it)"),
        (change(loss, "hydraulic: 2, control valve, 3, 1, 2, 3, 1.e-6, loss, -0.1, const, 1.,"), "the loss must not be negative, found -0.1"),
        (change("    hydraulic elements: 2;", "    hydraulic elements: 3;"), "control data declares 3 hydraulic elements, the model has 2"),
    ];
    assert_refused(name, &original, &cases);
    let name = "dc_motor_inertia.mbd";
    let original = std::fs::read_to_string(test_file(name)).unwrap();
    let change = |old: &str, new: &str| changed(&original, old, new);
    let motor = "electric: 1, motor, 1, 2, 0., 0., 1., 1, 2, G, L, R;";
    let cases = [
        (change(motor, "electric: 1, motor, 1, 2, 0., 0., 1., 1, 2, G, 0., R;"), "the inductance must be positive, found 0"),
        (change(motor, "electric: 1, motor, 1, 2, 0., 0., 0., 1, 2, G, L, R;"), "the axis is null"),
        (change(motor, "electric: 1, motor, 1, 2, 0., 0., 1., 1, 2, G, L, R, M0, const, 1.;"), "\"M0\" and \"M1\" require the motor's 'orientation' instead of an axis (MBDyn 1.7.3 refuses it too)"),
        (change(motor, "electric: 1, motor, 1, 2, orientation, eye, 1, 2, G, L, R, M0, const, 1., terminal pairs, 0;"), "the number of terminal pairs must be at least 1, found 0"),
        (change(motor, "electric: 1, motor, 1, 2, orientation, eye, 1, 2, G, L, R, M1, const, 1.;"), "'terminal pairs' (MBDyn 1.7.3 requires it after M0, M1)"),
        (change(motor, "electric: 1, motor, 1, 2, 0., 0., 1., 1, 2, G, L, linear, 1., 2.;"), "a resistance that varies with the current"),
        (change(motor, "electric: 1, motor, 1, 2, 0., 0., 1., 1, 3, G, L, R;"), "electric node 3 is not defined"),
        (change("    abstract: 1, differential;", "    abstract: 1, algebraic;"), "abstract node 1 is algebraic; MBDyn 1.7.3 writes a sensor into a differential abstract node"),
        (change("electric: 2, accelerometer, rotational, 2, 1, 0., 0., 1.;", "electric: 2, accelerometer, 2, 1, 0., 0., 1., 10., 1., 0.5, 1.;"), "the legacy accelerometer with its built-in transfer function is not supported by romdyn (MBDyn 1.7.3 runs it)"),
        (change("electric: 2, accelerometer, rotational, 2, 1, 0., 0., 1.;", "electric: 2, discrete control, 1, 1, 1;"), "electric element type 'discrete control' is not supported by romdyn (MBDyn 1.7.3 runs it)"),
    ];
    assert_refused(name, &original, &cases);
}
