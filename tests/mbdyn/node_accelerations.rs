//! Node accelerations in the motion file (MBDyn's `accelerations, yes`, issue 12):
//! `tests/mbdyn_files/node_accelerations.mbd` against closed forms and MBDyn 1.7.3.

use crate::common;

use std::path::Path;

use common::mbdyn::{read, read_test_file};
use romdyn::input::mbdyn::{build, parse_text};
use romdyn::model::MotionOutput;
use romdyn::analysis::{ObserverError, RunObserver, StepDone};
use romdyn::analysis::run;
use romdyn::kinematics::Vec3;
use romdyn::output::motion::{motion_rows, MotionRow};

/// The motion file's rows of every step, as `romdyn run` writes them.
struct Rows(MotionOutput, Vec<Vec<MotionRow>>);

impl RunObserver for Rows {
    fn step(&mut self, e: &StepDone) -> Result<(), ObserverError> {
        self.1.push(motion_rows(&self.0, &e.node_kinematics(), &e.node_accelerations(&self.0)));
        Ok(())
    }
}

fn run_rows(m: &romdyn::input::mbdyn::MbdynModel) -> Vec<Vec<MotionRow>> {
    let mut rows = Rows(m.problem.output.clone().expect("an MBDyn file lists its nodes"), Vec::new());
    run(&m.model, &m.problem, &mut rows).unwrap();
    rows.1
}

fn acc(step: &[MotionRow], label: u32) -> Option<(Vec3, Vec3)> {
    step.iter().find(|r| r.0 == label).unwrap_or_else(|| panic!("no row of node {label}")).3
}

#[test]
fn accelerations_follow_closed_forms_and_mbdyn() {
    let all = run_rows(&read_test_file("node_accelerations.mbd"));
    let (first, last) = (&all[0], &all[all.len() - 1]);
    // Node 1, a free body under constant loads: a = F/m + g, dw/dt = M/J_zz (file header),
    // at every step; 1e-12 (round-off of the momentum derivatives).
    for step in [first, last] {
        let (a, wd) = acc(step, 1).unwrap();
        assert!((a - Vec3::new(0.5, 1.0 - 9.81, 1.5)).norm() < 1e-12, "node 1 a = {a}");
        assert!((wd - Vec3::new(0.0, 0.0, 0.125)).norm() < 1e-12, "node 1 dw/dt = {wd}");
    }
    // Node 2, the pendulum's pivot, released horizontal at rest: dw/dt = −m g L/(J + m L²)
    // = −3 · 9.81 · 0.8 / 2.02 exactly at t = 0.
    let (a, wd) = acc(first, 2).unwrap();
    assert!(a.norm() < 1e-12 && (wd[2] + 3.0 * 9.81 * 0.8 / 2.02).abs() < 1e-12, "node 2 at t = 0: {a} {wd}");
    // At t = 1 s, −m g L cos ψ/(J + m L²) with ψ the node's angle: the accelerations come from
    // the integrator's momentum derivatives (h = 10 ms), 1.2e-3 relative off; 2e-3.
    let (k2, (a2, wd2)) = (&last.iter().find(|r| r.0 == 2).unwrap().1, acc(last, 2).unwrap());
    let psi = k2.r[(1, 0)].atan2(k2.r[(0, 0)]);
    let exact = -3.0 * 9.81 * 0.8 * psi.cos() / 2.02;
    assert!((wd2[2] - exact).abs() < 2e-3 * exact.abs(), "node 2 dw/dt {} against {exact}", wd2[2]);
    // Dummy node 4, 0.8 m along node 2's x axis: a₄ = a₂ + ω̇ × f + ω × (ω × f), ω̇₄ = ω̇₂
    // (rigid-body kinematics); 1e-12.
    let f = k2.r * Vec3::new(0.8, 0.0, 0.0);
    let (a4, wd4) = acc(last, 4).unwrap();
    assert!((a4 - (a2 + wd2.cross(&f) + k2.omega.cross(&k2.omega.cross(&f)))).norm() < 1e-12 && (wd4 - wd2).norm() < 1e-15);
    // Node 6 (`accelerations, no`) and the static node 3 write none.
    assert!(acc(last, 6).is_none() && acc(last, 3).is_none());
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, 1727489e) on this file, `output
    // precision: 16`, last .mov rows (node 5's without orientation columns: MBDyn 1.7.3 writes
    // none for a relative-frame dummy node). Measured: 4e-8 (node 2's angle differs by 3.7e-7°
    // between the programs, the initial derivatives' momenta); 1e-7.
    let mbdyn = [
        (2, [-2.7017684760629970e-03, -1.1487489060344641e-02, 0.0], [0.0, 0.0, 1.1631023242294596e+01]),
        (4, [1.2065589902555256e+00, -9.2726404480406135e+00, 0.0], [0.0, 0.0, 1.1631023242309659e+01]),
        (5, [7.2356766609824588e+00, -2.4055239628192355e+00, -1.4999999999999896e+00], [2.3342896472029015e-15, -3.7095995908442148e-16, 1.1506023242309659e+01]),
    ];
    for (label, a, wd) in mbdyn {
        let (ra, rwd) = acc(last, label).unwrap();
        assert!((ra - Vec3::from(a)).norm() < 1e-7 && (rwd - Vec3::from(wd)).norm() < 1e-7, "node {label}: {ra} {rwd} against MBDyn {a:?} {wd:?}");
    }
}

/// `default output: accelerations` turns them on for dynamic nodes (MBDyn 1.7.3 writes the
/// columns of node 1 and of the dummy node on it, not of the static node 2).
#[test]
fn default_output_asks_every_dynamic_node() {
    let text = "begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 0.01; time step: 1.e-2; method: ms, .6; tolerance: 1e-10; max iterations: 20; end: initial value;
begin: control data; structural nodes: 2+1; rigid bodies: 1; joints: 1; default output: accelerations; end: control data;
begin: nodes;
 structural: 1, dynamic, null, eye, null, 0., 0., 0.2;
 structural: 2, static, 1.,0.,0., eye, null, null;
 structural: 5, dummy, 1, offset, 1.,0.,0., eye;
end: nodes;
begin: elements;
 body: 1, 1, 2., null, diag, 1., 2., 4.;
 joint: 1, clamp, 2, node, node;
end: elements;";
    let m = read(text);
    let written: Vec<_> = m.problem.output.as_ref().unwrap().nodes.iter().map(|n| (n.label, n.accelerations)).collect();
    assert_eq!(written, [(1, true), (2, false), (5, true)]);
    // The dummy node spins with node 1 at 0.2 rad/s: centripetal −ω² r = −0.04 m/s² along x
    // (MBDyn 1.7.3's t = 0 row: -4.000e-02).
    let (a, _) = acc(&run_rows(&m)[0], 5).unwrap();
    assert!((a - Vec3::new(-0.04, 0.0, 0.0)).norm() < 1e-12, "{a}");
}

/// MBDyn 1.7.3 reads `accelerations` on dynamic nodes only ("ReadStructNode(2): semicolon
/// expected" on a static node, a parser error on a dummy node); romdyn names it.
#[test]
fn accelerations_on_static_and_dummy_nodes_are_refused() {
    for (node, kind) in [("structural: 2, static, null, eye, null, null, accelerations, yes;", "static"), ("structural: 2, dummy, 1, offset, null, eye, accelerations, yes;", "dummy")] {
        let text = format!("begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 0.01; time step: 1.e-2; end: initial value;
begin: control data; structural nodes: 2; end: control data;
begin: nodes;
 structural: 1, dynamic, null, eye, null, null;
 {node}
end: nodes;
begin: elements; end: elements;");
        let e = parse_text(&text, Path::new("t.mbd")).and_then(|d| build(&d)).err().expect("refused");
        let s = e.to_string();
        assert!(s.contains("t.mbd:6:") && s.contains(&format!("not on a {kind} node")), "{s}");
    }
}

/// A relative-frame dummy node's rows have no orientation columns, as MBDyn 1.7.3 writes
/// them (`x v ω` then `ẍ ω̇`: 15 numbers after the label in the test file's last row, as in
/// MBDyn's .mov); the other nodes keep theirs.
#[test]
fn relative_frame_rows_have_no_orientation_columns() {
    let m = read_test_file("node_accelerations.mbd");
    let dir = std::env::temp_dir().join(format!("romdyn_rf_rows_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("t.mov");
    let all = run_rows(&m);
    let mut w = romdyn::output::motion::MotionWriter::create(&path, romdyn::model::OrientationOutput::Euler123Degrees, 6).unwrap();
    w.write_rows(&all[all.len() - 1]).unwrap();
    w.finish().unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let words: Vec<(String, usize)> = text.lines().map(|l| (l.split_whitespace().next().unwrap().to_string(), l.split_whitespace().count() - 1)).collect();
    assert_eq!(words, [("1", 18), ("2", 18), ("3", 12), ("4", 18), ("5", 15), ("6", 12)].map(|(l, n)| (l.to_string(), n)));
    std::fs::remove_dir_all(&dir).ok();
}
