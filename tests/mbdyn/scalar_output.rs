//! `romdyn run` and `romdyn rom` on a model with scalar nodes (issue 34): the `.abs` rows
//! (MBDyn's layout: label, value, derivative of a differential node) read back against the
//! closed-form step response of `examples/pid_mass.mbd`, the `default output` and node
//! `output` flags, and ROM ports on scalar nodes from a ports file's shorthand.

use crate::common;

use common::cli::{listing, romdyn_at, temp_dir, write_file};

fn pid_text(replace: &[(&str, &str)]) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pid_mass.mbd");
    let mut text = std::fs::read_to_string(path).unwrap();
    for (a, b) in replace {
        assert!(text.contains(a), "{a}");
        text = text.replace(a, b);
    }
    text
}

#[test]
fn run_writes_the_abstract_nodes_rows() {
    let dir = temp_dir("scalar-abs");
    let file = write_file(&dir, "pid.mbd", &pid_text(&[("set: real F0 = 0.;", "set: real F0 = 1.;"), ("final time: 2.;", "final time: 0.01;")]));
    let (ok, out, err) = romdyn_at(&dir, &["run", &file]);
    assert!(ok, "{err}");
    assert!(out.contains("10 steps to t = 0.01 s"), "{out}");
    assert_eq!(listing(&dir), ["pid.abs", "pid.log", "pid.mbd", "pid.mov", "pid.out"]);
    let text = std::fs::read_to_string(dir.join("pid.abs")).unwrap();
    let rows: Vec<Vec<f64>> = text.lines().map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect()).collect();
    // Steps 0..=10, two differential nodes each: label, value, derivative.
    assert_eq!(rows.len(), 22);
    assert!(rows.iter().all(|r| r.len() == 3));
    assert_eq!((rows[0][0], rows[1][0], rows[20][0], rows[21][0]), (1.0, 2.0, 1.0, 2.0));
    // Step 0: at rest; the force starts the mass with ẍ = F/m = 0.5 m/s², so after 10 ms
    // x ≈ ½ 0.5 (0.01)² = 2.5e-5 m (the controller's force grows as (B0 x …): 10 %).
    // (The derivatives phase moves x by dCoef ẋ, ẋ by dCoef ẍ: 5e-19 m, 5e-10 m/s.)
    assert!(rows[0][1].abs() < 1e-18 && rows[0][2].abs() < 1e-9, "{:?}", rows[0]);
    assert!((rows[20][1] - 2.5e-5).abs() < 0.1 * 2.5e-5, "{:?}", rows[20]);
    // Node 2 is the controller's force u = B0 x + …, its derivative MBDyn's XP.
    assert!(rows[21][1] > 0.0 && rows[21][2] > 0.0, "{:?}", rows[21]);

    // `default output: none` writes no .abs; a node's `output, yes` brings its rows back.
    let dir = temp_dir("scalar-abs-none");
    let quiet = pid_text(&[("final time: 2.;", "final time: 0.01;"), ("forces: 1;", "forces: 1;\n    default output: none;"), ("abstract: 2, name, \"control force\", differential;", "abstract: 2, name, \"control force\", differential, value, 0., output, yes;")]);
    let file = write_file(&dir, "pid.mbd", &quiet);
    let (ok, _, err) = romdyn_at(&dir, &["run", &file]);
    assert!(ok, "{err}");
    let text = std::fs::read_to_string(dir.join("pid.abs")).unwrap();
    assert_eq!(text.lines().count(), 11, "{text}");
    assert!(text.lines().all(|l| l.starts_with("2 ")), "{text}");
}

/// The full model's static gain of output `name` in `romdyn rom`'s report (one input).
fn full_gain(report: &str, name: &str) -> f64 {
    let at = report.find(&format!("{name}\n  full model")).unwrap_or_else(|| panic!("{name}: {report}"));
    report[at..].lines().nth(1).unwrap().split_whitespace().last().unwrap().parse().unwrap()
}

#[test]
fn rom_takes_scalar_ports_from_the_command_line_and_a_ports_file() {
    let dir = temp_dir("scalar-rom");
    let file = write_file(&dir, "pid.mbd", &pid_text(&[]));
    let ports = write_file(&dir, "ports.json", r#"{ "inputs": ["1:abstract"], "outputs": ["1:abstract", "2:abstract", "1:abstract_rate"] }"#);
    let named = write_file(&dir, "named.json", r#"{ "inputs": [{ "name": "disturbance", "type": "abstract", "node": 1 }], "outputs": [{ "name": "position", "type": "abstract", "node": 1 }, { "name": "control force", "type": "abstract", "node": 2 }] }"#);
    let (ok, _, out) = romdyn_at(&dir, &["rom", &file, "--ports", &named, "--band", "0:100"]);
    assert!(ok, "{out}");
    assert!((full_gain(&out, "control force [-]") - 1.0).abs() < 1e-8 && full_gain(&out, "position [-]").abs() < 1e-10, "{out}");
    let bad = write_file(&dir, "bad.json", r#"{ "inputs": [{ "type": "abstract", "node": 1, "direction": [1, 0, 0] }] }"#);
    let (ok, _, err) = romdyn_at(&dir, &["rom", &file, "--ports", &bad, "--band", "0:100"]);
    assert!(!ok && err.contains("inputs[0]") && err.contains("a 'abstract' port has no direction"), "{err}");
    for args in [vec!["rom", &file, "--ports", &ports, "--band", "0:100"], vec!["rom", &file, "--input", "1:abstract", "--output", "1:abstract", "--output", "2:abstract", "--output", "1:abstract_rate", "--band", "0:100"]] {
        let (ok, _, out) = romdyn_at(&dir, &args);
        assert!(ok, "{out}");
        // (The ROM's report, static gains included, goes to stderr, the ROM to stdout.)
        // The static gains of the loop's polynomial (tests/multibody/scalar_nodes.rs): x/F = 0,
        // u/F = 1, ẋ/F = 0; the names carry the node kinds and units.
        assert!(out.contains("abstract node 2 [-]") && out.contains("abstract node 1 rate [1/s]"), "{out}");
        assert!((full_gain(&out, "abstract node 2 [-]") - 1.0).abs() < 1e-8, "{out}");
        assert!(full_gain(&out, "abstract node 1 [-]").abs() < 1e-10, "{out}");
    }
    // A port on a node the model does not have is named.
    let (ok, _, err) = romdyn_at(&dir, &["rom", &file, "--input", "7:abstract", "--output", "1:abstract", "--band", "0:100"]);
    assert!(!ok && err.contains("abstract node 7 is not defined"), "{err}");
}
