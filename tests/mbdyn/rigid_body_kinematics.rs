//! MBDyn's `rigid body kinematics` (a moving reference frame, issue 12):
//! `tests/mbdyn_files/rigid_body_kinematics.mbd` against closed forms and MBDyn 1.7.3, the
//! bodies' and nodes' frame terms against finite differences.

use crate::common;

use std::path::Path;

use common::mbdyn::{assert_jacobians_after_run, read_test_file, rewritten_test_file};
use romdyn::analysis::run;
use romdyn::dae::{Assembler, Coefficients};
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};
use romdyn::kinematics::{Mat3, Vec3};

fn final_positions(m: &MbdynModel) -> Vec<(u32, Vec3, Mat3)> {
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    m.model.nodes.iter().enumerate().map(|(i, n)| {
        let k = report.final_state.node_frame(&asm.dofs, i).kin;
        (n.label, k.x, k.r)
    }).collect()
}

fn at(rows: &[(u32, Vec3, Mat3)], label: u32) -> (Vec3, Mat3) {
    rows.iter().find(|r| r.0 == label).map(|r| (r.1, r.2)).unwrap()
}

#[test]
fn the_turning_frame_gives_closed_forms_and_mbdyn() {
    let rows = final_positions(&read_test_file("rigid_body_kinematics.mbd"));
    let rz = |a: f64| Mat3::new(a.cos(), -a.sin(), 0.0, a.sin(), a.cos(), 0.0, 0.0, 0.0, 1.0);
    let t = 1.0;
    // Node 2 in relative equilibrium, k (r − l₀) = m W² r at r = 1 (file header); 1e-12.
    assert!((at(&rows, 2).0 - Vec3::x()).norm() < 1e-12, "node 2 {}", at(&rows, 2).0);
    // Node 3, free: Rz(−2t) (−2t, 1, 0); node 5's node point Rz(−2t) (0.5 − 0.5 cos 2t,
    // t − 0.5 sin 2t, 1), its orientation the identity. ms ρ∞ = 0.6, h = 1 ms: 2.1e-6
    // measured (both programs); 1e-5 (the orientation 6e-12 rad).
    let x3 = rz(-2.0 * t) * Vec3::new(-2.0 * t, 1.0, 0.0);
    let x5 = rz(-2.0 * t) * Vec3::new(0.5 - 0.5 * (2.0 * t).cos(), t - 0.5 * (2.0 * t).sin(), 1.0);
    assert!((at(&rows, 3).0 - x3).norm() < 1e-5, "node 3 {} against {x3}", at(&rows, 3).0);
    assert!((at(&rows, 5).0 - x5).norm() < 1e-5, "node 5 {} against {x5}", at(&rows, 5).0);
    assert!((at(&rows, 5).1 - Mat3::identity()).norm() < 1e-10);
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, 1727489e) on this file, `output
    // precision: 16`, last .mov rows. Measured: 2.5e-15; 1e-12.
    let mbdyn = [
        (2, [1.0, 0.0, 0.0]),
        (3, [1.7415890053037031e+00, 1.4024472345162167e+00, 0.0]),
        (5, [2.0122361725807417e-01, -8.7079450265178815e-01, 1.0]),
    ];
    for (l, x) in mbdyn {
        assert!((at(&rows, l).0 - Vec3::from(x)).norm() < 1e-12, "node {l}: {} against MBDyn {x:?}", at(&rows, l).0);
    }
}

/// Every term of the frame's motion (a tilted angular velocity, an angular and an origin
/// acceleration) on the same bodies: MBDyn 1.7.3 on the file with `const, angular velocity,
/// 0.3, -0.2, 2., acceleration, 1., 2., 3., angular acceleration, 0.5, 0.1, -0.4`, last .mov
/// rows (16 digits). Measured: 2.1e-12 m (node 5, whose offset body turns); 1e-10.
#[test]
fn every_frame_term_as_mbdyn() {
    let every = "const, angular velocity, 0.3, -0.2, 2., acceleration, 1., 2., 3., angular acceleration, 0.5, 0.1, -0.4";
    let rows = final_positions(&rewritten_test_file("rigid_body_kinematics.mbd", &[("const, angular velocity, 0., 0., 2.", every)]));
    let mbdyn = [
        (2, [2.3663889975807531e-01, -2.0950672518213792e-01, -1.1495166488468744e+00]),
        (3, [3.7119767616665406e-01, 1.6727348992695685e+00, -1.7804307704765006e+00]),
        (5, [-6.6440651466515432e-01, -4.5483252815628628e-01, -3.0185546603898605e-01]),
    ];
    for (l, x) in mbdyn {
        assert!((at(&rows, l).0 - Vec3::from(x)).norm() < 1e-10, "node {l}: {} against MBDyn {x:?}", at(&rows, l).0);
    }
}

/// The `drive` form with a constant angular velocity is the `const` form; with an
/// orientation drive along the same axis (as the collection's `eig/rigidflap`) too, since
/// `Rᵀ W = W` for a rotation about W.
#[test]
fn the_drive_form_reads_template_drives() {
    let base = final_positions(&read_test_file("rigid_body_kinematics.mbd"));
    for form in ["drive, angular velocity, 0., 0., 1., const, 2.", "drive, orientation, 0., 0., 1., linear, 0., 2., angular velocity, 0., 0., 1., const, 2."] {
        let rows = final_positions(&rewritten_test_file("rigid_body_kinematics.mbd", &[("const, angular velocity, 0., 0., 2.", form)]));
        for (l, x, _) in &base {
            assert!((at(&rows, *l).0 - x).norm() < 1e-13, "{form}: node {l}");
        }
    }
}

/// The bodies' transport terms (`assert_jacobians_after_run`, central differences) and
/// the nodes' `2 W × β`, `W × γ`: the momentum columns of `J(c)` against central
/// differences of the assembled residual (`ẏ ± h`, `y ± c h`).
#[test]
fn frame_terms_match_finite_differences() {
    let mut m = read_test_file("rigid_body_kinematics.mbd");
    assert_jacobians_after_run(&mut m, Some(0.2), 1e-3);
    // Every term: a tilted angular velocity, an angular acceleration, an origin acceleration.
    let every = "const, angular velocity, 0.3, -0.2, 2., acceleration, 1., 2., 3., angular acceleration, 0.5, 0.1, -0.4";
    let mut m = rewritten_test_file("rigid_body_kinematics.mbd", &[("const, angular velocity, 0., 0., 2.", every)]);
    assert_jacobians_after_run(&mut m, Some(0.2), 1e-3);
    let m = read_test_file("rigid_body_kinematics.mbd");
    let mut short = read_test_file("rigid_body_kinematics.mbd");
    short.problem.final_time = 0.2;
    let st = run(&short.model, &short.problem, &mut ()).unwrap().final_state;
    let asm = Assembler::new(&m.model);
    let (c, form) = (1e-3, m.model.constraint_form);
    let jac = asm.jacobian(&st, Coefficients::newton(c, form)).to_dense();
    let mut worst = 0.0f64;
    for label in [2, 3, 5] {
        let first = asm.dofs.node_first[m.model.node_index(label).unwrap()];
        for j in first + 6..first + 12 {
            let h = 1e-6 * (1.0 + st.yp[j].abs());
            let f = |s: f64| {
                let mut p = st.clone();
                p.yp[j] += s * h;
                p.y[j] += s * c * h;
                asm.residual(&p, form, c)
            };
            let (fp, fm) = (f(1.0), f(-1.0));
            for r in 0..asm.dofs.len {
                worst = worst.max(((fp[r] - fm[r]) / (2.0 * h) - jac[(r, j)]).abs() / jac[(r, j)].abs().max(1.0));
            }
        }
    }
    // Linear in the momenta: round-off only; 1e-7 as `assert_jacobians_after_run`.
    assert!(worst < 1e-7, "worst relative error {worst:e}");
}

#[test]
fn a_null_rigid_body_kinematics_is_refused() {
    let text = "begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 0.01; time step: 1.e-2; end: initial value;
begin: control data; structural nodes: 1; rigid body kinematics: const; end: control data;
begin: nodes; structural: 1, static, null, eye, null, null; end: nodes;
begin: elements; end: elements;";
    let e = parse_text(text, Path::new("t.mbd")).and_then(|d| build(&d)).err().expect("refused").to_string();
    assert!(e.contains("t.mbd:3:") && e.contains("null rigid body kinematics"), "{e}");
}

/// A mass on a dynamic displacement node in the turning frame keeps the closed form (node 2
/// of the file as a 3-DoF point: relative equilibrium at (1, 0, 0); 1e-12). MBDyn 1.7.3
/// does not: its `Mass::AssVecRBK_int` (body.cc) puts only `m A` in the residual (it computes
/// `s₀ = m x` and leaves `Ẇ × s₀ + W × (W × s₀)` out, which its Jacobian has), so the rod
/// pulls the point in: (0.88269, 0.46348, 0) at 1 s. romdyn follows the physics here.
#[test]
fn a_mass_on_a_displacement_node_feels_the_turning_frame() {
    let m = rewritten_test_file("rigid_body_kinematics.mbd", &[
        ("structural: 2, dynamic, 1., 0., 0., eye, null, null;", "structural: 2, dynamic displacement, 1., 0., 0., null;"),
        ("body: 2, 2, 1., null, diag, 0.01, 0.01, 0.01;", "body: 2, 2, 1.;"),
    ]);
    let rows = final_positions(&m);
    assert!((at(&rows, 2).0 - Vec3::x()).norm() < 1e-12, "node 2 {}", at(&rows, 2).0);
}

/// Rotating flap and lag blades (`rotating_blades.mbd`, the `drive` form with the frame's
/// orientation turning): the eigenanalysis after one step against the closed forms of the
/// file header and MBDyn 1.7.3's eigenanalysis of the same file (its .m file's alpha, beta,
/// dCoef: 20.742458 and 5.6195133 rad/s). Measured: romdyn 20.742449 and 5.619503, 2e-6
/// relative from the closed forms (the eigenanalysis' dCoef of 5e-7 s); 1e-5.
#[test]
fn rotating_blades_have_the_centrifugal_frequencies() {
    use romdyn::dae::linearize;
    use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
    let m = read_test_file("rotating_blades.mbd");
    let st = run(&m.model, &m.problem, &mut ()).unwrap().final_state;
    let dae = linearize(&m.model, &st, &[], &[], Some(5e-7)).unwrap();
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Lambda).unwrap();
    let mut im: Vec<f64> = modal.modes.iter().filter(|md| md.kind == ModeKind::Dynamic && md.lambda.im > 0.0).map(|md| md.lambda.im).collect();
    im.sort_by(f64::total_cmp);
    let (w, e, d, jb) = (20.0f64, 0.05, 0.475, 0.95f64 * 0.95 / 12.0);
    let i = jb + d * d;
    let lag = (w * w * e * d / i).sqrt();
    let flap = (w * w * (1.0 + (e * d - 1e-3) / i)).sqrt();
    assert_eq!(im.len(), 2, "{im:?}");
    for (got, exact, mbdyn) in [(im[0], lag, 5.619513259278794), (im[1], flap, 20.74245823538515)] {
        assert!((got - exact).abs() < 1e-5 * exact, "{got} against the closed form {exact}");
        assert!((got - mbdyn).abs() < 1e-5 * mbdyn, "{got} against MBDyn {mbdyn}");
    }
}
