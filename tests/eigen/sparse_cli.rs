//! `romdyn eig|rom|freq --solver sparse` against `--solver dense` on the 1712-equation
//! pendulum chain written as an MBDyn file (100 links of 0.1 kg, 0.1 m, hanging under
//! gravity from a clamped node; `scripts/bench_vs_mbdyn.sh`'s chain, hanging), and the
//! option's errors. The dense route is validated against QZ on the whole pencil and the
//! paper's cases elsewhere (tests/eigen/eigen_deflation.rs, tests/eigen/sparse_eigen.rs).

use crate::common::cli::{romdyn, temp_dir};
use std::path::{Path, PathBuf};

/// The N-link chain hanging along −y (17 N + 12 equations).
fn chain_file(dir: &Path, n: usize) -> PathBuf {
    let mut s = String::from("begin: data;\n    problem: initial value;\nend: data;\nbegin: initial value;\n    initial time: 0.;\n    final time: 1.;\n    time step: 1.e-3;\n    tolerance: 1.e-9;\n    max iterations: 20;\nend: initial value;\n");
    s += &format!("begin: control data;\n    structural nodes: {};\n    rigid bodies: {n};\n    joints: {};\n    gravity;\nend: control data;\n", n + 1, n + 1);
    s += "begin: nodes;\n    structural: 0, static, null, eye, null, null;\n";
    for i in 1..=n {
        s += &format!("    structural: {i}, dynamic, 0., {:.1}, 0., eye, null, null;\n", -0.1 * i as f64);
    }
    s += "end: nodes;\nbegin: elements;\n    joint: 0, clamp, 0, node, node;\n";
    for i in 1..=n {
        s += &format!("    body: {i}, {i}, 0.1, null, diag, 1.e-4, 1.e-4, 1.e-4;\n    joint: {}, revolute hinge, {}, position, null, {i}, position, 0., 0.1, 0.;\n", n + i, i - 1);
    }
    s += "    gravity: uniform, single, 0., -1., 0., const, 9.81;\nend: elements;\n";
    let path = dir.join(format!("chain_{n}.mbd"));
    std::fs::write(&path, s).unwrap();
    path
}

/// The dynamic eigenvalues of `eig --json` as (re, im, error).
fn eigenvalues(json: &str) -> Vec<(f64, f64, f64)> {
    let v: serde_json::Value = serde_json::from_str(json).unwrap();
    v["eigenvalues"].as_array().unwrap().iter().filter(|e| e["kind"] == "dynamic").map(|e| (e["re"].as_f64().unwrap(), e["im"].as_f64().unwrap(), e["error"].as_f64().unwrap())).collect()
}

#[test]
fn eig_sparse_count_20_of_the_1712_equation_chain_equals_dense() {
    let dir = temp_dir("eig");
    let file = chain_file(&dir, 100);
    let f = file.to_str().unwrap();
    let (ok, dense, err) = romdyn(&["eig", f, "--static", "--count", "20", "--solver", "dense", "--json"]);
    assert!(ok, "{err}");
    let (ok, sparse, err) = romdyn(&["eig", f, "--static", "--count", "20", "--solver", "sparse", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&sparse).unwrap();
    assert_eq!(v["equations"], 1712);
    assert!(v["note"].as_str().is_some_and(|n| n.contains("sparse route") && n.contains("certified")), "{}", v["note"]);
    let (d, s) = (eigenvalues(&dense), eigenvalues(&sparse));
    assert_eq!((d.len(), s.len()), (40, 40));
    for (k, (a, b)) in d.iter().zip(&s).enumerate() {
        let norm = a.0.hypot(a.1);
        // Issue 13 acceptance: 1e-9 relative on the eigenvalues' imaginary parts; their real
        // parts (exactly 0: undamped) agree within the two routes' error estimates (eqs.
        // 32–35; the dense ones carry up to 8e-7 rad/s of rounding).
        assert!((a.1 - b.1).abs() <= 1e-9 * norm, "mode {}: {a:?} vs {b:?}", k + 1);
        assert!((a.0 - b.0).abs() <= 2.0 * (a.2 + b.2) + 1e-12 * norm, "mode {}: {a:?} vs {b:?}", k + 1);
    }
    // The text tables have the same columns and rows.
    let (ok, text, err) = romdyn(&["eig", f, "--static", "--count", "20", "--solver", "sparse"]);
    assert!(ok, "{err}");
    assert_eq!(text.lines().filter(|l| !l.starts_with('#') && l.contains(" dynamic ")).count(), 20, "{text}");
    assert!(text.contains("Re λ [rad/s]") && text.contains("energy share") && text.contains("# sparse route"), "{text}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn rom_sparse_static_gain_equals_dense() {
    let dir = temp_dir("rom");
    let file = chain_file(&dir, 100);
    let f = file.to_str().unwrap();
    let out = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let (dense_json, sparse_json) = (out("dense.json"), out("sparse.json"));
    // The dense run: a 2-point grid (its full-model response is a dense complex LU per point).
    let (ok, _, err) = romdyn(&["rom", f, "--static", "--input", "100:Fx", "--output", "100:x", "--count", "3", "--solver", "dense", "--points", "2", "-o", &dense_json]);
    assert!(ok, "{err}");
    let (ok, _, err) = romdyn(&["rom", f, "--static", "--input", "100:Fx", "--output", "100:x", "--count", "3", "--residualize", "--solver", "sparse", "-o", &sparse_json]);
    assert!(ok, "{err}");
    assert!(err.contains("statically corrected"), "{err}");
    let read = |p: &str| -> serde_json::Value { serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap() };
    let (d, s) = (read(&dense_json), read(&sparse_json));
    let gain = |v: &serde_json::Value, k: &str| v[k][0][0].as_f64().unwrap_or_else(|| panic!("{k}: {}", v[k]));
    let full = gain(&d, "full_static_gain");
    // The sparse ROM's static gain (3 modes, the others corrected by one sparse static solve)
    // and the sparse full gain equal the dense route's full-model gain (dense LU) to 1e-9.
    for (what, g) in [("sparse ROM", gain(&s, "rom_static_gain")), ("sparse full model", gain(&s, "full_static_gain"))] {
        assert!((g - full).abs() <= 1e-9 * full.abs(), "{what}: {g} vs dense {full}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn freq_sparse_full_model_response_equals_dense_at_5_frequencies() {
    // 30 links (522 equations: each dense run is a dense eigenanalysis too, kept small).
    let dir = temp_dir("freq");
    let file = chain_file(&dir, 30);
    let f = file.to_str().unwrap();
    let out = |name: &str| dir.join(name).to_str().unwrap().to_string();
    // The full model's frequency response, dense LU vs sparse LU at each frequency (one
    // symbolic factorization), at 5 frequencies from 0.1 to 0.8 Hz: 1e-9 relative.
    let (dense_prefix, sparse_prefix) = (out("dense_bode"), out("sparse_bode"));
    for (solver, prefix) in [("dense", &dense_prefix), ("sparse", &sparse_prefix)] {
        let (ok, _, err) = romdyn(&["freq", f, "--static", "--input", "30:Fx", "--output", "30:x", "--solver", solver, "--fmin", "0.1", "--fmax", "0.8", "--points", "5", "-o", prefix]);
        assert!(ok, "{solver}: {err}");
    }
    let table = |p: &str| -> Vec<Vec<f64>> {
        let text = std::fs::read_to_string(format!("{p}.csv")).unwrap();
        text.lines().filter(|l| !l.starts_with('#') && l.chars().next().is_some_and(|c| c.is_ascii_digit())).map(|l| l.split(',').map(|x| x.trim().parse().unwrap()).collect()).collect()
    };
    let (td, ts) = (table(&dense_prefix), table(&sparse_prefix));
    assert_eq!((td.len(), ts.len()), (5, 5), "{td:?}");
    // Columns: frequency, then re, im, magnitude, phase of the one channel; the phase of a
    // real response can print as ±180°, so re and im are compared relative to the magnitude
    // (the CSV keeps 11 significant digits).
    for (a, b) in td.iter().zip(&ts) {
        assert_eq!(a[0], b[0]);
        let mag = a[3];
        for k in 1..=3 {
            assert!((a[k] - b[k]).abs() <= 1e-9 * mag, "at {} Hz column {k}: {a:?} vs {b:?}", a[0]);
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn solver_bogus_is_a_clap_error_naming_the_values() {
    let (ok, _, err) = romdyn(&["eig", "examples/pendulum.mbd", "--solver", "bogus"]);
    assert!(!ok);
    assert!(err.contains("invalid value 'bogus' for '--solver <SOLVER>'") && err.contains("[possible values: auto, dense, sparse]"), "{err}");
    let (ok, help, _) = romdyn(&["rom", "--help"]);
    let help = help.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(ok && help.contains("--solver <SOLVER>") && help.contains("[default: auto]") && help.contains("sparse from 400 equations on"), "{help}");
}

#[test]
fn auto_keeps_the_shipped_examples_on_the_dense_route() {
    // The pendulum's 29 equations: the complete spectrum (22 zero, 5 infinite eigenvalues).
    let (ok, out, err) = romdyn(&["eig", "examples/pendulum.mbd"]);
    assert!(ok, "{err}");
    assert!(out.contains("2 dynamic, 22 zero, 5 infinite") && !out.contains("sparse route"), "{out}");
}
