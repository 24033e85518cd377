//! The `romdyn` binary end to end on the shipped example (CASES C1).

use crate::common::cli::{romdyn, temp_dir};

#[test]
fn eig_json_has_the_documented_fields_and_c1_eigenvalues() {
    let (ok, out, err) = romdyn(&["eig", "--pencil", "examples/two_masses.json", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["equations"], 5);
    assert_eq!(v["dcoef"], 1e-3);
    let ev = v["eigenvalues"].as_array().unwrap();
    assert_eq!(ev.len(), 5);
    // CASES C1, r = 10: −0.5 ± 9.987492 j rad/s (closed form), 1e-6 absolute.
    assert!((ev[0]["re"].as_f64().unwrap() + 0.5).abs() < 1e-6);
    assert!((ev[0]["im"].as_f64().unwrap() - 9.987492).abs() < 1e-6);
    assert_eq!(ev[0]["kind"], "dynamic");
    // Undamped f = |λ|/2π = sqrt(100)/2π = 1.591549 Hz; MBDyn's frequency |Im λ|/2π =
    // 9.987492/2π = 1.589559 Hz; ζ = r / (2 sqrt(k M)) = 0.05.
    assert!((ev[0]["undamped_freq_hz"].as_f64().unwrap() - 1.5915494).abs() < 1e-6);
    assert!((ev[0]["freq_hz"].as_f64().unwrap() - 1.5895591).abs() < 1e-6);
    assert!((ev[0]["damping"].as_f64().unwrap() - 0.05).abs() < 1e-9);
    let kinds: Vec<&str> = ev.iter().map(|e| e["kind"].as_str().unwrap()).collect();
    assert_eq!(kinds, ["dynamic", "dynamic", "infinite", "infinite", "infinite"]);
}

#[test]
fn eig_text_table_and_lambda_route_agree() {
    let (ok, direct, err) = romdyn(&["eig", "--pencil", "examples/two_masses.json"]);
    assert!(ok, "{err}");
    assert!(direct.contains("dynamic") && direct.contains("infinite") && direct.contains("[Hz]"), "{direct}");
    let (ok, lambda, err) = romdyn(&["eig", "--pencil", "examples/two_masses.json", "--route", "lambda", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&lambda).unwrap();
    assert!((v["eigenvalues"][0]["im"].as_f64().unwrap() - 9.987492).abs() < 1e-6);
    assert_eq!(v["counts"]["infinite"], 3);
}

#[test]
fn rom_to_stdout_json_and_files() {
    let (ok, out, err) = romdyn(&["rom", "--pencil", "examples/two_masses.json", "--count", "1"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["kind"], "ordinary");
    for k in ["E", "A", "B", "C", "D"] {
        assert!(v[k].is_array(), "{k}");
    }
    assert_eq!(v["A"].as_array().unwrap().len(), 2);
    // Static gain printed against the full model's 1/k = 1e-3 m/N.
    assert!(err.contains("full model                          1.000000e-3\n  ROM                                 1.000000e-3"), "{err}");

    let dir = temp_dir("rom");
    for ext in ["json", "mat", "npz"] {
        let path = dir.join(format!("rom.{ext}"));
        let (ok, _, err) = romdyn(&["rom", "--pencil", "examples/two_masses.json", "--count", "1", "-o", path.to_str().unwrap()]);
        assert!(ok, "{err}");
        assert!(path.metadata().unwrap().len() > 100, "{ext}");
    }
    let bode = dir.join("bode");
    let (ok, _, err) = romdyn(&["rom", "--pencil", "examples/two_masses.json", "--count", "1", "-o", dir.join("r.json").to_str().unwrap(), "--bode", bode.to_str().unwrap()]);
    assert!(ok, "{err}");
    for ext in ["csv", "svg", "png"] {
        assert!(dir.join(format!("bode.{ext}")).exists(), "{ext}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn freq_writes_table_and_plots() {
    let dir = temp_dir("freq");
    let prefix = dir.join("resp");
    let (ok, _, err) = romdyn(&["freq", "--pencil", "examples/two_masses.json", "--count", "1", "--fmin", "0.1", "--fmax", "10", "--points", "50", "-o", prefix.to_str().unwrap()]);
    assert!(ok, "{err}");
    let csv = std::fs::read_to_string(dir.join("resp.csv")).unwrap();
    // Header comment, column names, 50 frequencies; full model and ROM columns.
    assert_eq!(csv.lines().count(), 52);
    assert!(csv.contains("full model: x2 [m] / f (force on mass 2) [N] mag") && csv.contains("ROM: x2 [m] / f (force on mass 2) [N] mag"));
    // At 0.1 Hz the response is close to the static 1e-3 m/N: |H| = 1/|k − M ω² + j r ω| (closed form).
    let row: Vec<f64> = csv.lines().nth(2).unwrap().split(',').map(|x| x.parse().unwrap()).collect();
    let w = 2.0 * std::f64::consts::PI * 0.1;
    let exact = 1.0 / ((1000.0 - 10.0 * w * w).powi(2) + (10.0 * w).powi(2)).sqrt();
    assert!((row[3] - exact).abs() / exact < 1e-9 && (row[7] - exact).abs() / exact < 1e-9, "{row:?}");
    assert!(dir.join("resp.svg").exists() && dir.join("resp.png").exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_input_gives_a_clear_error_and_no_output() {
    let dir = temp_dir("bad");
    let bad = dir.join("bad.json");
    std::fs::write(&bad, "{\"Fyd\": [[1]], \"Fy\": [[1]], \"B\": [[1]]}").unwrap();
    let out = dir.join("rom.json");
    let (ok, _, err) = romdyn(&["rom", "--pencil", bad.to_str().unwrap(), "--count", "1", "-o", out.to_str().unwrap()]);
    assert!(!ok);
    assert!(err.contains("field \"C\": missing"), "{err}");
    assert!(!out.exists());
    let (ok, _, err) = romdyn(&["rom", "--pencil", "examples/two_masses.json", "--count", "7"]);
    assert!(!ok);
    assert!(err.contains("7 modes requested, the model has 1 dynamic modes"), "{err}");
    // A reversed or empty band is refused as Python and the sparse route refuse it (issue 31:
    // the CLI took FMIN = FMAX).
    for band in ["5:1", "2:2"] {
        let (ok, _, err) = romdyn(&["rom", "--pencil", "examples/two_masses.json", "--band", band]);
        assert!(!ok);
        assert!(err.contains("need 0 <= FMIN < FMAX"), "{band}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn eig_and_rom_on_an_mbdyn_model() {
    let (ok, out, err) = romdyn(&["eig", "examples/pendulum.mbd", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["equations"], 29);
    let first = &v["eigenvalues"][0];
    // ±3.130527 j rad/s (eq. 82, CASES C2), 1e-6 relative; the swing is node 2 moving along x.
    assert!((first["im"].as_f64().unwrap() - 3.130527).abs() < 3.2e-6, "{first}");
    assert_eq!(first["description"], "node 2 x 100 %");

    let dir = temp_dir("model");
    let path = dir.join("rom.json");
    let (ok, _, err) = romdyn(&["rom", "examples/pendulum.mbd", "--input", "2:Mz", "--output", "2:rz", "--count", "1", "-o", path.to_str().unwrap()]);
    assert!(ok, "{err}");
    // Static gain 1/(m g L) = 0.1019368 rad/(N m) (CASES C2).
    assert!(err.contains("node 2 rz [rad]\n  full model                  1.019368e-1\n  ROM                         1.019368e-1"), "{err}");
    let rom: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(rom["inputs"][0], "node 2 Mz [N m]");
    let (ok, _, err) = romdyn(&["rom", "examples/pendulum.mbd", "--input", "2:Qz", "--output", "2:rz", "--count", "1"]);
    assert!(!ok && err.contains("'2:Qz': expected NODE:COMPONENT with COMPONENT one of Fx|Fy|Fz|Mx|My|Mz"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `--set NAME=VALUE` on every command that reads a model (issue 37: only `sweep` had it, so
/// one ROM of a changed parameter meant editing the file). The compound pendulum of
/// examples/pendulum.mbd at L = 4 m: ω = √(m g L / (m L² + J)) = 1.565997 rad/s (m = 1 kg,
/// J = 1e-3 kg m², g = 9.81 m/s²), to the 7 printed digits; a range is refused outside sweep.
#[test]
fn set_gives_one_run_another_value() {
    let omega = (9.81f64 * 4.0 / (16.0 + 1e-3)).sqrt();
    assert!((omega - 1.565997).abs() < 1e-6);
    let (ok, out, err) = romdyn(&["eig", "examples/pendulum.mbd", "--set", "L=4"]);
    assert!(ok, "{err}");
    assert!(out.contains("±1.565997e0"), "{out}");
    let dir = temp_dir("set_run");
    let prefix = dir.join("p");
    let (ok, _, err) = romdyn(&["rom", "examples/pendulum.mbd", "--set", "L=4", "--input", "2:Mz", "--output", "2:rz", "--count", "1"]);
    assert!(ok && err.contains("±1.565997e0"), "{err}");
    let (ok, _, err) = romdyn(&["run", "examples/pendulum.mbd", "--set", "L=4", "-o", prefix.to_str().unwrap()]);
    assert!(ok, "{err}");
    // The run's eigenanalysis at t = 0 (the file asks for one) sees the longer pendulum too.
    let m = std::fs::read_to_string(dir.join("p_0.json")).unwrap();
    assert!(m.contains("1.56599"), "{m}");
    let (ok, _, err) = romdyn(&["eig", "examples/pendulum.mbd", "--set", "L=1:2:3"]);
    assert!(!ok && err.contains("--set: L: 3 values; one run takes one value"), "{err}");
    let (ok, _, err) = romdyn(&["check", "examples/pendulum.mbd", "--set", "Q=1"]);
    assert!(!ok && err.contains("--set Q: the file declares no variable 'Q'"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cut_opens_a_loop_and_refusals_name_the_option() {
    // The closed loop of examples/pid_mass.mbd has 4 dynamic eigenvalues; cut at its link,
    // the plant's pair and the controller's −1/τ remain, its integrator a zero eigenvalue
    // (tests/application/loop_cut.rs checks the numbers).
    let (ok, out, err) = romdyn(&["eig", "examples/pid_mass.mbd", "--cut", "genel:4"]);
    assert!(ok, "{err}");
    assert!(out.contains("3 dynamic, 1 zero"), "{out}");
    let (ok, out, err) = romdyn(&["rom", "examples/pid_mass.mbd", "--input", "1:abstract", "--output", "1:abstract", "--cut", "genel:4", "--count", "1"]);
    assert!(ok, "{err}");
    assert!(out.contains("cut genel cross spring support 4 at abstract node 1 (returned) [-]"), "{out}");
    let (ok, _, err) = romdyn(&["eig", "examples/pid_mass.mbd", "--cut", "genel:9"]);
    assert!(!ok);
    assert!(err.contains("--cut: genel:9: the model has no genel 9"), "{err}");
    let (ok, _, err) = romdyn(&["eig", "examples/pid_mass.mbd", "--cut", "joint:4"]);
    assert!(!ok);
    assert!(err.contains("'joint:4': expected genel:LABEL or force:LABEL"), "{err}");
}
