//! The `.m` files `romdyn run` writes, loaded by GNU Octave itself (the independent reader):
//! they must `source` cleanly, have MBDyn's sizes, and Octave's own QZ on
//! `eig(Aminus, Aplus)` must give the eigenvalues of the `alpha` rows and CASES C2.
//! Runs only when `octave-cli` (or `octave`) is on PATH; CI does not install it.

use crate::common;

use std::process::Command;

use common::cli::{listing, pendulum_variant, romdyn_at, temp_dir, write_file, EIGENANALYSIS, FINAL_TIME};

fn octave() -> Option<&'static str> {
    ["octave-cli", "octave"].into_iter().find(|exe| Command::new(exe).arg("--version").output().is_ok_and(|o| o.status.success()))
}

/// Runs `script` in `dir` with Octave; returns its stdout.
fn run_octave(exe: &str, dir: &std::path::Path, script: &str) -> String {
    std::fs::write(dir.join("check_eig.m"), script).unwrap();
    let out = Command::new(exe).args(["--no-gui", "--no-init-file", "--quiet", "check_eig.m"]).current_dir(dir).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "octave failed:\n{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    stdout
}

/// Prints sizes, then the imaginary parts of the two eigenvalues nearest ±3.13 rad/s from
/// `alpha` (λ = (1/dCoef)(Λ−1)/(Λ+1), MBDyn manual) and from Octave's `eig(Aminus, Aplus)`.
const SCRIPT: &str = "source('pendulum_0.m');
printf('%d %d %d %d %d\\n', size(Aplus), size(Aminus, 1), issparse(Aplus), size(alpha, 1));
L = (alpha(:, 1) + 1i * alpha(:, 2)) ./ alpha(:, 3);
from_alpha = (L - 1) ./ (L + 1) / dCoef;
E = eig(full(Aminus), full(Aplus));
from_qz = (E - 1) ./ (E + 1) / dCoef;
pick = @(l) sort(imag(l(isfinite(l) & abs(abs(imag(l)) - 3.13) < 0.01)));
printf('%.15e\\n', pick(from_alpha), pick(from_qz));
";

#[test]
fn octave_loads_the_m_file_and_its_qz_gives_the_pendulum_eigenvalues() {
    let Some(exe) = octave() else {
        eprintln!("skipped: octave is not on PATH (the .m files are checked without it in tests/mbdyn/run_command.rs)");
        return;
    };
    for (name, option) in [("full", "output matrices"), ("sparse", "output sparse matrices")] {
        let dir = temp_dir(&format!("octave-{name}"));
        let eigen = format!("    eigenanalysis: 0., {option}, output eigenvectors, output geometry;");
        let file = write_file(&dir, "pendulum.mbd", &pendulum_variant(&[(FINAL_TIME, "    final time: 0.;"), (EIGENANALYSIS, &eigen)]));
        let (ok, _, err) = romdyn_at(&dir, &["run", &file]);
        assert!(ok, "{err}");
        assert!(listing(&dir).contains(&"pendulum_0.m".to_string()));
        let out = run_octave(exe, &dir, SCRIPT);
        let lines: Vec<&str> = out.lines().collect();
        // Aplus 29 x 29, Aminus 29 rows, sparse only when asked, one alpha row per mode.
        assert_eq!(lines[0], format!("29 29 29 {} 29", (name == "sparse") as u8), "{out}");
        let v: Vec<f64> = lines[1..].iter().map(|l| l.trim().parse().unwrap()).collect();
        assert_eq!(v.len(), 4, "{out}");
        // ±3.130527 j rad/s (eq. 82, CASES C2, 1e-6 relative), from alpha and from Octave's QZ;
        // the two agree to 1e-9 relative (two QZ codes on the same pencil).
        for (k, sign) in [(0, -1.0), (1, 1.0), (2, -1.0), (3, 1.0)] {
            assert!((v[k] - sign * 3.130527).abs() / 3.130527 < 1e-6, "{name}: {v:?}");
        }
        assert!((v[0] - v[2]).abs() / 3.130527 < 1e-9 && (v[1] - v[3]).abs() / 3.130527 < 1e-9, "{name}: {v:?}");
        eprintln!("{name}: Octave's QZ gives {:.9} j, alpha gives {:.9} j rad/s", v[3], v[1]);
        std::fs::remove_dir_all(&dir).ok();
    }
}
