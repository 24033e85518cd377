//! A step drive evaluated exactly at its step time: MBDyn 1.7.3 takes half of (initial value
//! + step value) there (drive_.h, `StepDriveCaller::dGet`, `DoubleStepDriveCaller::dGet`),
//! not the value after the step. A step at the initial time therefore acts with that half
//! value in the derivatives phase, whose accelerations the first step's predictor reads:
//! the collection's DETC2007-35511/beam (a couple `double step, 0., 1.5, -COUPLE, 0.`) ran
//! 1.2e-4 m from MBDyn after 10 s while romdyn took the full value at t = 0.
//!
//! MBDyn numbers: MBDyn 1.7.3 (built from github:alex-marinov/mbdyn with
//! shared/tools/build-mbdyn.sh), `mbdyn -f step_at_start.mbd -o out`, its .mov and .frc with
//! the file's `output precision: 16`.

use std::path::Path;

use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::read_model;

#[test]
fn forces_take_half_the_step_at_the_step_time_as_in_mbdyn() {
    // tests/mbdyn_files/step_at_start.mbd: a 2 kg body on a free node, three absolute forces
    // with steps at t = 0 (x, z), 0.25 s (y) and 0.5 s (x), 8 steps of 0.125 s (the time
    // sum reaches those times exactly), ms 0.6. MBDyn's .frc reads x 2 N, y 0.5 N, z 1.25 N
    // at t = 0; y 1.25 N at t = 0.25 s; x 2 N at t = 0.5 s.
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/step_at_start.mbd");
    let m = read_model(&file).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, 0).kin;

    // MBDyn 1.7.3 on the same file, .mov node 1 at t = 1 s: position [m] and velocity [m/s].
    // Measured: romdyn 2.5e-16 m and 4e-16 m/s from these; with the full step value at the
    // step times (romdyn before 2026-12-03) x = 0.85278 m, 0.12 m away, which the tolerances
    // (1e-12 m, 1e-12 m/s) refuse.
    let x = [7.3016291438474645e-01, 3.9892586630214139e-01, 5.8742531665152553e-01];
    let v = [1.1543121820416098e+00, 9.8436967288237309e-01, 1.2097163168367058e+00];
    for k in 0..3 {
        assert!((kin.x[k] - x[k]).abs() < 1e-12, "x {k}: romdyn {} m, MBDyn {} m", kin.x[k], x[k]);
        assert!((kin.xdot[k] - v[k]).abs() < 1e-12, "v {k}: romdyn {} m/s, MBDyn {} m/s", kin.xdot[k], v[k]);
    }
}
