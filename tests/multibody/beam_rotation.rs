//! The three-node beam at large rotation, and why romdyn's `beam3` differs there from
//! MBDyn's (docs/src/mbdyn/beams.md, "beam.cc is incremental"): MBDyn 1.7.3's beam.cc is incremental. At each
//! step it interpolates the nodes' rotation increments (predicted `g_ref`, then Newton's
//! correction `g` from the predicted orientation), composes the section frame
//! `R_s = R(Σ N_i g_i) R(Σ N_i g_ref,i) R_s,prev` and accumulates the curvature
//! `κ = R_sᵀ G(g) g′ + [R_refᵀ G(g_ref) g_ref′ + κ_prev]`, updated after convergence; romdyn
//! interpolates the total rotation relative to the middle node (a function of the state).
//! The two agree to round-off below about 4° of relative rotation per element and part as
//! the cube of it; MBDyn's static result depends on the number of load steps and on the
//! integrator's predictor, romdyn's does not.
//!
//! MBDyn numbers: MBDyn 1.7.3 (built from github:alex-marinov/mbdyn with
//! shared/tools/build-mbdyn.sh), `mbdyn -f tests/mbdyn_files/beam3_tip_couple.mbd -o out`
//! with `H` set in the file, node 5's row of `out.mov` at t = 1 s. They are reproduced to
//! 5e-16 (1 and 10 steps) and 3e-15 (100 steps) by `scripts/beam3_planar_model.py`, a
//! planar model of that incremental formulation with MBDyn's `ms` predictor; the same
//! script with romdyn's formulation gives romdyn's 0.66463043648144 to 1.2e-12 m.

use std::path::Path;

use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{read_model_text, SetOverrides};
use romdyn::kinematics::Vec3;

/// Node 5's final position on `beam3_tip_couple.mbd` with step `h` [s].
fn tip(h: f64) -> Vec3 {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/beam3_tip_couple.mbd");
    let text = std::fs::read_to_string(&path).unwrap();
    let m = read_model_text(&text, &path, &SetOverrides::from([("H".to_string(), h)])).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    report.final_state.node_frame(&asm.dofs, 4).kin.x
}

#[test]
fn a_tip_couple_bends_two_beam3_into_the_same_arc_in_one_load_step_or_in_a_hundred() {
    let one = tip(1.0);
    // MBDyn 1.7.3 on the same file, tip x [m]: 0.66458978410585801 (H = 1), 0.66493938405041575
    // (H = 0.1), 0.66494703856909065 (H = 0.01), 0.66494706874126097 (H = 0.001): its
    // incremental curvature makes the equilibrium depend on the load path (5.4e-4 m between
    // 1 and 1000 steps) and on the integrator's predictor (H = 0.1 without the `method:`
    // line, MBDyn's default: 0.66493443703865718). romdyn's equilibrium is a function of
    // the nodes' positions and orientations only: measured equal to 1.4e-12 m (where Newton
    // stops, tolerance 1e-10 with EJ = 1 N m^2); 1e-10 m bounds it, 1e5 times below MBDyn's.
    for h in [0.1, 0.01] {
        let d = (tip(h) - one).norm();
        assert!(d < 1e-10, "H = {h}: tip {:?} against {:?} with one step ({d:e} m)", tip(h), one);
    }
    // Closed form: pure bending of the elastica, a circular arc of curvature M/EJ = 1.5 1/m,
    // tip at (sin 1.5, 1 − cos 1.5)/1.5 m. Two elements of 0.75 rad each: romdyn's
    // discretization error measured 4.4e-4 m (tip 0.664630, 0.619271), MBDyn's (1000 steps)
    // 5.9e-5 m; 1e-3 m bounds it.
    let k = 1.5_f64;
    let arc = Vec3::new(k.sin() / k, (1.0 - k.cos()) / k, 0.0);
    assert!((one - arc).norm() < 1e-3, "tip {one:?} against the arc {arc:?}");
}
