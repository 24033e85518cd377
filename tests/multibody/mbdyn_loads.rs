//! Loads of issue 12, point 3: forces and couples between two nodes (`absolute internal`,
//! `follower internal`, `total internal`), central gravity, viscous and viscoelastic rods
//! and scalar functions (cards, drive caller, `scalar function elastic` rods), against MBDyn 1.7.3 and closed forms, and their Jacobians against finite
//! differences.
//!
//! MBDyn numbers: MBDyn 1.7.3 (built from github:alex-marinov/mbdyn with
//! shared/tools/build-mbdyn.sh), `mbdyn -f FILE -o out` on the file named, with `output
//! precision: 15;` added to control data.

use crate::common::mbdyn::{read_test_file as read, test_file as path};

use romdyn::analysis::{check_model_jacobians, run, Reference, JACOBIAN_CHECK_TOLERANCE};
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};
use romdyn::kinematics::euler123;

/// Position, Euler 1-2-3 angles [deg], velocity and angular velocity of every node after
/// the file's run, as MBDyn's .mov writes them.
fn final_rows(m: &MbdynModel) -> Vec<[f64; 12]> {
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    (0..m.model.nodes.len())
        .map(|i| {
            let k = report.final_state.node_frame(&asm.dofs, i).kin;
            let e = euler123(&k.r).map(f64::to_degrees);
            [k.x[0], k.x[1], k.x[2], e[0], e[1], e[2], k.xdot[0], k.xdot[1], k.xdot[2], k.omega[0], k.omega[1], k.omega[2]]
        })
        .collect()
}

#[test]
fn internal_forces_and_couples_move_the_bodies_as_in_mbdyn() {
    // MBDyn 1.7.3, internal_forces.mbd, .mov at t = 1 s, nodes 1–4.
    let mbdyn: [[f64; 12]; 4] = [
        [5.000000009995000e-01, 2.500000004997500e-01, 0.0, -2.051282785599113e+01, -6.247980456559010e+00, 9.589339651523066e+01, 1.000000001000019e+00, 5.000000005000096e-01, 0.0, -3.175293787441749e-01, 2.762650459479987e-01, 2.384060998714109e+00],
        [7.499999995002978e-01, -1.250000002498750e-01, 0.0, 4.943655818942214e+01, 6.405936240373462e+01, -2.423414214257299e+01, -5.000000005000096e-01, -2.500000002500048e-01, 0.0, 1.044802001146971e+00, 2.063025250312728e+00, -8.243175347753362e-01],
        [1.326851889089348e-02, 9.920796426928061e-01, 1.131773902494702e-01, 3.754521928451062e+01, -4.279358055173351e+01, -1.288462883728870e+02, 7.443058666996372e-02, 6.245930071014583e-02, 4.755531212267115e-02, 2.543862243597073e+00, 7.977117530257652e-01, -3.706860069736000e+00],
        [-1.990277833634732e-02, 1.188053596076791e-02, 8.302339146251349e-01, -6.260836620559234e+01, -3.784822478121868e+01, -5.054181887344076e+01, -1.116458800050850e-01, -9.368895106574013e-02, -7.133296818479683e-02, -3.141998063584825e+00, -2.032977043682765e+00, 9.500349377002519e-01],
    ];
    let got = final_rows(&read("internal_forces.mbd"));
    for (k, (g, w)) in got.iter().zip(&mbdyn).enumerate() {
        for j in 0..12 {
            // 1e-7 relative to the row's largest entry of that kind (MBDyn's derivatives
            // phase leaves velocities 1e-9 off, and the steps' tolerance is 1e-9).
            let scale = w[j / 3 * 3..j / 3 * 3 + 3].iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert!((g[j] - w[j]).abs() < 1e-7 * scale, "node {} entry {j}: romdyn {g:?}, MBDyn {w:?}", k + 1);
        }
    }
}

#[test]
fn the_total_internal_force_pushes_along_its_line_and_its_couple_spins() {
    // Closed forms (constant loads from rest, no rotation of the force's frame): node 3
    // (1.5 kg) moves F t²/(2 m) with F = √2 (1, −1, 0) N, node 2 (2 kg) the opposite way;
    // node 4 (J_zz = 0.2) spins up at M/J = 1.5 rad/s², node 5 (J_zz = 0.4) at −0.75.
    let got = final_rows(&read("total_internal_force.mbd"));
    let r = 2f64.sqrt();
    let want_x = [[1.0 - r / 4.0, r / 4.0], [r / 3.0, 1.0 - r / 3.0]];
    for k in 0..2 {
        assert!((got[k][0] - want_x[k][0]).abs() < 1e-12 && (got[k][1] - want_x[k][1]).abs() < 1e-12, "node {}: {:?}", k + 2, got[k]);
        assert!(got[k][5].abs() < 1e-9, "no moment on the line of the force: {:?}", got[k]);
    }
    assert!((got[2][11] - 1.5).abs() < 1e-12 && (got[3][11] + 0.75).abs() < 1e-12, "{:?} {:?}", got[2], got[3]);
    // Angles ½ α t²: 0.75 rad and −0.375 rad; the integrator's rotation error is 4e-8 rad.
    assert!((got[2][5].to_radians() - 0.75).abs() < 1e-7 && (got[3][5].to_radians() + 0.375).abs() < 1e-7, "{:?} {:?}", got[2], got[3]);
}

#[test]
fn internal_force_jacobians_agree_with_finite_differences() {
    // At t = 0.5 s, where every node has turned: each element's J(c) against central
    // differences of its residual (romdyn check's tolerance, 1e-6).
    for name in ["internal_forces.mbd", "total_internal_force.mbd"] {
        let m = read(name);
        let check = check_model_jacobians(&m.model, &m.problem, Reference::At(0.5), JACOBIAN_CHECK_TOLERANCE).unwrap_or_else(|e| panic!("{e}"));
        assert!(check.passed(), "{name}:\n{}", check.to_text());
        let forces = check.elements.iter().filter(|e| e.element.contains("internal")).count();
        assert_eq!(forces, if name == "internal_forces.mbd" { 4 } else { 2 }, "{}", check.to_text());
    }
}

#[test]
fn a_total_force_on_one_node_is_refused_as_mbdyn_refuses_it() {
    // MBDyn 1.7.3 (force.cc, ReadForce) builds a total force only between two nodes.
    let text = std::fs::read_to_string(path("total_internal_force.mbd")).unwrap().replace("force: 1, total internal, 3,", "force: 1, total, 3,");
    let e = parse_text(&text, &path("total_internal_force.mbd")).and_then(|d| build(&d)).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("total_internal_force.mbd:") && e.contains("'total' (on one node) is not implemented by MBDyn 1.7.3"), "{e}");
}

#[test]
fn satellites_of_a_central_mass_keep_their_circular_orbits_as_in_mbdyn() {
    let m = read("central_gravity.mbd");
    let got = final_rows(&m);
    // MBDyn 1.7.3, central_gravity.mbd, .mov at its last step (t = 6.01 s: MBDyn's step
    // count), nodes 1 and 2: position and velocity.
    let mbdyn = [
        [1.818638607165426e-01, 9.998346112118742e+00, 0.0, -2.582950386237261e+00, 4.698230264946786e-02, 0.0],
        [1.043550258534162e+01, 0.0, 1.706166127342225e+01, 1.558347173539495e+00, 0.0, -9.531390716429995e-01],
    ];
    let gm = 1e12 * 6.67384e-11;
    for (k, (radius, w)) in [(10.0f64, &mbdyn[0]), (20.0, &mbdyn[1])].into_iter().enumerate() {
        let g = got[k];
        let (x, v) = ([g[0], g[1], g[2]], [g[6], g[7], g[8]]);
        for j in 0..3 {
            // 1e-8 of the radius and of the orbital speed.
            assert!((x[j] - w[j]).abs() < 1e-8 * radius && (v[j] - w[3 + j]).abs() < 1e-8 * (gm / radius).sqrt(), "node {}: {g:?} against MBDyn {w:?}", k + 1);
        }
        // Closed form: the circle at ω = sqrt(G M / r³); the step of 10 ms (ω h = 2.6e-3
        // and 9e-4) leaves a phase error below 2e-6 of the radius.
        let phase = (gm / radius.powi(3)).sqrt() * 6.01;
        let want = if k == 0 { [radius * phase.cos(), radius * phase.sin(), 0.0] } else { [radius * phase.sin(), 0.0, radius * phase.cos()] };
        for j in 0..3 {
            assert!((x[j] - want[j]).abs() < 2e-6 * radius, "node {}: {x:?} against the circle {want:?}", k + 1);
        }
    }
    let check = check_model_jacobians(&m.model, &m.problem, Reference::At(3.0), JACOBIAN_CHECK_TOLERANCE).unwrap_or_else(|e| panic!("{e}"));
    assert!(check.passed() && check.elements.iter().filter(|e| e.element.contains("central gravity")).count() == 2, "{}", check.to_text());
}

#[test]
fn viscous_and_viscoelastic_rods_damp_as_the_oscillator_and_as_mbdyn() {
    let m = read("viscous_rods.mbd");
    let got = final_rows(&m);
    // MBDyn 1.7.3, viscous_rods.mbd, .mov at t = 1 s, nodes 2, 4 and 5 (all 12 columns).
    let mbdyn: [[f64; 12]; 3] = [
        [9.663124060681888e-01, 0.0, 0.0, 0.0, 0.0, 0.0, 1.853208890589248e-01, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3.057433499983126e-01, -2.671156434994701e-02, 1.686957749319286e+00, -1.916267996212133e+01, -2.227481948907115e+01, 5.479859976838198e+01, 3.292842940988197e-01, -1.363888748485297e-02, 3.180109982861405e-01, -3.339859027816979e-02, 1.745770994028593e-01, 1.020020804578551e+00],
        [1.055477504376590e+00, -7.399869449510532e-03, 1.990788644723363e+00, 5.380848452000251e-01, -5.099761448585273e-01, 4.857603137181466e+01, 9.342601578572135e-02, -1.374296043504009e-02, -7.392545401655829e-03, 7.019141846169343e-03, -8.040372387673597e-03, 1.070629102345544e-01],
    ];
    for (k, w) in mbdyn.iter().enumerate() {
        let g = &got[k + 1];
        for j in 0..12 {
            // 1e-7 relative to the largest entry of that kind (measured 1e-9).
            let scale = w[j / 3 * 3..j / 3 * 3 + 3].iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert!((g[j] - w[j]).abs() < 1e-7 * scale, "row {k} entry {j}: romdyn {g:?}, MBDyn {w:?}");
        }
    }
    // Node 2: the damped oscillator x − 1 = 0.1 e^{−ζωt} (cos ω_d t + ζ/√(1−ζ²) sin ω_d t),
    // ω = √(EA/(m L₀)) = 10 rad/s, ζ = C/(2 m L₀ ω) = 0.1, at t = 1 s: 0.96631483 m,
    // 0.18534571 m/s; the 1 ms step's phase error (ω h)² ω t/12 leaves 3e-6 m and 3e-5 m/s.
    assert!((got[1][0] - 0.9663148319409587).abs() < 5e-6 && (got[1][6] - 0.18534570698460584).abs() < 5e-5, "{:?}", got[1]);
    let check = check_model_jacobians(&m.model, &m.problem, Reference::At(0.5), JACOBIAN_CHECK_TOLERANCE).unwrap_or_else(|e| panic!("{e}"));
    assert!(check.passed() && check.elements.iter().filter(|e| e.element.starts_with("rod")).count() == 3, "{}", check.to_text());
}

#[test]
fn scalar_functions_drive_a_force_and_make_a_rod_law_as_in_mbdyn() {
    let m = read("scalar_functions.mbd");
    let got = final_rows(&m);
    // MBDyn 1.7.3, scalar_functions.mbd, .mov at t = 1 s: node 2's x and ẋ (the
    // multilinear rod), node 3's x and ẋ, node 4's z and ż, node 5's y and ẏ (the cubic
    // spline: the same to 13 digits).
    let mbdyn = [
        (1, 0, 9.246313752732457e-01, 9.033477102924566e+00),
        (2, 0, 4.424745664906943e-01, 1.192474530966040e+00),
        (3, 2, 3.333333830604273e-01, 8.333332346367369e-01),
        (4, 1, 1.543438740505890e+01, 5.701209519101053e-01),
    ];
    for (k, j, x, v) in mbdyn {
        // 1e-7 (measured 1e-8: the rod law's kinks at the breakpoints).
        assert!((got[k][j] - x).abs() < 1e-7 && (got[k][6 + j] - v).abs() < 1e-7, "node {}: {:?} against MBDyn {x}, {v}", k + 1, got[k]);
    }
    // Closed forms for the pushed unit masses from rest, x(1) = ∫₀¹ (1 − s) f(s) ds and
    // ẋ(1) = ∫₀¹ f: f = 0.5 eˢ + s² gives 0.5 (e − 2) + 1/12 and 0.5 (e − 1) + 1/3; the
    // chebychev series 1 + 0.5 ξ − 0.25 (2ξ² − 1), ξ = s − 1, is 0.25 + 1.5 s − 0.5 s²:
    // 1/3 and 5/6. The 1 ms step's error, of order h² f''/12, is 3e-7 on the first (measured
    // 3.2e-7 and 2.8e-7) and 1e-7 on the second (measured 5e-8 and 1e-7).
    let e = std::f64::consts::E;
    assert!((got[2][0] - (0.5 * (e - 2.0) + 1.0 / 12.0)).abs() < 1e-6 && (got[2][6] - (0.5 * (e - 1.0) + 1.0 / 3.0)).abs() < 1e-6, "{:?}", got[2]);
    assert!((got[3][2] - 1.0 / 3.0).abs() < 1e-6 && (got[3][8] - 5.0 / 6.0).abs() < 1e-6, "{:?}", got[3]);
    let check = check_model_jacobians(&m.model, &m.problem, Reference::At(0.5), JACOBIAN_CHECK_TOLERANCE).unwrap_or_else(|e| panic!("{e}"));
    assert!(check.passed(), "{}", check.to_text());
}

#[test]
fn scalar_function_cards_are_checked_as_mbdyn_checks_them() {
    let base = std::fs::read_to_string(path("scalar_functions.mbd")).unwrap();
    for (old, new, want) in [
        ("-.5, -70.,\n    0., 0.,", "-.5, -70.,\n    -.5, 0.,", "multilinear scalar function: the x values must increase, found -0.5 then -0.5"),
        ("\"push\", sum, \"half exp\"", "\"push\", sum, \"half exps\"", "scalar function \"half exps\" is not defined"),
        ("\"spring\", multilinear,\n    -1., -100.,\n    -.5, -70.,", "\"spring\", cubic spline,\n    -1., -100.,\n    -1., -70.,", "cubic spline scalar function: the x values must increase, found -1 then -1"),
        ("scalar function: \"half exp\", exp, .5;", "scalar function: \"half exp\", log, base, -2., .5;", "log scalar function: the base must be positive, found -2"),
    ] {
        assert!(base.contains(old), "{old}");
        let e = parse_text(&base.replace(old, new), &path("scalar_functions.mbd")).and_then(|d| build(&d)).map(|_| ()).unwrap_err().to_string();
        assert!(e.contains("scalar_functions.mbd:") && e.contains(want), "{e}");
    }
}

/// scalar_functions.mbd with force 3's drive replaced by a string drive.
fn with_push_drive(expression: &str) -> Result<MbdynModel, romdyn::input::mbdyn::MbdynError> {
    let base = std::fs::read_to_string(path("scalar_functions.mbd")).unwrap_or_default();
    let old = "scalar function, \"push\";";
    assert!(base.contains(old));
    parse_text(&base.replace(old, &format!("string, \"{expression}\";")), &path("scalar_functions.mbd")).and_then(|d| build(&d))
}

#[test]
fn string_drives_call_scalar_functions_through_model_sf() {
    // modelns.cc: `model::sf::NAME(x [, order])` is the scalar function card's value (order
    // 0) or derivative (order 1). As a string drive, `model::sf::push(Time)` is the
    // `scalar function, "push"` drive: the same final state to round-off.
    let card = final_rows(&read("scalar_functions.mbd"));
    let string = final_rows(&with_push_drive("model::sf::push(Time)").unwrap_or_else(|e| panic!("{e}")));
    for (a, b) in card.iter().zip(&string) {
        assert!(a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12), "{a:?} against {b:?}");
    }
    // The derivative of 0.5 eᵗ + t² less 0.5 eᵗ is 2 t: from rest x(1) = 1/3 m, ẋ(1) = 1 m/s
    // (the 1 ms step's error is 2e-7 m). MBDyn 1.7.3 on that file, .mov at t = 1 s:
    // node 3 x = 3.333335312265708e-01 m (romdyn: the same to 1e-13).
    let got = final_rows(&with_push_drive("model::sf::push(Time, 1) - exp(Time)/2.").unwrap_or_else(|e| panic!("{e}")));
    assert!((got[2][0] - 1.0 / 3.0).abs() < 3e-7 && (got[2][6] - 1.0).abs() < 1e-6, "{:?}", got[2]);
    assert!((got[2][0] - 3.333335312265708e-01).abs() < 1e-10, "{:?}", got[2]);
    // MBDyn 1.7.3 has no top-level `sf` namespace ("unable to find namespace \"sf\"").
    for (expression, want) in [
        ("sf::push(Time)", "unknown namespace 'sf'"),
        ("model::sf::pull(Time)", "model::sf::pull: scalar function \"pull\" is not defined before this drive"),
        ("model::sf::push(Time, 2)", "model::sf::push: the derivative order must be 0 or 1"),
    ] {
        let e = with_push_drive(expression).map(|_| ()).unwrap_err().to_string();
        assert!(e.contains("scalar_functions.mbd:") && e.contains(want), "{expression}: {e}");
    }
}

#[test]
fn time_varying_gravity_drops_the_bodies_as_its_integral_and_as_mbdyn() {
    let m = read("driven_gravity.mbd");
    let got = final_rows(&m);
    for (k, g) in got.iter().enumerate() {
        // Closed form: g_z = −2 t from rest gives z(1) = −1/3 m, ż(1) = −1 m/s; the step of
        // 1 ms leaves 6.7e-7 m (the position's integration error, as for an applied force
        // with the same ramp: MBDyn 1.7.3 on that force gives romdyn's −3.333339992500e-1).
        assert!((g[2] + 1.0 / 3.0).abs() < 1e-6 && (g[8] + 1.0).abs() < 1e-9, "node {}: {g:?}", k + 1);
        // No rotation: the weight acts at the centre of mass, the node's moment S × g is
        // balanced by the inertia about the node.
        assert!(g[3..6].iter().all(|a| a.abs() < 1e-9), "node {} turned: {g:?}", k + 1);
        // MBDyn 1.7.3, driven_gravity.mbd, .mov at t = 1 s: z = −3.333325009999893e-01,
        // ż = −9.999984999999654e-01 for both nodes. MBDyn's bodies read the field that the
        // gravity element stored in its own residual (gravity.cc, UniformGravity::AssRes),
        // one evaluation late: its first step sees g(0) = 0 (ż(h) = 0 where g gives −h²),
        // which leaves 1.5e-6 m/s after 1 s. romdyn evaluates g at the step's time, as
        // MBDyn evaluates a force's drive.
        assert!((g[2] + 3.333325009999893e-01).abs() < 2e-6 && (g[8] + 9.999984999999654e-01).abs() < 2e-6, "node {}: {g:?}", k + 1);
    }
    let check = check_model_jacobians(&m.model, &m.problem, Reference::At(0.5), JACOBIAN_CHECK_TOLERANCE).unwrap_or_else(|e| panic!("{e}"));
    assert!(check.passed() && check.elements.iter().filter(|e| e.element.contains("driven uniform gravity")).count() == 2, "{}", check.to_text());
}
