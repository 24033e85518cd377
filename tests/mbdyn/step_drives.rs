//! Drive callers with a memory of the time steps (MBDyn's `sample and hold` and `discrete
//! filter`, issue 12): `tests/mbdyn_files/step_drives.mbd` against closed forms and MBDyn
//! 1.7.3, a second run of the same model, the elements' Jacobians with the drives held, what
//! a linearization sees, and the errors.

use crate::common;

use common::mbdyn::{assert_jacobians_after_run, assert_not_linearized, read_test_file, test_file as path};
use romdyn::analysis::run;
use romdyn::dae::{Assembler, State};
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};

fn text() -> String {
    std::fs::read_to_string(path("step_drives.mbd")).unwrap_or_else(|e| panic!("{e}"))
}

fn from_text(t: &str) -> Result<MbdynModel, String> {
    parse_text(t, &path("step_drives.mbd")).and_then(|d| build(&d)).map_err(|e| e.to_string())
}

/// (z, ż) of each node, in node order, at the end of a run up to `final_time`.
fn final_z(m: &mut MbdynModel, final_time: f64) -> Vec<(f64, f64)> {
    m.problem.final_time = final_time;
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    (0..m.model.nodes.len()).map(|k| report.final_state.node_frame(&asm.dofs, k).kin).map(|k| (k.x[2], k.xdot[2])).collect()
}

#[test]
fn held_and_filtered_forces_give_the_closed_forms_and_mbdyns_motion() {
    let mut m = read_test_file("step_drives.mbd");
    let end = final_z(&mut m, 1.0);
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn) on this file, `output precision:
    // 16`, last row of its .mov (t = 1 s): z and ż of nodes 2 to 5. Same method, steps and
    // drive memory: measured within 7e-15 m; asserted to 1e-12 relative to the motions'
    // amplitude (1 m).
    let mbdyn = [
        (4.8236734700990902e-01, -1.7570417754554504e+00),
        (-1.3380145419008443e-01, -8.3573217980460079e-02),
        (-1.3390582629714795e-01, 7.3153071787752280e-02),
        (-1.3390582629714795e-01, 7.3153071787752280e-02),
    ];
    for (k, (&(z, v), (mz, mv))) in end[1..].iter().zip(mbdyn).enumerate() {
        eprintln!("node {}: z {z:.16e} (MBDyn {mz:.16e}), ż {v:.16e} (MBDyn {mv:.16e})", k + 2);
        assert!((z - mz).abs() < 1e-12 && (v - mv).abs() < 1e-12, "node {}: {z}, {v} against MBDyn {mz}, {mv}", k + 2);
    }
    // Nodes 4 and 5: the filter y_k = b₁ ũ₀ with ũ₀ the input at the new step's time is the
    // input itself (MBDyn's convention, drive.h `MyDiscreteFilter::Set`): the same motion.
    assert!((end[3].0 - end[4].0).abs() < 1e-14 && (end[3].1 - end[4].1).abs() < 1e-14, "{:?} {:?}", end[3], end[4]);

    // Node 2 before the sample: the free oscillator z = 2 sin t (ms, h = 1 ms: 1e-7).
    let early = final_z(&mut m, 0.1);
    assert!((early[1].0 - 2.0 * 0.1f64.sin()).abs() < 1e-7, "{:?}", early[1]);
    // After it, a unit oscillator under the constant force −F0, F0 = 10 z(0.199 s) =
    // 20 sin(0.199): it oscillates about z = −F0, so (z + F0)² + ż² is the same at any two
    // times; the centre c from the states at 0.3 s and 1 s is −F0. The held force is
    // constant to the digit (a re-sampled or lost hold would move the centre by 10 z);
    // the integrator's 1 ms steps: 1e-6 relative.
    let mid = final_z(&mut m, 0.3);
    let ((z1, v1), (z2, v2)) = (mid[1], end[1]);
    let centre = (z1 * z1 + v1 * v1 - z2 * z2 - v2 * v2) / (2.0 * (z1 - z2));
    let f0 = 20.0 * 0.199f64.sin();
    eprintln!("centre {centre:.12e}, −F0 {:.12e}", -f0);
    assert!((centre + f0).abs() < 1e-6 * f0, "centre {centre} against −F0 = {}", -f0);

    // The same model run again starts from the drives' initial memory: the same numbers.
    assert_eq!(final_z(&mut m, 1.0), end);
}

#[test]
fn jacobians_hold_the_step_drives() {
    // After the sample (t = 0.25 s): every element's Jacobian against central differences;
    // the drives' memory is fixed within a step, so they are constants there.
    let checks = assert_jacobians_after_run(&mut read_test_file("step_drives.mbd"), Some(0.25), 1e-3);
    assert!(checks.iter().any(|c| c.element == "absolute force 2"), "{checks:?}");
}

#[test]
fn a_linearization_sees_the_held_value_and_the_filters_direct_term() {
    // A sample and hold of a node's position is an input to the linearization (its held
    // value, no derivative): the model is linearized.
    let m = read_test_file("step_drives.mbd");
    let asm = Assembler::new(&m.model);
    let st = State::initial(&m.model, &asm.dofs);
    assert!(romdyn::dae::linearize(&m.model, &st, &[], &[], None).is_ok());
    // A filter whose direct term b₀ u reads the state within the step is refused, as any
    // drive reading the state.
    let t = text().replacen("sine, 0., W, 10., forever, 0.;", "node, 3, structural, string, \"X[3]\", linear, 0., 10.;", 1);
    let why = "the filter's b₀ ∂u/∂z is in no Jacobian: the linearization would miss it";
    assert_not_linearized(&from_text(&t).unwrap(), &["absolute force 3", "reads the model's state"], why);
}

#[test]
fn bad_step_drives_name_the_place_and_what_was_expected() {
    let base = text();
    let cases = [
        ("initial value, 0.;", "initial value, zero;", "initial value of the sample and hold"),
        ("2, 1.911197067426073, -0.914975834801434,", "2, 1.911197067426073,", "discrete filter"),
        ("2, 1.911197067426073, -0.914975834801434,", "-1, 1.911197067426073, -0.914975834801434,", "number of coefficients a"),
    ];
    for (old, new, expected) in cases {
        assert!(base.contains(old), "{old}");
        let e = match from_text(&base.replacen(old, new, 1)) {
            Err(e) => e,
            Ok(_) => panic!("{new} must be refused"),
        };
        assert!(e.contains("step_drives.mbd:") && e.contains(expected), "{new}: {e}");
    }
}
