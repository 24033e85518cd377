//! The paper's application (§8, issue 11): ports at points of bodies, dummy-spring removal
//! (eqs. 92–95), imposed motion and transmissibility (eqs. 96–100), each against a closed
//! form.

use crate::common;

use faer::c64;
use romdyn::dae::ports::{Direction, Excitation, InputPort, Measurement, OutputPort, Point, PortMap};
use romdyn::dae::{element_part, linearize_ports, Assembler, State};
use romdyn::element::{Anchor, DeformableDisplacement, DeformableHinge, Joint, LinearViscoelastic, RigidBody};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::linear::LinearDae;
use romdyn::model::{Model, ModelBuilder};
use romdyn::rom::{full_frequency_response, select_modes, transmissibility, with_spring_ports, without_elements, DescriptorRom, ModeSelection};
use romdyn::solve::{static_solution, NewtonSettings};

fn ground(label: u32) -> Anchor {
    Anchor::Node { label, offset: Vec3::zeros(), orientation: Mat3::identity() }
}

/// Every dynamic mode kept, nothing residualized.
fn rom_all(dae: &LinearDae) -> DescriptorRom {
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Lambda).unwrap();
    let sel = select_modes(&modal, &ModeSelection::Band { fmin_hz: 0.0, fmax_hz: 1e12 }).unwrap();
    DescriptorRom::project(dae, &modal, &sel, false).unwrap()
}

fn rotation(axis: Vec3, angle: f64) -> Mat3 {
    *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle).matrix()
}

/// Two free bodies with rotated frames, joined by a spring (ports only need a model).
fn two_bodies() -> (Model, State) {
    let mut b = ModelBuilder::new();
    b.dynamic_node(1, Vec3::new(0.1, -0.2, 0.3), rotation(Vec3::new(1.0, 2.0, 3.0), 0.7), Vec3::zeros(), Vec3::zeros())
        .dynamic_node(2, Vec3::new(1.0, 0.5, -0.4), rotation(Vec3::new(-1.0, 0.5, 2.0), 1.1), Vec3::zeros(), Vec3::zeros())
        .element(RigidBody::new(1, 1, 2.0, Vec3::zeros(), Mat3::identity()))
        .element(RigidBody::new(2, 2, 3.0, Vec3::zeros(), Mat3::identity()));
    let model = b.build().unwrap();
    let asm = Assembler::new(&model);
    let st = State::initial(&model, &asm.dofs);
    (model, st)
}

fn input(name: &str, excitation: Excitation) -> InputPort {
    InputPort { name: name.into(), excitation }
}
fn output(name: &str, measurement: Measurement) -> OutputPort {
    OutputPort { name: name.into(), measurement }
}

#[test]
fn a_point_force_is_the_node_force_plus_the_moment_of_its_offset() {
    let (model, st) = two_bodies();
    let ports = PortMap::new(&model, &st);
    let offset = Vec3::new(0.3, -0.7, 0.25);
    let d_node = Vec3::new(0.2, 1.0, -0.5);
    let r0 = model.nodes[1].orientation;
    let d = (r0 * d_node).normalize();
    let r = r0 * offset;
    let point = ports.input_column(&input("f", Excitation::Force { point: Point::offset(2, offset), direction: Direction::node(d_node) })).unwrap();
    let force = ports.input_column(&input("F", Excitation::Force { point: Point::node(2), direction: Direction::global(d) })).unwrap();
    let moment_dir = r.cross(&d);
    let moment = ports.input_column(&input("M", Excitation::Moment { node: 2, direction: Direction::global(moment_dir) })).unwrap();
    // Closed form: F at p = x + R f is F at x plus the moment (R f) × F; 1e-12 absolute on unit loads.
    for i in 0..point.len() {
        let expected = force[i] + moment_dir.norm() * moment[i];
        assert!((point[i] - expected).abs() < 1e-12, "row {i}: {} vs {expected}", point[i]);
    }
    // The same point given by its global position at the reference.
    let at = ports.input_column(&input("f", Excitation::Force { point: Point::at(2, model.nodes[1].position + r), direction: Direction::global(d) })).unwrap();
    assert!(point.iter().zip(&at).all(|(a, b)| (a - b).abs() < 1e-12));
}

#[test]
fn a_relative_sensor_is_the_difference_of_two_point_outputs_and_collocated_with_its_actuator() {
    let (model, st) = two_bodies();
    let ports = PortMap::new(&model, &st);
    let (pa, pb) = (Point::offset(1, Vec3::new(0.4, 0.1, -0.2)), Point::offset(2, Vec3::new(-0.3, 0.2, 0.6)));
    let d = Direction::global(Vec3::new(1.0, -2.0, 0.5));
    let rel = ports.output_row(&output("lvdt", Measurement::Relative { from: pa, to: pb, direction: d })).unwrap().c;
    let a = ports.output_row(&output("a", Measurement::Displacement { point: pa, direction: d })).unwrap().c;
    let b = ports.output_row(&output("b", Measurement::Displacement { point: pb, direction: d })).unwrap().c;
    // Exact: the relative displacement is p_b − p_a along d (1e-15 on unit directions).
    for j in 0..rel.len() {
        assert!((rel[j] - (b[j] - a[j])).abs() < 1e-15);
    }
    // Collocation: the actuator's B̃ column is the LVDT's C̃ row (equilibrium row of each
    // unknown: dynamic node rows 6..12 hold force/moment for unknowns 0..6).
    let act = ports.input_column(&input("act", Excitation::Actuator { from: pa, to: pb, direction: d })).unwrap();
    for node in 0..2 {
        for k in 0..6 {
            assert!((act[12 * node + 6 + k] - rel[12 * node + k]).abs() < 1e-15);
        }
    }
}

/// A mass m on a spring k and damper c to a base of mass mb, itself on soft dummy springs k0
/// to a clamped ground node; all nodes at the origin, so the directions decouple.
fn base_excited(m: f64, k: f64, c: f64, mb: f64, k0: f64) -> (Model, State) {
    let mut b = ModelBuilder::new();
    b.static_node(1, Vec3::zeros(), Mat3::identity())
        .dynamic_node(2, Vec3::zeros(), Mat3::identity(), Vec3::zeros(), Vec3::zeros())
        .dynamic_node(3, Vec3::zeros(), Mat3::identity(), Vec3::zeros(), Vec3::zeros())
        .element(Joint::clamp(1, 1, Vec3::zeros(), Mat3::identity()))
        .element(RigidBody::new(2, 2, mb, Vec3::zeros(), mb * Mat3::identity()))
        .element(RigidBody::new(3, 3, m, Vec3::zeros(), m * Mat3::identity()))
        .element(DeformableDisplacement { label: 10, a: ground(1), b: ground(2), law: LinearViscoelastic::isotropic(k0, 0.0), rest: Vec3::zeros() })
        .element(DeformableHinge { label: 11, a: ground(1), b: ground(2), law: LinearViscoelastic::isotropic(k0, 0.0) })
        .element(DeformableDisplacement { label: 12, a: ground(2), b: ground(3), law: LinearViscoelastic::isotropic(k, c), rest: Vec3::zeros() })
        .element(DeformableHinge { label: 13, a: ground(2), b: ground(3), law: LinearViscoelastic::isotropic(k, c) });
    let model = b.build().unwrap();
    let asm = Assembler::new(&model);
    let st = State::initial(&model, &asm.dofs);
    (model, st)
}

fn x_dir() -> Direction {
    Direction::global(Vec3::new(1.0, 0.0, 0.0))
}

#[test]
fn velocity_output_of_a_rom_is_j_omega_times_its_displacement() {
    let (model, st) = base_excited(2.0, 800.0, 3.0, 5.0, 50.0);
    let p = Point::offset(3, Vec3::new(0.0, 0.0, 0.0));
    let outputs = [output("x", Measurement::Displacement { point: p, direction: x_dir() }), output("v", Measurement::Velocity { point: p, direction: x_dir() })];
    let inputs = [input("F", Excitation::Force { point: Point::node(2), direction: x_dir() })];
    let dae = linearize_ports(&model, &st, &inputs, &outputs, None).unwrap();
    assert_eq!(dae.output_names[1], "v [m/s]");
    let rom = rom_all(&dae).to_ordinary().unwrap();
    let freqs = [0.5, 3.0, 20.0];
    let h = rom.frequency_response(&freqs);
    let full = full_frequency_response(&dae, &freqs);
    for (k, f) in freqs.iter().enumerate() {
        let jw = c64::new(0.0, 2.0 * std::f64::consts::PI * f);
        // v = jω x exactly for the ROM's own outputs (its C and D for v are C_v A, C_v B); 1e-9 relative.
        let (x, v) = (h[k][(0, 0)], h[k][(1, 0)]);
        assert!((v - jw * x).norm() < 1e-9 * v.norm(), "{f} Hz: {v} vs {}", jw * x);
        // ... and the full model's, with all modes kept: 1e-9.
        assert!((full[k][(1, 0)] - v).norm() < 1e-9 * v.norm());
    }
}

fn exact_t(m: f64, k: f64, c: f64, f: f64) -> c64 {
    let w = 2.0 * std::f64::consts::PI * f;
    c64::new(k, w * c) / c64::new(k - m * w * w, w * c)
}

#[test]
fn base_excited_mass_spring_damper_transmissibility_is_the_closed_form() {
    let (m, k, c) = (2.0, 800.0, 3.0);
    // Five frequencies around the resonance (3.18 Hz); far above it the modal sum that gives
    // T ~ 1/ω² cancels and rounding grows like (ω/ω₀)².
    let freqs = [0.3, 1.0, 2.0, 3.18, 6.0];
    let inputs = [input("Fb", Excitation::Force { point: Point::node(2), direction: x_dir() })];
    let outputs = [output("x", Measurement::Displacement { point: Point::node(3), direction: x_dir() }), output("xb", Measurement::Displacement { point: Point::node(2), direction: x_dir() })];
    let mut full_t = Vec::new();
    for (mb, k0) in [(5.0, 50.0), (40.0, 0.5)] {
        let (model, st) = base_excited(m, k, c, mb, k0);
        let dae = linearize_ports(&model, &st, &inputs, &outputs, None).unwrap();
        let rom = rom_all(&dae);
        let ordinary = rom.to_ordinary().unwrap();
        let imposed = ordinary.imposed_motion(1).unwrap();
        // The imposed-motion model has the fixed-base eigenvalues: −c/2m ± j sqrt(k/m − (c/2m)²).
        let (sigma, wd) = (-c / (2.0 * m), (k / m - (c / (2.0 * m)).powi(2)).sqrt());
        assert!(imposed.rom.eigenvalues.iter().any(|l| (l - c64::new(sigma, wd)).norm() < 1e-9 * wd), "{:?}", imposed.rom.eigenvalues);
        let h_rom = ordinary.frequency_response(&freqs);
        let h_ss = imposed.rom.frequency_response(&freqs);
        let h_full = full_frequency_response(&dae, &freqs);
        let mut row = Vec::new();
        for (i, f) in freqs.iter().enumerate() {
            let exact = exact_t(m, k, c, *f);
            // T(jω) = (k + jωc)/(k − mω² + jωc), eq. 100 from the ROM with all modes: 1e-9 relative.
            let t = transmissibility(&h_rom[i], 1).unwrap()[(0, 0)];
            assert!((t - exact).norm() < 1e-9 * exact.norm(), "ROM {f} Hz: {t} vs {exact}: {:.1e}", (t - exact).norm() / exact.norm());
            // ... the proper state-space model from the imposed displacement: 1e-9.
            let t = h_ss[i][(0, 0)];
            assert!((t - exact).norm() < 1e-9 * exact.norm(), "state space {f} Hz: {t} vs {exact}: {:.1e}", (t - exact).norm() / exact.norm());
            let t = transmissibility(&h_full[i], 1).unwrap()[(0, 0)];
            assert!((t - exact).norm() < 1e-9 * exact.norm(), "full {f} Hz: {t} vs {exact}: {:.1e}", (t - exact).norm() / exact.norm());
            row.push(t);
        }
        full_t.push(row);
    }
    // The transmissibility does not depend on the base mass and dummy springs (full model, 1e-9).
    for i in 0..freqs.len() {
        assert!((full_t[0][i] - full_t[1][i]).norm() < 1e-9 * full_t[0][i].norm());
    }
}

/// Eigenvalues of a corrected ROM, sorted by modulus.
fn eigenvalues_of(rom: &DescriptorRom) -> Vec<c64> {
    rom.eigenvalues.clone()
}

#[test]
fn removing_the_dummy_spring_of_two_masses_leaves_a_rigid_body_and_the_closed_form_pair() {
    let (m1, m2, k, k0) = (2.0, 8.0, 1000.0, 1.0);
    let mut b = ModelBuilder::new();
    b.static_node(1, Vec3::zeros(), Mat3::identity())
        .dynamic_node(2, Vec3::zeros(), Mat3::identity(), Vec3::zeros(), Vec3::zeros())
        .dynamic_node(3, Vec3::zeros(), Mat3::identity(), Vec3::zeros(), Vec3::zeros())
        .element(Joint::clamp(1, 1, Vec3::zeros(), Mat3::identity()))
        .element(RigidBody::new(2, 2, m1, Vec3::zeros(), Mat3::identity()))
        .element(RigidBody::new(3, 3, m2, Vec3::zeros(), Mat3::identity()))
        .element(DeformableDisplacement { label: 10, a: ground(1), b: ground(2), law: LinearViscoelastic::elastic(Mat3::from_diagonal(&Vec3::new(k0, 0.0, 0.0))), rest: Vec3::zeros() })
        .element(DeformableDisplacement { label: 11, a: ground(2), b: ground(3), law: LinearViscoelastic::elastic(Mat3::from_diagonal(&Vec3::new(k, 0.0, 0.0))), rest: Vec3::zeros() });
    let model = b.build().unwrap();
    let asm = Assembler::new(&model);
    let st = State::initial(&model, &asm.dofs);
    let inputs = [input("F2", Excitation::Force { point: Point::node(3), direction: x_dir() })];
    let outputs = [output("x2", Measurement::Displacement { point: Point::node(3), direction: x_dir() })];
    let dae = linearize_ports(&model, &st, &inputs, &outputs, None).unwrap();
    let part = element_part(&model, &st, 10).unwrap();
    assert_eq!(part.element, "deformable displacement joint 10");
    let (aug, fb) = with_spring_ports(&dae, std::slice::from_ref(&part));
    let grounded = rom_all(&aug);
    assert_eq!(grounded.eigenvalues.len(), 4, "two dynamic pairs with the dummy spring");
    let free = grounded.without_springs(&fb).unwrap();
    let eig = eigenvalues_of(&free);
    let w = (k * (m1 + m2) / (m1 * m2)).sqrt();
    // Closed form: a double zero (rigid body) and ±j sqrt(k (m1+m2)/(m1 m2)), 1e-6 relative to ω.
    assert!(eig[0].norm() < 1e-6 * w && eig[1].norm() < 1e-6 * w, "{eig:?}");
    assert!((eig[2] - c64::new(0.0, w)).norm() < 1e-6 * w && (eig[3] - c64::new(0.0, -w)).norm() < 1e-6 * w, "{eig:?}");
    // The full model with the spring's Jacobian contribution removed has the same pair.
    let modal = ModalAnalysis::compute(&without_elements(&dae, &[part.clone()]).jacobians, EigenRoute::Lambda).unwrap();
    let full: Vec<c64> = modal.of_kind(ModeKind::Dynamic).map(|i| modal.modes[i].lambda).collect();
    assert!(full.iter().any(|l| (l - eig[2]).norm() < 1e-6 * w), "{full:?}");
    // Eq. 95 as printed (A − B_e K C_e) doubles the dummy spring instead of removing it: the
    // ROM's low pair moves from the grounded one, by the factor that 2 k0 gives.
    let be = grounded.b.get(.., 1..).to_owned();
    let ce = grounded.c.get(1.., ..).to_owned();
    let mut printed = grounded.clone();
    printed.a = &grounded.a - &be * &fb.k * &ce;
    let low = |r: &DescriptorRom| {
        let o = r.to_ordinary().unwrap();
        o.a.eigenvalues().unwrap().iter().map(|l| l.norm()).fold(f64::INFINITY, f64::min)
    };
    // Two-mass chain on k0: the low eigenvalue for 2 k0 is the exact root of
    // m1 m2 ω⁴ − (K0 (m2) + k (m1 + m2)) ω² + K0 k = 0 with K0 = 2 k0 (1e-6 relative).
    let k2 = 2.0 * k0;
    let (a2, b2, c2) = (m1 * m2, -(k2 * m2 + k * (m1 + m2)), k2 * k);
    let w_low = ((-b2 - (b2 * b2 - 4.0 * a2 * c2).sqrt()) / (2.0 * a2)).sqrt();
    assert!((low(&printed) / w_low - 1.0).abs() < 1e-6, "{} vs {w_low}", low(&printed));
}

#[test]
fn removing_the_spring_of_an_inverted_pendulum_leaves_a_real_positive_eigenvalue() {
    // CASES C3 data: m = 1 kg, J = 0.001 kg m², L = 1 m, g = 9.81 m/s², upright; a torsional
    // spring kθ = 2 m g L makes it stable: λ² = −(kθ − m g L)/I_O; without it λ = ±sqrt(m g L/I_O).
    let (m, j, l, g) = (1.0, 0.001, 1.0, 9.81);
    let kt = 2.0 * m * g * l;
    let mut b = ModelBuilder::new();
    b.static_node(1, Vec3::zeros(), Mat3::identity())
        .dynamic_node(2, Vec3::new(0.0, l, 0.0), Mat3::identity(), Vec3::zeros(), Vec3::zeros())
        .element(Joint::clamp(1, 1, Vec3::zeros(), Mat3::identity()))
        .element(Joint::revolute_hinge(2, ground(1), Anchor::Node { label: 2, offset: Vec3::new(0.0, -l, 0.0), orientation: Mat3::identity() }))
        .element(RigidBody::new(3, 2, m, Vec3::zeros(), j * Mat3::identity()))
        .element(DeformableHinge { label: 4, a: ground(1), b: ground(2), law: LinearViscoelastic::isotropic(kt, 0.0) })
        .gravity(Vec3::new(0.0, -g, 0.0));
    let model = b.build().unwrap();
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    let inputs = [input("M", Excitation::Moment { node: 2, direction: Direction::global(Vec3::new(0.0, 0.0, 1.0)) })];
    let outputs = [output("theta", Measurement::Rotation { node: 2, direction: Direction::global(Vec3::new(0.0, 0.0, 1.0)) })];
    let dae = linearize_ports(&model, &st, &inputs, &outputs, None).unwrap();
    let part = element_part(&model, &st, 4).unwrap();
    let (aug, fb) = with_spring_ports(&dae, std::slice::from_ref(&part));
    let grounded = rom_all(&aug);
    let i_o = j + m * l * l;
    let w = ((kt - m * g * l) / i_o).sqrt();
    assert!(grounded.eigenvalues.iter().all(|e| (e.im.abs() - w).abs() < 1e-6 * w), "{:?}", grounded.eigenvalues);
    let free = grounded.without_springs(&fb).unwrap();
    let s = (m * g * l / i_o).sqrt();
    // Closed form (CASES C3): ±3.130527 rad/s, real, one unstable; 1e-6 relative.
    assert!((s - 3.130527).abs() < 1e-6);
    let eig = free.eigenvalues.clone();
    assert_eq!(eig.len(), 2);
    assert!(eig.iter().any(|e| (e - c64::new(s, 0.0)).norm() < 1e-6 * s) && eig.iter().any(|e| (e - c64::new(-s, 0.0)).norm() < 1e-6 * s), "{eig:?}");
    // The full model without the hinge's Jacobian: the same real pair.
    let modal = ModalAnalysis::compute(&without_elements(&dae, &[part]).jacobians, EigenRoute::Lambda).unwrap();
    assert!(modal.modes.iter().any(|md| (md.lambda - c64::new(s, 0.0)).norm() < 1e-6 * s), "{:?}", modal.modes.iter().map(|m| m.lambda).collect::<Vec<_>>());
}

#[test]
fn a_bad_ports_file_names_file_line_and_column_and_the_cli_takes_ports() {
    let dir = std::env::temp_dir().join(format!("romdyn-ports-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.json");
    std::fs::write(&bad, "{\n  \"outputs\": [\n    {\"type\": \"displacement\", \"node\": 3, \"direction\": [1, 0]}\n  ]\n}\n").unwrap();
    let exe = env!("CARGO_BIN_EXE_romdyn");
    let out = std::process::Command::new(exe).args(["eig", "examples/ham_sas.mbd", "--static", "--load-steps", "1", "--ports"]).arg(&bad).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    // serde_json's position of the short array: line 3.
    assert!(err.contains("bad.json:3:"), "{err}");
    // The HAM-SAS ports file labels the table modes in the modal table.
    let out = std::process::Command::new(exe).args(["eig", "examples/ham_sas.mbd", "--static", "--load-steps", "1", "--ports", "examples/ham_sas_ports.json"]).output().unwrap();
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(table.contains("table pitch (ry) 100 %"), "{table}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--remove-spring` from the command line: the inverted pendulum (CASES C3) held upright by a
/// torsional spring kθ = 2 m g L (a dummy spring, eq. 94); removing it gives the free model's
/// real pair ±sqrt(m g L / I_O) = ±3.130527 rad/s (closed form, CASES C3; printed to 6 digits).
#[test]
fn the_cli_removes_a_dummy_spring_and_prints_the_free_pendulums_real_pair() {
    let dir = common::cli::temp_dir("remove-spring");
    let text = common::cli::example_variant(
        "inverted_pendulum.mbd",
        &[
            ("    joints: 2;", "    joints: 3;"),
            ("    body: 3,", "    joint: 4, deformable hinge, 1, 2, linear elastic isotropic, 2. * M * 9.81 * L;\n    body: 3,"),
        ],
    );
    let file = common::cli::write_file(&dir, "held.mbd", &text);
    let mat = dir.join("free.mat");
    let mat_s = mat.to_string_lossy().into_owned();
    let args = ["rom", file.as_str(), "--static", "--input", "2:Mz", "--output", "2:rz", "--count", "1"];
    // With the spring: a stable pair at ±j sqrt((kθ − m g L)/I_O) = ±3.130527 j.
    // The report goes to stderr (stdout carries the ROM itself when there is no -o).
    let (ok, _, held) = common::cli::romdyn(&args);
    assert!(ok, "{held}");
    assert!(held.contains("±3.130527e0"), "{held}");
    let mut removed = args.to_vec();
    removed.extend(["--remove-spring", "4", "-o", mat_s.as_str()]);
    let (ok, _, free) = common::cli::romdyn(&removed);
    assert!(ok, "{free}");
    assert!(mat.exists());
    // Both signs of the real pair are the ROM's eigenvalues, the positive one called unstable,
    // each with the motion of the free model's mode (the pendulum's tip swinging in x).
    assert!(free.contains("deformable hinge 4"), "{free}");
    assert!(free.contains(" 3.130527e0 +0.000000e0j     0.498239 Hz   real, node 2 horizontal (x) 100 %, unstable"), "{free}");
    assert!(free.contains("-3.130527e0 +0.000000e0j     0.498239 Hz   real, node 2 horizontal (x) 100 %, stable\n"), "{free}");
    // A label that is not a spring is refused, naming it.
    let mut bad = args.to_vec();
    bad.extend(["--remove-spring", "3"]);
    let (ok, _, err) = common::cli::romdyn(&bad);
    assert!(!ok && err.contains("body 3") && err.contains("cannot be removed as a spring"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// MBDyn's `name, "…"` after a node label names the node in the modal table's label column
/// (issue 11: mode labels from the model file, a ports file's names take precedence). The
/// pendulum's mode is the bob's horizontal swing (closed form: ±j sqrt(g/L) = ±3.130527 j).
#[test]
fn node_names_from_the_mbdyn_file_label_the_modes() {
    let dir = common::cli::temp_dir("node-names");
    let text = common::cli::pendulum_variant(&[(common::cli::PENDULUM_NODE, "    structural: 2, name, \"bob\", dynamic, 0., -L, 0., eye, null, null;")]);
    let file = common::cli::write_file(&dir, "named.mbd", &text);
    let (ok, table, err) = common::cli::romdyn(&["eig", file.as_str()]);
    assert!(ok, "{err}");
    let row = table.lines().find(|l| l.contains("±3.130527e0")).unwrap_or_else(|| panic!("{table}"));
    assert!(row.contains("bob horizontal (x) 100 %"), "{table}");
    // Without names there is no label column.
    let (ok, plain, _) = common::cli::romdyn(&["eig", "examples/pendulum.mbd"]);
    assert!(ok && !plain.contains("label"), "{plain}");
    let _ = std::fs::remove_dir_all(&dir);
}
