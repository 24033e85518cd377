//! `romdyn run` on the pendulum of CASES C2: the MBDyn-compatible files and their layouts,
//! the period read back from the `.mov`, the eigenvalues read back from the `.m`, and what a
//! bad file or a failing run leaves behind.

use crate::common;

use std::path::Path;

use common::lambda_of_alpha;
use common::cli::{romdyn_at, listing, pendulum_variant, romdyn, temp_dir, write_file, DISPLACED_NODE, EIGENANALYSIS, FINAL_TIME, PENDULUM_NODE};
use romdyn::input::octave_m::read_octave_script;

/// ω = sqrt((g/L)/(1 + J/(m L²))) = 3.130527 rad/s (eq. 82, CASES C2).
const OMEGA: f64 = 3.130527;

#[test]
fn run_writes_the_mbdyn_files_with_their_layouts() {
    let dir = temp_dir("run-layouts");
    let file = write_file(
        &dir,
        "pendulum.mbd",
        &pendulum_variant(&[(FINAL_TIME, "    final time: 0.1;"), (EIGENANALYSIS, "    eigenanalysis: 0., output matrices, output eigenvectors, output geometry, use lapack;")]),
    );
    let (ok, out, err) = romdyn_at(&dir, &["run", &file]);
    assert!(ok, "{err}");
    assert!(out.contains("100 steps to t = 0.1 s"), "{out}");
    assert!(out.contains("eigenanalysis 0 at t = 0 s (dCoef = 0.5 s): 2 dynamic"), "{out}");
    // MBDyn 1.7.3 names the one analysis's file `PREFIX_0.m` too (solver.cc `Eig`, run here).
    assert_eq!(listing(&dir), ["pendulum.log", "pendulum.mbd", "pendulum.mov", "pendulum.out", "pendulum_0.json", "pendulum_0.m"]);

    // .out: derivatives line, key, `Step` + 8 columns for steps 0..=100, t = k h (1e-12 s), an
    // eigenvalue table of all 29 modes, the end line.
    let text = std::fs::read_to_string(dir.join("pendulum.out")).unwrap();
    assert!(text.contains("# Derivatives solution step at time 0 performed in"), "{text}");
    assert!(text.contains("# Step Time TStep NIter ResErr SolErr SolConv Out\n"));
    let steps: Vec<Vec<&str>> = text.lines().filter(|l| l.starts_with("Step ")).map(|l| l.split_whitespace().collect()).collect();
    assert_eq!(steps.len(), 101);
    for (k, s) in steps.iter().enumerate() {
        assert_eq!(s.len(), 9, "{s:?}");
        assert_eq!(s[1].parse::<usize>().unwrap(), k);
        assert!((s[2].parse::<f64>().unwrap() - k as f64 * 1e-3).abs() < 1e-12, "{s:?}");
        assert!(s[5].parse::<f64>().unwrap() <= 1e-9, "residual within the file's tolerance: {s:?}");
    }
    let table: Vec<&str> = text.lines().skip_while(|l| !l.starts_with("Mode n.")).skip(1).take_while(|l| !l.starts_with("Step")).collect();
    assert_eq!(table.len(), 29);
    let first: Vec<&str> = table[0].split_whitespace().collect();
    // "1: σ + ω j ζ% f": ω = 3.130527 rad/s, f = ω/2π = 0.498239 Hz (CASES C2, 1e-6 relative).
    assert_eq!((first[0], first[2], first[4]), ("1:", "+", "j"));
    assert!((first[3].parse::<f64>().unwrap() - OMEGA).abs() / OMEGA < 1e-6, "{first:?}");
    assert!((first[6].parse::<f64>().unwrap() - OMEGA / (2.0 * std::f64::consts::PI)).abs() < 1e-6, "{first:?}");
    assert!(text.lines().last().is_some_and(|l| l.starts_with("# End of simulation at time 1.000000000000e-1 after 100 steps;")), "{text}");

    // .mov: nodes x (steps + 1) lines of 13 columns, labels 1, 2 in turn; node 2 hangs at y = −L.
    let mov = std::fs::read_to_string(dir.join("pendulum.mov")).unwrap();
    let rows: Vec<Vec<f64>> = mov.lines().map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 2 * 101);
    assert!(rows.iter().all(|r| r.len() == 13));
    assert!(rows.iter().enumerate().all(|(i, r)| r[0] == [1.0, 2.0][i % 2]));
    assert!((rows[201][2] + 1.0).abs() < 1e-9, "{:?}", rows[201]);

    // .log: the model summary and the node index entries.
    let log = std::fs::read_to_string(dir.join("pendulum.log")).unwrap();
    for entry in ["model summary:\n", " equations: 29 (18 node, 11 constraint)\n", "structural node: 2 0e0 -1e0 0e0 euler123", "struct node dofs: 0 6\n", "struct node momentum dofs: 12\n", "struct node labels: 1 2\n"] {
        assert!(log.contains(entry), "{entry:?} in {log}");
    }

    // .m: MBDyn's variables and sizes; alpha gives ±3.130527 j (CASES C2, 1e-6 relative).
    let m = read_octave_script(&dir.join("pendulum_0.m")).unwrap();
    let names: Vec<&str> = m.variables.iter().map(|v| v.0.as_str()).collect();
    assert_eq!(names, ["dTime", "dCoef", "Aplus", "Aminus", "labels", "idx", "X0", "alpha", "VL", "VR"]);
    let size = |n: &str| m.get(n).map(|v| (v.rows, v.cols)).unwrap();
    assert_eq!((size("Aplus"), size("Aminus"), size("alpha"), size("VR"), size("VL")), ((29, 29), (29, 29), (29, 3), (29, 29), (29, 29)));
    assert_eq!((m.get("labels").unwrap().re.clone(), m.get("idx").unwrap().re.clone()), (vec![1.0, 2.0], vec![0.0, 6.0]));
    assert_eq!(m.get("X0").unwrap().re[6..9], [0.0, -1.0, 0.0]);
    let dcoef = m.get("dCoef").and_then(|v| v.scalar()).unwrap();
    assert_eq!(dcoef, 0.5);
    let alpha = m.get("alpha").unwrap();
    let mut swing: Vec<(f64, f64)> = (0..29).map(|k| lambda_of_alpha([alpha.get(k, 0), alpha.get(k, 1), alpha.get(k, 2)], dcoef)).filter(|l| (l.1.abs() - OMEGA).abs() / OMEGA < 1e-6).collect();
    swing.sort_by(|a, b| a.1.total_cmp(&b.1));
    assert_eq!(swing.len(), 2, "±3.130527 j among the alpha rows");
    assert!(swing.iter().all(|l| l.0.abs() < 1e-9) && swing[0].1 < 0.0 && swing[1].1 > 0.0, "{swing:?}");

    // .json: the same analysis. Written part by part as it is serialized
    // (src/output/eigen_json.rs), laid out as serde_json prints the document held whole
    // (keys sorted), full matrices, geometry, vectors and energy shares included.
    let text = std::fs::read_to_string(dir.join("pendulum_0.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    common::assert_canonical_json(&text);
    assert_eq!((json["dCoef"].as_f64(), json["equations"].as_u64(), json["counts"]["dynamic"].as_u64()), (Some(0.5), Some(29), Some(2)));
    assert!((json["eigenvalues"][0]["im"].as_f64().unwrap() - OMEGA).abs() / OMEGA < 1e-6);
    assert_eq!((json["Aplus"].as_array().unwrap().len(), json["VR"][0].as_array().unwrap().len(), json["alpha"].as_array().unwrap().len()), (29, 29, 29));
    std::fs::remove_dir_all(&dir).ok();
}

/// Times of downward zero crossings of node 2's x in a `.mov` (linear interpolation).
fn downward_crossings(mov: &Path, h: f64) -> Vec<f64> {
    let text = std::fs::read_to_string(mov).unwrap();
    let x: Vec<f64> = text.lines().filter(|l| l.starts_with("2 ")).map(|l| l.split_whitespace().nth(1).unwrap().parse().unwrap()).collect();
    (1..x.len()).filter(|&k| x[k - 1] > 0.0 && x[k] <= 0.0).map(|k| h * ((k - 1) as f64 + x[k - 1] / (x[k - 1] - x[k]))).collect()
}

#[test]
fn pendulum_period_read_from_the_mov_matches_cases_c2() {
    // Released from rest at 0.1 rad: T = 4 sqrt(I_O/(m g L)) K(sin(0.05)) = 2.008325 s
    // (CASES C2, computed, 7 digits). With h = 1e-3 s and the file's ms, ρ∞ = 0.6, the period
    // error is O((ωh)²) ≈ 1e-5 at most; crossings are interpolated linearly between steps.
    // Measured 7.8e-7 relative; tolerance 1e-5 relative.
    let dir = temp_dir("run-period");
    let file = write_file(&dir, "swing.mbd", &pendulum_variant(&[(FINAL_TIME, "    final time: 2.6;"), (PENDULUM_NODE, DISPLACED_NODE), (EIGENANALYSIS, "")]));
    let (ok, out, err) = romdyn(&["run", &file, "-o", &dir.join("out/swing").to_string_lossy()]);
    assert!(ok, "{err}");
    // MBDyn's count: 2600 additions of 1e-3 s sum to just below 2.6 s, so one more step.
    assert!(out.contains("2601 steps"), "{out}");
    let c = downward_crossings(&dir.join("out/swing.mov"), 1e-3);
    assert_eq!(c.len(), 2, "{c:?}");
    let period = c[1] - c[0];
    assert!((period - 2.008325).abs() / 2.008325 < 1e-5, "period {period} s");
    assert!(!listing(&dir.join("out")).iter().any(|f| f.ends_with(".m") || f.ends_with(".json")), "no eigenanalysis requested");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn several_eigenanalyses_are_numbered_and_a_time_after_the_end_is_reported() {
    let dir = temp_dir("run-list");
    let file = write_file(
        &dir,
        "pendulum.mbd",
        &pendulum_variant(&[(FINAL_TIME, "    final time: 0.05;"), (EIGENANALYSIS, "    eigenanalysis: list, 3, 0., 0.02, 1., output sparse matrices, parameter, 0.002;")]),
    );
    let (ok, out, err) = romdyn_at(&dir, &["run", &file]);
    assert!(ok, "{err}");
    assert!(out.contains("eigenanalysis 1 at t = 0.02 s"), "{out}");
    assert!(out.contains("eigenanalyses not done (the run ended first): t = 1 s"), "{out}");
    let files = listing(&dir);
    for f in ["pendulum_0.m", "pendulum_0.json", "pendulum_1.m", "pendulum_1.json"] {
        assert!(files.contains(&f.to_string()), "{f} in {files:?}");
    }
    assert!(!files.iter().any(|f| f.starts_with("pendulum_2")), "{files:?}");
    // Sparse matrices come back at full size through spconvert.
    let m = read_octave_script(&dir.join("pendulum_1.m")).unwrap();
    let a = m.get("Aplus").unwrap();
    assert!(a.from_sparse && (a.rows, a.cols) == (29, 29) && !m.variables.iter().any(|v| v.0 == "VR"));
    assert_eq!(m.get("dTime").and_then(|v| v.scalar()).map(|t| (t - 0.02).abs() < 1e-12), Some(true));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_analyses_files_take_the_suffix_width_and_format_as_mbdyn() {
    // MBDyn 1.7.3 (solver.cc `Eig`): `_` then K; `suffix width, N` pads K with zeros to N
    // digits; `compute` to ⌊log₁₀ count⌋ + 1 (so 10 analyses give `_00`); `suffix format`
    // is a printf format of K; a width other than 0 wins over a format.
    let cases = [
        ("", 2, vec!["p_0.m", "p_1.m"]),
        ("suffix width, 3,", 2, vec!["p_000.m", "p_001.m"]),
        ("suffix width, compute,", 2, vec!["p_0.m", "p_1.m"]),
        ("suffix width, compute,", 10, vec!["p_00.m", "p_09.m"]),
        ("suffix format, \"mode-%02d\",", 2, vec!["p_mode-00.m", "p_mode-01.m"]),
        ("suffix format, \"%-3d\", suffix width, 2,", 2, vec!["p_00.m", "p_01.m"]),
    ];
    for (k, (option, count, expected)) in cases.into_iter().enumerate() {
        let dir = temp_dir(&format!("run-suffix-{k}"));
        let times = (0..count).map(|i| format!("{}", i as f64 * 1e-3)).collect::<Vec<_>>().join(", ");
        let eigen = format!("    eigenanalysis: list, {count}, {times}, {option} output matrices;");
        let file = write_file(&dir, "p.mbd", &pendulum_variant(&[(FINAL_TIME, "    final time: 0.01;"), (EIGENANALYSIS, &eigen)]));
        let (ok, _, err) = romdyn_at(&dir, &["run", &file]);
        assert!(ok, "{option}: {err}");
        let files = listing(&dir);
        for f in &expected {
            assert!(files.contains(&f.to_string()), "{option}: {f} in {files:?}");
            assert!(files.contains(&f.replace(".m", ".json")), "{option}: {f} json in {files:?}");
        }
        assert_eq!(files.iter().filter(|f| f.ends_with(".m")).count(), count, "{option}: {files:?}");
        std::fs::remove_dir_all(&dir).ok();
    }
    // A format that is not one integer conversion is refused where it is written.
    for (format, message) in [("%s", "found 's' after '%'"), ("%d-%d", "more than one conversion"), ("k", "no integer conversion"), ("a/%d", "path separator")] {
        let dir = temp_dir("run-suffix-bad");
        let eigen = format!("    eigenanalysis: 0., suffix format, \"{format}\", output matrices;");
        let file = write_file(&dir, "p.mbd", &pendulum_variant(&[(FINAL_TIME, "    final time: 0.01;"), (EIGENANALYSIS, &eigen)]));
        let (ok, _, err) = romdyn_at(&dir, &["run", &file]);
        assert!(!ok && err.contains("p.mbd:") && err.contains("suffix format: the format") && err.contains(message), "{format}: {err}");
        assert_eq!(listing(&dir), ["p.mbd"], "{format}: nothing written");
        std::fs::remove_dir_all(&dir).ok();
    }
}

#[test]
fn a_bad_file_gives_file_line_column_and_writes_nothing() {
    let dir = temp_dir("run-bad");
    let file = write_file(&dir, "bad.mbd", &pendulum_variant(&[("    time step: 1.e-3;", "    time step: 1.e-3 +;")]));
    let (ok, _, err) = romdyn_at(&dir, &["run", &file]);
    assert!(!ok);
    let line = pendulum_variant(&[]).lines().position(|l| l.contains("time step:")).unwrap() + 1;
    assert!(err.contains(&format!("bad.mbd:{line}:")), "{err}");
    assert_eq!(listing(&dir), ["bad.mbd"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_failing_run_names_step_residual_and_worst_equation_and_keeps_what_converged() {
    // Released at 1 rad, one Newton iteration per step cannot reach 1e-9: step 1 fails, and
    // the files hold step 0 (the initial derivatives), with the failure as the .out file's
    // last line (issue 30, finding 7: MBDyn leaves what converged for the user to look at).
    let dir = temp_dir("run-fail");
    let node = "    structural: 2, dynamic, L*sin(1.), -L*cos(1.), 0., euler123, 0., 0., 1., null, null;";
    let file = write_file(&dir, "fail.mbd", &pendulum_variant(&[(PENDULUM_NODE, node), ("    max iterations: 10;", "    max iterations: 1;")]));
    let (ok, out, err) = romdyn_at(&dir, &["run", &file]);
    assert!(!ok, "{out}");
    assert!(err.contains("the run failed; the files hold the solution up to the last converged step 0 (t = 0 s)"), "{err}");
    assert!(err.contains("step 1 of 2001 (t = 0.001 s): Newton failed at t = 0.001 s, iteration 1: residual norm"), "{err}");
    let worst = err.split("; worst equation: ").nth(1).unwrap_or("");
    assert!(["node 1 ", "node 2 ", "clamp 1 ", "revolute hinge 2 "].iter().any(|p| worst.starts_with(p)), "{err}");
    assert_eq!(err.matches("Newton failed").count(), 1, "{err}");
    // The eigenanalysis at t = 0 came before the failure: its files are kept with the rest.
    assert_eq!(listing(&dir), ["fail.log", "fail.mbd", "fail.mov", "fail.out", "fail_0.json", "fail_0.m"], "the converged part, no temporary file");
    let out_file = std::fs::read_to_string(dir.join("fail.out")).unwrap();
    let last = out_file.lines().last().unwrap();
    assert!(last.starts_with("# Simulation FAILED after 0 converged steps") && last.contains("Newton failed at t = 0.001 s"), "{last}");
    // Both nodes at t = 0, one row each.
    assert_eq!(std::fs::read_to_string(dir.join("fail.mov")).unwrap().lines().count(), 2);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_run_that_fails_mid_way_writes_every_converged_step_and_exits_non_zero() {
    // A couple whose drive stops being a number after 10 ms (the square root of a negative
    // time difference): step 11 cannot converge. The files hold steps 0..10, as MBDyn's hold
    // what it computed before it stopped.
    let dir = temp_dir("run-fail-mid");
    let couple = "    body: 3, 2, M, null, diag, J, J, J;\n    couple: 4, absolute, 2, single, 0., 0., 1., string, \"sqrt(0.0105 - Time)\";";
    let text = pendulum_variant(&[("    body: 3, 2, M, null, diag, J, J, J;", couple), ("    rigid bodies: 1;", "    rigid bodies: 1;\n    forces: 1;")]);
    let file = write_file(&dir, "mid.mbd", &text);
    let (ok, out, err) = romdyn_at(&dir, &["run", &file]);
    assert!(!ok, "{out}");
    assert!(err.contains("the files hold the solution up to the last converged step 10 (t = 0.01 s)"), "{err}");
    assert!(err.contains("step 11 of 2001"), "{err}");
    let out_file = std::fs::read_to_string(dir.join("mid.out")).unwrap();
    assert_eq!(out_file.lines().filter(|l| l.starts_with("Step ")).count(), 11, "steps 0..10");
    assert!(out_file.lines().last().unwrap().starts_with("# Simulation FAILED after 10 converged steps (last converged time 1.000000000000e-2"), "{out_file}");
    // 11 times (0, 1, …, 10 ms) of 2 nodes.
    assert_eq!(std::fs::read_to_string(dir.join("mid.mov")).unwrap().lines().count(), 22);
    // The eigenanalysis at t = 0 was done before the failure: its files are kept too.
    assert_eq!(listing(&dir), ["mid.log", "mid.mbd", "mid.mov", "mid.out", "mid_0.json", "mid_0.m"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn rom_from_the_m_file_reproduces_the_pendulum_eigenvalues_and_static_gain() {
    let dir = temp_dir("run-pencil");
    let file = write_file(&dir, "pendulum.mbd", &pendulum_variant(&[(FINAL_TIME, "    final time: 0.;")]));
    let (ok, _, err) = romdyn_at(&dir, &["run", &file]);
    assert!(ok, "{err}");
    // Node 2 starts at unknown 6 (0-based): its moment about z is equation 6 + 6 + 5 + 1 = 18
    // and its rotation about z is unknown 6 + 5 + 1 = 12 (1-based).
    let pencil = dir.join("pendulum_0.m").to_string_lossy().into_owned();
    let rom = dir.join("rom.json").to_string_lossy().into_owned();
    let (ok, _, err) = romdyn(&["rom", "--pencil", &pencil, "--input-row", "18", "--output-col", "12", "--count", "1", "-o", &rom]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&rom).unwrap()).unwrap();
    let ev = v["eigenvalues"].as_array().unwrap();
    assert_eq!(ev.len(), 2);
    // ±3.130527 j rad/s through the file (eq. 82, CASES C2, 1e-6 relative).
    for (e, sign) in ev.iter().zip([1.0, -1.0]) {
        assert!(e["re"].as_f64().unwrap().abs() < 1e-6 && (e["im"].as_f64().unwrap() - sign * OMEGA).abs() / OMEGA < 1e-6, "{e}");
    }
    // Static gain 1/(m g L) = 0.1019368 rad/(N m) (CASES C2).
    assert!(err.contains("equation 18 (generalized force)") && err.contains("\nunknown 12\n"), "{err}");
    assert!(err.lines().any(|l| l.trim_start().starts_with("ROM ") && l.trim_end().ends_with("1.019368e-1")), "{err}");
    assert_eq!(v["inputs"][0], "equation 18 (generalized force)");
    let (ok, _, err) = romdyn(&["eig", "--pencil", &pencil, "--input-row", "40"]);
    assert!(!ok && err.contains("input row 40 is out of range: the pencil has 29 equations (1-based)"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 9, point 12: without `-o`, `romdyn run` writes in the current directory, not
/// beside the input (a run of `examples/pendulum.mbd` must not write inside `examples/`).
#[test]
fn run_writes_in_the_current_directory_by_default() {
    let input = temp_dir("run-default-input");
    let here = temp_dir("run-default-here");
    let file = write_file(&input, "pendulum.mbd", &pendulum_variant(&[(FINAL_TIME, "    final time: 0.01;")]));
    let (ok, _, err) = romdyn_at(&here, &["run", &file]);
    assert!(ok, "{err}");
    assert_eq!(listing(&input), vec!["pendulum.mbd".to_string()]);
    for f in ["pendulum.out", "pendulum.mov", "pendulum.log"] {
        assert!(listing(&here).contains(&f.to_string()), "{:?}", listing(&here));
    }
    std::fs::remove_dir_all(&input).ok();
    std::fs::remove_dir_all(&here).ok();
}
