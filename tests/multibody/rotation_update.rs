//! How the integrator updates the nodes' orientations within a time step: as MBDyn's
//! strnode.cc, the predicted rotation and angular velocity become the references after the
//! prediction and Newton's correction composes with them (`R = R(δg) R_pred`, `ω = G(δg) δġ
//! + R(δg) W_pred`; `State::after_predict`). Before, romdyn corrected the parameters of the
//! whole step's rotation additively, which parted from MBDyn at large rotations per step.
//!
//! MBDyn numbers: MBDyn 1.7.3 (built from github:alex-marinov/mbdyn with
//! shared/tools/build-mbdyn.sh), `mbdyn -f FILE -o out` on the file named, its .mov with the
//! file's `output precision: 16`.

use std::path::Path;

use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::read_model;
use romdyn::kinematics::{euler123, Vec3};

#[test]
fn a_spinning_top_turns_as_in_mbdyn() {
    // tests/mbdyn_files/spinning_top.mbd: a free body, J = diag(1, 2, 3) kg m², from
    // ω = (0.3, 0.2, 6) rad/s, 100 steps of 0.01 s (0.06 rad each), ms 0.6.
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/spinning_top.mbd");
    let m = read_model(&file).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    let kin = report.final_state.node_frame(&asm.dofs, 0).kin;

    // Closed form: no torque, so the angular momentum R J Rᵀ ω is constant in the global
    // frame, J ω(0) = (0.3, 0.4, 18) N m s (ms integrates the momentum's derivative, zero,
    // exactly: Newton's tolerance 1e-10 is what is left).
    let j = Vec3::new(1.0, 2.0, 3.0);
    let h = kin.r * j.component_mul(&(kin.r.transpose() * kin.omega));
    assert!((h - Vec3::new(0.3, 0.4, 18.0)).norm() < 1e-9, "angular momentum {h:?}");

    // MBDyn 1.7.3 on the same file, .mov node 1 at t = 1 s: Euler 1-2-3 angles [deg] and ω
    // [rad/s]. Measured: romdyn 5.5e-10 deg and 3.4e-11 rad/s from these (1.7e-15 deg after
    // the first step); with the additive update (romdyn before 2026-12-03) 6.7e-4 deg and
    // 1.2e-4 rad/s, which the tolerances (1e-8 deg, 1e-9 rad/s) refuse.
    let angles = [-9.2535193716893327e-01, -2.8511751378323724e-01, -1.5884866781171706e+01];
    let omega = [3.3074945202869993e-01, 1.0437645433159731e-01, 6.0016161307052123e+00];
    let e = euler123(&kin.r) * (180.0 / std::f64::consts::PI);
    for k in 0..3 {
        assert!((e[k] - angles[k]).abs() < 1e-8, "angle {k}: romdyn {} deg, MBDyn {} deg", e[k], angles[k]);
        assert!((kin.omega[k] - omega[k]).abs() < 1e-9, "ω {k}: romdyn {} rad/s, MBDyn {} rad/s", kin.omega[k], omega[k]);
    }
}
