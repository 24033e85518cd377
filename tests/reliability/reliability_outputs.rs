//! Issue 32's findings on outputs (round 3 of the reliability probe): each run through the
//! `romdyn` binary in a folder of its own, asserting the exit status, the message and what
//! the folder holds afterwards.

use crate::common;

use common::cli::{listing, romdyn_at, temp_dir, write_file};

#[test]
fn a_frequency_range_beyond_what_doubles_hold_is_refused_before_anything_is_written() {
    // 1e-160 to 1e160 Hz looped without end in the plotting library's log axis (the CSV
    // already written, full of NaN): the grid's ends are refused, by option, before any
    // computation. The range romdyn accepts: 1e-30 to 1e30 Hz (romdyn::limits).
    let dir = temp_dir("freq-range");
    let file = write_file(&dir, "p.mbd", &std::fs::read_to_string("examples/pendulum.mbd").unwrap());
    for (fmin, fmax, option, value) in [("1e-160", "1e160", "--fmin", "1e-160"), ("1", "1e31", "--fmax", "1e31")] {
        let (ok, _, err) = romdyn_at(&dir, &["freq", &file, "--static", "--input", "2:Fx", "--output", "2:x", "-o", "p", "--fmin", fmin, "--fmax", fmax]);
        assert!(!ok);
        assert!(err.contains(&format!("{option}: {value} Hz is outside romdyn's frequency range, 1e-30 to 1e30 Hz")), "{err}");
        assert_eq!(listing(&dir), ["p.mbd"], "nothing written");
    }
    // The widest accepted range draws (and writes the set).
    let (ok, _, err) = romdyn_at(&dir, &["freq", &file, "--static", "--input", "2:Fx", "--output", "2:x", "-o", "p", "--fmin", "1e-30", "--fmax", "1e30"]);
    assert!(ok, "{err}");
    assert_eq!(listing(&dir), ["p.csv", "p.mbd", "p.png", "p.svg"]);
    let csv = std::fs::read_to_string(dir.join("p.csv")).unwrap();
    assert!(!csv.contains("NaN"), "every response finite at 1e-30..1e30 Hz");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn sweep_job_counts_and_mode_counts_are_bounded_before_any_work() {
    let dir = temp_dir("sweep-bounds");
    let file = write_file(&dir, "p.mbd", &std::fs::read_to_string("examples/pendulum.mbd").unwrap());
    let sweep = |extra: &[&str]| {
        let mut args = vec!["sweep", file.as_str(), "--set", "L=1,2", "--input", "2:Mz", "--output", "2:rz", "--count", "1"];
        args.extend_from_slice(extra);
        romdyn_at(&dir, &args)
    };
    let (ok, _, err) = sweep(&["--jobs", "0"]);
    assert!(!ok && err.contains("--jobs 0: need at least 1 job"), "{err}");
    let (ok, _, err) = sweep(&["--lowest", "20000"]);
    assert!(!ok && err.contains("--lowest 20000: at most 10000 modes"), "{err}");
    // More jobs than cores: reduced to the cores with a warning, and the sweep runs (1000
    // threads made a 0.35 s sweep take 66 s).
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let (ok, out, err) = sweep(&["--jobs", "1000", "--lowest", "1"]);
    assert!(ok, "{err}");
    assert!(err.contains(&format!("warning: --jobs 1000: this machine runs {cores} threads at once; using {cores}")), "{err}");
    assert_eq!(out.lines().filter(|l| !l.starts_with('#')).count(), 3, "header and two points: {out}");
    assert_eq!(listing(&dir), ["p.mbd"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_all_zero_pencil_is_refused_before_any_factorization() {
    // A 2000 x 2000 pencil of zeros (Matrix Market, no entry): an unknown and an equation
    // with no entry make it singular for every λ; the one pass that finds them now comes
    // before the deflation's factorizations (the refusal took 18 s and 690 MB; 0.3 s after,
    // measured 2026-12-06 in the test build).
    let dir = temp_dir("zero-pencil");
    let n = 2000;
    write_file(&dir, "z.mtx", &format!("%%MatrixMarket matrix coordinate real general\n{n} {n} 0\n"));
    let column: String = (0..n).map(|_| "1.0\n").collect();
    write_file(&dir, "b.mtx", &format!("%%MatrixMarket matrix array real general\n{n} 1\n{column}"));
    write_file(&dir, "c.mtx", &format!("%%MatrixMarket matrix array real general\n1 {n}\n{column}"));
    let pencil = write_file(&dir, "p.json", r#"{"Fyd": "z.mtx", "Fy": "z.mtx", "B": "b.mtx", "C": "c.mtx"}"#);
    let (ok, _, err) = romdyn_at(&dir, &["eig", "--pencil", &pencil]);
    assert!(!ok);
    assert!(err.contains("the pencil is singular") && err.contains("unknown 1 has no entry in F_yd or F_y"), "{err}");
    assert_eq!(listing(&dir), ["b.mtx", "c.mtx", "p.json", "z.mtx"]);
    std::fs::remove_dir_all(&dir).ok();
}
