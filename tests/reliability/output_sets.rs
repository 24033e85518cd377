//! Issue 32, point 3: the files of `sweep` (and, through the same `output::atomic::write_set`,
//! of `rom` and `freq`) are one set, complete or absent: paths checked before any work,
//! two outputs that would be one file refused, special files refused, the set put in place
//! together at the end (SIGTERM leaves nothing, SIGKILL a complete set or none).

#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const PENDULUM: &str = include_str!("../../examples/pendulum.mbd");
const SET: [&str; 4] = ["p.csv", "p.mat", "p.png", "p.svg"];

fn folder(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("romdyn-sets-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("p.mbd"), PENDULUM).unwrap();
    d
}

/// The folder's files but the model.
fn outputs(d: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).filter(|n| n != "p.mbd").collect();
    v.sort();
    v
}

/// `romdyn sweep` of the pendulum over `points` lengths, writing `p.mat`, `p.csv` and
/// `p.{svg,png}` (extra arguments after).
fn sweep(d: &Path, points: usize, extra: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_romdyn"));
    let set = format!("L=1:2:{points}");
    c.args(["sweep", "p.mbd", "--set", &set, "--input", "2:Mz", "--output", "2:rz", "--count", "1", "--lowest", "1", "--jobs", "1"]).args(extra).current_dir(d);
    c
}

/// Starts `command`, waits `after`, sends `signal`: (exit code, whether it ended first).
fn interrupted(mut command: Command, after: Duration, signal: &str) -> (Option<i32>, bool) {
    let mut child = command.stdout(Stdio::null()).stderr(Stdio::null()).spawn().unwrap();
    let start = Instant::now();
    while start.elapsed() < after && child.try_wait().unwrap().is_none() {
        std::thread::sleep(Duration::from_millis(5));
    }
    let ended = child.try_wait().unwrap().is_some();
    if !ended {
        assert!(Command::new("kill").args([signal, &child.id().to_string()]).status().unwrap().success());
    }
    (child.wait().unwrap().code(), ended)
}

/// The long sweep the signal tests stop: 20 000 points, a few seconds of work before the
/// writing.
fn long_sweep(d: &Path) -> Command {
    sweep(d, 20_000, &["-o", "p.mat", "--table", "p.csv", "--plot", "p"])
}

#[test]
fn a_sweep_stopped_by_sigterm_leaves_no_file_and_by_sigkill_a_complete_set_or_none() {
    let d = folder("sweep-signals");
    for ms in [30, 300, 1500] {
        let (code, ended) = interrupted(long_sweep(&d), Duration::from_millis(ms), "-TERM");
        if ended {
            assert_eq!(outputs(&d), SET, "the sweep ended first: its set is whole");
            outputs(&d).iter().for_each(|f| std::fs::remove_file(d.join(f)).unwrap());
            continue;
        }
        assert!(matches!(code, Some(143) | None), "after {ms} ms: status {code:?}");
        assert_eq!(outputs(&d), Vec::<String>::new(), "SIGTERM after {ms} ms");
    }
    for ms in [20, 400, 2000] {
        let (_, ended) = interrupted(long_sweep(&d), Duration::from_millis(ms), "-KILL");
        let journal = d.join(".p.csv.romdyn-commit");
        if journal.exists() {
            assert!(romdyn::output::atomic::recover_set(&journal).unwrap());
        }
        let left = outputs(&d);
        let set: Vec<String> = left.iter().filter(|n| !n.starts_with('.')).cloned().collect();
        assert!(set.is_empty() || set == SET, "SIGKILL after {ms} ms (ended: {ended}): {left:?}");
        // The next sweep writing there removes what the killed one left under temporary names.
        let o = sweep(&d, 3, &["--table", "q.csv"]).output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let hidden: Vec<String> = outputs(&d).into_iter().filter(|n| n.starts_with('.')).collect();
        assert!(hidden.is_empty(), "after {ms} ms: {hidden:?}");
        outputs(&d).iter().for_each(|f| std::fs::remove_file(d.join(f)).unwrap());
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn output_paths_are_checked_before_any_work() {
    let d = folder("sweep-paths");
    let refused = |extra: &[&str], message: &str| {
        let before = outputs(&d);
        let o = sweep(&d, 2, extra).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(o.status.code(), Some(1), "{extra:?}: {err}");
        assert!(err.contains(message), "{extra:?}: expected {message:?} in {err}");
        assert!(!err.contains("design point"), "refused before the sweep: {err}");
        assert_eq!(outputs(&d), before, "{extra:?}: nothing written");
    };
    // Two options naming one file (one output silently overwrote the other).
    refused(&["-o", "p.mat", "--table", "p.mat"], "-o and --table would both write this file");
    refused(&["--table", "p.svg", "--plot", "p"], "--table and --plot would both write this file");
    // A prefix naming a folder (it wrote hidden files dir/.svg, dir/.png).
    std::fs::create_dir(d.join("dir")).unwrap();
    refused(&["--plot", "dir/"], "--plot: names no file");
    // A directory in the way of a later output, found before the first is written.
    std::fs::create_dir(d.join("p.png")).unwrap();
    refused(&["--table", "p.csv", "--plot", "p"], "p.png: --plot: is a directory");
    std::fs::remove_dir(d.join("p.png")).unwrap();
    std::fs::remove_dir(d.join("dir")).unwrap();
    // A special file: a FIFO where the table would go (as -o /dev/null made /dev/null.csv).
    assert!(Command::new("mkfifo").arg(d.join("p.csv")).status().unwrap().success());
    let o = sweep(&d, 2, &["--table", "p.csv"]).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.code() == Some(1) && err.contains("--table: is a special file"), "{err}");
    std::fs::remove_file(d.join("p.csv")).unwrap();
    // The plot prefix itself a special file.
    assert!(Command::new("mkfifo").arg(d.join("p")).status().unwrap().success());
    let o = sweep(&d, 2, &["--plot", "p"]).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.code() == Some(1) && err.contains("--plot: is a special file"), "{err}");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn a_runs_prefix_must_name_a_regular_file() {
    let d = folder("run-prefix");
    let run = |prefix: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_romdyn")).args(["run", "p.mbd", "-o", prefix]).current_dir(&d).output().unwrap();
        (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned())
    };
    // `-o /dev/null` as root made /dev/null.out and its siblings: a FIFO stands for it here.
    assert!(Command::new("mkfifo").arg(d.join("sink")).status().unwrap().success());
    let (code, err) = run("sink");
    assert!(code == Some(1) && err.contains("sink: -o: is a special file"), "{err}");
    // A prefix ending in '/' that is no folder made hidden files nodir/.out, ….
    let (code, err) = run("nodir/");
    assert!(code == Some(1) && err.contains("-o: names no file"), "{err}");
    assert_eq!(outputs(&d), ["sink"]);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn cms_checks_its_output_before_reducing() {
    // `romdyn cms` (issue 35) writes one file, PREFIX.fem: a special file, a folder in the
    // way and a prefix naming no file are refused before the reduction, leaving nothing.
    let d = folder("cms-prefix");
    std::fs::copy(crate::common::mbdyn::test_file("cms_substructure.mbd"), d.join("s.mbd")).unwrap();
    let cms = |prefix: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_romdyn")).args(["cms", "s.mbd", "--interface", "9", "--modes", "2", "-o", prefix]).current_dir(&d).output().unwrap();
        (o.status.code(), String::from_utf8_lossy(&o.stdout).into_owned(), String::from_utf8_lossy(&o.stderr).into_owned())
    };
    assert!(Command::new("mkfifo").arg(d.join("sink.fem")).status().unwrap().success());
    let (code, out, err) = cms("sink");
    assert!(code == Some(1) && err.contains("-o: is a special file") && out.is_empty(), "{out}{err}");
    let (code, out, err) = cms("nodir/");
    assert!(code == Some(1) && err.contains("-o: names no file") && out.is_empty(), "{out}{err}");
    std::fs::create_dir(d.join("taken.fem")).unwrap();
    let (code, out, err) = cms("taken");
    assert!(code == Some(1) && err.contains("is a directory") && out.is_empty(), "{out}{err}");
    assert_eq!(outputs(&d), ["s.mbd", "sink.fem", "taken.fem"]);
    let (code, _, err) = cms("good");
    assert!(code == Some(0) && d.join("good.fem").is_file(), "{err}");
    std::fs::remove_dir_all(&d).ok();
}

const BEAM: &str = include_str!("../../examples/simply_supported_beam.mbd");

/// `romdyn ARGS` on the README beam (`b.mbd` in `d`), its static equilibrium, input 5:Fy,
/// output 5:y.
fn beam_command(d: &Path, args: &[&str]) -> Command {
    std::fs::write(d.join("b.mbd"), BEAM).unwrap();
    let mut c = Command::new(env!("CARGO_BIN_EXE_romdyn"));
    c.args([args[0], "b.mbd", "--static", "--input", "5:Fy", "--output", "5:y"]).args(&args[1..]).current_dir(d);
    c
}

/// The folder's files but the models.
fn files(d: &Path) -> Vec<String> {
    outputs(d).into_iter().filter(|n| n != "b.mbd").collect()
}

#[test]
fn rom_and_freq_check_their_outputs_before_any_work_and_write_them_as_one_set() {
    let d = folder("rom-paths");
    let refused = |args: &[&str], message: &str| {
        let before = files(&d);
        let o = beam_command(&d, args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(message), "{args:?}: expected {message:?} in {err}");
        assert!(!err.contains("equations, route"), "refused before the eigenanalysis: {err}");
        assert_eq!(files(&d), before, "{args:?}: nothing written");
    };
    refused(&["rom", "--count", "1", "--bode", "p", "--grid", "p"], "--bode and --grid would both write this file");
    refused(&["rom", "--count", "1", "-o", "p.mat", "--imposed-out", "p.mat"], "-o and --imposed-out would both write this file");
    std::fs::create_dir(d.join("p.png")).unwrap();
    refused(&["rom", "--count", "1", "-o", "p.mat", "--bode", "p"], "p.png: --bode: is a directory");
    refused(&["freq", "-o", "p"], "p.png: -o: is a directory");
    std::fs::remove_dir(d.join("p.png")).unwrap();
    refused(&["freq", "-o", "dir/"], "-o: names no file");
    // Written: the ROM file and the Bode set together.
    let o = beam_command(&d, &["rom", "--count", "1", "-o", "p.mat", "--bode", "p"]).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("wrote p.mat\nwrote p.csv, p.svg, p.png"), "{err}");
    assert_eq!(files(&d), ["p.csv", "p.mat", "p.png", "p.svg"]);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn rom_and_freq_stopped_by_a_signal_leave_a_complete_set_or_none() {
    let d = folder("rom-signals");
    // 200 000 frequencies: the responses and the plots take long enough to be interrupted.
    let rom: &[&str] = &["rom", "--count", "1", "-o", "p.mat", "--bode", "p", "--points", "200000"];
    let freq: &[&str] = &["freq", "-o", "p", "--points", "200000"];
    let rom_set = ["p.csv", "p.mat", "p.png", "p.svg"];
    let freq_set = ["p.csv", "p.png", "p.svg"];
    for (args, set) in [(rom, &rom_set[..]), (freq, &freq_set[..])] {
        for (signal, ms) in [("-TERM", 100), ("-TERM", 1200), ("-KILL", 300), ("-KILL", 2500)] {
            let (code, ended) = interrupted(beam_command(&d, args), Duration::from_millis(ms), signal);
            // A set whose renames a SIGKILL cut is completed from its journal.
            for j in files(&d).into_iter().filter(|n| n.ends_with(".romdyn-commit")) {
                assert!(romdyn::output::atomic::recover_set(&d.join(j)).unwrap());
            }
            let left = files(&d);
            let shown: Vec<String> = left.iter().filter(|n| !n.starts_with('.')).cloned().collect();
            assert!(shown.is_empty() || shown == set, "{} {signal} after {ms} ms (ended {ended}): {left:?}", args[0]);
            if signal == "-TERM" && !ended {
                assert!(matches!(code, Some(143) | None), "status {code:?}");
                assert!(left.is_empty(), "SIGTERM leaves no temporary: {left:?}");
            }
            left.iter().for_each(|f| std::fs::remove_file(d.join(f)).unwrap());
        }
    }
    std::fs::remove_dir_all(&d).ok();
}

/// A tmpfs of `kib` KiB mounted on a fresh folder, unmounted when dropped; `None` (with a
/// message) where mounting is not allowed (not root, or a container without the right).
struct SmallDisk(PathBuf);

impl SmallDisk {
    fn mount(name: &str, kib: usize) -> Option<SmallDisk> {
        let d = std::env::temp_dir().join(format!("romdyn-full-{name}-{}", std::process::id()));
        let _ = std::fs::create_dir_all(&d);
        let ok = Command::new("mount").args(["-t", "tmpfs", "-o", &format!("size={kib}k"), "tmpfs"]).arg(&d).stderr(Stdio::null()).status().is_ok_and(|s| s.success());
        if !ok {
            eprintln!("skipped: cannot mount a tmpfs on {} here (needs root and the right to mount)", d.display());
            let _ = std::fs::remove_dir(&d);
            return None;
        }
        Some(SmallDisk(d))
    }
}

impl Drop for SmallDisk {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
        let _ = std::fs::remove_dir(&self.0);
    }
}

#[test]
fn a_full_disk_leaves_a_complete_set_or_none() {
    // 96 KiB: the CSV (30 KB) and the SVG (35 KB) fit, the PNG (157 KB) does not; before,
    // freq left the CSV and the SVG, a set that looked complete but for its plot.
    let Some(disk) = SmallDisk::mount("freq", 96) else { return };
    let d = &disk.0;
    std::fs::write(d.join("p.mbd"), PENDULUM).unwrap();
    let run = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_romdyn")).args(args).current_dir(d).output().unwrap();
        (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned())
    };
    let (code, err) = run(&["freq", "p.mbd", "--static", "--input", "2:Fx", "--output", "2:x", "-o", "p"]);
    assert!(code == Some(1) && err.contains("No space left on device"), "{err}");
    assert_eq!(outputs(d), Vec::<String>::new(), "freq: none of the set, no temporary");
    let (code, err) = run(&["rom", "p.mbd", "--static", "--input", "2:Fx", "--output", "2:x", "--count", "1", "-o", "p.json", "--bode", "p"]);
    assert!(code == Some(1) && err.contains("No space left on device"), "{err}");
    assert_eq!(outputs(d), Vec::<String>::new(), "rom: none of the set, no temporary");
    let (code, err) = run(&["sweep", "p.mbd", "--set", "L=1:2:50", "--input", "2:Mz", "--output", "2:rz", "--count", "1", "--lowest", "1", "--table", "p.csv", "--plot", "p"]);
    assert!(code == Some(1) && err.contains("No space left on device"), "{err}");
    assert_eq!(outputs(d), Vec::<String>::new(), "sweep: none of the set, no temporary");
}
