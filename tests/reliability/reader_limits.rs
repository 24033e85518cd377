//! Issue 32, findings 1, 2 and 5: the MBDyn reader and its evaluators on deep, doubling
//! and long inputs, and the messages of evaluations that fail during the run. The inputs
//! are generated here, at the sizes of the probe's reproducers; each refusal is checked
//! for its exit status, its message and `FILE:LINE:COLUMN` (the line the generator wrote
//! the offending card on), and for the folder holding only what the test wrote.

use std::fmt::Write;
use std::path::Path;
use std::process::{Command, Stdio};

use crate::common;

use common::cli::{listing, temp_dir, write_file, TempDir};
use romdyn::input::mbdyn::parse_text;
use romdyn::limits::{MAX_EVALUATION_DEPTH, MAX_EVALUATION_TERMS, MAX_INCLUDE_DEPTH};

/// The lines before the cards of [`model`].
const HEAD: &str = "begin: data; problem: initial value; end: data;\n";

/// A one-body model with `cards` after [`HEAD`] (card k of `cards` is on line k + 1) and
/// a force on the body driven by `force` (on line 10 after the cards' lines).
fn model(cards: &str, force: &str, final_time: f64, step: f64) -> String {
    format!(
        "{HEAD}{cards}\
         begin: initial value; initial time: 0.; final time: {final_time}; time step: {step}; tolerance: 1.e-9; max iterations: 10; end: initial value;\n\
         begin: control data; structural nodes: 1; rigid bodies: 1; forces: 1; end: control data;\n\
         begin: nodes;\n    structural: 1, dynamic, null, eye, null, null;\nend: nodes;\n\
         begin: elements;\n    body: 1, 1, 1., null, eye;\n    force: 1, absolute, 1, position, null, 1., 0., 0.,\n        {force};\nend: elements;\n"
    )
}

/// A fresh folder holding `files`.
fn folder(name: &str, files: &[(&str, &str)]) -> TempDir {
    let d = temp_dir(&format!("reader-limits-{name}"));
    for (f, text) in files {
        write_file(&d, f, text);
    }
    d
}

/// Runs romdyn with `args` in `d`: (exit status, stdout, stderr).
fn romdyn_in(d: &Path, args: &[&str]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_romdyn")).args(args).current_dir(d).stdin(Stdio::null()).output().unwrap();
    (out.status.code(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

/// `romdyn run`, `eig` and `check` on `files` (the first the model): each exits 1 with every
/// piece of `message` on stderr, without a panic or an abort, and leaves no file.
fn refused_by_every_command(name: &str, files: &[(&str, &str)], message: &[&str]) {
    let d = folder(name, files);
    let before = listing(&d);
    for command in ["run", "eig", "check"] {
        let (code, stdout, stderr) = romdyn_in(&d, &[command, files[0].0]);
        assert_eq!(code, Some(1), "{name}, {command}: exit status (a stack overflow aborts with none)\nstdout: {stdout}\nstderr: {stderr}");
        assert!(!stderr.contains("panicked") && !stderr.contains("overflow"), "{name}, {command}: {stderr}");
        for m in message {
            assert!(stderr.contains(m), "{name}, {command}: expected {m:?} in\n{stderr}");
        }
        assert_eq!(listing(&d), before, "{name}, {command}: files left behind");
    }
    std::fs::remove_dir_all(&d).ok();
}

// Finding 1: crashes on deep or doubling inputs.

/// 2000 string drives, each calling the previous one through `model::drive`: the probe's
/// stack overflow (SIGABRT). The card that makes the chain 65 evaluations deep is refused
/// where it is written; 64 deep is accepted and computes `Time + 63` (each adds 1: the
/// closed form of the chain).
#[test]
fn a_chain_of_string_drives_is_refused_at_the_depth_limit() {
    let chain = |n: usize| {
        let mut s = String::from("drive caller: 1, string, \"Time\";\n");
        for k in 2..=n {
            let _ = writeln!(s, "drive caller: {k}, string, \"model::drive({}, Time) + 1.\";", k - 1);
        }
        s
    };
    // Card k is on line k + 1 (after HEAD); its string starts at column 27 for k < 100.
    let first_over = MAX_EVALUATION_DEPTH + 1;
    assert_eq!(first_over, 65, "the message checked below is for the limit of 64");
    let text = model(&chain(2000), "reference, 2000", 0.01, 1e-3);
    refused_by_every_command("chain", &[("chain.mbd", &text)], &["chain.mbd:66:27: error: string drive \"model::drive(64, Time) + 1.\": the drive nests 65 evaluations deep", "more than romdyn's limit of 64"]);

    // At the limit the chain is read and runs: the force on the free 1 kg body is drive
    // 64, t + 63 N (closed form of the chain: each drive adds 1), so from rest
    // v(T) = T²/2 + 63 T and x(T) = T³/6 + 63 T²/2 at T = 0.01 s.
    let text = model(&chain(MAX_EVALUATION_DEPTH), &format!("reference, {MAX_EVALUATION_DEPTH}"), 0.01, 1e-3);
    let d = folder("chain-64", &[("c.mbd", &text)]);
    let (code, _, stderr) = romdyn_in(&d, &["run", "c.mbd"]);
    assert_eq!(code, Some(0), "{stderr}");
    let mov = std::fs::read_to_string(d.join("c.mov")).unwrap();
    let last: Vec<f64> = mov.lines().last().unwrap().split_whitespace().skip(1).map(|x| x.parse().unwrap()).collect();
    let t: f64 = 0.01;
    let (x, v) = (t.powi(3) / 6.0 + 63.0 * t * t / 2.0, t * t / 2.0 + 63.0 * t);
    // Tolerances: the integrator's error on a cubic path in 10 steps (measured 1.1e-6 on x)
    // and the derivatives phase's 6.3e-8 m/s on v (its warning).
    assert!(((last[0] - x) / x).abs() < 1e-5, "x = {} against {x}", last[0]);
    assert!(((last[6] - v) / v).abs() < 1e-6, "v = {} against {v}", last[6]);
    std::fs::remove_dir_all(&d).ok();
}

/// 25 `sum` scalar functions, each adding the previous one to itself: the probe's 2^N
/// memory (out of memory after 20–30 s). Function k makes 2^(k+1) − 1 evaluations per
/// call (closed form of T_k = 1 + 2 T_{k−1}, T_0 = 1), so f16, 131071 > 1e5, is the first
/// refused; f15 (65535) is read, shares its operands, and is 2^15 at any x (1 doubled 15
/// times).
#[test]
fn doubling_scalar_functions_are_refused_at_the_evaluation_budget() {
    let mut cards = String::from("scalar function: \"f0\", const, 1.;\n");
    for k in 1..25 {
        let _ = writeln!(cards, "scalar function: \"f{k}\", sum, \"f{}\", \"f{}\";", k - 1, k - 1);
    }
    assert_eq!(MAX_EVALUATION_TERMS, 100_000, "the card refused below is the first over 1e5");
    let text = model(&cards, "scalar function, \"f24\"", 0.01, 1e-3);
    // f16 is card 17, on line 18; its name starts at column 18.
    refused_by_every_command("sf-doubling", &[("sf.mbd", &text)], &["sf.mbd:18:18: error: scalar function \"f16\" makes 131071 evaluations each time it is called", "limit of 100000"]);

    let within: String = cards.lines().take(16).map(|l| format!("{l}\n")).collect();
    let doc = parse_text(&format!("{within}set: real y = model::sf::f15(0.7);\n"), Path::new("m.mbd")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(doc.variables.real("y"), Some(32768.0));
}

/// The same doubling through drive caller cards: `array` of two references to the previous
/// card. Card k makes 2^k − 1 evaluations (T_1 = 1, T_k = 1 + 2 T_{k−1}): card 17
/// (131071) is refused, each copy bounded by the budget before it is made.
#[test]
fn doubling_drive_references_are_refused_at_the_evaluation_budget() {
    let mut cards = String::from("drive caller: 1, sine, 0., 1., 1., forever, 0.;\n");
    for k in 2..=30 {
        let _ = writeln!(cards, "drive caller: {k}, array, 2, reference, {}, reference, {};", k - 1, k - 1);
    }
    let text = model(&cards, "reference, 30", 0.01, 1e-3);
    // Card 17 on line 18: the message points at the term that crosses the budget (the
    // second reference, column 44), before its copy is kept.
    refused_by_every_command("drive-doubling", &[("d.mbd", &text)], &["d.mbd:18:44: error: this array drive caller makes 131071 evaluations each time it is called"]);
}

/// A 150-deep `include:` chain (the probe's 5000-deep one ran over a minute without a
/// limit): the include that would make 101 files is refused in the file that writes it.
#[test]
fn an_include_chain_is_refused_at_the_depth_limit() {
    let mut files: Vec<(String, String)> = vec![("main.mbd".into(), model("include: \"inc1.mbd\";\n", "const, 1.", 0.01, 1e-3))];
    for k in 1..150 {
        files.push((format!("inc{k}.mbd"), format!("set: real w{k} = {k}.;\ninclude: \"inc{}.mbd\";\n", k + 1)));
    }
    files.push(("inc150.mbd".into(), "set: real last = 1.;\n".into()));
    let refs: Vec<(&str, &str)> = files.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    assert_eq!(MAX_INCLUDE_DEPTH, 100);
    // main.mbd is file 1, inc99.mbd file 100: its include (line 2, column 1) would be the 101st.
    refused_by_every_command("include", &refs, &["inc99.mbd:2:1: error: include: \"inc100.mbd\" would make a chain of 101 files", "limit of 100"]);
}

// Finding 2: a reader linear in its input (the times are in benches/mbdyn_reader.rs).

/// 4000 alternating `set:` and string drive cards (the probe's 800 pairs took 24 s, 1000
/// over a minute: each drive card read every card before it again), then a `set:` that
/// calls the last drive while the file is read: v_3999 · Time at Time = 1.5 is
/// 3999 · 1.5, the drive reading the variables as they stand then.
#[test]
fn thousands_of_set_and_string_drive_pairs_read_and_evaluate() {
    let mut s = String::new();
    for k in 0..4000 {
        let _ = writeln!(s, "set: real v{k} = {k}.;\ndrive caller: {}, string, \"v{k}*Time\";", k + 1);
    }
    let _ = writeln!(s, "set: v3999 = 2.*v3999;\nset: real z = model::drive(4000, 1.5);");
    let doc = parse_text(&s, Path::new("m.mbd")).unwrap_or_else(|e| panic!("{e}"));
    // v3999 was doubled by the `set:` before the call: 7998 · 1.5.
    assert_eq!(doc.variables.real("z"), Some(7998.0 * 1.5));
}

// Finding 5: runtime evaluation errors name the drive and where it is written.

/// A run that fails at `t` on a drive: exit status 1, the message names `what`, and the
/// folder holds the inputs and the run's output set up to the failure (issue 30: the
/// files up to the last converged step), no temporary file.
fn run_fails_on_the_drive(name: &str, text: &str, what: &[&str]) {
    let file = format!("{name}.mbd");
    let d = folder(name, &[(&file, text)]);
    let (code, stdout, stderr) = romdyn_in(&d, &["run", &file]);
    assert_eq!(code, Some(1), "{name}: exit status\nstdout: {stdout}\nstderr: {stderr}");
    for m in what {
        assert!(stderr.contains(m), "{name}: expected {m:?} in\n{stderr}");
    }
    let expected: Vec<String> = [format!("{name}.log"), file.clone(), format!("{name}.mov"), format!("{name}.out")].into_iter().collect();
    let mut expected = expected;
    expected.sort();
    assert_eq!(listing(&d), expected, "{name}: only the inputs and the run's output set");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn drives_that_fail_during_the_run_name_their_place() {
    // 1/(0.5 − t) is finite at the check (t = 0) and divides by zero at the step t = 0.5.
    let text = model("", "string, \"1./(0.5 - Time)\"", 1.0, 0.1);
    run_fails_on_the_drive("division", &text, &["Newton failed at t = 0.5 s", "string drive \"1./(0.5 - Time)\" at division.mbd:10:17: division by zero at Time = 0.5"]);

    // A scalar function dividing by zero: q = 1/(1 − x), x the time, NaN at t = 1 (the
    // div of ScalarFunctionsImpl.cc has no value there).
    let cards = "scalar function: \"one\", const, 1.;\nscalar function: \"g\", linear, 0., 1., 1., 0.;\nscalar function: \"q\", div, \"one\", \"g\";\n";
    let text = model(cards, "scalar function, \"q\"", 1.5, 0.25);
    run_fails_on_the_drive("sf-division", &text, &["Newton failed at t = 1 s", "scalar function drive caller \"q\" at sf-division.mbd:13:9: its value at 1 is NaN"]);
}

/// Values that overflow where the file is read are refused there, with their place.
#[test]
fn drives_that_overflow_at_the_check_are_refused_where_written() {
    for (expression, value) in [("10.^400.", "inf"), ("1e309 - Time", "inf"), ("-1e309*(1. + Time)", "-inf")] {
        let text = model("", &format!("string, \"{expression}\""), 0.01, 1e-3);
        refused_by_every_command("overflow", &[("o.mbd", &text)], &[&format!("o.mbd:10:17: error: string drive \"{expression}\": the value at Time = 0 is {value}, not a finite number")]);
    }
}

#[test]
fn help_of_help_succeeds() {
    for args in [&["help", "--help"][..], &["help", "-h"], &["help", "eig", "--help"]] {
        let out = Command::new(env!("CARGO_BIN_EXE_romdyn")).args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(0), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        assert!(String::from_utf8_lossy(&out.stdout).contains("Usage: romdyn"), "{args:?}");
    }
}

#[test]
fn a_mode_damped_twice_and_an_actuator_on_one_node_are_refused() {
    let pendulum = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pendulum.mbd")).unwrap();
    let d = folder("damping", &[("p.mbd", &pendulum)]);
    let before = listing(&d);
    let (code, _, stderr) = romdyn_in(&d, &["rom", "p.mbd", "--input", "2:Mz", "--output", "2:rz", "--count", "1", "--damping", "1=0.02,1=0.05"]);
    // A command-line value clap refuses: exit status 2, as for every bad option value.
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("mode 1 is given a damping ratio twice (0.02 and 0.05)"), "{stderr}");
    assert_eq!(listing(&d), before);

    let ports = r#"{"inputs": [{"name": "A", "type": "actuator", "from": 2, "to": 2, "at": [0, -1, 0], "direction": [1, 0, 0]}], "outputs": ["2:rz"]}"#;
    std::fs::write(d.join("ports.json"), ports).unwrap();
    let before = listing(&d);
    let (code, _, stderr) = romdyn_in(&d, &["rom", "p.mbd", "--ports", "ports.json", "--count", "1"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("ports.json") && stderr.contains("a 'actuator' port acts between two nodes, \"from\" and \"to\" are both node 2"), "{stderr}");
    assert_eq!(listing(&d), before);
    std::fs::remove_dir_all(&d).ok();
}

/// 64 string drives (the depth limit), each with its call in five parentheses: 7
/// expression levels a drive, 448 in all, over the 200 the evaluators of one thread may
/// nest (about 5 KB of stack a level). Before that bound a sweep's 2 MiB worker threads
/// overflowed their stack (SIGABRT, as the probe's Python `romdyn.sweep`); now every
/// design point fails with the drive where the bound is crossed, and nothing is written.
#[test]
fn deeply_nested_string_drives_fail_cleanly_in_a_sweep() {
    let mut cards = String::from("set: real P = 1.;\ndrive caller: 1, string, \"Time\";\n");
    for k in 2..=MAX_EVALUATION_DEPTH {
        let _ = writeln!(cards, "drive caller: {k}, string, \"(((((model::drive({}, Time)))))) + 1.\";", k - 1);
    }
    let text = model(&cards, &format!("reference, {MAX_EVALUATION_DEPTH}"), 0.01, 1e-3).replace("body: 1, 1, 1.,", "body: 1, 1, P,");
    let d = folder("sweep-nesting", &[("c.mbd", &text)]);
    let before = listing(&d);
    // Drive k is on line k + 2; the evaluation from drive 64 down crosses 200 levels in
    // drive 31 (measured: 6 counted levels a drive, 34 drives; the failure named is the
    // innermost, where the bound is crossed): line 33, its string at column 27.
    let (code, stdout, stderr) = romdyn_in(&d, &["sweep", "c.mbd", "--set", "P=1,2,3", "--input", "1:Fx", "--output", "1:x", "--count", "1", "--jobs", "3"]);
    assert_eq!(code, Some(1), "exit status (a stack overflow aborts with none)\nstdout: {stdout}\nstderr: {stderr}");
    assert!(!stderr.contains("overflow"), "{stderr}");
    for point in 1..=3 {
        assert!(stderr.contains(&format!("design point {point} (P = {point}) failed")), "{stderr}");
    }
    assert!(stderr.contains("at c.mbd:33:27: expressions nested more than 200 levels deep"), "{stderr}");
    assert_eq!(listing(&d), before, "files left behind");
    std::fs::remove_dir_all(&d).ok();
}
