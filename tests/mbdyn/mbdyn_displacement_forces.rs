//! MBDyn's `absolute displacement` and `absolute internal displacement` forces (issue 12,
//! point 3): `tests/mbdyn_files/displacement_forces.mbd` against closed forms and MBDyn 1.7.3.

use crate::common;

use common::mbdyn::{assert_jacobians_after_run, read_test_file};
use romdyn::analysis::run;
use romdyn::dae::Assembler;

#[test]
fn displacement_forces_push_the_nodes_without_turning_them() {
    let m = read_test_file("displacement_forces.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = |k: usize| report.final_state.node_frame(&asm.dofs, k).kin;
    // Closed forms at t = 1 s (file header) and MBDyn 1.7.3 (built from
    // github:alex-marinov/mbdyn, 1727489e) on this file, `output precision: 16`, last .mov row.
    let cases = [
        ("node 1 x", kin(0).x[0], 0.25, 2.5001482617187581e-01),
        ("node 1 vx", kin(0).xdot[0], 0.75, 7.5000000000000144e-01),
        ("node 2 y", kin(1).x[1], 3.0, 3.0000000198968859e+00),
        ("node 3 y", kin(2).x[1], 2.0, 1.9999999801031370e+00),
    ];
    for (what, x, exact, mbdyn) in cases {
        // ms with ρ∞ = 0.6 and h = 10 ms on t³/4: 1.5e-5 m (both programs); 1e-4.
        assert!((x - exact).abs() < 1e-4, "{what}: {x} against the closed form {exact}");
        // The same steps as MBDyn: measured to 1e-15; 1e-12.
        assert!((x - mbdyn).abs() < 1e-12, "{what}: {x} against MBDyn {mbdyn}");
    }
    // No arm, no moment: nothing turns (node 1 keeps its 90° about z).
    for k in 0..3 {
        assert_eq!(kin(k).omega, romdyn::kinematics::Vec3::zeros(), "node {}", k + 1);
    }
    assert_jacobians_after_run(&mut read_test_file("displacement_forces.mbd"), None, 1e-2);
}
