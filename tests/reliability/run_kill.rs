//! `romdyn run` stopped at several moments: by SIGTERM (the output folder must hold no
//! output and no temporary file, exit status 128 + 15) and by SIGKILL (the folder must
//! hold the run's complete set of files or none of them; the temporaries a killed process
//! could not remove are removed by the next run writing there; a set whose commit journal
//! `.NAME.romdyn-commit` exists is incomplete and is completed by `recover_set`).

#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const PENDULUM: &str = include_str!("../../examples/pendulum.mbd");
const SET: [&str; 5] = ["p.log", "p.mov", "p.out", "p_0.json", "p_0.m"];

fn folder(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("romdyn-kill-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    // 200 s at 1 ms: 200 000 steps, several seconds of work.
    std::fs::write(d.join("p.mbd"), PENDULUM.replace("final time: 2.;", "final time: 200.;")).unwrap();
    std::fs::write(d.join("short.mbd"), PENDULUM).unwrap();
    d
}

fn outputs(d: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).filter(|n| !n.ends_with(".mbd")).collect();
    v.sort();
    v
}

/// Starts the long run, waits `after`, sends `signal`; returns the exit status code and
/// whether the run had already ended.
fn interrupted(d: &Path, after: Duration, signal: &str) -> (Option<i32>, bool) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_romdyn")).args(["run", "p.mbd"]).current_dir(d).stdout(Stdio::null()).stderr(Stdio::null()).spawn().unwrap();
    let start = Instant::now();
    while start.elapsed() < after {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let ended = child.try_wait().unwrap().is_some();
    if !ended {
        let ok = Command::new("kill").args([signal, &child.id().to_string()]).status().unwrap();
        assert!(ok.success());
    }
    let status = child.wait().unwrap();
    (status.code(), ended)
}

#[test]
fn sigterm_leaves_no_output_and_no_temporary() {
    let d = folder("term");
    for ms in [30, 150, 400, 900] {
        let (code, ended) = interrupted(&d, Duration::from_millis(ms), "-TERM");
        if ended {
            // The run finished first: then its set is complete.
            assert_eq!(outputs(&d), SET);
            continue;
        }
        // 143 = 128 + SIGTERM (romdyn's handler); None = killed before it was installed.
        assert!(matches!(code, Some(143) | None), "after {ms} ms: status {code:?}");
        assert_eq!(outputs(&d), Vec::<String>::new(), "after {ms} ms");
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn sigkill_leaves_a_complete_set_or_none() {
    let d = folder("kill");
    for ms in [20, 100, 300, 700, 1500] {
        let (_, ended) = interrupted(&d, Duration::from_millis(ms), "-KILL");
        let journal = d.join(".p.romdyn-commit");
        if journal.exists() {
            assert!(romdyn::output::atomic::recover_set(&journal).unwrap());
        }
        let left = outputs(&d);
        let set: Vec<String> = left.iter().filter(|n| !n.starts_with('.')).cloned().collect();
        assert!(set.is_empty() || set == SET, "after {ms} ms (ended: {ended}): {left:?}");
        if ended {
            assert_eq!(set, SET);
        }
        // The next run writing in the folder removes the killed run's temporaries.
        let o = Command::new(env!("CARGO_BIN_EXE_romdyn")).args(["run", "short.mbd"]).current_dir(&d).output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let hidden: Vec<String> = outputs(&d).into_iter().filter(|n| n.starts_with('.')).collect();
        assert!(hidden.is_empty(), "after {ms} ms: {hidden:?}");
        for f in std::fs::read_dir(&d).unwrap() {
            let p = f.unwrap().path();
            if !p.to_string_lossy().ends_with(".mbd") {
                std::fs::remove_file(p).unwrap();
            }
        }
    }
    std::fs::remove_dir_all(&d).ok();
}
