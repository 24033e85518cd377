//! Running the `romdyn` binary on temporary copies of the shipped examples.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Runs `romdyn` with `args` in the crate directory: (success, stdout, stderr).
pub fn romdyn(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_romdyn")).args(args).current_dir(env!("CARGO_MANIFEST_DIR")).output().expect("romdyn runs");
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

/// Runs `romdyn` with `args` in `dir` (where `romdyn run` writes by default): (success,
/// stdout, stderr).
#[allow(dead_code)]
pub fn romdyn_at(dir: &Path, args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_romdyn")).args(args).current_dir(dir).output().expect("romdyn runs");
    (out.status.success(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

/// A fresh, empty temporary directory for one test, removed with what it holds when the
/// value is dropped (a test that fails leaves nothing behind either: its panic drops it).
pub fn temp_dir(name: &str) -> TempDir {
    let d = std::env::temp_dir().join(format!("romdyn-test-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    std::fs::create_dir_all(&d).expect("temp dir");
    TempDir(d)
}

/// A temporary directory removed on drop ([`temp_dir`]); a path by `Deref`.
pub struct TempDir(PathBuf);

impl std::ops::Deref for TempDir {
    type Target = PathBuf;
    fn deref(&self) -> &PathBuf {
        &self.0
    }
}

impl AsRef<Path> for TempDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

/// `examples/NAME` with each `(from, to)` replacement applied (each must match).
pub fn example_variant(name: &str, replacements: &[(&str, &str)]) -> String {
    let mut text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)).expect("example");
    for (from, to) in replacements {
        assert!(text.contains(from), "examples/{name} no longer contains {from:?}");
        text = text.replace(from, to);
    }
    text
}

/// `examples/pendulum.mbd` with each `(from, to)` replacement applied (each must match).
pub fn pendulum_variant(replacements: &[(&str, &str)]) -> String {
    example_variant("pendulum.mbd", replacements)
}

/// Writes `text` as `dir/name` and returns its path as a string.
pub fn write_file(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).expect("write");
    p.to_string_lossy().into_owned()
}

/// The file names in `dir`, sorted.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir).expect("dir").map(|e| e.expect("entry").file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

pub const FINAL_TIME: &str = "    final time: 2.;";
pub const EIGENANALYSIS: &str = "    eigenanalysis: 0., output matrices, output eigenvectors, use lapack;";
pub const PENDULUM_NODE: &str = "    structural: 2, dynamic, 0., -L, 0., eye, null, null;";
/// The pendulum node released from rest at 0.1 rad (hinge geometry follows the node frame).
pub const DISPLACED_NODE: &str = "    structural: 2, dynamic, L*sin(0.1), -L*cos(0.1), 0., euler123, 0., 0., 0.1, null, null;";
