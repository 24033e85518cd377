//! Reader constructs of real MBDyn files (issue 12, points 1 and 2 of the reader's
//! refusals): each checked against what MBDyn's own reader does (its source cited per
//! test), with a file of `tests/mbdyn_files/` written in MBDyn's style where the construct
//! changes a model's numbers.

use crate::common;
use common::mbdyn::{read_test_file as read, test_file as path};

use std::path::Path;

use romdyn::analysis::run;
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};

fn read_text(text: &str) -> Result<MbdynModel, String> {
    parse_text(text, Path::new("m.mbd")).and_then(|d| build(&d)).map_err(|e| e.to_string())
}

#[test]
fn eval_functions_cast_their_argument() {
    // mathp.cc (MBDyn development version), `mp_eval`: the same conversions as the casts
    // `bool(…)`, `integer(…)`, `real(…)`, `string(…)` (GetBool, GetInt truncates, GetReal).
    let v = common::mbdyn::variables("set: integer I = integer_eval(7.9); set: bool B = bool_eval(0.25); set: real R = real_eval(3) / 2; set: bool Z = bool_eval(0);");
    let r = |n| v.real(n).unwrap();
    assert_eq!((r("I"), r("B"), r("R"), r("Z")), (7.0, 1.0, 1.5, 0.0));
    let s = common::mbdyn::variables("set: string S = string_eval(3);");
    assert_eq!(s.get("S").map(|v| v.value.to_string()), Some("\"3\"".to_string()));
}

#[test]
fn real_eval_freezes_a_string_drive_when_its_card_is_read() {
    // eval_functions.mbd: VAL = 5.5, then 7.5 after drive 2, then 9.5 after drive 4.
    // MBDyn (mathp.cc, development version, `readfunc`: an `_eval` call is evaluated while
    // the expression is parsed and replaced by its value; a `StringDriveCaller` evaluates
    // the rest when called): drive 1 "VAL" = 9.5 during the run, drive 2 = 5.5 (frozen),
    // drive 3 = 9.5 + 5.5 = 15, drive 4 = real_eval(7.5 + 5.5) = 13 (frozen when read).
    // Unit masses from rest under constant forces: x(t) = F t²/2, ẋ = F t at the last step
    // (t = 1.1 s: MBDyn's step count, 11 steps of 0.1 s), exact for the integrator on a
    // quadratic, to the Newton tolerance 1e-10.
    let m = read("eval_functions.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = romdyn::dae::Assembler::new(&m.model);
    let t = report.final_state.t;
    assert!((t - 1.1).abs() < 1e-12, "last step at t = {t}");
    for (k, force) in [9.5, 5.5, 15.0, 13.0].into_iter().enumerate() {
        let kin = report.final_state.node_frame(&asm.dofs, k).kin;
        let (x, v) = (kin.x[0], kin.xdot[0]);
        assert!((x - force * t * t / 2.0).abs() < 1e-8 && (v - force * t).abs() < 1e-8, "node {}: x = {x}, v = {v}, want F = {force}", k + 1);
    }
}

/// The text around a frozen `_eval` keeps its literals' types: `1./2.` stays real division
/// (MBDyn types `1/2` as integer, 0), so `"1./2.*real_eval(2.*VAL)"` is drive 2's 5.5 again.
#[test]
fn a_staticized_string_drive_keeps_its_real_literals() {
    let t = std::fs::read_to_string(path("eval_functions.mbd")).unwrap();
    let changed = t.replacen("drive caller: 2, string, \"real_eval(VAL)\";", "drive caller: 2, string, \"1./2.*real_eval(2.*VAL)\";", 1);
    assert_ne!(changed, t);
    let m = parse_text(&changed, &path("eval_functions.mbd")).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = romdyn::dae::Assembler::new(&m.model);
    let t = report.final_state.t;
    // Unit mass from rest under 5.5 N: x = F t²/2 at t = 1.1 s, to the Newton tolerance (as above).
    let x = report.final_state.node_frame(&asm.dofs, 1).kin.x[0];
    assert!((x - 5.5 * t * t / 2.0).abs() < 1e-8, "node 2: x = {x}, want F = 5.5 N");
}

#[test]
fn a_bad_eval_argument_is_reported_where_it_is_written() {
    let e = match read_text("set: real x = real_eval(\"a\");") {
        Err(e) => e,
        Ok(_) => panic!("a string cast into real must be an error"),
    };
    assert!(e.contains("m.mbd:1:15") && e.contains("cannot cast the string"), "{e}");
}

#[test]
fn the_drive_drive_caller_composes_two_drives_as_mbdyn() {
    // drive_composition.mbd; closed forms x(1) = 1/12 and 1/2 − sin(2)/4 (the file's
    // header); MBDyn 1.7.3 (1727489e, `mbdyn -f drive_composition.mbd`, last .mov rows):
    // 8.333353121875209e-02 and 2.726756253407116e-01.
    let m = read("drive_composition.mbd");
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = romdyn::dae::Assembler::new(&m.model);
    let cases = [(1.0 / 12.0, 8.333353121875209e-02), (0.5 - 2f64.sin() / 4.0, 2.726756253407116e-01)];
    for (k, (exact, mbdyn)) in cases.into_iter().enumerate() {
        let x = report.final_state.node_frame(&asm.dofs, k).kin.x[0];
        // ms (ρ∞ = 0.6, h = 1 ms) on smooth forces: 1e-5 relative to the closed form; the
        // same method and steps as MBDyn: to the Newton tolerance.
        assert!((x - exact).abs() < 1e-5 * exact, "node {}: {x} against the closed form {exact}", k + 1);
        assert!((x - mbdyn).abs() < 1e-9, "node {}: {x} against MBDyn {mbdyn}", k + 1);
    }
}

/// A free unit body at the origin with `elements`, 0.1 s in 10 steps.
fn free_body(elements: &str, counters: &str) -> String {
    format!(
        "begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 0.1; time step: 1.e-2; tolerance: 1.e-10; max iterations: 10; derivatives tolerance: 1.e-6; derivatives max iterations: 10; end: initial value;
begin: control data; structural nodes: 1; rigid bodies: 1; {counters} end: control data;
begin: nodes; structural: 1, dynamic, null, eye, null, null; end: nodes;
begin: elements; body: 1, 1, 1., null, diag, 1., 1., 1.; {elements} end: elements;"
    )
}

#[test]
fn an_internal_couple_on_one_node_cancels_as_in_mbdyn() {
    // strforce.cc, `ReadStructuralForce`: the two nodes of an internal couple are not
    // compared (MBDyn's tests/forces/force/force-old has `follower internal, 1, 1., 0., 0.,
    // 2, …`, node 2 read as 1); the couple and its reaction act on the same node and
    // cancel: the body stays at rest, while the same couple alone turns it (ω = M t).
    let couple = "couple: 1, follower internal, 1, 1, 0., 0., 2., const, 1.;";
    let m = read_text(&free_body(couple, "forces: 1;")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = romdyn::dae::Assembler::new(&m.model);
    let w = report.final_state.node_frame(&asm.dofs, 0).kin.omega;
    assert!(w.norm() < 1e-12, "ω = {w}");
    let alone = read_text(&free_body("couple: 1, follower, 1, 0., 0., 2., const, 1.;", "forces: 1;")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&alone.model, &alone.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let w = report.final_state.node_frame(&asm.dofs, 0).kin.omega;
    // To 1e-6: what the derivatives phase leaves at its tolerance (2e-8 here).
    assert!((w[2] - 2.0 * report.final_state.t).abs() < 1e-6, "ω = {w}");
}

#[test]
fn an_initial_assembly_tolerance_of_zero_is_read_as_mbdyn_reads_it() {
    // dataman3.cc reads `tolerance: 0` (and the deprecated `initial tolerance`); the
    // assembly passes only on an exact residual, which a free body has (no joints).
    assert!(read_text(&free_body("", "initial tolerance: 0;")).is_ok());
    let e = read_text(&free_body("", "tolerance: -1.e-6;")).err().unwrap_or_default();
    assert!(e.contains("must not be negative") && e.contains("MBDyn 1.7.3"), "{e}");
}

#[test]
fn a_python_preprocessor_source_is_named_as_such() {
    // contrib/PythonPreprocessor/examples/LateralBuckling2_v2.mbd begins so; MBDyn 1.7.3
    // stops there too ("<begin> expected at line 5").
    let e = read_text("#beginpreprocess\nfrom MBDynLib import *\n#endpreprocess\nbegin: data; problem: initial value; end: data;").err().unwrap_or_default();
    assert!(e.contains("m.mbd:2:22") && e.contains("Python preprocessor") && e.contains("MBDynPreprocess.py"), "{e}");
}

#[test]
fn extra_arguments_of_a_structural_node_say_mbdyn_stops_too() {
    // strnode.cc, `ReadStructNode`: "semicolon expected" (a2m/samples/bipendolo.mbd writes
    // the assembly stiffnesses without the `assembly` keyword).
    let t = free_body("", "").replace("null, null; end: nodes", "null, null, 0, 0, 1; end: nodes");
    let e = read_text(&t).err().unwrap_or_default();
    assert!(e.contains("unexpected extra argument") && e.contains("semicolon expected"), "{e}");
}

#[test]
fn joint_regularizations_are_counted_and_the_unsupported_kinds_named() {
    // MBDyn's tests/stiff/pendulum_reg, tests/joints/total/totalhint: jointreg.cc's
    // Tikhonov regularization is read (tests/total_equation.rs); the counter must match the
    // cards, and 'dynamic' and 'jacobian' (which change MBDyn's Newton matrix) are refused.
    let e = read_text(&free_body("", "joint regularizations: 1;")).err().unwrap_or_default();
    assert!(e.contains("m.mbd:3:") && e.contains("control data declares 1 joint regularizations, the model has 0"), "{e}");
    let clamp = "joint: 2, clamp, 1, node, node; joint regularization: 2, jacobian;";
    let e = read_text(&free_body(clamp, "joints: 1; joint regularizations: 1;")).err().unwrap_or_default();
    assert!(e.contains("m.mbd:5:") && e.contains("joint regularization 'jacobian' is not supported by romdyn"), "{e}");
}
