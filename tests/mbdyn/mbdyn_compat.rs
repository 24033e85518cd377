//! Syntax real MBDyn files use that MBDyn 1.7.3's reader accepts (issue 12, point 1): each
//! construct is in a file of `tests/mbdyn_files/` written as MBDyn's own test files are, and
//! is read here against the same model in the current syntax (the construct replaced by its
//! documented equivalent: same residual at pseudo-random states, same problem), plus the
//! numbers the construct must produce (closed forms, stated next to each assertion). What
//! MBDyn's reader does is cited from its source (mbdyn/base, mbdyn/struct) per construct.

use crate::common;
use common::mbdyn::{read_test_file as read, test_file as path};

use common::mbdyn::rewritten_test_file as rewritten;

use std::path::Path;

use common::mbdyn::residual;
use common::cli::temp_dir;
use romdyn::analysis::{run, RunFiles};
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};
use romdyn::kinematics::Vec3;
use romdyn::model::{Method, OrientationOutput};

fn text(name: &str) -> String {
    std::fs::read_to_string(path(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The file's text with each `(old, new)` replaced; every `old` must occur (so a test cannot
/// pass by replacing nothing).

/// Same nodes, same residual at three noisy states and times (1e-12 relative), same problem.
fn assert_same(a: &MbdynModel, b: &MbdynModel) {
    assert_eq!(a.model.nodes.len(), b.model.nodes.len(), "node count");
    assert_eq!(a.model.elements.len(), b.model.elements.len(), "element count");
    for (seed, t) in [(7, 0.0), (11, 0.37), (13, 2.5)] {
        let (x, y) = (residual(&a.model, t, seed), residual(&b.model, t, seed));
        let scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for (i, (p, q)) in x.iter().zip(&y).enumerate() {
            assert!((p - q).abs() <= 1e-12 * scale, "t = {t}, equation {i}: {p} against {q}");
        }
    }
    assert_eq!(a.problem, b.problem);
}

#[test]
fn older_spellings_and_compatible_offsets_read_as_the_current_syntax() {
    // solver.cc (Solver::ReadData): `begin: multistep` and `problem: multistep` (mbdyn.cc)
    // are the initial value problem, `crank nicholson` is Crank-Nicolson, `fictitious steps
    // …` are the dummy steps, `newton raphson: true` is `nonlinear solver: newton raphson`.
    // joint.cc (MBDYN_X_COMPATIBLE_INPUT): pin and hinge offsets without `position`, `hinge`
    // for `orientation`. body.cc: `inertial, {node | R}` is the inertia's frame (R J Rᵀ:
    // diag(1, 2, 3)e-2 turned by π/2 about z is diag(2, 1, 3)e-2). dataman3.cc: `name, "…"`
    // after node and element labels; control data read twice keeps the later count.
    // tpldrive_impl.cc: `zero` is `null`. Input manual §Reference: the keywords of
    // `reference:` are optional. A string may span lines (parser.cc, GetStringWithDelims).
    let legacy = read("compat_pendulum.mbd");
    let modern = rewritten(
        "compat_pendulum.mbd",
        &[
            ("problem: multistep", "problem: initial value"),
            ("begin: multistep", "begin: initial value"),
            ("end: multistep", "end: initial value"),
            ("crank nicholson", "crank nicolson"),
            ("fictitious steps number: 0;", "dummy steps number: 0;"),
            ("newton raphson: true;", "nonlinear solver: newton raphson;"),
            ("\"a double pendulum\nin the older syntax\"", "\"a double pendulum\""),
            ("    joints: 1;\n", ""),
            ("    position, 0., 0., 0.,\n    orientation, euler123", "    0., 0., 0.,\n    euler123"),
            ("    velocity, null,\n    angular velocity, null;", "    null,\n    null;"),
            (", name, \"upper\"", ""),
            (", name, \"lower\"", ""),
            (", name, \"pivot\"", ""),
            (", name, \"bob\"", ""),
            ("revolute pin, 1, -1., 0., 0., hinge, eye, 0., 0., 0., hinge, eye", "revolute pin, 1, position, -1., 0., 0., orientation, eye, position, 0., 0., 0., orientation, eye"),
            ("revolute hinge, 1, 0.5, 0., 0., hinge, eye, 2, -0.5, 0., 0., hinge, eye", "revolute hinge, 1, position, 0.5, 0., 0., orientation, eye, 2, position, -0.5, 0., 0., orientation, eye"),
            (", inertial, node;", ";"),
            ("diag, 1.e-2, 2.e-2, 3.e-2, inertial, euler123, 0., 0., pi/2;", "diag, 2.e-2, 1.e-2, 3.e-2;"),
            ("position, null, zero;", "position, null, null;"),
        ],
    );
    assert_same(&legacy, &modern);
    assert_eq!(legacy.problem.method, Method::CrankNicolson);
    // Two bodies, two joints and the couple; node 1 at R_z(π/6) (1, 0, 0) from reference 10.
    assert_eq!(legacy.model.elements.len(), 5);
    let (c, s) = ((std::f64::consts::PI / 6.0).cos(), (std::f64::consts::PI / 6.0).sin());
    assert!((legacy.model.nodes[0].position - Vec3::new(c, s, 0.0)).norm() < 1e-15);
}

#[test]
fn spherical_hinge_and_pin_offsets_are_read_without_position() {
    // joint.cc reads both offsets of a spherical hinge and the node offset and the absolute
    // point of a spherical pin whether or not `position` precedes them.
    let legacy = read("compat_spherical.mbd");
    let modern = rewritten(
        "compat_spherical.mbd",
        &[
            ("spherical pin, 1, -0.5, 0., 0., 0., 0., 0.", "spherical pin, 1, position, -0.5, 0., 0., position, 0., 0., 0."),
            ("spherical hinge, 1, reference, node, 0.5, 0., 0., 2, reference, node, null", "spherical hinge, 1, position, reference, node, 0.5, 0., 0., 2, position, reference, node, null"),
        ],
    );
    assert_same(&legacy, &modern);
    // The rigid rotation about z at 1 rad/s keeps the pin and the hinge closed: after 10 steps
    // node 2 is still 1 m from the pin (|x₂| = 1 to the Newton tolerance).
    let report = run(&legacy.model, &legacy.problem, &mut ()).unwrap();
    let asm = romdyn::dae::Assembler::new(&legacy.model);
    let x2 = report.final_state.node_frame(&asm.dofs, 1).kin.x;
    assert!((x2.norm() - 1.0).abs() < 1e-8, "|x2| = {}", x2.norm());
}

#[test]
fn the_beam_card_is_beam3() {
    // MBDyn reads `beam:` with the three-node beam's reader (dataman4.cc, case BEAM/BEAM3).
    assert_same(&read("beam_card.mbd"), &rewritten("beam_card.mbd", &[("beam: 1,", "beam3: 1,")]));
}

#[test]
fn a_second_derivatives_tolerance_is_read_and_the_first_one_used() {
    let pair = read("derivatives_tolerance_pair.mbd");
    // MBDyn 1.7.3 itself rejects the second value ("invalid call to GetDescription"): later
    // versions read a residual and a solution tolerance; romdyn reads both, uses the first.
    assert_eq!(pair.problem.derivatives_tolerance, 1e-6);
    assert_same(&pair, &rewritten("derivatives_tolerance_pair.mbd", &[("derivatives tolerance: 1.e-6, 1.e-9;", "derivatives tolerance: 1.e-6;")]));
}

#[test]
fn use_automatic_differentiation_changes_nothing() {
    assert_same(&read("automatic_differentiation.mbd"), &rewritten("automatic_differentiation.mbd", &[("    use automatic differentiation;\n", "")]));
}

#[test]
fn dummy_nodes_and_output_flags_select_the_mov_rows() {
    let m = read("dummy_output.mbd");
    let out = m.problem.output.clone().unwrap();
    assert_eq!(out.every, 2);
    let labels: Vec<_> = out.nodes.iter().filter(|n| n.written).map(|n| n.label).collect();
    // default output: none; node 2 `output, yes`; 3 and 4 by `output: structural, range, 3, 4`;
    // node 5 `output, no` (dataman3.cc, DataManager::ReadNodes).
    assert_eq!(labels, [2, 3, 4]);
    assert_eq!(out.nodes[1].orientation, OrientationOutput::RotationVector);
    assert_eq!(out.nodes[3].orientation, OrientationOutput::Euler321Degrees);

    let dir = temp_dir("dummy-output");
    let prefix = dir.join("dummy_output");
    let mut files = RunFiles::create(&prefix, "dummy_output.mbd", &m.model, &m.problem).unwrap();
    let report = run(&m.model, &m.problem, &mut files).unwrap();
    files.finish(&report).unwrap();
    let mov = std::fs::read_to_string(dir.join("dummy_output.mov")).unwrap();
    let rows: Vec<Vec<f64>> = mov.lines().map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect()).collect();
    // Steps 0, 2, …, 10 (output frequency 2), three rows each, in file order.
    assert_eq!(rows.len(), 6 * 3);
    assert_eq!(rows.iter().map(|r| r[0] as u32).take(6).collect::<Vec<_>>(), [2, 3, 4, 2, 3, 4]);
    // Step 0 (closed form): node 2 at (1, 0, 0) turning at ω = 0.5 rad/s about z; node 3 at
    // (1.5, 0, 0) with v = ω × (1.5, 0, 0) = (0, 0.75, 0); node 4 at (1.5, 0.2, 0) with R_z(π/4)
    // R₃, Euler 3-2-1 angles (45°, 0, 0), v = ω × (1.5, 0.2, 0) = (−0.1, 0.75, 0).
    let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12);
    assert!(close(&rows[1][1..4], &[1.5, 0.0, 0.0]) && close(&rows[1][7..10], &[0.0, 0.75, 0.0]), "{:?}", rows[1]);
    assert!(close(&rows[2][1..7], &[1.5, 0.2, 0.0, 45.0, 0.0, 0.0]) && close(&rows[2][7..13], &[-0.1, 0.75, 0.0, 0.0, 0.0, 0.5]), "{:?}", rows[2]);
    // Later rows: node 3 stays 1.5 m from the hinge at the origin.
    for r in rows.iter().filter(|r| r[0] == 3.0) {
        assert!((Vec3::new(r[1], r[2], r[3]).norm() - 1.5).abs() < 1e-9, "{r:?}");
    }
}

/// `output precision: N` (dataman3.cc; output.cc writes scientific notation with N digits
/// after the point, 6 by default): the `.mov` numbers carry N digits; without it romdyn
/// writes 12; beyond 30 is refused naming the place.
#[test]
fn output_precision_sets_the_mov_digits() {
    let digits_of = |m: &MbdynModel, name: &str| {
        let dir = temp_dir(name);
        let prefix = dir.join("dummy_output");
        let mut files = RunFiles::create(&prefix, "dummy_output.mbd", &m.model, &m.problem).unwrap();
        let report = run(&m.model, &m.problem, &mut files).unwrap();
        files.finish(&report).unwrap();
        let mov = std::fs::read_to_string(dir.join("dummy_output.mov")).unwrap();
        let first = mov.split_whitespace().nth(1).unwrap().to_string();
        // "d.ddd…e±x": the digits between the point and the exponent.
        first.split(['e', 'E']).next().unwrap().split('.').nth(1).map_or(0, str::len)
    };
    assert_eq!(digits_of(&read("dummy_output.mbd"), "precision-default"), 12);
    let m = rewritten("dummy_output.mbd", &[("    output frequency: 2;\n", "    output frequency: 2;\n    output precision: 16;\n")]);
    assert_eq!(m.problem.output.as_ref().unwrap().precision, Some(16));
    assert_eq!(digits_of(&m, "precision-16"), 16);
    let t = text("dummy_output.mbd").replace("    output frequency: 2;\n", "    output frequency: 2;\n    output precision: 31;\n");
    let e = parse_text(&t, &path("dummy_output.mbd")).and_then(|d| build(&d)).err().expect("31 digits refused");
    assert!(e.to_string().contains("dummy_output.mbd:30:23") && e.to_string().contains("at most 30 digits, found 31"), "{e}");
}

#[test]
fn files_without_a_method_get_mbdyn_defaults() {
    // solver.cc (Solver::ReadData) and solver_impl.h: ms with ρ∞ = 0, tolerance 1e-6 on the
    // residual's 2-norm, at most 1 iteration, the same for the derivatives, derivatives
    // coefficient 1e-6 (times the time step).
    let m = rewritten("automatic_differentiation.mbd", &[("    method: ms, .6;\n    tolerance: 1.e-9;\n    max iterations: 10;\n", ""), ("    derivatives tolerance: 1.e-6;\n    derivatives max iterations: 10;\n", "")]);
    let p = &m.problem;
    assert_eq!((p.method, p.tolerance, p.max_iterations, p.derivatives_tolerance, p.derivatives_max_iterations, p.derivatives_coefficient), (Method::Ms { rho: 0.0 }, 1e-6, 1, 1e-6, 1, 1e-6));
    assert_eq!(p.residual_norm, romdyn::model::ResidualNorm::Euclidean);
}

/// Final positions [m] and velocities [m/s] (x, y, vx, vy) of the moving nodes after 1 s,
/// from MBDyn 1.7.3 (github:alex-marinov/mbdyn 1727489e, built with
/// shared/tools/build-mbdyn.sh) on the file named, with `output precision: 15;` added to
/// control data so that the .mov carries 16 digits (the physics is the file's).
const MBDYN_AFTER_1S: [(&str, &[[f64; 4]]); 3] = [
    ("default_pendulum.mbd", &[[-9.861388655041513e-01, -1.659220839496368e-01, -2.992003118115070e-01, 1.778368129224172e+00]]),
    (
        "default_double_pendulum.mbd",
        &[
            [-5.836155501578368e-01, -8.120301038840766e-01, -3.177552013625006e+00, 2.283732691968736e+00],
            [-1.443953624661910e+00, -1.321753948292666e+00, -3.851263704087549e+00, 3.420901574874445e+00],
        ],
    ),
    (
        "default_chain.mbd",
        &[
            [2.214041710103559e-01, -9.751821332752559e-01, -9.194557292597751e-01, -2.087549845787199e-01],
            [4.349673501842904e-01, -1.952111387879444e+00, -2.727784210194222e+00, -6.040539766494291e-01],
            [7.109461033631994e-01, -2.913275124084016e+00, -3.616970332056697e+00, -8.593833964772684e-01],
            [8.534739980919601e-01, -3.903065909666746e+00, -6.524487017942838e+00, -1.277916236495490e+00],
            [1.445937765093792e+00, -4.708663007967157e+00, -1.331813238000851e+01, -6.274621912321413e+00],
        ],
    ),
];

#[test]
fn without_a_method_line_the_trajectories_are_mbdyns() {
    // Issue 12 acceptance: 1e-6 relative to MBDyn after 1 s (the integrator's tolerance),
    // relative to the largest entry of each node's position and velocity.
    for (name, want) in MBDYN_AFTER_1S {
        let m = read(name);
        let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(report.steps, 1000);
        let asm = romdyn::dae::Assembler::new(&m.model);
        for (k, w) in want.iter().enumerate() {
            let kin = report.final_state.node_frame(&asm.dofs, k + 1).kin;
            let got = [kin.x[0], kin.x[1], kin.xdot[0], kin.xdot[1]];
            let (dx, dv) = ((got[0] - w[0]).hypot(got[1] - w[1]) / w[0].hypot(w[1]), (got[2] - w[2]).hypot(got[3] - w[3]) / w[2].hypot(w[3]));
            eprintln!("{name} node {}: position {dx:.1e}, velocity {dv:.1e} from MBDyn", k + 2);
            assert!(dx < 1e-6 && dv < 1e-6, "{name} node {}: romdyn {got:?}, MBDyn {w:?}", k + 2);
        }
    }
}

#[test]
fn scalar_drive_callers_push_free_masses_as_their_formulas_say() {
    // A unit mass from rest under f(t) moves x(1) = ∫₀¹ (1 − s) f(s) ds. Closed forms: string
    // "2.*Time": 1/3; double ramp (up to 0.5 at t = 0.5, back to 0 at 1): 1/8; exponential
    // 1 − e^(−2t): (1 − e⁻²)/4; array const 1 + time: 2/3; frequency sweep sin 2t:
    // 1/2 − sin(2)/4; mult time·time: 1/12; cubic t³: 1/20. MBDyn 1.7.3 (1727489e) on this
    // file (which sets output precision 15), .mov at t = 1 s.
    let e2 = (-2f64).exp();
    let cases: [(f64, f64); 7] = [
        (1.0 / 3.0, 3.333335312265706e-01),
        (0.125, 1.249999843789098e-01),
        ((1.0 - e2) / 4.0, 2.161661524270788e-01),
        (2.0 / 3.0, 6.666667666127852e-01),
        (0.5 - 2f64.sin() / 4.0, 2.726756253407116e-01),
        (1.0 / 12.0, 8.333353121875209e-02),
        (0.05, 5.000019789326103e-02),
    ];
    let m = read("scalar_drives.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = romdyn::dae::Assembler::new(&m.model);
    for (k, (exact, mbdyn)) in cases.iter().enumerate() {
        let x = report.final_state.node_frame(&asm.dofs, k).kin.x[0];
        eprintln!("node {}: x(1) = {x:.12e}, closed form {exact:.12e}, MBDyn {mbdyn:.12e}", k + 1);
        // Integration error of ms (ρ∞ = 0.6, h = 1 ms) on these smooth forces: below 1e-5
        // relative (4e-5 on the cubic's t³, whose start is the steepest relative to x).
        assert!((x - exact).abs() < 5e-5 * exact, "node {}: {x} against the closed form {exact}", k + 1);
        // Same method, same steps as MBDyn: to the Newton tolerance.
        assert!((x - mbdyn).abs() < 1e-8 * mbdyn.abs().max(1.0), "node {}: {x} against MBDyn {mbdyn}", k + 1);
    }
}

#[test]
fn a_string_drive_error_names_the_expression() {
    let t = text("scalar_drives.mbd").replace("\"2.*Time\"", "\"2.*Tme\"");
    let e = match parse_text(&t, &path("scalar_drives.mbd")).and_then(|d| build(&d)) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("an undefined name in a string drive must be an error"),
    };
    assert!(e.contains("scalar_drives.mbd:46:") && e.contains("string drive \"2.*Tme\""), "{e}");
}

#[test]
fn absolute_forces_act_in_the_global_frame_and_steps_are_counted_as_mbdyn_does() {
    // MBDyn 1.7.3 (1727489e) on absolute_force_direction.mbd: each node at x = 6.050001e-03 m,
    // y unchanged, after 11 steps (t = 0.11 s). Closed form for a unit force on a unit mass
    // from rest, x = t²/2 = 6.05e-3 m, plus what MBDyn's derivatives phase leaves (its
    // momenta are Newton's, p = dCoef·F with dCoef = 1e-6 h = 1e-8 s: the motion is as from
    // v = dCoef·a, which the first Crank–Nicolson step carries into x as h/2 of it):
    // x = t²/2 + dCoef (t − h/2) = 6.05105e-3 m, to 1e-11 (6e-12 measured: the Newton
    // tolerance, 1e-9 N).
    let m = read("absolute_force_direction.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    assert_eq!(report.steps, 11);
    let asm = romdyn::dae::Assembler::new(&m.model);
    let (t, h, dcoef) = (0.11, 0.01, 1e-8);
    for k in 0..3 {
        let x = report.final_state.node_frame(&asm.dofs, k).kin.x;
        // MBDyn prints 7 digits: 6.050001e-03 is within 5e-10 of its value.
        assert!((x[0] - (t * t / 2.0 + dcoef * (t - h / 2.0))).abs() < 1e-11 && (x[0] - 6.050001e-03).abs() < 5e-10, "node {}: {x:?}", k + 1);
        assert!((x[1] - k as f64).abs() < 1e-12, "node {}: {x:?}", k + 1);
    }
}

#[test]
fn a_deformable_hinge_through_large_rotations_follows_mbdyn() {
    // MBDyn 1.7.3 (1727489e) on deformable_hinge.mbd (output precision 15): node 2 after 1 s,
    // Euler 1-2-3 angles [deg] and angular velocity [rad/s]. Tolerance 1e-6 relative: the
    // Newton tolerance is 1e-10, the rotation reaches 100°.
    let angles = [-1.323475225362522e+01, 4.110035429228613e+00, 1.001665540446363e+02];
    let omega = [1.026512979338265e+00, -3.553228082602391e-01, -1.012633278987992e+00];
    let m = read("deformable_hinge.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = romdyn::dae::Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, 1).kin;
    let e = romdyn::kinematics::euler123(&kin.r).map(f64::to_degrees);
    for k in 0..3 {
        assert!((e[k] - angles[k]).abs() < 1e-6 * 100.0, "angle {k}: {} against MBDyn {}", e[k], angles[k]);
        assert!((kin.omega[k] - omega[k]).abs() < 1e-6 * 1.1, "ω {k}: {} against MBDyn {}", kin.omega[k], omega[k]);
    }
}

#[test]
fn the_derivatives_phase_keeps_the_velocities_written_and_reports_inconsistent_ones() {
    // MBDyn's derivatives phase holds positions and velocities (strnode.cc,
    // StructNode::DerivativesUpdate) and solves for the momenta's derivatives: a body in free
    // fall keeps v = (1, 0, 0) m/s exactly (romdyn's earlier phase gave it g·dCoef), its
    // momentum derivative is m g = (0, −2·9.81, 0) N.
    let text = "begin: data; problem: initial value; end: data;
        begin: initial value; initial time: 0.; final time: 0.; time step: 1.e-3; end: initial value;
        begin: control data; structural nodes: 1; rigid bodies: 1; gravity; end: control data;
        begin: nodes; structural: 1, dynamic, 0., 0., 0., eye, 1., 0., 0., null; end: nodes;
        begin: elements; body: 1, 1, 2., null, eye; gravity: uniform, 0., -1., 0., const, 9.81; end: elements;";
    let m = parse_text(text, Path::new("free_fall.mbd")).and_then(|d| build(&d)).unwrap();
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let st = &report.final_state;
    assert_eq!(&st.yp[0..3], &[1.0, 0.0, 0.0]);
    assert!((st.yp[7] + 2.0 * 9.81).abs() < 1e-12 && st.yp[6].abs() < 1e-12, "β' = {:?}", &st.yp[6..9]);
    assert!(report.inconsistent_velocity.is_none());

    // A pendulum bob given a radial velocity of 0.5 m/s violates its hinge at 0.5 m/s. MBDyn's
    // initial assembly removes it (MBDyn 1.7.3 on default_pendulum.mbd so changed: the .mov
    // at t = 0 has node 2's velocity 0, 0, 0); with `skip initial joint assembly` it is kept,
    // and reported.
    let edits = [("structural: 2, dynamic, 1., 0., 0., eye, null, null;", "structural: 2, dynamic, 1., 0., 0., eye, 0.5, 0., 0., null;"), ("    final time: 1.;", "    final time: 0.;")];
    let assembled = rewritten("default_pendulum.mbd", &edits);
    let report = run(&assembled.model, &assembled.problem, &mut ()).unwrap();
    let asm = romdyn::dae::Assembler::new(&assembled.model);
    assert!(report.inconsistent_velocity.is_none() && report.final_state.node_frame(&asm.dofs, 1).kin.xdot.norm() < 1e-15);
    let skip = [edits[0], edits[1], ("    gravity;\n", "    gravity;\n    skip initial joint assembly;\n")];
    let bad = rewritten("default_pendulum.mbd", &skip);
    let report = run(&bad.model, &bad.problem, &mut ()).unwrap();
    let (equation, rate) = report.inconsistent_velocity.clone().expect("the violation is reported");
    assert!((rate.abs() - 0.5).abs() < 1e-6, "{equation}: {rate}");
    assert_eq!(report.final_state.node_frame(&asm.dofs, 1).kin.xdot, Vec3::new(0.5, 0.0, 0.0));
}

#[test]
fn in_line_in_plane_and_prismatic_slide_as_the_closed_form_and_mbdyn() {
    // sliders.mbd: from rest under g = 9.81 m/s², after 1 s node 2 is g sin30°/2 = 2.4525 m
    // down the line (cos30°, 0, −sin30°), node 3 at (0, 5, 0) + (g − (g·n) n)/2 with
    // n = (0, sin30°, cos30°). MBDyn 1.7.3 (1727489e, output precision 15):
    // (2.123927307027063, 0, −1.226250002451271) and (0, 7.123927307027264, −1.226250002451388).
    let (s, c) = (0.5f64, 0.75f64.sqrt());
    let d = 9.81 * s / 2.0;
    let closed = [Vec3::new(d * c, 0.0, -d * s), Vec3::new(0.0, 5.0 + 9.81 * c * s / 2.0, -9.81 * (1.0 - c * c) / 2.0)];
    let mbdyn = [Vec3::new(2.123927307027063, 0.0, -1.226250002451271), Vec3::new(0.0, 7.123927307027264, -1.226250002451388)];
    let m = read("sliders.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = romdyn::dae::Assembler::new(&m.model);
    for k in 0..2 {
        let kin = report.final_state.node_frame(&asm.dofs, k + 1).kin;
        // The motion is a parabola in time, which ms integrates to rounding: 1e-9 m.
        assert!((kin.x - closed[k]).norm() < 1e-8, "node {}: {} against the closed form {}", k + 2, kin.x, closed[k]);
        assert!((kin.x - mbdyn[k]).norm() < 1e-8, "node {}: {} against MBDyn {}", k + 2, kin.x, mbdyn[k]);
        // Prismatic: no rotation.
        assert!((kin.r - romdyn::kinematics::Mat3::identity()).norm() < 1e-12);
    }
}

#[test]
fn a_conical_pendulum_on_a_distance_joint_keeps_its_circle() {
    // conical_pendulum.mbd: uniform circular motion at ω = sqrt(g/(L cos30°)) on the circle of
    // radius L sin30° at height −L cos30°: after 1 s at (0.5 cos ω, 0.5 sin ω, −cos30°).
    // MBDyn 1.7.3 (1727489e, output precision 15): (−4.875022163242603e-01,
    // −1.110926869790308e-01, −8.660254060815498e-01).
    let w = (9.81 / (std::f64::consts::PI / 6.0).cos()).sqrt();
    let closed = Vec3::new(0.5 * w.cos(), 0.5 * w.sin(), -(0.75f64).sqrt());
    let mbdyn = Vec3::new(-4.875022163242603e-01, -1.110926869790308e-01, -8.660254060815498e-01);
    let m = read("conical_pendulum.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = romdyn::dae::Assembler::new(&m.model);
    let x = report.final_state.node_frame(&asm.dofs, 1).kin.x;
    // The phase error of ms (ρ∞ = 0.6) at ω h = 3.4e-3 over 1 s: below 5e-6 m.
    assert!((x - closed).norm() < 5e-6, "{x} against the closed form {closed}");
    assert!((x - mbdyn).norm() < 1e-8, "{x} against MBDyn {mbdyn}");
    assert!((x.norm() - 1.0).abs() < 1e-9);
}

/// The 100-link pendulum chain of scripts/bench_vs_mbdyn.sh (nodes 0.1 m apart along x,
/// hinged about z, tolerance 1e-9, derivatives tolerance 1e-6 with at most 10 iterations),
/// stopped after the derivatives phase, with the derivatives coefficient line given.
fn chain_100_derivatives(coefficient: &str) -> MbdynModel {
    let mut t = String::from(
        "begin: data; problem: initial value; end: data;
        begin: initial value; initial time: 0.; final time: 1.; time step: 1.e-3; method: ms, .6;
        tolerance: 1.e-9; max iterations: 20; derivatives tolerance: 1.e-6; derivatives max iterations: 10;\n",
    );
    t += coefficient;
    t += "\nabort after: derivatives; end: initial value;
        begin: control data; structural nodes: 101; rigid bodies: 100; joints: 101; gravity; end: control data;
        begin: nodes; structural: 0, static, null, eye, null, null;\n";
    for i in 1..=100 {
        t += &format!("structural: {i}, dynamic, {:.1}, 0., 0., eye, null, null;\n", 0.1 * i as f64);
    }
    t += "end: nodes; begin: elements; joint: 0, clamp, 0, node, node;\n";
    for i in 1..=100 {
        t += &format!("body: {i}, {i}, 0.1, null, diag, 1.e-4, 1.e-4, 1.e-4;\njoint: {}, revolute hinge, {}, position, null, {i}, position, -0.1, 0., 0.;\n", 100 + i, i - 1);
    }
    t += "gravity: uniform, single, 0., -1., 0., const, 9.81; end: elements;";
    parse_text(&t, Path::new("chain_100.mbd")).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn derivatives_coefficient_auto_retries_as_mbdyn() {
    // MBDyn 1.7.3 on this file (scripts/bench_vs_mbdyn.sh's chain_100): at the coefficient
    // 1e-6 (dCoef 1e-9 s) the hinges' rounding, about 1.4e-15 m at x = 8.3 m, divided by
    // dCoef leaves a residual above 1e-6 and 10 iterations fail (romdyn's did too); with `auto` it prints
    // "Derivatives(1/13) t=0 coef=1e-05 tol=1e-06" and converges in 1 iteration with error
    // 4.42469e-07 (its .out). stepsol.cc DerivativeSolver::Advance: coef × 10 up to 6 times,
    // then coef / 10 up to 6 times.
    let sequence: Vec<f64> = romdyn::model::AutoCoefficient::default().sequence(1e-9).collect();
    let expected = [1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15];
    assert_eq!(sequence.len(), 13);
    assert!(sequence.iter().zip(expected).all(|(a, b)| (a - b).abs() <= 1e-12 * b), "{sequence:?}");

    // romdyn's derivatives phase judges the hinges' rows by their violation (tests/
    // derivatives_phase.rs), not by it divided by dCoef: at 1e-6 it converges in 1 iteration
    // where MBDyn 1.7.3 stops, so `auto` needs no retry.
    let fixed = chain_100_derivatives("derivatives coefficient: 1.e-6;");
    assert!(fixed.problem.derivatives_coefficient_auto.is_none());
    let report = run(&fixed.model, &fixed.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(report.derivatives_iterations, 1);

    let auto = chain_100_derivatives("derivatives coefficient: auto;");
    assert_eq!(auto.problem.derivatives_coefficient_auto, Some(romdyn::model::AutoCoefficient { retries: 6, factor: 10.0 }));
    let report = run(&auto.model, &auto.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(report.derivatives_iterations, 1, "MBDyn: 1 iteration at coef 1e-5; romdyn at its first, 1e-6");
    assert!(report.derivatives_tolerance_raised.is_none());

    let custom = chain_100_derivatives("derivatives coefficient: 1.e-7, auto, max iterations, 2, factor, 3.;");
    assert_eq!((custom.problem.derivatives_coefficient, custom.problem.derivatives_coefficient_auto), (1e-7, Some(romdyn::model::AutoCoefficient { retries: 2, factor: 3.0 })));
}

#[test]
fn a_total_pin_joints_ground_side_can_refer_to_its_node_as_the_other_node() {
    // joint.cc reads a total pin joint's absolute side with the node as the other side
    // (`GetPosRel(AbsRefFrame, RF, fn)`), so `reference, other node` is the node's frame (as
    // zanoni-mbdyn/blendyn's tests/bladeflap writes it; MBDyn 1.7.3 runs that file). Node 6
    // is at (0, -2, 0), turned by eye.
    let other = rewritten("driven_joints.mbd", &[("        position, 0., -2., 0.,\n        position constraint", "        position, reference, other node, null,\n        position constraint")]);
    assert_same(&read("driven_joints.mbd"), &other);
}

#[test]
fn a_chain_of_total_joints_takes_mbdyns_newton_iterations() {
    // tests/mbdyn_files/total_joint_chain.mbd: the benchmark's 10-link chain (ms 0.6, h = 1 ms,
    // tolerance 1e-9, derivatives coefficient auto) with total joints, whose position
    // constraint MBDyn states in node 1's frame as romdyn does. MBDyn 1.7.3 (1727489e) on this
    // file: 1 derivatives iteration, 1795 over the 1000 steps ("total iterations: 1796"), and
    // the final x, y, ẋ, ẏ of nodes 1–10 below (its .mov, output precision 16). On the
    // revolute-hinge file MBDyn takes 1508 where romdyn takes 1795: MBDyn's hinge reactions
    // are global and its ms predictor extrapolates them consistently with the momenta, a
    // reaction in a turning frame it does not; romdyn's joints are all of the second kind.
    // Tolerances: the positions and velocities to 1e-6 relative (issue 12's acceptance).
    // romdyn now takes 1771 iterations: its derivatives phase no longer turns the joints'
    // rounding-level violations at t = 0 into accelerations `Φ/c²` (tests/mbdyn/derivatives_phase.rs),
    // which MBDyn's does and which cost it 24 iterations in the first steps (romdyn's count
    // was MBDyn's 1795 before). The count to 1 % of 1771, and never above MBDyn's.
    let want: [[f64; 4]; 10] = [
        [-8.6540740162471874e-02, -5.0106888669452586e-02, 2.4842889544906790e-01, -4.2906979316987681e-01],
        [-1.8627732598513463e-01, -4.2853375835018533e-02, 2.2819244622744883e-01, -7.0724155938220046e-01],
        [-2.8158476677372596e-01, -1.2579761410418991e-02, 2.2348603380073995e-01, -7.2205789958233557e-01],
        [-3.7335716141251635e-01, 2.7142116468937934e-02, 3.2553530945492998e-01, -4.8628830807490714e-01],
        [-4.6444626531083133e-01, 6.8406812651050725e-02, 4.0516481474992161e-01, -3.1051368849779432e-01],
        [-5.6380172036286602e-01, 7.9742312260820625e-02, 4.1317193341564273e-01, -2.4033038192936765e-01],
        [-6.5711017649291159e-01, 4.3776606169777028e-02, 3.9187302992970841e-01, -1.8507392705741896e-01],
        [-7.3946838246827284e-01, -1.2943107409541493e-02, 3.5438205317465055e-01, -1.3063648550382614e-01],
        [-8.1253438829685154e-01, -8.1217251800065518e-02, 3.3873393715127781e-01, -1.1389012369466589e-01],
        [-8.6897045014719698e-01, -1.6377008895799741e-01, 3.4143555164025297e-01, -1.1573703955648694e-01],
    ];
    let m = read("total_joint_chain.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(report.steps, 1000);
    assert_eq!(report.derivatives_iterations, 1, "MBDyn 1.7.3: 1 derivatives iteration");
    let iterations = report.newton_iterations as f64;
    assert!((iterations - 1771.0).abs() <= 0.01 * 1771.0 && iterations <= 1795.0, "romdyn {iterations} Newton iterations, 1771 expected (MBDyn 1.7.3 1795)");
    let asm = romdyn::dae::Assembler::new(&m.model);
    for (k, w) in want.iter().enumerate() {
        let kin = report.final_state.node_frame(&asm.dofs, k + 1).kin;
        let (dx, dv) = ((kin.x[0] - w[0]).hypot(kin.x[1] - w[1]) / w[0].hypot(w[1]), (kin.xdot[0] - w[2]).hypot(kin.xdot[1] - w[3]) / w[2].hypot(w[3]));
        assert!(dx < 1e-6 && dv < 1e-6, "node {}: position {dx:.1e}, velocity {dv:.1e} from MBDyn", k + 1);
    }
}

#[test]
fn the_derivatives_phase_keeps_newtons_momenta_as_mbdyn_and_says_what_they_change() {
    // absolute_force_direction.mbd (unit forces on unit masses from rest, h = 10 ms, 11
    // steps) with `derivatives coefficient: 1.` (dCoef = h) and `derivatives tolerance:
    // 1e-1`. MBDyn 1.7.3 (1727489e) on that file: the derivatives phase converges in 1
    // iteration with error 0.0173205 (√3 · dCoef · 1 N: the momenta it keeps are Newton's,
    // dCoef F off m v = 0), and each node ends at x = 7.098438e-03 m (7 digits) instead of the
    // 6.05e-3 m of a start from rest: the motion is as from v = dCoef a = 1e-2 m/s. romdyn
    // reports that change of the written velocity (larger than the tolerance, 1e-9).
    let m = rewritten(
        "absolute_force_direction.mbd",
        &[("derivatives max iterations: 10;", "derivatives max iterations: 10; derivatives coefficient: 1.;"), ("derivatives tolerance: 1e-6;", "derivatives tolerance: 1e-1;")],
    );
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((report.steps, report.derivatives_iterations), (11, 1));
    let asm = romdyn::dae::Assembler::new(&m.model);
    for k in 0..3 {
        let x = report.final_state.node_frame(&asm.dofs, k).kin.x;
        // MBDyn's 7 digits: within 5e-10.
        assert!((x[0] - 7.098438e-03).abs() < 5e-10, "node {}: {x:?} against MBDyn 7.098438e-03", k + 1);
    }
    let (velocity, change) = report.momentum_velocity_change.clone().expect("the velocity change is reported");
    // dCoef · F / m = 1e-2 m/s along x, to rounding.
    assert!(velocity.ends_with("velocity x") && (change - 1e-2).abs() < 1e-12, "{velocity}: {change}");
}

#[test]
fn where_mbdyns_momenta_leave_the_derivatives_above_the_tolerance_romdyn_sets_them_and_says_so() {
    // absolute_force_direction.mbd with `derivatives coefficient: 1.` (dCoef = h = 10 ms) and
    // its derivatives tolerance 1e-6: the momenta Newton leaves are dCoef·F = 1e-2 kg m/s off
    // m v, above the tolerance (MBDyn 1.7.3 stops on this file: "An error occurred during the
    // execution of MBDyn"). romdyn then sets them from their definitions, converges, starts
    // from rest (x = t²/2 = 6.05e-3 m after 0.11 s, closed form, to the Newton tolerance) and
    // reports MBDyn's way's failure.
    let m = rewritten("absolute_force_direction.mbd", &[("derivatives max iterations: 10;", "derivatives max iterations: 10; derivatives coefficient: 1.;")]);
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let failure = report.mbdyn_momenta_failure.clone().expect("MBDyn's momenta do not converge here");
    assert!(failure.contains("linear momentum x definition (1.000e-2)"), "{failure}");
    assert!(report.momentum_velocity_change.is_none(), "{:?}", report.momentum_velocity_change);
    let asm = romdyn::dae::Assembler::new(&m.model);
    for k in 0..3 {
        let x = report.final_state.node_frame(&asm.dofs, k).kin.x;
        assert!((x[0] - 6.05e-3).abs() < 1e-12, "node {}: {x:?}", k + 1);
    }
}

/// A one-body model whose initial value block carries `cards`, read.
fn with_newton_cards(cards: &str) -> Result<bool, String> {
    let text = format!("begin: data; problem: initial value; end: data;\nbegin: initial value; initial time: 0.; final time: 0.01; time step: 1.e-3;\n{cards}\nend: initial value;\nbegin: control data; structural nodes: 1; rigid bodies: 1; end: control data;\nbegin: nodes; structural: 1, dynamic, null, eye, null, null; end: nodes;\nbegin: elements; body: 1, 1, 1., null, eye; end: elements;\n");
    parse_text(&text, Path::new("m.mbd")).and_then(|d| build(&d)).map(|m| m.problem.modified_newton).map_err(|e| e.to_string())
}

/// MBDyn's `nonlinear solver` card and its deprecated spelling, every form MBDyn 1.7.3 reads
/// (input manual, "Nonlinear Solver": `newton raphson [, {true | modified, ITERATIONS [, keep
/// jacobian matrix] [, honor element requests]}]`, the same after `line search`; solver.cc,
/// `Solver::ReadData`: also `keep jacobian`, and the deprecated `newton raphson: {true |
/// modified [, ITERATIONS]}`): romdyn keeps a factorization while the residual falls fast
/// exactly when MBDyn would run its modified Newton; full Newton otherwise, as MBDyn, and
/// the last card read decides (both set MBDyn's one `bTrueNewtonRaphson`).
#[test]
fn the_nonlinear_solver_card_chooses_modified_newton() {
    let with = |card: &str| with_newton_cards(card).unwrap_or_else(|e| panic!("{card}: {e}"));
    assert!(!with(""));
    assert!(!with("nonlinear solver: newton raphson;"));
    assert!(!with("nonlinear solver: newton raphson, true;"));
    assert!(with("nonlinear solver: newton raphson, modified, 4;"));
    assert!(with("nonlinear solver: newton raphson, modified, 4, keep jacobian matrix;"));
    assert!(with("nonlinear solver: newton raphson, modified, 5, keep jacobian;"));
    assert!(with("nonlinear solver: newton raphson, modified, 5, honor element requests;"));
    assert!(with("nonlinear solver: newton raphson, modified, 5, keep jacobian matrix, honor element requests;"));
    assert!(!with("nonlinear solver: line search;"));
    assert!(!with("nonlinear solver: line search, abort at lambda min, no, verbose, yes;"));
    assert!(with("nonlinear solver: line search, modified, 3, keep jacobian matrix, lambda min, 1e-1;"));
    // The deprecated spelling (MBDyn: "Newton Raphson is deprecated"), ITERATIONS optional.
    assert!(with("newton raphson: modified, 4;"));
    assert!(with("newton raphson: modified;"));
    assert!(!with("newton raphson: true;"));
    // The last card wins; `default` and `matrix free` leave the kind as it was.
    assert!(!with("newton raphson: modified, 4; nonlinear solver: newton raphson;"));
    assert!(with("nonlinear solver: newton raphson; newton raphson: modified, 1;"));
    assert!(with("newton raphson: modified, 4; nonlinear solver: default;"));
}

/// A Newton card MBDyn would refuse, or whose word it does not know, is an error at the
/// argument, saying what was expected (MBDyn reads ITERATIONS with `GetInt` after
/// `modified`, and warns and runs full Newton after an unknown word in the deprecated card:
/// romdyn asks for one it knows rather than guess).
#[test]
fn a_bad_newton_card_is_refused_where_it_is_wrong() {
    for (card, at, expected) in [
        ("nonlinear solver: newton raphson, modified;", "m.mbd:3:", "the iterations one Jacobian matrix is reused for"),
        ("nonlinear solver: newton raphson, modified, 2.5;", "m.mbd:3:45", "a whole number"),
        ("nonlinear solver: newton raphson, modified, -1;", "m.mbd:3:45", "cannot be negative"),
        ("nonlinear solver: newton raphson, modified, 4, keep everything;", "m.mbd:3:48", "unexpected extra argument"),
        ("nonlinear solver: broyden;", "m.mbd:3:19", "the nonlinear solver (newton raphson, line search, default, matrix free)"),
        ("newton raphson: sometimes;", "m.mbd:3:17", "the Newton-Raphson kind (true, modified)"),
    ] {
        let e = with_newton_cards(card).expect_err(card);
        assert!(e.contains(at) && e.contains(expected), "{card}: {e}");
    }
}
