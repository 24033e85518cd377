//! Scalar nodes (abstract, electric, hydraulic) and the genels on them (issue 34): every
//! genel's analytic Jacobian against central finite differences of its residual, the
//! reader's cards, and a PID position loop written with genels (examples/pid_mass.mbd)
//! whose closed-loop poles are the roots of its characteristic polynomial; a second-order
//! Butterworth `scalar filter` (the input manual's example) with its poles and DC gain.

use std::path::Path;

use crate::common;
use common::mbdyn::test_file;
use faer::c64;
use romdyn::dae::{Assembler, NodeInput, NodeOutput, State};
use romdyn::input::mbdyn::read_model;
use romdyn::model::ConstraintForm;
use romdyn::rom::ModeSelection;
use romdyn::study::{RomRequest, Study, StudySource};

#[test]
fn every_genel_jacobian_matches_finite_differences() {
    let m = read_model(&test_file("genels_all.mbd")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(m.model.scalar_nodes.len(), 9);
    assert_eq!(m.model.elements.len(), 14);
    let model_of = |form| {
        let mut model = read_model(&test_file("genels_all.mbd")).unwrap().model;
        model.constraint_form = form;
        model
    };
    // Central differences of residuals linear or sinusoidal in the unknowns: 1e-8.
    assert_eq!(common::mbdyn::assert_model_jacobians(model_of, 34, 1e-8), 14);
}

/// The roots of `p[0] sⁿ + p[1] sⁿ⁻¹ + … + p[n]` as the eigenvalues of its companion matrix
/// (nalgebra's real Schur form: independent of romdyn's QZ).
fn roots(p: &[f64]) -> Vec<c64> {
    let n = p.len() - 1;
    let companion = nalgebra::DMatrix::from_fn(n, n, |i, j| if i == 0 { -p[j + 1] / p[0] } else if i == j + 1 { 1.0 } else { 0.0 });
    companion.complex_eigenvalues().iter().map(|z| c64::new(z.re, z.im)).collect()
}

/// Each of `want` is within `tol · |w|` of one of `got` (and the counts agree).
fn assert_same_roots(got: &[c64], want: &[c64], tol: f64) {
    assert_eq!(got.len(), want.len(), "got {got:?}, want {want:?}");
    for w in want {
        let d = got.iter().map(|g| (g - w).norm()).fold(f64::INFINITY, f64::min);
        assert!(d <= tol * w.norm(), "{w} not among {got:?} (closest {d:e})");
    }
}

/// examples/pid_mass.mbd's numbers: m, c, k and the monic filter's A1, B0, B1, B2.
struct Pid {
    m: f64,
    c: f64,
    k: f64,
    a1: f64,
    b: [f64; 3],
}

const PID: Pid = {
    let (m, k, c, kp, ki, kd, tau) = (2.0, 50.0, 0.4, 100.0, 200.0, 10.0, 0.01);
    Pid { m, c, k, a1: 1.0 / tau, b: [(kp * tau + kd) / tau, (kp + ki * tau) / tau, ki / tau] }
};

impl Pid {
    /// `P(s) = (m s² + c s + k)(s² + A1 s) + B0 s² + B1 s + B2`.
    fn characteristic(&self) -> [f64; 5] {
        [self.m, self.m * self.a1 + self.c, self.c * self.a1 + self.k + self.b[0], self.k * self.a1 + self.b[1], self.b[2]]
    }
    /// `X/F = D/P` and `U/F = N/P` at `s` (`D = s² + A1 s`, `N = B0 s² + B1 s + B2`).
    fn responses(&self, s: c64) -> (c64, c64) {
        let p = self.characteristic().iter().fold(c64::new(0.0, 0.0), |acc, &x| acc * s + x);
        let d = s * s + s * self.a1;
        let n = s * s * self.b[0] + s * self.b[1] + self.b[2];
        (d / p, n / p)
    }
}

fn pid_study() -> Study {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pid_mass.mbd");
    let m = read_model(&path).unwrap_or_else(|e| panic!("{e}"));
    let inputs = vec!["1:abstract".parse::<NodeInput>().unwrap()];
    let outputs = vec!["1:abstract".parse::<NodeOutput>().unwrap(), "2:abstract".parse::<NodeOutput>().unwrap()];
    Study::builder(StudySource::model(m.model, m.problem)).node_ports(inputs, outputs).build().unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn pid_loop_closed_loop_poles_are_the_roots_of_its_characteristic_polynomial() {
    let study = pid_study();
    let dynamic: Vec<c64> = study.modal().modes.iter().filter(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).map(|m| m.lambda).collect();
    // Source: the characteristic polynomial of the loop (examples/pid_mass.mbd's header),
    // its roots by nalgebra's companion matrix; tolerance 1e-8 relative.
    assert_same_roots(&dynamic, &roots(&PID.characteristic()), 1e-8);
    // The modes move no mass: the table shares them out by participation factors (issue
    // 34), which add up to 1 over the loop's states. The real poles are the controller's:
    // the derivative filter's (−94.8 rad/s, near −1/TAU) and the integrator's (−1.44
    // rad/s) live in the scalar filter's states (at least 90 %); the plant's oscillation
    // (−2.0 ± 8.3j rad/s) lives mostly in the mass (its node and the genel mass's
    // derivative, at least 60 %).
    let energy = study.energy();
    let filter = |i: usize| energy[i].iter().filter(|s| s.element.as_deref() == Some("genel scalar filter")).map(|s| s.share).sum::<f64>();
    let plant = |i: usize| energy[i].iter().filter(|s| s.who() == "abstract node 1" || s.element.as_deref() == Some("genel mass")).map(|s| s.share).sum::<f64>();
    for (i, mode) in study.modal().modes.iter().enumerate().filter(|(_, m)| m.kind == romdyn::eigen::ModeKind::Dynamic) {
        let total: f64 = energy[i].iter().map(|s| s.share).sum();
        assert!((total - 1.0).abs() < 1e-12, "{:?}", energy[i]);
        if mode.lambda.im == 0.0 {
            assert!(filter(i) > 0.9, "λ = {}: {:?}", mode.lambda, energy[i]);
        } else {
            assert!(plant(i) > 0.6, "λ = {}: {:?}", mode.lambda, energy[i]);
        }
    }
}

#[test]
fn pid_loop_rom_keeps_the_poles_static_gains_and_responses_of_the_polynomial() {
    let study = pid_study();
    let rom = study.reduce(&RomRequest::new(ModeSelection::band(0.0, 100.0).unwrap())).unwrap_or_else(|e| panic!("{e}"));
    assert_same_roots(&rom.ordinary.eigenvalues, &roots(&PID.characteristic()), 1e-8);
    // Static gains from the polynomial: X/F = D(0)/P(0) = 0 (integral action), U/F =
    // N(0)/P(0) = B2/B2 = 1 (the controller takes the whole disturbance).
    let full = rom.static_gains.full.as_ref().unwrap();
    let reduced = rom.static_gains.rom.as_ref().unwrap();
    for g in [full, reduced] {
        assert!(g[(0, 0)].abs() < 1e-10, "x/F = {:e}", g[(0, 0)]);
        assert!((g[(1, 0)] - 1.0).abs() < 1e-8, "u/F = {}", g[(1, 0)]);
    }
    // The ROM's frequency responses against D/P and N/P at 0.3, 1 and 4 Hz, 1e-8 relative.
    let freqs = [0.3, 1.0, 4.0];
    for (h, f) in rom.ordinary.frequency_response(&freqs).iter().zip(freqs) {
        let (x, u) = PID.responses(c64::new(0.0, 2.0 * std::f64::consts::PI * f));
        for (got, want) in [(h[(0, 0)], x), (h[(1, 0)], u)] {
            assert!((got - want).norm() < 1e-8 * want.norm(), "{f} Hz: {got} vs {want}");
        }
    }
}

#[test]
fn butterworth_scalar_filter_has_its_poles_and_unit_dc_gain() {
    // The input manual's 2nd-order Butterworth at 1 Hz (§Scalar filter), its input a node
    // held at the port's force by a unit spring support: poles ωc (−1 ± j)/√2, DC gain 1.
    let m = read_model(&test_file("scalar_filter_butterworth.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let inputs = vec!["101:abstract".parse::<NodeInput>().unwrap()];
    let outputs = ["100:abstract", "102:abstract", "103:abstract"].map(|o| o.parse::<NodeOutput>().unwrap()).to_vec();
    let study = Study::builder(StudySource::model(m.model, m.problem)).node_ports(inputs, outputs).build().unwrap_or_else(|e| panic!("{e}"));
    let wc = 2.0 * std::f64::consts::PI;
    let pole = c64::new(-wc / 2f64.sqrt(), wc / 2f64.sqrt());
    let dynamic: Vec<c64> = study.modal().modes.iter().filter(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).map(|m| m.lambda).collect();
    // Three filters (the scalar filter, the same one as a state space SISO and as a MIMO).
    assert_same_roots(&dynamic, &[pole, pole.conj(), pole, pole.conj(), pole, pole.conj()], 1e-10);
    let rom = study.reduce(&RomRequest::new(ModeSelection::band(0.0, 10.0).unwrap())).unwrap_or_else(|e| panic!("{e}"));
    let g = rom.static_gains.rom.as_ref().unwrap();
    // The MIMO genel in descriptor form, `2 ẋ = 2 A x + 2 B u` (`matrix E`): the same poles.
    let text = std::fs::read_to_string(test_file("scalar_filter_butterworth.mbd")).unwrap();
    let mimo = "        matrix A, -sqrt(2.)*WC, -(WC^2), 1., 0.,\n        matrix B, 1., 0.,\n        matrix C, 0., WC^2;";
    assert!(text.contains(mimo));
    let descriptor = text.replace(mimo, "        matrix E, 2., 0., 0., 2.,\n        matrix A, -2.*sqrt(2.)*WC, -2.*(WC^2), 2., 0.,\n        matrix B, 2., 0.,\n        matrix C, 0., WC^2;");
    let m = common::mbdyn::read(&descriptor);
    let inputs = vec!["101:abstract".parse::<NodeInput>().unwrap()];
    let outputs = vec!["103:abstract".parse::<NodeOutput>().unwrap()];
    let e_study = Study::builder(StudySource::model(m.model, m.problem)).node_ports(inputs, outputs).build().unwrap_or_else(|e| panic!("{e}"));
    let dynamic: Vec<c64> = e_study.modal().modes.iter().filter(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).map(|m| m.lambda).collect();
    assert_same_roots(&dynamic, &[pole, pole.conj(), pole, pole.conj(), pole, pole.conj()], 1e-10);
    for out in 0..3 {
        assert!((g[(out, 0)] - 1.0).abs() < 1e-10, "DC gain of output {out}: {}", g[(out, 0)]);
    }
}

/// The closed form of the loop's response to a unit step of the disturbance `F`: `X/F =
/// D/P` and `U/F = N/P` in the controllable canonical realization of `1/P`, `x(t) = c_x
/// A⁻¹ (e^{At} − I) b` (nalgebra's matrix exponential).
fn pid_step_response(t: f64) -> (f64, f64) {
    let p = PID.characteristic();
    let a = nalgebra::DMatrix::from_fn(4, 4, |i, j| if i == 0 { -p[j + 1] / p[0] } else if i == j + 1 { 1.0 } else { 0.0 });
    let mut b = nalgebra::DVector::zeros(4);
    b[0] = 1.0 / p[0];
    // D(s) = s² + A1 s, N(s) = B0 s² + B1 s + B2 on the states [s³, s², s, 1]/P.
    let cx = nalgebra::RowDVector::from_row_slice(&[0.0, 1.0, PID.a1, 0.0]);
    let cu = nalgebra::RowDVector::from_row_slice(&[0.0, PID.b[0], PID.b[1], PID.b[2]]);
    let integral = a.clone().try_inverse().unwrap() * ((a * t).exp() - nalgebra::DMatrix::identity(4, 4)) * b;
    ((cx * &integral)[0], (cu * &integral)[0])
}

#[test]
fn pid_loop_step_response_follows_the_closed_form() {
    // examples/pid_mass.mbd with a 1 N disturbance step, integrated by romdyn (MBDyn's ms
    // method, ρ∞ = 0.6, h = 1 ms) to 0.5 s: position and control force against the closed
    // form; tolerance 1e-3 of the peak (the method's error, O(h²) on the slowest mode).
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pid_mass.mbd");
    let text = std::fs::read_to_string(&path).unwrap().replace("set: real F0 = 0.;", "set: real F0 = 1.;").replace("final time: 2.;", "final time: 0.5;");
    let m = common::mbdyn::read(&text);
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let st = &report.final_state;
    let first = Assembler::new(&m.model).dofs.scalar_first;
    let (x, u) = pid_step_response(st.t);
    let peak = (0..50).map(|k| pid_step_response(0.01 * k as f64).0.abs()).fold(0.0, f64::max);
    assert!((st.t - 0.5).abs() < 1e-12);
    assert!((st.y[first] - x).abs() < 1e-3 * peak, "x(0.5 s) = {:e}, closed form {x:e} (peak {peak:e})", st.y[first]);
    assert!((st.y[first + 1] - u).abs() < 1e-3, "u(0.5 s) = {}, closed form {u}", st.y[first + 1]);
}

#[test]
fn dof_and_node_drive_callers_read_scalar_nodes() {
    // An abstract force driven by 'dof' of a differential node's derivative and by 'node …
    // string "x"' of an algebraic node: its contribution is 2 ẋ₁ + 3 x₂ (MBDyn's DofDriveCaller
    // and the node's private data "x", "xP").
    let text = common::mbdyn::file(
        "abstract nodes: 3; forces: 2;",
        "abstract: 1, differential, value, 0.25, derivative, -0.5;\nabstract: 2, algebraic, value, 0.75;\nabstract: 3;",
        "force: 1, abstract, 3, abstract, dof, 1, abstract, differential, linear, 0., 2.;\nforce: 2, abstract, 3, abstract, node, 2, abstract, string, \"x\", linear, 0., 3.;",
    );
    let m = common::mbdyn::read(&text);
    let asm = Assembler::new(&m.model);
    let st = State::initial(&m.model, &asm.dofs);
    let f = asm.residual(&st, ConstraintForm::Plain, 1.0);
    // Residual `… − f` on node 3's equation.
    assert!((f[asm.dofs.scalar_first + 2] + (2.0 * -0.5 + 3.0 * 0.75)).abs() < 1e-15, "{f:?}");
    assert!(m.model.elements.iter().all(|e| e.reads_state()));
}

#[test]
fn unsupported_scalar_cards_are_refused_by_name_and_place() {
    // `file` puts control data on line 2, nodes from line 4, elements after `begin: elements;`.
    let refused = |control: &str, nodes: &str, elements: &str| -> String {
        let text = common::mbdyn::file(control, nodes, elements);
        match romdyn::input::mbdyn::parse_text(&text, Path::new("m.mbd")).and_then(|d| romdyn::input::mbdyn::build(&d)) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("accepted: {text}"),
        }
    };
    let nodes = "abstract: 1;\nabstract: 2, algebraic;";
    let cases = [
        (refused("abstract nodes: 2; thermal nodes: 1;", nodes, ""), "m.mbd:2:", "control data declares thermal nodes, which romdyn does not support"),
        (refused("abstract nodes: 3;", &format!("{nodes}\nthermal: 3;"), ""), "m.mbd:6:", "node type 'thermal' is not supported by romdyn"),
        (refused("abstract nodes: 2;", "abstract: 1;\nabstract: 2, algebraic, value, 1., derivative, 2.;", ""), "m.mbd:5:", "an algebraic node has no derivative"),
        (refused("abstract nodes: 2; electric elements: 1;", nodes, ""), "m.mbd:2:", "control data declares 1 electric elements, the model has 0"),
        (refused("abstract nodes: 2; electric elements: 1;", nodes, "electric: 1, resistor, 1, 2, 10.;"), "m.mbd:8:", "unknown electric element type 'resistor': MBDyn 1.7.3 has none either"),
        (refused("abstract nodes: 2;", "abstract: 1, differential, output, yes;\nabstract: 2;", ""), "m.mbd:4:", "MBDyn 1.7.3 reads a value whenever an argument follows the node type"),
        (refused("abstract nodes: 2; genels: 1;", nodes, "genel: 1, swashplate, 1;"), "m.mbd:8:", "genel type 'swashplate' is not supported by romdyn"),
        (refused("abstract nodes: 2; genels: 1;", nodes, "genel: 1, spring, 1, abstract, algebraic, 2, abstract, linear viscous, 1.;"), "m.mbd:8:", "only elastic constitutive laws are allowed"),
        (refused("abstract nodes: 2; genels: 1;", nodes, "genel: 1, spring support, 2, abstract, linear elastic, 1.;"), "m.mbd:8:", "the algebraic value of a differential node is required"),
        (refused("abstract nodes: 2; genels: 1;", nodes, "genel: 1, mass, 1, abstract, const, 1.;"), "m.mbd:8:", "the order of differential abstract node 1"),
        (refused("abstract nodes: 2; genels: 1;", nodes, "genel: 1, clamp, 2, abstract, algebraic, const, 1.;"), "m.mbd:8:", "abstract node 2 is algebraic"),
        (refused("abstract nodes: 2; genels: 1;", nodes, "genel: 1, clamp, 3, abstract, const, 1.;"), "m.mbd:8:", "abstract node 3 is not defined"),
        (refused("abstract nodes: 2; genels: 1;", nodes, "genel: 1, clamp, 1, structural, 1, algebraic, const, 1.;"), "m.mbd:8:", "a degree of freedom of a structural node is not supported by romdyn"),
        (refused("abstract nodes: 2; genels: 1;", nodes, "genel: 1, scalar filter, 2, abstract, drive, const, 1., 1, 1., 2, 1., 1., 1.;"), "m.mbd:8:", "the input order 2 exceeds the output order 1"),
        (refused("abstract nodes: 2; hydraulic nodes: 1;", &format!("{nodes}\nhydraulic: 2;"), ""), "m.mbd:6:", "MBDyn 1.7.3 refuses it (\"Abstract(2) already defined\""),
        (refused("abstract nodes: 3;", nodes, ""), "m.mbd:2:", "control data declares 3 abstract nodes, the model has 2"),
    ];
    for (message, place, expected) in cases {
        assert!(message.contains(place) && message.contains(expected), "expected '{place}' and '{expected}' in: {message}");
    }
}

/// Runs `text` (an MBDyn file) with romdyn and returns the final state's scalar node values
/// and derivatives, by node in file order.
fn final_scalars(text: &str) -> Vec<(f64, f64)> {
    let m = common::mbdyn::read(text);
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let first = Assembler::new(&m.model).dofs.scalar_first;
    (0..m.model.scalar_nodes.len()).map(|i| (report.final_state.y[first + i], report.final_state.yp[first + i])).collect()
}

#[test]
fn pid_loop_and_filters_run_as_mbdyn_1_7_3() {
    // MBDyn 1.7.3 (built from alex-marinov/mbdyn, `output precision: 15`) on
    // examples/pid_mass.mbd with F0 = 1 N: its .abs rows at t = 2.001 s (2001 steps, as
    // romdyn). romdyn agrees to 1.5e-10 of each node's scale over the whole run; here the
    // values to 1e-9 relative, node 1's derivative to 1e-8 (5e-10 left by the derivatives
    // phase decays through the ms method's derivative recurrence).
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pid_mass.mbd");
    let text = std::fs::read_to_string(&path).unwrap().replace("set: real F0 = 0.;", "set: real F0 = 1.;");
    let got = final_scalars(&text);
    let mbdyn = [(5.138952106512982e-04, -1.675533418822703e-03), (9.776215484637594e-01, -8.667848539175486e-02)];
    for (k, ((x, xp), (mx, mxp))) in got.iter().zip(mbdyn).enumerate() {
        assert!((x - mx).abs() < 1e-9 * mx.abs(), "node {}: {x:e} vs MBDyn {mx:e}", k + 1);
        assert!((xp - mxp).abs() < 1e-8 * mxp.abs(), "node {} derivative: {xp:e} vs MBDyn {mxp:e}", k + 1);
    }
    // tests/mbdyn_files/scalar_filter_butterworth.mbd (a 1 Hz unit sine into both filters):
    // MBDyn 1.7.3's outputs at t = 2.001 s, all three -7.071177425805828e-01 (the steady state's
    // -sin(2π t)/√2 lagging 90°, after the transient), to 1e-12.
    let text = std::fs::read_to_string(test_file("scalar_filter_butterworth.mbd")).unwrap();
    let got = final_scalars(&text);
    for k in [0, 2, 3] {
        assert!((got[k].0 - -7.071177425805828e-01).abs() < 1e-12, "output node {k}: {:e}", got[k].0);
    }
    assert!((got[1].0 - 6.283143964870634e-03).abs() < 1e-15, "input node: {:e}", got[1].0);
}

#[test]
fn mbdyn_eigenanalysis_of_the_loops_differs_only_by_its_state_space_jacobian() {
    // MBDyn 1.7.3's eigenanalysis at t = 0 (`eigenanalysis: 0., use lapack, output
    // eigenvectors`, dCoef 0.5 s), its .m file's alpha rows read as λ = (Λ − 1)/(dCoef (Λ + 1)):
    // - the Butterworth filters: ωc(−1 ± j)/√2 twice, as romdyn (7 printed digits: 1e-6);
    let mbdyn_filter = [c64::new(-4.442882944659381, 4.4428842104493365), c64::new(-4.442882944659381, -4.4428842104493365)];
    let wc = 2.0 * std::f64::consts::PI;
    for l in mbdyn_filter {
        assert!((l - c64::new(-wc / 2f64.sqrt(), l.im.signum() * wc / 2f64.sqrt())).norm() < 1e-6 * wc);
    }
    // - the PID loop: 2.08979 ± 22.2901j, −104.570, 0.190795, an unstable loop where its own
    //   run (and romdyn's, and the polynomial) is stable. They are the roots of the loop's
    //   polynomial with the filter's input column negated and its feedthrough left out,
    //   P̃ = (m s² + c s + k)(s² + A1 s) − (N(s) − B0 D(s)): genfilt.cc's
    //   `GenelStateSpaceSISO::AssJac` writes `+b dCoef` where the residual's derivative is
    //   `−b dCoef`, and no `−d` on the output row. Its residual is right, so its runs agree
    //   with romdyn's (`pid_loop_and_filters_run_as_mbdyn_1_7_3`); its linearization of a
    //   loop closed through a state-space genel with a dof input is not.
    let mbdyn_pid = [c64::new(2.089784612669962, 22.290082685212752), c64::new(2.0897988713475324, -22.29008121437997), c64::new(-104.57032523094162, 0.0), c64::new(0.19079540252484425, 0.0)];
    let flipped = [PID.m, PID.m * PID.a1 + PID.c, PID.c * PID.a1 + PID.k, PID.k * PID.a1 - (PID.b[1] - PID.b[0] * PID.a1), -PID.b[2]];
    assert_same_roots(&mbdyn_pid, &roots(&flipped), 2e-6);
    // romdyn's poles are the true polynomial's (above), not these.
    let study = pid_study();
    assert!(study.modal().modes.iter().all(|m| m.lambda.re < 0.0 || m.kind != romdyn::eigen::ModeKind::Dynamic));
}

#[test]
fn a_mass_genel_keeps_its_nodes_initial_derivative() {
    // tests/mbdyn_files/genel_mass_initial_rate.mbd: m = 3, F = 1.5, x(0) = .5, ẋ(0) = 2;
    // closed form x(1 s) = .5 + 2 + 1.5/(2 · 3) = 2.75, ẋ(1 s) = 2.5. The genel's own
    // unknown started at 0, so the derivatives phase set ẋ = 0 (x(1 s) was .75). MBDyn
    // 1.7.3 on the same file (.abs at t = 1 s): 2.7500000049935589, 2.5000000049939222.
    // 1e-8: the method's start-up error (5e-9 in both programs).
    let m = read_model(&test_file("genel_mass_initial_rate.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let (st, first) = (&report.final_state, Assembler::new(&m.model).dofs.scalar_first);
    assert!((st.t - 1.0).abs() < 1e-12);
    assert!((st.y[first] - 2.75).abs() < 1e-8, "x(1 s) = {}", st.y[first]);
    assert!((st.yp[first] - 2.5).abs() < 1e-8, "ẋ(1 s) = {}", st.yp[first]);
    assert!((st.y[first] - 2.7500000049935589).abs() < 1e-10, "x(1 s) = {}, MBDyn 2.7500000049935589", st.y[first]);
}
