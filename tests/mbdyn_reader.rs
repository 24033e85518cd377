//! Reader constructs of real MBDyn files (issue 12, points 1 and 2 of the reader's
//! refusals): each checked against what MBDyn's own reader does (its source cited per
//! test), with a file of `tests/mbdyn_files/` written in MBDyn's style where the construct
//! changes a model's numbers.

mod common;

use std::path::{Path, PathBuf};

use romdyn::analysis::run;
use romdyn::input::mbdyn::{build, parse_text, read_model, MbdynModel};

fn path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files").join(name)
}

fn read(name: &str) -> MbdynModel {
    read_model(&path(name)).unwrap_or_else(|e| panic!("{e}"))
}

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

#[test]
fn a_bad_eval_argument_is_reported_where_it_is_written() {
    let e = match read_text("set: real x = real_eval(\"a\");") {
        Err(e) => e,
        Ok(_) => panic!("a string cast into real must be an error"),
    };
    assert!(e.contains("m.mbd:1:15") && e.contains("cannot cast the string"), "{e}");
}
