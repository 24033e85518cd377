//! The motor's cogging torque (issue 34; elec/motor.cc `M0`, `M1`, `terminal pairs`) on
//! tests/mbdyn_files/dc_motor_cogging.mbd: its Jacobian against finite differences in both
//! constraint forms, and MBDyn 1.7.3's run of the same file (`output precision: 16` added).

use crate::common;
use common::cli::temp_dir;
use common::mbdyn::test_file;
use romdyn::analysis::{run, RunFiles};
use romdyn::input::mbdyn::read_model;

#[test]
fn cogging_torque_jacobian_matches_finite_differences() {
    // Central differences at states moved by noise (the rotor's angle, hence the electrical
    // angle, anywhere), both constraint forms: 1e-7, the motor and the sensors among the
    // compared elements.
    let compared = common::mbdyn::assert_model_jacobians(
        |form| {
            let mut model = read_model(&test_file("dc_motor_cogging.mbd")).unwrap_or_else(|e| panic!("{e}")).model;
            model.constraint_form = form;
            model
        },
        51,
        1e-7,
    );
    assert!(compared > 0);
}

#[test]
fn cogging_motor_runs_as_mbdyn() {
    let m = read_model(&test_file("dc_motor_cogging.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let dir = temp_dir("motor-cogging");
    let prefix = dir.join("run");
    let mut files = RunFiles::create(&prefix, "dc_motor_cogging.mbd", &m.model, &m.problem).unwrap();
    let report = run(&m.model, &m.problem, &mut files).unwrap_or_else(|e| panic!("{e}"));
    files.finish(&report).unwrap();
    let mov = std::fs::read_to_string(dir.join("run.mov")).unwrap();
    let last: Vec<f64> = mov.lines().last().unwrap().split_whitespace().map(|x| x.parse().unwrap()).collect();
    // MBDyn 1.7.3's last `.mov` row of node 2 (t = 0.1 s): its angle about z [deg] and
    // angular velocity [rad/s]. romdyn's rows over the run: 1.4e-13 deg and 8.3e-14 rad/s
    // from MBDyn's (its abstract nodes 2e-12 of their scale). Without the cogging torque
    // (dc_motor_inertia.mbd) the rotor is at 72.28° and 18.42 rad/s: the cogging terms
    // change the run by 5 %.
    assert_eq!(last[0], 2.0);
    assert!((last[6] - 76.90248205081585).abs() < 1e-11 * 76.9, "angle {}", last[6]);
    assert!((last[12] - 19.082128288307956).abs() < 1e-11 * 19.08, "omega {}", last[12]);
    // And the instant t = 0.05 s: 26.083273232582073°, 15.913268455941525 rad/s.
    let mid: Vec<f64> = mov.lines().nth(2 * 500 + 1).unwrap().split_whitespace().map(|x| x.parse().unwrap()).collect();
    assert!((mid[6] - 26.083273232582073).abs() < 1e-11 * 26.08 && (mid[12] - 15.913268455941525).abs() < 1e-11 * 15.91, "{mid:?}");
}
