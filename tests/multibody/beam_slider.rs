//! MBDyn's `beam slider` (issue 12, point 3): its analytic Jacobian against central finite
//! differences of its residual (both constraint forms, on and between beams, inside and
//! across the finite volumes and their smearing zones), a bead sliding down a rigid chain
//! of two beams against the closed form and MBDyn 1.7.3, a bead on a parabola whose
//! linearization gives `sqrt(g/R)`, and the reader's refusals.

use crate::common;
use common::mbdyn::test_file as path;

use common::fixtures::Noise;
use romdyn::analysis::run;
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::element::{BeamSlider, SliderBeam, SliderKind};
use romdyn::input::mbdyn::{build, parse_text, read_model};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::model::ConstraintForm;
use romdyn::model::{Model, ModelBuilder};

/// A slider on node 10 along two beams (nodes 1–3, 3–5) through random, slightly curved
/// positions with random orientations and offsets.
fn slider_model(form: ConstraintForm, kind: SliderKind, smearing: f64) -> Model {
    let mut n = Noise(777);
    let mut b = ModelBuilder::new();
    for k in 1..=5u32 {
        let x = Vec3::new(k as f64, 0.0, 0.0) + 0.2 * n.vec();
        if k == 1 {
            b.static_node(k, x, n.rotation());
        } else {
            b.dynamic_node(k, x, n.rotation(), n.vec(), n.vec());
        }
    }
    b.dynamic_node(10, Vec3::new(2.0, 0.3, 0.1), n.rotation(), n.vec(), n.vec());
    let mut offsets = || [0.1 * n.vec(), 0.1 * n.vec(), 0.1 * n.vec()];
    let (first, mut second) = (offsets(), offsets());
    second[0] = first[2];
    let beams = vec![SliderBeam { nodes: [1, 2, 3], offsets: first }, SliderBeam { nodes: [3, 4, 5], offsets: second }];
    let mut n = Noise(31);
    b.boxed_element(Box::new(BeamSlider { label: 7, node: 10, offset: 0.1 * n.vec(), orientation: n.rotation(), kind, beams, initial: 0.0, smearing, start_rate: None }));
    b.constraint_form(form);
    b.build().unwrap()
}

#[test]
fn beam_slider_jacobians_match_finite_differences() {
    // Abscissas S (beam 1 on [−1, 1], beam 2 on [1, 3]): node 1's, node 2's and node 3's
    // volumes, both smearing zones (|s ∓ 1/√3| < .1) on each beam, beyond the chain's end;
    // each at least 1e-3 from a boundary, where the residual is only continuous.
    let cases = [(SliderKind::Classic, 0.1, vec![-0.9, -0.6, 0.2, 0.55, 0.8, 1.45, 2.5, 3.3]), (SliderKind::Spherical, 0.0, vec![-0.7, 0.2, 1.9, 2.7])];
    for (kind, smearing, abscissas) in cases {
        for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
            let model = slider_model(form, kind, smearing);
            let asm = Assembler::new(&model);
            let s = asm.dofs.element_first[0];
            for &abscissa in &abscissas {
                let mut st = State::initial(&model, &asm.dofs);
                let mut n = Noise(99);
                st.t = 0.3;
                for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
                    *x += 0.05 * n.next();
                }
                // Forces and moments of a few newtons, the abscissa where asked.
                for k in s + 1..asm.dofs.len {
                    st.y[k] = 3.0 * n.next();
                }
                st.y[s] = abscissa;
                for w in check_jacobians(&asm, &st, 0.37, form) {
                    assert!(w.relative_error < 1e-6, "{kind:?} {form:?} S = {abscissa}: {} d({})/d({}): analytic {:e}, fd {:e} (error {:e})", w.element, w.equation, w.unknown, w.analytic, w.finite_difference, w.relative_error);
                }
            }
        }
    }
}

#[test]
fn beads_slide_down_a_rigid_chain_as_the_closed_form_and_mbdyn() {
    // beam_slider.mbd at t = 1 s: s(t) = v₀ t + g sin(A) t²/2 along d = (cos A, 0, −sin A),
    // A = 30°, from node 1 (v₀ = 1 m/s) and from node 5 (v₀ = −4 m/s, s₀ = 4 m).
    // MBDyn 1.7.3 (1727489e, the same file), .mov: node 10 at (2.989952710811544e+00, 0,
    // −1.726250002451296e+00) m, Euler 1-2-3 (3.224437610009478e+01, 2.602678541837146e+01,
    // −1.547190040401684e+01) deg, ω = (4.330127018922084e-01, −3.6e-13,
    // −2.499999999999584e-01) rad/s; node 20 at (2.123927307027076e+00, 0,
    // −1.226250002451279e+00) m; .jnt: the force on slider 10 (4.247854605099204e+00, 0,
    // 7.357499999197253e+00) N, clamp 3 (−1.489929186766352e+00, 0, −2.580633051159100e+00)
    // N and clamp 4 (−7.005780039245499e+00, 0, −1.213436697462509e+01) N.
    let m = read_model(&path("beam_slider.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    assert!(report.inconsistent_velocity.is_none(), "{:?}", report.inconsistent_velocity);
    let asm = Assembler::new(&m.model);
    let st = &report.final_state;
    let kin = |label: u32| st.node_frame(&asm.dofs, m.model.node_index(label).unwrap()).kin;
    let (a, g) = (std::f64::consts::PI / 6.0, 9.81);
    let d = Vec3::new(a.cos(), 0.0, -a.sin());
    let s = |s0: f64, v0: f64| s0 + v0 + g * a.sin() / 2.0;
    // ms integrates constant accelerations exactly; the derivatives phase, as MBDyn's, keeps
    // Newton's momenta p = p(v) + dCoef ṗ (stepsol.cc), which starts the beads 2.5e-9 m/s off
    // along z (dCoef g): 2.5e-9 m/s and 2.5e-9 m after 1 s, so 5e-9 against the closed form.
    for (label, s0, v0) in [(10, 0.0, 1.0), (20, 4.0, -4.0)] {
        assert!((kin(label).x - s(s0, v0) * d).norm() < 5e-9, "node {label} at {} against {}", kin(label).x, s(s0, v0) * d);
        assert!((kin(label).xdot - (v0 + g * a.sin()) * d).norm() < 5e-9, "node {label} velocity {}", kin(label).xdot);
    }
    // MBDyn's positions are the same 2.5e-9 m lower along z (its derivatives phase, which
    // romdyn's follows): 1e-11 m.
    let mbdyn10 = Vec3::new(2.989952710811544e+00, 0.0, -1.726250002451296e+00);
    let mbdyn20 = Vec3::new(2.123927307027076e+00, 0.0, -1.226250002451279e+00);
    assert!((kin(10).x - mbdyn10).norm() < 1e-11 && (kin(20).x - mbdyn20).norm() < 1e-11, "{} {} against MBDyn", kin(10).x, kin(20).x);
    // The classic slider keeps its axis 1 along the line and spins at .5 rad/s about it:
    // turned by .5 rad about d from its initial frame (axis 1 along d), within the 6e-9 rad
    // that ms makes integrating the orientation parameters over 1000 steps (1e-8).
    let r0 = Mat3::from_columns(&[d, Vec3::y(), d.cross(&Vec3::y())]);
    let turned = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(d), 0.5).into_inner() * r0;
    assert!((kin(10).r - turned).norm() < 1e-8, "node 10 frame {} against {}", kin(10).r, turned);
    assert!((kin(10).omega - 0.5 * d).norm() < 1e-9, "ω = {}", kin(10).omega);
    let euler = romdyn::kinematics::euler123(&kin(10).r).map(f64::to_degrees);
    let mbdyn_euler = Vec3::new(3.224437610009478e+01, 2.602678541837146e+01, -1.547190040401684e+01);
    assert!((euler - mbdyn_euler).norm() < 1e-8, "Euler {euler} against MBDyn {mbdyn_euler}");

    // Reactions: each bead's weight across the line, m g cos A = 8.4957 N along the normal
    // n = (sin A, 0, cos A), taken by the clamp of the node whose finite volume holds the
    // bead: node 4 for bead 10 (s = .4525 on beam 2); bead 20 (s = −.5475, .0298 from the
    // boundary −1/√3, smearing .1) shares its reaction between nodes 3 and 4 with weights
    // .5 ∓ (1/√3 + s)/(2 · .1) = .35075, .64925.
    let normal = Vec3::new(a.sin(), 0.0, a.cos());
    let weight = g * a.cos();
    let element = |t: &str, label: u32| (0..m.model.elements.len()).find(|&e| m.model.elements[e].type_name() == t && m.model.elements[e].label() == label).unwrap();
    let force = |e: usize| Vec3::from_fn(|i, _| st.y[asm.dofs.element_first[e] + 1 + i]);
    // The multipliers hold to Newton's tolerance on the momentum rows over dCoef: 1.3e-8 N
    // for slider 20 (MBDyn's 2.7e-8 N); 1e-7 N.
    for label in [10, 20] {
        assert!((force(element("beam slider", label)) - weight * normal).norm() < 1e-7, "slider {label} force {}", force(element("beam slider", label)));
    }
    let w3 = 0.5 - (1.0 / 3f64.sqrt() + (s(4.0, -4.0) - 3.0)) / 0.2;
    let clamp = |label: u32| {
        let e = element("clamp", label);
        r0 * Vec3::from_fn(|i, _| st.y[asm.dofs.element_first[e] + i])
    };
    // The clamp's multiplier is its residual's force, −(reaction on the node) = MBDyn's .jnt.
    // The derivatives phase's dCoef offset (above) puts bead 20's abscissa 4.9e-9 past the
    // exact one, as MBDyn's (.jnt: 1.452500004902558), which moves the smeared shares by
    // 5 × 4.9e-9 × 8.5 N = 2.1e-7 N: 5e-7 N against the closed form.
    assert!((clamp(3) + w3 * weight * normal).norm() < 5e-7, "clamp 3 {}", clamp(3));
    assert!((clamp(4) + (2.0 - w3) * weight * normal).norm() < 5e-7, "clamp 4 {}", clamp(4));
    let mbdyn3 = Vec3::new(-1.489929186766352e+00, 0.0, -2.580633051159100e+00);
    let mbdyn4 = Vec3::new(-7.005780039245499e+00, 0.0, -1.213436697462509e+01);
    // Against MBDyn, whose abscissa romdyn's now follows: 2.6e-8 N measured (2e-9 relative),
    // where Newton stops within its tolerance: it was 3.4e-9 N when romdyn's initial
    // assembly set the abscissa's rate (2379 Newton iterations over the run, now 2249 with
    // the slider left out of the assembly as MBDyn's); 5e-8 N.
    assert!((clamp(3) - mbdyn3).norm() < 5e-8 && (clamp(4) - mbdyn4).norm() < 5e-8, "clamps {} {} against MBDyn", clamp(3), clamp(4));
}

#[test]
fn a_bead_on_a_parabola_oscillates_at_sqrt_g_over_r() {
    // beam_slider_parabola.mbd: the linearization at rest on z = x²/(2R), R = 1 m: the one
    // dynamic pair ±j sqrt(g/R) = ±3.1320919526731650j rad/s (closed form of a point mass on
    // a curve of curvature 1/R), through the slider's abscissa (a coordinate: its rows in
    // F_ẏ and F_y as positions).
    let m = read_model(&path("beam_slider_parabola.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let eig = &report.eigenanalyses[0];
    assert_eq!(eig.dynamic.len(), 2, "{:?}", eig.dynamic);
    let omega = 9.81f64.sqrt();
    for l in &eig.dynamic {
        assert!(l.re.abs() < 1e-9 && (l.im.abs() - omega).abs() < 1e-9 * omega, "λ = {l}, sqrt(g/R) = {omega}");
    }
}

#[test]
fn beam_slider_cards_romdyn_cannot_honour_are_refused_by_name() {
    let text = std::fs::read_to_string(path("beam_slider.mbd")).unwrap();
    let card = "        type, classic,\n        2,";
    assert!(text.contains(card));
    let cases = [
        (card.replace("classic", "spline"), "'spline' is not supported"),
        (card.replace("2,", "2,\n            3, null, null, null,"), "beam 3 is not defined"),
        (text.replace("            2, same, null, null,\n        initial beam, 1,", "            2, same, null, null,\n        initial beam, 1, friction,"), "friction"),
        (card.replace("2,", "0,"), "at least one beam"),
    ];
    for (changed, expected) in cases {
        let t = if changed.contains("begin: data") { changed } else { text.replace(card, &changed) };
        let err = parse_text(&t, &path("beam_slider.mbd")).and_then(|d| build(&d)).err().unwrap_or_else(|| panic!("accepted, expected {expected}"));
        assert!(err.to_string().contains(expected), "{err}");
    }
    // Beam 2 must continue beam 1 (its node 1 is beam 1's node 3) with the same offset.
    let t = text.replace("            2, same, null, null,\n        initial beam, 1,", "            2, 0., 0., .1, null, null,\n        initial beam, 1,");
    let err = parse_text(&t, &path("beam_slider.mbd")).and_then(|d| build(&d)).err().unwrap();
    assert!(err.to_string().contains("differs from that of node 3"), "{err}");
}

#[test]
fn a_slider_written_off_its_initial_node_and_off_the_line_starts_at_the_nearest_point() {
    // beam_slider.mbd with bead 10 written .5 m down the line and 1 mm below it, its
    // `initial node` still 1: romdyn starts its abscissa at the nearest point of the line,
    // s = .5 m (MBDyn's derivatives phase solves for it from the initial node on), and its
    // initial assembly puts the node on the line (MBDyn's beam slider takes no part in
    // MBDyn's assembly). Then s(1) = .5 + v₀ + g sin(A)/2 = 3.9525 m, as the closed form.
    let text = std::fs::read_to_string(path("beam_slider.mbd")).unwrap();
    let written = "structural: 10, dynamic, reference, 1, 0., 0., 0.,";
    assert!(text.contains(written));
    let t = text.replace(written, "structural: 10, dynamic, reference, 1, .5, 0., -.001,");
    let m = parse_text(&t, &path("beam_slider.mbd")).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let assembly = report.assembly;
    assert!((assembly.moved_position - 1e-3).abs() < 1e-9, "assembly moved the nodes by {} m", assembly.moved_position);
    let asm = Assembler::new(&m.model);
    let x = report.final_state.node_frame(&asm.dofs, m.model.node_index(10).unwrap()).kin.x;
    let a = std::f64::consts::PI / 6.0;
    let want = (0.5 + 1.0 + 9.81 * a.sin() / 2.0) * Vec3::new(a.cos(), 0.0, -a.sin());
    assert!((x - want).norm() < 1e-8, "node 10 at {x}, closed form {want}");
}

#[test]
fn a_slotted_lever_whose_written_velocities_miss_the_slider_moves_as_mbdyn() {
    // beam_slider_slotted_lever.mbd: a crank (1 kg, R = .3 m, 10 rad/s) whose pin slides
    // along a flexible lever (one beam3 on three nodes, pivoted at one end) at x = .6 m,
    // between beam nodes; the lever is written at rest, so the written velocities do not
    // satisfy the slider. MBDyn 1.7.3's beam slider takes no part in its initial assembly
    // (beamslider.cc: empty `InitialAssRes`), which keeps them; the first step changes them.
    // romdyn's assembly made them satisfy the slider (it gave the lever's middle node
    // 1.94 m/s) and node 10 ended 2.2e-2 m from MBDyn's at t = .1 s; now the slider, written
    // on the line, is left out of the assembly, with its abscissa's rate the written
    // velocities' along the line.
    let m = read_model(&path("beam_slider_slotted_lever.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    assert!(report.inconsistent_velocity.is_some(), "the written velocities miss the slider, as written");
    let asm = Assembler::new(&m.model);
    let kin = |label: u32| report.final_state.node_frame(&asm.dofs, m.model.node_index(label).unwrap()).kin;
    // MBDyn 1.7.3 on the same file, .mov at t = .1 s: node 10 (4.1326196630401130e-01,
    // 8.6791274756057607e-02, 0) m, node 3 (9.7746364816563747e-01, 2.1102883641434234e-01,
    // 0) m. Measured: 4.5e-8 and 1.8e-8 relative (node 10), 3.3e-9 and 7.1e-8 (node 3);
    // 1e-6 relative.
    for (label, want) in [(10, Vec3::new(4.1326196630401130e-01, 8.6791274756057607e-02, 0.0)), (3, Vec3::new(9.7746364816563747e-01, 2.1102883641434234e-01, 0.0))] {
        let x = kin(label).x;
        for c in 0..2 {
            assert!((x[c] - want[c]).abs() < 1e-6 * want[c].abs(), "node {label} at {x} against MBDyn's {want}");
        }
    }
}
