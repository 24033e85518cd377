//! Electric elements (issue 34): MBDyn's `motor`, `accelerometer` (translational and
//! rotational) and `displacement` on tests/mbdyn_files/dc_motor_inertia.mbd, a DC motor
//! driving an inertia: Jacobians against finite differences, the closed form of the
//! motor's second-order speed response (poles, step response, steady speed), the sensors'
//! closed forms, an RL circuit (the motor with its rotor held), an RC circuit written with
//! genels on an electric node, and MBDyn 1.7.3's numbers on the same file.

use crate::common;
use common::mbdyn::test_file;
use faer::c64;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::read_model;
use romdyn::study::{Study, StudySource};

/// dc_motor_inertia.mbd's numbers: J, G, L, R, V0, RA, RB.
const J: f64 = 1e-4;
const G: f64 = 0.05;
const L: f64 = 1e-3;
const R: f64 = 1.0;
const V0: f64 = 1.0;
const RA: f64 = 0.1;
const RB: f64 = 0.2;

/// The poles of `w/V0 = G/(J L s² + J R s + G²)`: `(−R/L ± √((R/L)² − 4 G²/(J L)))/2`.
fn poles() -> [f64; 2] {
    let (b, c) = (R / L, G * G / (J * L));
    let root = (b * b - 4.0 * c).sqrt();
    [(-b + root) / 2.0, (-b - root) / 2.0]
}

/// The step response from rest: rotation φ, speed ω, angular acceleration ω̇ and current i.
fn step_response(t: f64) -> (f64, f64, f64, f64) {
    let [p1, p2] = poles();
    let k = G * V0 / (J * L);
    let (e1, e2) = ((p1 * t).exp(), (p2 * t).exp());
    let phi = k * (t / (p1 * p2) + (e1 - 1.0) / (p1 * p1 * (p1 - p2)) + (e2 - 1.0) / (p2 * p2 * (p2 - p1)));
    let omega = k * (1.0 / (p1 * p2) + e1 / (p1 * (p1 - p2)) + e2 / (p2 * (p2 - p1)));
    let alpha = k * (e1 / (p1 - p2) + e2 / (p2 - p1));
    (phi, omega, alpha, J * alpha / G)
}

#[test]
fn electric_element_jacobians_match_finite_differences() {
    let model_of = |form| {
        let mut model = read_model(&test_file("dc_motor_inertia.mbd")).unwrap_or_else(|e| panic!("{e}")).model;
        model.constraint_form = form;
        model
    };
    // Central differences at a state moved by noise (rotations, rates, currents): 1e-7, the
    // differences' truncation on the rotation columns.
    assert_eq!(common::mbdyn::assert_model_jacobians(model_of, 41, 1e-7), 9);
}

#[test]
fn dc_motor_eigenvalues_are_the_closed_form_and_mbdyns() {
    let m = read_model(&test_file("dc_motor_inertia.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let study = Study::builder(StudySource::model(m.model, m.problem)).node_ports(vec!["1:abstract".parse().unwrap()], vec!["1:abstract".parse().unwrap()]).build().unwrap_or_else(|e| panic!("{e}"));
    let mut dynamic: Vec<c64> = study.modal().modes.iter().filter(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).map(|m| m.lambda).collect();
    dynamic.sort_by(|a, b| b.re.total_cmp(&a.re));
    // Source: the closed form above (−25.658…, −974.34… rad/s), 1e-10 relative.
    assert_eq!(dynamic.len(), 2, "{dynamic:?}");
    for (got, want) in dynamic.iter().zip(poles()) {
        assert!((got - c64::new(want, 0.0)).norm() < 1e-10 * want.abs(), "{got} vs {want}");
    }
    // MBDyn 1.7.3 on the same file with `eigenanalysis: 0.05, parameter, 1.e-3, use lapack`
    // and `output precision: 16` (its .m file, λ = (Λ − 1)/(dCoef (Λ + 1))): the same two
    // poles, -25.65835097474342 and -974.3416490253383, to 1e-10.
    for (got, mbdyn) in dynamic.iter().zip([-25.65835097474342, -974.3416490253383]) {
        assert!((got.re - mbdyn).abs() < 1e-10 * mbdyn.abs(), "{got} vs MBDyn {mbdyn}");
    }
}

#[test]
fn dc_motor_modes_are_labelled_by_the_rotor_and_the_current_they_live_in() {
    // Issue 34: the modal table shares a mode out over the rotor's kinetic energy ½ J |λ φ|²
    // and the inductance's magnetic energy ½ L |i|². Closed form: J λ² φ = G i (the rotor's
    // equation), so the current's share is L / (L + G²/(J λ²)) in either mode: 97.4 % in the
    // −974 rad/s mode, 2.6 % in the −25.7 rad/s one. Tolerance 1e-8.
    let m = read_model(&test_file("dc_motor_inertia.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let study = Study::builder(StudySource::model(m.model, m.problem)).build().unwrap_or_else(|e| panic!("{e}"));
    let energy = study.energy();
    for (i, mode) in study.modal().modes.iter().enumerate().filter(|(_, m)| m.kind == romdyn::eigen::ModeKind::Dynamic) {
        let lambda2 = mode.lambda.norm_sqr();
        let current = L / (L + G * G / (J * lambda2));
        let share = |who: &str| energy[i].iter().find(|s| s.who() == who).map_or(0.0, |s| s.share);
        assert!((share("motor 1 current") - current).abs() < 1e-8, "λ = {}: {:?}", mode.lambda, energy[i]);
        assert!((share("node 2 rz") - (1.0 - current)).abs() < 1e-8, "λ = {}: {:?}", mode.lambda, energy[i]);
        let (top, label) = if current > 0.5 { ("motor 1 current", current) } else { ("node 2 rz", 1.0 - current) };
        let text = romdyn::eigen::describe(&energy[i]);
        assert!(text.starts_with(&format!("{top} {:.0} %", 100.0 * label)), "{text}");
    }
}

#[test]
fn dc_motor_step_response_follows_the_closed_form_and_mbdyn() {
    let m = read_model(&test_file("dc_motor_inertia.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let (st, first) = (&report.final_state, asm.dofs.scalar_first);
    assert!((st.t - 0.1).abs() < 1e-12);
    let (phi, omega, alpha, current) = step_response(st.t);
    let motor = m.model.elements.iter().position(|e| e.type_name() == "motor").unwrap();
    let i = st.y[asm.dofs.element_first[motor]];
    // Closed form at t = 0.1 s (the slow pole's 2.6 time constants), tolerance 1e-5 of each
    // quantity's scale: the ms method's error at h = 0.1 ms (h |p₁| = 2.6e-3, h |p₂| = 0.097).
    let frame = st.node_frame(&asm.dofs, 1).kin;
    let (angle, speed) = (frame.r[(1, 0)].atan2(frame.r[(0, 0)]) + std::f64::consts::TAU * (phi / std::f64::consts::TAU).round(), frame.omega[2]);
    assert!((speed - omega).abs() < 1e-5 * V0 / G, "ω = {speed}, closed form {omega}");
    assert!((angle - phi).abs() < 1e-5 * phi, "φ = {angle}, closed form {phi}");
    assert!((i - current).abs() < 1e-5 * (V0 / R), "i = {i}, closed form {current}");
    assert!((st.y[first + 2] - alpha).abs() < 1e-5 * G * V0 / R / J, "rotational accelerometer {} vs ω̇ = {alpha}", st.y[first + 2]);
    assert!((st.y[first + 3] - RA * alpha).abs() < 1e-5 * RA * G * V0 / R / J, "translational accelerometer {} vs RA ω̇ = {}", st.y[first + 3], RA * alpha);
    let distance = (RA * RA + RB * RB - 2.0 * RA * RB * phi.cos()).sqrt();
    assert!((st.y[first + 4] - distance).abs() < 1e-5 * RB, "displacement {} vs {distance}", st.y[first + 4]);
    assert!(omega > 0.9 * V0 / G, "ω = {omega}: within 10 % of the steady V0/G");
    // MBDyn 1.7.3 on the same file with `output precision: 16`, its .abs rows at t = 0.1 s
    // (abstract nodes 1, 2, 3: value, derivative). romdyn agrees to 1.4e-12 of each node's
    // scale over the 1000 steps (values) and 7.4e-11 (derivatives), and its .mov (angle,
    // speed) to 1.5e-15; here the final values to 1e-11 relative, their derivatives to 3e-8
    // (1.5e-8 found: the derivatives are 1/35 of their early peak here; MBDyn's own two
    // accelerometers, exactly proportional, differ by 2.2e-8 in their derivatives).
    let mbdyn = [(4.0506059782510505e+01, -1.0393187138601934e+03), (4.0506059782591342e+00, -1.0393186906611014e+02), (1.9448773655718557e-01, 1.8044694071289129e+00)];
    for (k, (x, xp)) in mbdyn.into_iter().enumerate() {
        let (gx, gxp) = (st.y[first + 2 + k], st.yp[first + 2 + k]);
        assert!((gx - x).abs() < 1e-11 * x.abs(), "abstract node {}: {gx:e} vs MBDyn {x:e}", k + 1);
        assert!((gxp - xp).abs() < 3e-8 * xp.abs(), "abstract node {} derivative: {gxp:e} vs MBDyn {xp:e}", k + 1);
    }
}

#[test]
fn motor_with_its_rotor_held_is_an_rl_circuit() {
    // dc_motor_inertia.mbd with the rotor clamped (ω = 0): L di/dt + R i = V0, so i(t) =
    // V0/R (1 − e^{−R t/L}) and the one eigenvalue −R/L = −1000 rad/s. h = 1 µs: the ms
    // method's error at h R/L = 1e-3 is below 1e-6 of V0/R.
    let m = common::mbdyn::rewritten_test_file("dc_motor_inertia.mbd", &[
        ("joint: 2, revolute hinge,\n        1, position, null, orientation, eye,\n        2, position, null, orientation, eye;", "joint: 2, clamp, 2, node, node;"),
        ("final time: 0.1;", "final time: 0.005;"),
        ("time step: 1.e-4;", "time step: 1.e-6;"),
    ]);
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let motor = m.model.elements.iter().position(|e| e.type_name() == "motor").unwrap();
    let (t, i) = (report.final_state.t, report.final_state.y[asm.dofs.element_first[motor]]);
    let want = V0 / R * (1.0 - (-R * t / L).exp());
    assert!((i - want).abs() < 1e-6 * V0 / R, "i({t}) = {i}, closed form {want}");
    let study = Study::builder(StudySource::model(m.model, m.problem)).node_ports(vec!["1:abstract".parse().unwrap()], vec!["1:abstract".parse().unwrap()]).build().unwrap_or_else(|e| panic!("{e}"));
    let dynamic: Vec<c64> = study.modal().modes.iter().filter(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).map(|m| m.lambda).collect();
    assert_eq!(dynamic.len(), 1, "{dynamic:?}");
    assert!((dynamic[0] - c64::new(-R / L, 0.0)).norm() < 1e-10 * R / L, "{}", dynamic[0]);
}

#[test]
fn a_genel_on_an_electric_node_makes_an_rc_circuit() {
    // A resistor R and a capacitor C from electric node 1 to ground, written as one `genel
    // spring support` with a `linear viscoelastic` law (current V/R + C dV/dt; a `genel
    // mass` would be an inductance-like second-order term, m d²V/dt²), and a current source
    // I0 (`force: abstract`): C dV/dt + V/R = I0, so V(t) = I0 R (1 − e^{−t/(R C)}) and the
    // one eigenvalue −1/(R C) = −1000 rad/s. h = 1 µs: error below 1e-6 of I0 R. MBDyn
    // 1.7.3 on the same file (`output precision: 16`): V = 1.9865106300544138 at t =
    // 4.999 ms, where romdyn's .ele reads 1.9865106300544102.
    let (r, c, i0) = (1e3, 1e-6, 2e-3);
    let text = format!(
        "begin: data; problem: initial value; end: data;\n\
         begin: initial value; initial time: 0.; final time: 5.e-3; time step: 1.e-6; tolerance: 1.e-12; method: ms, .6; end: initial value;\n\
         begin: control data; electric nodes: 1; genels: 1; forces: 1; end: control data;\n\
         begin: nodes; electric: 1, value, 0.; end: nodes;\n\
         begin: elements;\n\
         genel: 1, spring support, 1, electric, algebraic, linear viscoelastic, {g:e}, {c:e};\n\
         force: 1, abstract, 1, electric, const, {i0:e};\n\
         end: elements;\n",
        g = 1.0 / r
    );
    let m = common::mbdyn::read(&text);
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let first = Assembler::new(&m.model).dofs.scalar_first;
    let (t, v) = (report.final_state.t, report.final_state.y[first]);
    let want = i0 * r * (1.0 - (-t / (r * c)).exp());
    assert!((v - want).abs() < 1e-6 * i0 * r, "V({t}) = {v}, closed form {want}");
    let study = Study::builder(StudySource::model(m.model, m.problem)).node_ports(vec!["1:electric".parse().unwrap()], vec!["1:electric".parse().unwrap()]).build().unwrap_or_else(|e| panic!("{e}"));
    let dynamic: Vec<c64> = study.modal().modes.iter().filter(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).map(|m| m.lambda).collect();
    assert_eq!(dynamic.len(), 1, "{dynamic:?}");
    assert!((dynamic[0] - c64::new(-1.0 / (r * c), 0.0)).norm() < 1e-10 / (r * c), "{}", dynamic[0]);
    // The mode lives in the capacitor's voltage, the one state (its participation factor 1).
    let energy = study.energy();
    let i = study.modal().modes.iter().position(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).unwrap();
    assert_eq!(romdyn::eigen::describe(&energy[i]), "electric node 1 100 %");
    // Its static gain V/I0 = R through the electric ports (a current [A] in, a voltage out).
    let rom = study.reduce(&romdyn::study::RomRequest::new(romdyn::rom::ModeSelection::Lowest(1))).unwrap_or_else(|e| panic!("{e}"));
    let g = rom.static_gains.full.as_ref().unwrap()[(0, 0)];
    assert!((g - r).abs() < 1e-10 * r, "V/I = {g}, R = {r}");
}

#[test]
fn motor_private_data_read_by_element_drives() {
    // `element, 1, electric, string, NAME` drives (motor.cc's private data) on abstract
    // forces, each held by a unit spring support on its own abstract node: the node's value
    // is the datum. At the final state: "i" the motor's current unknown, "omega" the
    // rotor's ω_z, "U" = V0, "M" = G i, "Pel" = V0 i, to Newton's tolerance (1e-10).
    let data = ["i", "omega", "U", "M", "Pel"];
    let nodes: String = (0..data.len()).map(|k| format!("    abstract: {}, differential;\n", 4 + k)).collect();
    let elements: String = data.iter().enumerate().map(|(k, name)| format!("    genel: {}, spring support, {n}, abstract, algebraic, linear elastic, 1.;\n    force: {}, abstract, {n}, abstract, element, 1, electric, string, \"{name}\", linear, 0., 1.;\n", 3 + k, 1 + k, n = 4 + k)).collect();
    let m = common::mbdyn::rewritten_test_file("dc_motor_inertia.mbd", &[
        ("    abstract nodes: 3;", "    abstract nodes: 8;\n    forces: 5;"),
        ("    genels: 2;", "    genels: 7;"),
        ("    abstract: 3, differential, value, RB - RA;\n", &format!("    abstract: 3, differential, value, RB - RA;\n{nodes}")),
        ("    electric: 4, displacement, 2, RA, 0., 0., 1, RB, 0., 0., 3;\n", &format!("    electric: 4, displacement, 2, RA, 0., 0., 1, RB, 0., 0., 3;\n{elements}")),
        ("final time: 0.1;", "final time: 0.01;"),
    ]);
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let st = &report.final_state;
    let motor = m.model.elements.iter().position(|e| e.type_name() == "motor").unwrap();
    let i = st.y[asm.dofs.element_first[motor]];
    let omega = st.node_frame(&asm.dofs, 1).kin.omega[2];
    let node = |label: u32| st.y[asm.dofs.scalar_first + m.model.scalar_nodes.iter().position(|n| n.id.label == label && n.id.kind == romdyn::model::ScalarNodeKind::Abstract).unwrap()];
    for (k, want) in [i, omega, V0, G * i, V0 * i].into_iter().enumerate() {
        assert!((node(4 + k as u32) - want).abs() < 1e-10 * want.abs().max(1.0), "{}: {} vs {want}", data[k], node(4 + k as u32));
    }
    assert!(i > 0.1 && omega > 1.0, "i = {i}, ω = {omega}: the motor runs");
}
