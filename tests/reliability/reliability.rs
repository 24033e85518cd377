//! Reproducers of issue 10's findings, each run through the `romdyn` binary in a folder of
//! its own: every test asserts the exit status, the message (file, line:column or field)
//! and that the folder holds afterwards only the inputs the test wrote (no output file, no
//! temporary file).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

const PENDULUM: &str = include_str!("../../examples/pendulum.mbd");

/// A fresh folder with the given files.
fn folder(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let d = std::env::temp_dir().join(format!("romdyn-reliability-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    for (f, text) in files {
        std::fs::write(d.join(f), text).unwrap();
    }
    d
}

/// The sorted names in a folder.
fn listing(d: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

struct Outcome {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

fn romdyn_in(d: &Path, args: &[&str]) -> Outcome {
    let out = Command::new(env!("CARGO_BIN_EXE_romdyn")).args(args).current_dir(d).stdin(Stdio::null()).output().unwrap();
    Outcome { code: out.status.code(), stdout: String::from_utf8_lossy(&out.stdout).into(), stderr: String::from_utf8_lossy(&out.stderr).into() }
}

/// Runs `args` in a folder holding `files`; asserts exit status 1, that stderr contains
/// every piece of `message`, no panic, and that no file appeared.
fn refused(name: &str, files: &[(&str, &str)], args: &[&str], message: &[&str]) -> String {
    let d = folder(name, files);
    let before = listing(&d);
    let o = romdyn_in(&d, args);
    assert_eq!(o.code, Some(1), "{name}: exit status\nstdout: {}\nstderr: {}", o.stdout, o.stderr);
    assert!(!o.stderr.contains("panicked"), "{name}: {}", o.stderr);
    for m in message {
        assert!(o.stderr.contains(m), "{name}: expected {m:?} in\n{}", o.stderr);
    }
    assert_eq!(listing(&d), before, "{name}: files left behind");
    std::fs::remove_dir_all(&d).ok();
    o.stderr
}

fn pencil_json(fyd: &str, fy: &str) -> String {
    format!(r#"{{"Fyd": {fyd}, "Fy": {fy}, "B": [[1], [0]], "C": [[1, 0]]}}"#)
}

// Point 1: panics and aborts in the readers.

#[test]
fn matrix_market_symmetric_forms_must_be_square() {
    for (sym, body) in [("symmetric", "1\n2\n3\n4\n5\n"), ("skew-symmetric", "1\n2\n3\n")] {
        let mtx = format!("%%MatrixMarket matrix array real {sym}\n2 3\n{body}");
        refused(sym, &[("a.mtx", &mtx), ("p.json", r#"{"Fyd": "a.mtx", "Fy": "a.mtx", "B": [[1],[0]], "C": [[1,0]]}"#)], &["eig", "--pencil", "p.json"], &["p.json: field \"Fyd\": a.mtx:2:1: a ", "must be square, the size line declares 2 x 3"]);
    }
    // A symmetric coordinate entry whose mirror (3, 1) would be out of range.
    let mtx = "%%MatrixMarket matrix coordinate real symmetric\n3 2 1\n1 3 1.0\n";
    refused("mirror", &[("a.mtx", mtx), ("p.json", r#"{"Fyd": "a.mtx", "Fy": "a.mtx", "B": [[1],[0]], "C": [[1,0]]}"#)], &["eig", "--pencil", "p.json"], &["a.mtx:2:1: a symmetric matrix must be square, the size line declares 3 x 2"]);
}

#[test]
fn declared_sizes_beyond_the_budget_are_refused_before_allocating() {
    let json = r#"{"Fyd": "a.mtx", "Fy": "a.mtx", "B": [[1],[0]], "C": [[1,0]]}"#;
    // Budget: romdyn::limits::MAX_DENSE_ENTRIES = 5e7 entries; 100000^2 = 1e10.
    refused("mtx-huge", &[("a.mtx", "%%MatrixMarket matrix coordinate real general\n100000 100000 0\n"), ("p.json", json)], &["eig", "--pencil", "p.json"], &["a.mtx:2:1: the matrix is 100000 x 100000 = 10000000000 entries, more than romdyn's budget of 50000000 entries"]);
    refused("m-zeros", &[("p.m", "dCoef = 1;\nAplus = zeros(100000, 100000);\n")], &["eig", "--pencil", "p.m"], &["p.m:2:9: zeros(100000, 100000) is 100000 x 100000"]);
    refused("m-spconvert", &[("p.m", "dCoef = 1;\nT = [1 1 1; 99999 99999 2];\nAplus = spconvert(T);\n")], &["eig", "--pencil", "p.m"], &["p.m:3:19: spconvert(T): the matrix (its size is the largest row and column index) is 99999 x 99999"]);
    // Just below the budget is accepted by the reader (a 7064 x 7064 zero matrix is 5.0e7
    // entries; its parse is checked in the library test below to keep this test fast).
    let below = romdyn::input::matrix_market::parse_matrix("%%MatrixMarket matrix coordinate real general\n50000000 1 0\n", Path::new("a.mtx"));
    assert_eq!(below.map(|m| m.nrows()).ok(), Some(50_000_000));
    let above = romdyn::input::matrix_market::parse_matrix("%%MatrixMarket matrix coordinate real general\n50000001 1 0\n", Path::new("a.mtx"));
    assert!(above.is_err());
    // Found by cargo-fuzz (matrix_market, an out-of-memory of 2 GB): a 1 x 38 888 882
    // matrix is stored as 8 x 38 888 882 by faer, beyond the budget.
    let wide = romdyn::input::matrix_market::parse_matrix("%%MatrixMarket matrix coordinate pattern general\n1 38888882 388888888883\n1 2 9\n", Path::new("a.mtx"));
    assert!(wide.unwrap_err().to_string().starts_with("a.mtx:2:1: the matrix is 1 x 38888882 = 38888882 entries, more than romdyn's budget"));
    // Found by cargo-fuzz (matrix_market, a timeout: 27 minutes on one input): a matrix with
    // no rows and 3.9e18 columns holds no entry but was accepted and never finished.
    let empty = romdyn::input::matrix_market::parse_matrix("%%MatrixMarket matrix coordinate pattern general\n0 3888888888888888888  3\n", Path::new("a.mtx"));
    assert!(empty.unwrap_err().to_string().starts_with("a.mtx:2:1: the matrix is 0 x 3888888888888888888"));
    // Octave zeros(R, C): 7064^2 = 49 900 096 entries is within, 7072^2 = 50 013 184 beyond
    // (rows count in multiples of 8, faer's storage).
    let m = Path::new("p.m");
    assert!(romdyn::input::octave_m::parse_octave_script("A = zeros(7064, 7064);\n", m).is_ok());
    let e = romdyn::input::octave_m::parse_octave_script("A = zeros(7072, 7072);\n", m).unwrap_err().to_string();
    assert!(e.starts_with("p.m:1:5: zeros(7072, 7072) is 7072 x 7072 = 50013184 entries, more than romdyn's budget"), "{e}");
    // JSON: the numbers are counted (by their separators) before parsing.
    let text = format!("{{\"Fyd\": [[{}0]]}}", "0,".repeat(50_000_001));
    let e = romdyn::input::pencil::parse_pencil(&text, Path::new("p.json")).unwrap_err().to_string();
    assert!(e.starts_with("p.json: 50000001 values: more than romdyn's budget of 50000000 numbers"), "{e}");
}

#[test]
fn frequency_grid_beyond_the_budget_is_refused() {
    let json = pencil_json("[[1, 0], [0, 1]]", "[[0, -1], [4, 0]]");
    // Budget: romdyn::limits::MAX_FREQUENCY_POINTS = 1e6.
    refused("points", &[("p.json", &json)], &["freq", "--pencil", "p.json", "--points", "100000000", "-o", "f"], &["frequency grid: 100000000 points: a frequency grid has 2 to 1000000 points"]);
    assert!(romdyn::rom::frequency_grid(1.0, 10.0, 1_000_000).is_ok());
}

#[test]
fn a_closed_output_pipe_ends_quietly() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut child = Command::new(env!("CARGO_BIN_EXE_romdyn"))
        .args(["eig", "examples/simply_supported_beam.mbd"])
        .current_dir(root)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Close the reading end at once, as `| head -1` does after one line.
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    // 141 = 128 + SIGPIPE, the status a shell shows for a tool stopped by a closed pipe.
    assert!(matches!(out.status.code(), Some(0) | Some(141)), "{:?} {stderr}", out.status);
    assert!(stderr.is_empty(), "{stderr}");
}

// Point 2: hangs.

#[test]
fn huge_step_counts_are_refused_with_the_place() {
    let long = PENDULUM.replace("final time: 2.;", "final time: 1e308;");
    refused("final-time", &[("p.mbd", &long)], &["run", "p.mbd"], &["p.mbd:", "is more than 1.8e308 steps, more than romdyn's limit of 1e8 steps per run"]);
    let tiny = PENDULUM.replace("time step: 1.e-3;", "time step: 1e-300;");
    refused("time-step", &[("p.mbd", &tiny)], &["run", "p.mbd"], &["p.mbd:", "steps, more than romdyn's limit of 1e8 steps per run"]);
    // Budget: romdyn::limits::MAX_LOAD_STEPS = 1e5.
    refused("load-steps", &[("p.mbd", PENDULUM)], &["eig", "p.mbd", "--static", "--load-steps", "100000000"], &["100000000 load increments: more than romdyn's limit of 100000"]);
}

#[cfg(unix)]
#[test]
fn devices_and_fifos_are_refused_without_blocking() {
    for dev in ["/dev/zero", "/dev/urandom"] {
        let text = PENDULUM.replace("begin: data;", &format!("include: \"{dev}\";\nbegin: data;"));
        let line = text.lines().position(|l| l.starts_with("include")).unwrap() + 1;
        refused("dev", &[("p.mbd", &text)], &["eig", "p.mbd"], &[&format!("p.mbd:{line}:10: error: cannot include \"{dev}\": cannot read: it is a device, not a regular file")]);
    }
    let d = folder("fifo", &[]);
    let status = Command::new("mkfifo").arg(d.join("f.mbd")).status().unwrap();
    assert!(status.success());
    std::fs::write(d.join("p.mbd"), "include: \"f.mbd\";\n").unwrap();
    let before = listing(&d);
    for (file, want) in [("f.mbd", "f.mbd: error: cannot read: it is a FIFO (named pipe), not a regular file"), ("p.mbd", "p.mbd:1:10: error: cannot include \"f.mbd\": cannot read: it is a FIFO")] {
        let o = romdyn_in(&d, &["eig", file]);
        assert_eq!(o.code, Some(1));
        assert!(o.stderr.contains(want), "{}", o.stderr);
    }
    assert_eq!(listing(&d), before);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn an_all_zero_pencil_is_singular() {
    let json = r#"{"Fyd": "z.mtx", "Fy": "z.mtx", "B": [[1]], "C": [[1]]}"#.replace("[[1]], \"C\": [[1]]", "{\"matrix_market\": \"b.mtx\"}, \"C\": {\"matrix_market\": \"c.mtx\"}");
    let files = [
        ("z.mtx", "%%MatrixMarket matrix coordinate real general\n2000 2000 0\n"),
        ("b.mtx", "%%MatrixMarket matrix coordinate real general\n2000 1 1\n1 1 1\n"),
        ("c.mtx", "%%MatrixMarket matrix coordinate real general\n1 2000 1\n1 1 1\n"),
        ("p.json", &json),
    ];
    refused("zero-2000", &files, &["eig", "--pencil", "p.json"], &["the pencil is singular: det(λ F_yd + F_y) = 0 for every λ", "unknown 1 has no entry in F_yd or F_y"]);
}

// Point 3: wrong results with exit 0.

#[test]
fn singular_pencils_are_reported_not_labelled() {
    let zero = pencil_json("[[0, 0], [0, 0]]", "[[0, 0], [0, 0]]");
    refused("zero", &[("p.json", &zero)], &["eig", "--pencil", "p.json"], &["the pencil is singular"]);
    refused("zero-freq", &[("p.json", &zero)], &["freq", "--pencil", "p.json", "--fmin", "1", "--fmax", "10", "-o", "f"], &["the pencil is singular"]);
    // Common null vector (1, 1): F_yd v = F_y v = 0, no zero row or column.
    let common = pencil_json("[[1, -1], [2, -2]]", "[[3, -3], [1, -1]]");
    refused("common", &[("p.json", &common)], &["eig", "--pencil", "p.json"], &["the pencil is singular", "rank deficient at two unrelated shifts"]);
}

#[test]
fn extreme_scaling_keeps_the_right_labels() {
    // (λ F_yd + F_y) v = 0 with F_yd = s I, F_y = s [[0, -1], [4, 0]]: λ = ±2j rad/s for
    // any s (closed form); s = 1e308 and 1e-300.
    for s in ["1e308", "1e-300"] {
        let json = pencil_json(&format!("[[{s}, 0], [0, {s}]]"), &format!("[[0, -{s}], [4{}, 0]]", if s == "1e308" { "e307".to_string() } else { format!("{}", &s[1..]) }));
        let json = if s == "1e308" { pencil_json("[[1e308, 0], [0, 1e308]]", "[[0, -2.5e307], [1e308, 0]]") } else { json };
        let d = folder("extreme", &[("p.json", &json)]);
        let o = romdyn_in(&d, &["eig", "--pencil", "p.json", "--json"]);
        assert_eq!(o.code, Some(0), "{s}: {}", o.stderr);
        let v: serde_json::Value = serde_json::from_str(&o.stdout).unwrap();
        let ev = v["eigenvalues"].as_array().unwrap();
        let kinds: Vec<&str> = ev.iter().map(|e| e["kind"].as_str().unwrap()).collect();
        assert_eq!(kinds, ["dynamic", "dynamic"], "{s}: {}", o.stdout);
        // With 1e308: F_y = 1e308 [[0, -1/4], [1, 0]] gives λ² = -1/4, λ = ±0.5j; else ±2j.
        let want = if s == "1e308" { 0.5 } else { 2.0 };
        assert!((ev[0]["im"].as_f64().unwrap().abs() - want).abs() < 1e-12 * want, "{s}: {}", o.stdout);
        std::fs::remove_dir_all(&d).ok();
    }
}

#[test]
fn octave_pencils_with_subnormal_dcoef_or_non_finite_entries_are_refused() {
    refused("dcoef", &[("p.m", "dCoef = 1e-320;\nAplus = [1 0; 0 1];\nAminus = [1 0; 0 -1];\n")], &["eig", "--pencil", "p.m"], &["p.m:1:1: 'dCoef' must be a positive normal number (s), found 1e-320"]);
    refused("nan", &[("p.m", "dCoef = 1;\nAplus = [1 NaN; 0 1];\nAminus = [1 0; 0 -1];\n")], &["eig", "--pencil", "p.m"], &["p.m:2:1: 'Aplus' entry (1, 2) is NaN: a Jacobian must be finite"]);
    refused("inf", &[("p.m", "dCoef = 1;\nAplus = [1 0; 0 1];\nAminus = [1 0; -Inf -1];\n")], &["eig", "--pencil", "p.m"], &["p.m:3:1: 'Aminus' entry (2, 1) is -inf"]);
}

#[test]
fn octave_pencils_with_entries_of_1e308_keep_their_labels() {
    // F_yd = (J + J*)/2 = 1e308 I and F_y = (J - J*)/(2 dCoef) = 1e308 [[0, 1/2], [-2, 0]]
    // both overflow when formed directly; λ² + 1 = 0 gives λ = ±1j rad/s (closed form).
    let d = folder("big-m", &[("p.m", "dCoef = 0.5;\nAplus = [1e308 0.25e308; -1e308 1e308];\nAminus = [1e308 -0.25e308; 1e308 1e308];\n")]);
    let o = romdyn_in(&d, &["eig", "--pencil", "p.m", "--json"]);
    assert_eq!(o.code, Some(0), "{}", o.stderr);
    let v: serde_json::Value = serde_json::from_str(&o.stdout).unwrap();
    let ev = v["eigenvalues"].as_array().unwrap();
    assert!(ev.iter().all(|e| e["kind"] == "dynamic"), "{}", o.stdout);
    assert!((ev[0]["im"].as_f64().unwrap().abs() - 1.0).abs() < 1e-12, "{}", o.stdout);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn a_zero_dcoef_is_refused() {
    let json = pencil_json("[[1, 0], [0, 1]]", "[[0, -1], [4, 0]]");
    refused("dcoef0", &[("p.json", &json)], &["eig", "--pencil", "p.json", "--dcoef", "0"], &["--dcoef", "dCoef must be a positive finite time step coefficient [s], got 0"]);
}

#[test]
fn files_without_a_model_are_refused() {
    for (name, text) in [("empty", ""), ("blank", "  \n\t\n"), ("comments", "# nothing\n/* at all */\n")] {
        for cmd in ["run", "check", "eig"] {
            refused(name, &[("m.mbd", text)], &[cmd, "m.mbd"], &["m.mbd:1:1: error: the file defines no nodes and no elements"]);
        }
    }
}

#[test]
fn static_eigenanalysis_of_a_singular_model_is_refused() {
    let twice = PENDULUM.replace("joints: 2;", "joints: 3;").replace("    body: 3", "    joint: 8, revolute hinge, 1, position, null, 2, position, 0., L, 0.;\n    body: 3");
    refused("dup-hinge", &[("p.mbd", &twice)], &["eig", "p.mbd", "--static"], &["the pencil is singular", "a common null vector of F_yd and F_y involves revolute hinge", "revolute hinge 8"]);
    let no_inertia = PENDULUM.replace("revolute hinge", "spherical hinge").replace("set: const real J = 1.e-3;", "set: const real J = 0.;");
    refused("no-inertia", &[("p.mbd", &no_inertia)], &["eig", "p.mbd", "--static"], &["the pencil is singular", "unknown 11 has no entry", "involves node 2 gy"]);
}

#[test]
fn json_pencils_with_a_duplicate_field_are_refused() {
    let json = "{\"Fyd\": [[1]],\n \"Fy\": [[1]], \"B\": [[1]], \"C\": [[1]],\n \"Fy\": [[2]]}";
    refused("dup", &[("p.json", json)], &["eig", "--pencil", "p.json"], &["p.json:3:", "invalid JSON: field \"Fy\" appears twice"]);
}

// Point 4: singular models named where they are singular.

#[test]
fn singular_models_name_the_unknowns_without_an_equation() {
    let node = "    structural: 2, dynamic, 0., -L, 0., eye, null, null;";
    let unconnected = PENDULUM.replace("structural nodes: 2;", "structural nodes: 3;").replace(node, &format!("{node}\n    structural: 9, static, 5., 0., 0., eye, null, null;"));
    refused("unconnected", &[("p.mbd", &unconnected)], &["eig", "p.mbd"], &["initial derivatives", "the matrix is singular: structural rank 29 of 35; unknowns no equation determines: node 9 x"]);
    let massless = PENDULUM.replace("structural nodes: 2;", "structural nodes: 3;").replace(node, &format!("{node}\n    structural: 9, dynamic, 5., 0., 0., eye, null, null;"));
    refused("massless", &[("p.mbd", &massless)], &["eig", "p.mbd"], &["unknowns no equation determines: node 9 x"]);
    let clamp_twice = PENDULUM.replace("joints: 2;", "joints: 3;").replace("joint: 1, clamp, 1, node, node;", "joint: 1, clamp, 1, node, node;\n    joint: 7, clamp, 1, node, node;");
    refused("clamp-twice", &[("p.mbd", &clamp_twice)], &["eig", "p.mbd"], &["the matrix is singular", "equations left without an unknown: clamp 7 constraint"]);
    let no_inertia = PENDULUM.replace("revolute hinge", "spherical hinge").replace("set: const real J = 1.e-3;", "set: const real J = 0.;");
    refused("j0", &[("p.mbd", &no_inertia)], &["eig", "p.mbd"], &["the matrix is singular", "node 2 g"]);
}

#[test]
fn a_failing_static_load_increment_is_named() {
    // A free body under gravity has no static equilibrium.
    let free = PENDULUM.replace("joints: 2;", "").replace("joint: 1, clamp, 1, node, node;", "").replace("structural nodes: 2;", "structural nodes: 1;").replace("    structural: 1, static, null, eye, null, null;\n", "");
    let free = free.replace("    joint: 2, revolute hinge,\n        1, position, null,\n        2, position, 0., L, 0.;\n", "");
    refused("free", &[("p.mbd", &free)], &["eig", "p.mbd", "--static"], &["static equilibrium", "load increment 1 of 10"]);
}

// Point 5: output sets.

#[test]
fn a_directory_in_the_way_stops_the_run_before_it_starts() {
    let d = folder("dir-in-way", &[("p.mbd", PENDULUM)]);
    std::fs::create_dir(d.join("p.mov")).unwrap();
    let before = listing(&d);
    let o = romdyn_in(&d, &["run", "p.mbd"]);
    assert_eq!(o.code, Some(1), "{}", o.stderr);
    assert!(o.stderr.contains("p.mov: is a directory"), "{}", o.stderr);
    assert_eq!(listing(&d), before);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn stale_temporaries_of_dead_processes_are_removed_by_the_next_run() {
    // PID 4194305 is above Linux's largest (2^22): no such process runs.
    let d = folder("stale", &[("p.mbd", PENDULUM), (".p.mov.tmp-4194305-12345", "half a run")]);
    let o = romdyn_in(&d, &["run", "p.mbd"]);
    assert_eq!(o.code, Some(0), "{}", o.stderr);
    assert_eq!(listing(&d), ["p.log", "p.mbd", "p.mov", "p.out", "p_0.json", "p_0.m"]);
    std::fs::remove_dir_all(&d).ok();
}

// Point 6: lenient inputs.

#[test]
fn lenient_inputs_are_refused_or_accepted_as_documented() {
    let early = PENDULUM.replace("eigenanalysis: 0.,", "eigenanalysis: -1.,");
    let line = early.lines().position(|l| l.contains("eigenanalysis: -1.")).unwrap() + 1;
    refused("eigen-time", &[("p.mbd", &early)], &["run", "p.mbd"], &[&format!("p.mbd:{line}:5: error: eigenanalysis time -1 s is before the initial time 0 s")]);
    let elements_first = {
        let (head, rest) = PENDULUM.split_at(PENDULUM.find("begin: nodes;").unwrap());
        let (nodes, elements) = rest.split_at(rest.find("begin: elements;").unwrap());
        format!("{head}{elements}\n{nodes}")
    };
    let line = elements_first.lines().position(|l| l.starts_with("begin: nodes;")).unwrap() + 1;
    refused("order", &[("p.mbd", &elements_first)], &["eig", "p.mbd"], &[&format!("p.mbd:{line}:1: error: block 'nodes' must come before 'elements'")]);
    let negative = PENDULUM.replace("body: 3, 2, M, null, diag, J, J, J;", "body: 3, 2, M, null, diag, J, -J, J;");
    let line = negative.lines().position(|l| l.contains("diag, J, -J, J")).unwrap() + 1;
    refused("inertia", &[("p.mbd", &negative)], &["eig", "p.mbd"], &[&format!("p.mbd:{line}:26: error: the inertia is not symmetric positive semi-definite (principal moments")]);
    let itself = PENDULUM.replace("        2, position, 0., L, 0.;", "        1, position, null;");
    let line = itself.lines().position(|l| l.contains("joint: 2, revolute hinge")).unwrap() + 1;
    refused("itself", &[("p.mbd", &itself)], &["eig", "p.mbd"], &[&format!("p.mbd:{line}:12: error: revolute hinge 2 connects node 1 to itself")]);
    let o = refused("missing", &[], &["eig", "missing.mbd"], &["missing.mbd: error: cannot read: No such file or directory"]);
    assert!(!o.contains(":0:0:"), "{o}");
    let o = refused("missing-pencil", &[], &["eig", "--pencil", "missing.json"], &["missing.json: cannot read: No such file or directory (os error 2)"]);
    assert_eq!(o.matches("os error").count(), 1, "{o}");
    let mut latin1 = PENDULUM.as_bytes().to_vec();
    latin1.splice(0..0, b"# caf\xE9\n".iter().copied());
    let d = folder("latin1", &[]);
    std::fs::write(d.join("p.mbd"), &latin1).unwrap();
    let o = romdyn_in(&d, &["eig", "p.mbd"]);
    assert_eq!(o.code, Some(1));
    assert!(o.stderr.contains("p.mbd:1:6: error: byte 0xE9 is not UTF-8 text"), "{}", o.stderr);
    // A UTF-8 byte-order mark is accepted: the pendulum's ±3.130527 j rad/s (CASES C2, docs/src/cases.md).
    std::fs::write(d.join("p.mbd"), format!("\u{feff}{PENDULUM}")).unwrap();
    let o = romdyn_in(&d, &["eig", "p.mbd"]);
    assert_eq!(o.code, Some(0), "{}", o.stderr);
    assert!(o.stdout.contains("3.130527e0"), "{}", o.stdout);
    std::fs::remove_dir_all(&d).ok();
}

/// Allocation failure is a message and exit status 1, never Rust's abort: a 7000 x 7000
/// all-zero pencil (two dense matrices of 392 MB each, within the 5e7-entry budget) read
/// under a 600 MB address-space limit (`ulimit -v`, POSIX sh).
#[test]
fn out_of_memory_is_a_message_not_an_abort() {
    let mtx = "%%MatrixMarket matrix coordinate real general\n7000 7000 0\n";
    let pencil = r#"{"Fyd": "z.mtx", "Fy": "z.mtx", "B": "b.mtx", "C": "c.mtx"}"#;
    let b = "%%MatrixMarket matrix coordinate real general\n7000 1 1\n1 1 1\n";
    let c = "%%MatrixMarket matrix coordinate real general\n1 7000 1\n1 1 1\n";
    let d = folder("oom", &[("z.mtx", mtx), ("b.mtx", b), ("c.mtx", c), ("p.json", pencil)]);
    let cmd = format!("ulimit -v 600000 && exec '{}' eig --pencil p.json", env!("CARGO_BIN_EXE_romdyn"));
    let out = Command::new("sh").args(["-c", &cmd]).current_dir(&d).stdin(Stdio::null()).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("romdyn: error: out of memory: the system refused ") && !err.contains("memory allocation of"), "{err}");
    std::fs::remove_dir_all(&d).ok();
}

/// A constitutive law whose scalar function leaves its domain (`log` at zero rotation) gives
/// a residual that is not finite: the failure names the element that put it there and the
/// equation, in the initial assembly and in the derivatives' Newton alike (issue 32: both
/// said only "the residual is not finite"), and where the element is written. The file:
/// tests/mbdyn_files/function_hinge.mbd with a `log` in place of its cubic part and a second
/// hinge, 5, carrying it.
#[test]
fn a_law_out_of_its_domain_is_named_by_its_element() {
    let original = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/function_hinge.mbd")).unwrap();
    let text = original
        .replace("scalar function: \"cubic part\", pow, 3.;", "scalar function: \"cubic part\", log, 10.;")
        .replace("joints: 2;", "joints: 3;")
        .replace(
            "joint: 2, deformable hinge, 1, 2, scalar function elastic isotropic, \"stiffening\";",
            "joint: 2, deformable hinge, 1, 2, linear elastic, 10.;\n    joint: 5, deformable hinge, 1, 2, scalar function elastic isotropic, \"stiffening\";",
        );
    let run = |text: &str| {
        let m = romdyn::input::mbdyn::parse_text(text, Path::new("f.mbd")).and_then(|d| romdyn::input::mbdyn::build(&d)).unwrap_or_else(|e| panic!("{e}"));
        romdyn::analysis::run(&m.model, &m.problem, &mut ()).err().map(|e| e.to_string()).unwrap_or_default()
    };
    // Where hinge 5 is written: its line, column 5 (after the indentation).
    let line = text.lines().position(|l| l.contains("joint: 5,")).unwrap() + 1;
    let e = run(&text);
    assert!(e.contains("initial assembly diverged") && e.contains(&format!("= NaN, from deformable hinge 5 (f.mbd:{line}:5)")), "{e}");
    let skipped = text.replace("    output precision: 15;", "    output precision: 15;\n    skip initial joint assembly;");
    let e = run(&skipped);
    assert!(e.contains(&format!("the residual is not finite: deformable hinge 5 (f.mbd:{}:5): its contribution to node 2 moment", line + 1)) && e.contains("is NaN"), "{e}");
    // Issue 32 point 5: the law's scalar functions are named by their own cards, the
    // function the law names and those it is made of (`sum` of two), each once.
    let card = |text: &str, name: &str| text.lines().position(|l| l.starts_with(&format!("scalar function: \"{name}\""))).unwrap() + 1;
    let functions = |text: &str| format!("(it evaluates scalar function \"stiffening\" (f.mbd:{}:1), scalar function \"linear part\" (f.mbd:{}:1), scalar function \"cubic part\" (f.mbd:{}:1))", card(text, "stiffening"), card(text, "linear part"), card(text, "cubic part"));
    assert!(run(&text).contains(&format!("from deformable hinge 5 (f.mbd:{line}:5) {}", functions(&text))), "{}", run(&text));
    assert!(e.contains(&format!("is NaN {}", functions(&skipped))), "{e}");
    // The same law written on a `constitutive law:` card the hinge refers to: the card's
    // functions are the hinge's.
    let referred = skipped
        .replace("joint: 5, deformable hinge, 1, 2, scalar function elastic isotropic, \"stiffening\";", "joint: 5, deformable hinge, 1, 2, reference, 7;")
        .replace("scalar function: \"stiffening\", sum, \"linear part\", \"cubic part\";", "scalar function: \"stiffening\", sum, \"linear part\", \"cubic part\";\nconstitutive law: 7, 3, scalar function elastic isotropic, \"stiffening\";");
    assert!(referred.contains("reference, 7;") && referred.contains("constitutive law: 7"));
    let e = run(&referred);
    assert!(e.contains(&format!("is NaN {}", functions(&referred))), "{e}");
    // A force whose `dof` drive caller card takes the log of the node's x, which the node's
    // velocity (−2 m/s from x = 1 m) drives below zero at t ≈ 0.5 s: the run names the force,
    // the drive caller card it refers to and that card's scalar function, each by its place.
    let thrown = "begin: data; problem: initial value; end: data;\n\
        begin: initial value; initial time: 0.; final time: 1.; time step: 1.e-2; tolerance: 1e-9; max iterations: 20; end: initial value;\n\
        begin: control data; structural nodes: 1; rigid bodies: 1; forces: 1; end: control data;\n\
        scalar function: \"lg\", log, 1.;\n\
        drive caller: 3, dof, 1, structural, 1, algebraic, scalar function, \"lg\";\n\
        begin: nodes; structural: 1, dynamic, 1., 0., 0., eye, -2., 0., 0., null; end: nodes;\n\
        begin: elements;\n  body: 1, 1, 1., null, eye;\n  force: 1, absolute, 1, position, null, 1., 0., 0., reference, 3;\nend: elements;\n";
    let e = run(thrown);
    assert!(e.contains("absolute force 1 (f.mbd:9:3): its contribution to node 1 force x equilibrium is NaN (it evaluates drive caller 3 (f.mbd:5:1), scalar function \"lg\" (f.mbd:4:1))"), "{e}");
    // An element that evaluates no scalar function adds nothing.
    assert!(!e.contains("deformable hinge 2 (f.mbd") , "{e}");
}
