//! MBDyn's displacement-only structural nodes (`static displacement`, `dynamic
//! displacement`, issue 12): `tests/mbdyn_files/displacement_nodes.mbd` against closed forms
//! and MBDyn 1.7.3, the nodes' own Jacobian rows against finite differences, and the
//! elements MBDyn refuses on them.

use crate::common;

use std::path::Path;

use common::mbdyn::{assert_jacobians_after_run, read_test_file};
use romdyn::analysis::run;
use romdyn::dae::{Assembler, Coefficients};
use romdyn::input::mbdyn::{build, parse_text};
use romdyn::kinematics::Vec3;

#[test]
fn displacement_nodes_follow_closed_forms_and_mbdyn() {
    let m = read_test_file("displacement_nodes.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = |label: u32| report.final_state.node_frame(&asm.dofs, m.model.node_index(label).unwrap()).kin;
    let g = 9.81;
    // Node 1, 2 kg under (0, 0, 4) N and gravity from v0 = (1, 0, 0): x = t, z = −7.81 t²/2
    // at t = 1 s (file header); ms on a constant acceleration: 7.8e-9 (both programs); 1e-7.
    let k1 = kin(1);
    assert!((k1.x - Vec3::new(1.0, 0.0, -7.81 / 2.0)).norm() < 1e-7, "node 1: {}", k1.x);
    // Node 4, the point pendulum: on its 1 m circle (1e-9: Newton's tolerance), energy
    // ½ v² + g z = 0 kept to 1e-5 (ms ρ∞ = 0.6, h = 1 ms; measured 1e-6).
    let k4 = kin(4);
    assert!((k4.x.norm() - 1.0).abs() < 1e-9, "node 4 radius {}", k4.x.norm());
    assert!((0.5 * k4.xdot.norm_squared() + g * k4.x[2]).abs() < 1e-5, "node 4 energy");
    // Node 5 on the rod (k = 100 N/m, 1 kg): z = −2 − g/100 − (0.1 − g/100) cos(10 t); 1e-6
    // (measured 1.4e-7 at ωh = 0.01).
    let z5 = -2.0 - g / 100.0 - (0.1 - g / 100.0) * 10f64.cos();
    assert!((kin(5).x[2] - z5).abs() < 1e-6, "node 5 z {} against {z5}", kin(5).x[2]);
    // Node 6, static: the three rods' forces EA (l − l₀)/l₀ balance (0, 5, 0) N at t = 1 s;
    // 1e-7 N (Newton's tolerance 1e-10 on the residual); a small-displacement estimate
    // K⁻¹ F is within 2 % (geometric nonlinearity).
    let x6 = kin(6).x;
    let anchors = [Vec3::zeros(), Vec3::x(), Vec3::z()];
    let mut sum = Vec3::new(0.0, 5.0, 0.0);
    let mut k = romdyn::kinematics::Mat3::zeros();
    for a in anchors {
        let (l0, d) = ((Vec3::new(0.0, 1.0, 0.0) - a).norm(), a - x6);
        sum += 1e3 * (d.norm() - l0) / l0 * d / d.norm();
        let n = (Vec3::new(0.0, 1.0, 0.0) - a) / l0;
        k += 1e3 / l0 * n * n.transpose();
    }
    assert!(sum.norm() < 1e-7, "node 6 equilibrium residual {sum}");
    let linear = k.try_inverse().unwrap() * Vec3::new(0.0, 5.0, 0.0);
    assert!((x6 - Vec3::new(0.0, 1.0, 0.0) - linear).norm() < 2e-2 * linear.norm());
    // Displacement nodes keep their orientation and do not turn.
    for l in [1, 4, 5, 6] {
        assert!(kin(l).r == romdyn::kinematics::Mat3::identity() && kin(l).omega == Vec3::zeros(), "node {l} turned");
    }
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, 1727489e) on this file, `output
    // precision: 16`, last .mov rows. Measured: 1.3e-14 (node 6 positions: 4e-16); 1e-11.
    let mbdyn = [
        (1, [1.0000000000000184e+00, 0.0, -3.9050000078061760e+00]),
        (4, [-9.8629060298072957e-01, 0.0, -1.6501771563050152e-01]),
        (5, [0.0, 0.0, -2.0965056619017264e+00]),
        (6, [4.8945455539904275e-03, 1.0049273331629232e+00, 4.8945455539904396e-03]),
    ];
    for (l, x) in mbdyn {
        assert!((kin(l).x - Vec3::from(x)).norm() < 1e-11, "node {l}: {} against MBDyn {x:?}", kin(l).x);
    }
    // Accelerations (`accelerations, yes` on nodes 1 and 4; strnode.cc: β̇/m): node 1's
    // (0, 0, 4/2 − 9.81) to 1e-12; node 4's as MBDyn 1.7.3's last row, measured 3.4e-9; 1e-8.
    let wanted: Vec<bool> = m.model.nodes.iter().map(|n| n.label == 1 || n.label == 4).collect();
    let acc = romdyn::dae::node_accelerations(&asm, &report.final_state, &wanted);
    let (a1, w1) = acc[m.model.node_index(1).unwrap()].unwrap();
    assert!((a1 - Vec3::new(0.0, 0.0, -7.81)).norm() < 1e-12 && w1 == Vec3::zeros(), "node 1: {a1} {w1}");
    let (a4, _) = acc[m.model.node_index(4).unwrap()].unwrap();
    assert!((a4 - Vec3::new(4.7898355874939824e+00, 0.0, -9.0086056396510337e+00)).norm() < 1e-8, "node 4: {a4}");
    // The elements' Jacobians (rods, distance, bodies, forces) at the last state.
    let mut m = read_test_file("displacement_nodes.mbd");
    assert_jacobians_after_run(&mut m, Some(0.1), 1e-3);
}

/// The nodes' own rows (a static displacement node's `g = 0`, a dynamic one's `γ̇ + g`):
/// every column of `J(c)` of a displacement node's rotation unknowns against central
/// differences of the assembled residual, moved as Newton moves them (`ẏ ± h`, `y ± c h`).
#[test]
fn displacement_node_rows_match_finite_differences() {
    let m = read_test_file("displacement_nodes.mbd");
    let mut m2 = read_test_file("displacement_nodes.mbd");
    m2.problem.final_time = 0.3;
    let st = run(&m2.model, &m2.problem, &mut ()).unwrap().final_state;
    let asm = Assembler::new(&m.model);
    let (c, form) = (1e-3, m.model.constraint_form);
    let jac = asm.jacobian(&st, Coefficients::newton(c, form)).to_dense();
    let (mut worst, mut at_worst) = (0.0f64, (0, 0, 0.0, 0.0));
    for label in [1, 4, 5, 6] {
        let i = m.model.node_index(label).unwrap();
        let first = asm.dofs.node_first[i];
        // The rotation parameters g and the angular momenta γ (the position and linear
        // momentum columns are the elements', checked by `assert_jacobians_after_run`).
        let own: Vec<usize> = if m.model.nodes[i].kind.unknowns() == 12 { vec![3, 4, 5, 9, 10, 11] } else { vec![3, 4, 5] };
        for j in own.into_iter().map(|k| first + k) {
            let h = 1e-6 * (1.0 + st.yp[j].abs());
            let at = |s: f64| {
                let mut p = st.clone();
                p.yp[j] += s * h;
                p.y[j] += s * c * h;
                asm.residual(&p, form, c)
            };
            let (fp, fm) = (at(1.0), at(-1.0));
            for r in 0..asm.dofs.len {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                let e = (fd - jac[(r, j)]).abs() / jac[(r, j)].abs().max(1.0);
                if e > worst {
                    (worst, at_worst) = (e, (r, j, fd, jac[(r, j)]));
                }
            }
        }
    }
    // These columns enter the node rows linearly and the elements' (none writes a moment
    // on a displacement node) not at all: round-off only; 1e-7 as `assert_jacobians_after_run`.
    assert!(worst < 1e-7, "worst relative error {worst:e} at (row, column, fd, analytic) {at_worst:?}");
}

fn refused(nodes: &str, elements: &str) -> String {
    let text = format!(
        "begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 0.01; time step: 1.e-2; end: initial value;
begin: control data; structural nodes: 3; end: control data;
begin: nodes;
 structural: 1, static, null, eye, null, null;
 structural: 2, dynamic displacement, 1., 0., 0., null;
 structural: 3, static displacement, 0., 1., 0., null;
{nodes}
end: nodes;
begin: elements;
{elements}
end: elements;"
    );
    parse_text(&text, Path::new("t.mbd")).and_then(|d| build(&d)).err().expect("refused").to_string()
}

/// What MBDyn 1.7.3 reads only on 6-DoF nodes is refused by name, at the node's label.
#[test]
fn elements_that_need_rotations_are_refused_on_displacement_nodes() {
    let cases = [
        ("", "joint: 1, clamp, 2, node, node;", "t.mbd:11:", "displacement node (no rotations)"),
        ("", "joint: 1, spherical hinge, 1, null, 2, null;", "t.mbd:11:", "displacement node (no rotations)"),
        ("", "joint: 1, rod, 1, position, 0., 0., 1., 2, from nodes, linear elastic, 1.;", "t.mbd:11:", "with an offset needs two nodes with rotations"),
        ("", "joint: 1, distance, 2, position, 0., 0., 1., 1, const, 1.;", "t.mbd:11:", "with an offset needs two nodes with rotations"),
        ("", "body: 1, 3, 1.;", "t.mbd:11:", "static displacement node"),
        ("", "force: 1, absolute, 2, position, null, 1., 0., 0., const, 1.;", "t.mbd:11:", "displacement node (no rotations)"),
        (" structural: 4, dummy, 2, offset, null, eye;", "", "t.mbd:8:", "a dummy node needs a base with rotations"),
        (" structural: 4, static displacement, null, null, accelerations, yes;", "", "t.mbd:8:", "not on a static displacement node"),
    ];
    for (nodes, elements, at, what) in cases {
        let e = refused(nodes, elements);
        assert!(e.contains(at) && e.contains(what), "{nodes} {elements}: {e}");
    }
}

/// A dynamic displacement node between two prestressed rods (EA = 200 N, l₀ = 1.9 m, 2 m
/// each side, no gravity): axial `ω² = 2 EA/(l₀ m)`, lateral `ω² = 2 T/(l m)` with the
/// tension `T = EA (l − l₀)/l₀`, twice each; the held rotations add no finite mode (both
/// constraint forms, both routes; 1e-9 relative, the eigensolver's round-off).
#[test]
fn a_displacement_node_between_rods_has_the_string_modes() {
    use romdyn::dae::{linearize, State};
    use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
    use romdyn::model::ConstraintForm;
    let text = "begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 0.01; time step: 1.e-3; end: initial value;
begin: control data; skip initial joint assembly; structural nodes: 3; rigid bodies: 1; joints: 4; end: control data;
begin: nodes;
    structural: 3, static, null, eye, null, null;
    structural: 5, dynamic displacement, 0., 0., -2., null;
    structural: 7, static, 0., 0., -4., eye, null, null;
end: nodes;
begin: elements;
    body: 5, 5, 1.;
    joint: 1, clamp, 3, node, node;
    joint: 2, clamp, 7, node, node;
    joint: 3, rod, 3, 5, 1.9, linear elastic, 200.;
    joint: 4, rod, 7, 5, 1.9, linear elastic, 200.;
end: elements;";
    let tension = 200.0 * 0.1 / 1.9;
    let (axial, lateral) = ((2.0 * 200.0 / 1.9f64).sqrt(), (2.0 * tension / 2.0f64).sqrt());
    for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
        let mut m = common::mbdyn::read(text);
        m.model.constraint_form = form;
        let asm = Assembler::new(&m.model);
        let dae = linearize(&m.model, &State::initial(&m.model, &asm.dofs), &[], &[], None).unwrap();
        for route in [EigenRoute::Direct, EigenRoute::Lambda] {
            let modal = ModalAnalysis::compute(&dae.jacobians, route).unwrap();
            assert_eq!(modal.count(ModeKind::Dynamic), 6, "{form:?} {route:?}");
            let mut im: Vec<f64> = modal.modes.iter().filter(|md| md.kind == ModeKind::Dynamic && md.lambda.im > 0.0).map(|md| md.lambda.im).collect();
            im.sort_by(f64::total_cmp);
            for (got, want) in im.iter().zip([lateral, lateral, axial]) {
                assert!((got - want).abs() < 1e-9 * want, "{form:?} {route:?}: {got} against {want}");
            }
            // MBDyn 1.7.3 on the same file with `eigenanalysis: 0., use lapack` (its .m file's
            // alpha, beta and dCoef, printed to 7 digits): 3.2444285, 14.509522 rad/s; 1e-6.
            for (got, mbdyn) in [(im[0], 3.244428519835277), (im[2], 14.509522300663962)] {
                assert!((got - mbdyn).abs() < 1e-6 * mbdyn, "{got} against MBDyn {mbdyn}");
            }
        }
    }
}

/// With the initial assembly (the file without `skip initial joint assembly`): the rod
/// moves node 5 towards its rest length (9.9e-2 m) in both programs; node 5 after 1 s as
/// MBDyn 1.7.3 on that file, -2.1795873762456219 m (measured 4e-15); 1e-11.
#[test]
fn the_initial_assembly_moves_displacement_nodes_as_mbdyn() {
    let m = common::mbdyn::rewritten_test_file("displacement_nodes.mbd", &[("    skip initial joint assembly;\n", "")]);
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let z5 = report.final_state.node_frame(&asm.dofs, m.model.node_index(5).unwrap()).kin.x[2];
    assert!((z5 - -2.1795873762456219).abs() < 1e-11, "node 5 z {z5}");
}
