//! Modes tracked across design points and ROMs interpolated between them (issue 37 points 1
//! and 2), on tests/mbdyn_files/crossing_modes.mbd: a mass M = 2 kg on springs KX = 250 N/m
//! along x and KY along y, its other motions locked, whose two modes ±j √(KX/M) (x) and
//! ±j √(KY/M) (y) cross at KY = KX (closed form).

use std::path::{Path, PathBuf};

use romdyn::analysis::Reference;
use romdyn::rom::ModeSelection;
use romdyn::study::{EigenSettings, Ports, RomForm, RomRequest};
use romdyn::sweep::{grid, mac, run_point, sweep, Parameter, SweepOptions, SweepResults};

const M: f64 = 2.0;
const KX: f64 = 250.0;

fn file() -> (String, PathBuf) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/crossing_modes.mbd");
    (std::fs::read_to_string(&path).unwrap(), path)
}

/// Forces along x and y in, displacements along x and y out, both modes kept.
fn options() -> SweepOptions {
    SweepOptions {
        reference: Reference::Initial,
        ports: Ports::Nodes { inputs: vec!["2:Fx".parse().unwrap(), "2:Fy".parse().unwrap()], outputs: vec!["2:x".parse().unwrap(), "2:y".parse().unwrap()] },
        eigen: EigenSettings::default(),
        rom: RomRequest::new(ModeSelection::Lowest(2)),
        form: RomForm::Ordinary,
        modes: 2,
        continuation: false,
        beam_update: romdyn::input::mbdyn::BeamUpdateChoice::default(),
    }
}

fn run(set: &str) -> SweepResults {
    let (text, path) = file();
    let p: Parameter = set.parse().unwrap();
    sweep(&text, &path, std::slice::from_ref(&p.name), grid(std::slice::from_ref(&p)).unwrap(), &options(), &|| {})
}

/// The tracked modes' eigenvalues at point `k`.
fn tracked(r: &SweepResults, k: usize) -> Vec<faer::c64> {
    let t = r.tracking();
    let point = r.results[k].as_ref().unwrap();
    t.matches[k].as_ref().unwrap().iter().map(|m| point.modes[m.as_ref().unwrap().candidate].lambda).collect()
}

#[test]
fn tracking_follows_each_mode_through_the_crossing() {
    // KY = 100 … 400 N/m in 8 points (none at the crossing KY = 250).
    let r = run("KY=100:400:8");
    let t = r.tracking();
    // At KY = 100 the y mode is the lower: mode 1 is y, mode 2 is x (energy labels).
    assert_eq!(t.labels, vec!["node 2 y 100 %".to_string(), "node 2 x 100 %".to_string()]);
    let first_shapes: Vec<Vec<faer::c64>> = (0..2).map(|j| r.results[0].as_ref().unwrap().modes[j].shapes[0].clone()).collect();
    for k in 0..8 {
        let ky = r.points[k][0];
        let lam = tracked(&r, k);
        // Closed form: mode 1 = ±j √(KY/M), mode 2 = ±j √(KX/M), 1e-8 relative.
        for (l, w) in lam.iter().zip([(ky / M).sqrt(), (KX / M).sqrt()]) {
            assert!((l.im - w).abs() < 1e-8 * w && l.re.abs() < 1e-8 * w, "KY = {ky}: {l} against {w}");
        }
        // Each tracked mode keeps its shape (MAC with the first point's, 1 to 1e-12).
        let point = r.results[k].as_ref().unwrap();
        for (j, m) in t.matches[k].as_ref().unwrap().iter().enumerate() {
            let shape = &point.modes[m.as_ref().unwrap().candidate].shapes[0];
            assert!(mac(shape, &first_shapes[j]) > 1.0 - 1e-12, "KY = {ky}, mode {}", j + 1);
        }
        // Numbered by rank instead, mode 1 would jump from y to x after the crossing.
        let lowest = point.modes[0].lambda.im;
        assert!((lowest - (ky.min(KX) / M).sqrt()).abs() < 1e-8 * lowest);
        // The crossing is flagged at the first point beyond it (KY = 271.4), and only there.
        let crossed = t.matches[k].as_ref().unwrap().iter().all(|m| m.as_ref().unwrap().crossing);
        assert_eq!(crossed, k == 4, "KY = {ky}");
    }
    let csv = r.modes_csv();
    assert!(csv.lines().next().unwrap().contains("mode 1 (node 2 y 100 %) freq [Hz]"), "{csv}");
    assert!(csv.lines().nth(5).unwrap().contains("modes 1, 2 crossed"), "{csv}");
}

#[test]
fn a_design_point_at_the_crossing_itself_does_not_swap_the_modes() {
    // KY = 100 … 400 in 7 points: KY = 250 = KX is a point, where the two modes are one
    // double eigenvalue and the solver's vectors any basis of the plane; the points after
    // it are matched against the last confident shapes.
    let r = run("KY=100:400:7");
    assert_eq!(r.points[3][0], 250.0);
    for k in 0..7 {
        let ky = r.points[k][0];
        let lam = tracked(&r, k);
        for (l, w) in lam.iter().zip([(ky / M).sqrt(), (KX / M).sqrt()]) {
            assert!((l.im - w).abs() < 1e-8 * w, "KY = {ky}: {l} against {w}");
        }
    }
}

#[test]
fn stacked_roms_share_one_basis_and_interpolate_to_the_closed_form() {
    let r = run("KY=100:400:8");
    let s = r.stacked().unwrap();
    let get = |name: &str| s.arrays.iter().find(|a| a.name == name).unwrap();
    // States: mode 1 (y) re, im, then mode 2 (x) re, im at every point.
    let tracks = get("state_tracks");
    assert!(tracks.data.chunks(4).all(|c| c == [1.0, 1.0, 2.0, 2.0]), "{:?}", tracks.data);
    // The y displacement sees only mode 1, through its Re state, with a positive entry at
    // every point (the reference component made real positive); the Im state's entry is 0.
    let c = get("C");
    for k in 0..8 {
        let at = |i: usize, j: usize| c.data[i + 2 * j + 8 * k];
        assert!(at(1, 0) > 0.0 && at(1, 1).abs() < 1e-12 && at(1, 2).abs() < 1e-12, "point {k}");
    }
    // Interpolated at KY = 250, halfway between 228.57 and 271.43: linear interpolation of A's
    // entries ±ω gives the mean of the two ω, so its eigenvalue error is, in closed form,
    // |(ω(228.57) + ω(271.43))/2 − ω(250)| / ω(250) = 9.20e-4 (ω = √(KY/M)).
    let (text, path) = file();
    let exact = run_point(&text, &path, &["KY".to_string()], &[250.0], &options(), None).unwrap();
    let (rom, exact_rom, check) = r.check_interpolation(&[250.0], &exact).unwrap();
    let w = |k: f64| (k / M).sqrt();
    let (a, b) = (r.points[3][0], r.points[4][0]);
    let expected = ((w(a) + w(b)) / 2.0 - w(250.0)).abs() / w(250.0);
    assert!((check.eigenvalues - expected).abs() < 1e-6 * expected, "{} against {expected}", check.describe());
    // The x mode does not move: its block of A is exact.
    assert!((rom.a[(2, 3)] - exact_rom.a[(2, 3)]).abs() < 1e-12 * w(KX));
    // Measured: A 6.5e-4, B 2.6e-6, C 2.0e-3, static gain 2.6e-3 (second order in the
    // step of 42.9 N/m); a basis that flipped a sign between the points would give O(1).
    for (name, e) in &check.matrices {
        assert!(*e < 5e-3, "{name}: {}", check.describe());
    }
    assert!(check.static_gain < 5e-3, "{}", check.describe());
    // Outside the sweep's values there is nothing to interpolate from.
    assert!(r.interpolate(&[450.0]).unwrap_err().to_string().contains("outside the sweep's values 100 to 400"));
}

#[test]
fn a_rom_through_a_crossing_that_keeps_one_mode_is_not_interpolated() {
    // One mode kept: the lowest, y before the crossing and x after it.
    let (text, path) = file();
    let p: Parameter = "KY=100:400:8".parse().unwrap();
    let one = SweepOptions { rom: RomRequest::new(ModeSelection::Lowest(1)), ..options() };
    let r = sweep(&text, &path, std::slice::from_ref(&p.name), grid(std::slice::from_ref(&p)).unwrap(), &one, &|| {});
    let e = r.interpolate(&[250.0]).unwrap_err().to_string();
    assert!(e.contains("do not keep the same tracked modes"), "{e}");
    assert!(r.interpolate(&[150.0]).is_ok());
}

#[test]
fn cli_interpolates_checks_and_writes_the_rom() {
    let dir = std::env::temp_dir().join(format!("romdyn_track_cli_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (_, path) = file();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_romdyn"))
        .args(["sweep".as_ref(), path.as_os_str()])
        .args(["--set", "KY=100:400:8", "--input", "2:Fx", "--input", "2:Fy", "--output", "2:x", "--output", "2:y", "--count", "2", "--lowest", "2", "--interpolate", "KY=250"])
        .arg("--interpolated")
        .arg(dir.join("mid.json"))
        .arg("--table")
        .arg(dir.join("t.csv"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("interpolated ROM at KY = 250 (4 states) against the ROM computed there: relative differences A 6.5"), "{stderr}");
    let rom: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join("mid.json")).unwrap()).unwrap();
    assert_eq!(rom["states"][0], "mode 1 re");
    // A parameter the sweep does not vary is refused before any point runs.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_romdyn")).args(["sweep".as_ref(), path.as_os_str()]).args(["--set", "KY=100:400:2", "--count", "1", "--interpolate", "KX=1"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(1) && stderr.contains("--interpolate KX: not a swept parameter (swept: KY)"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// tests/mbdyn_files/veering_modes.mbd: the lower (`lower = true`) or upper eigenvalue ω² of
/// `[[K1 + KC, −KC], [−KC, K2 + KC]] / M` and its eigenvector (x of nodes 2 and 3).
fn veering_mode(k1: f64, lower: bool) -> (f64, [f64; 2]) {
    let (k2, kc) = (250.0, 5.0);
    let (a, b, d) = (k1 + kc, -kc, k2 + kc);
    let (mean, half) = ((a + d) / 2.0, (((a - d) / 2.0).powi(2) + b * b).sqrt());
    let w2 = if lower { mean - half } else { mean + half };
    // (a − w²) x + b y = 0.
    let v = [-b, a - w2];
    let n = (v[0] * v[0] + v[1] * v[1]).sqrt();
    (w2 / M, [v[0] / n, v[1] / n])
}

fn veering(set: &str) -> SweepResults {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/veering_modes.mbd");
    let text = std::fs::read_to_string(&path).unwrap();
    let p: Parameter = set.parse().unwrap();
    let o = SweepOptions { ports: Ports::Nodes { inputs: vec!["2:Fx".parse().unwrap()], outputs: vec!["2:x".parse().unwrap()] }, ..options() };
    sweep(&text, &path, std::slice::from_ref(&p.name), grid(std::slice::from_ref(&p)).unwrap(), &o, &|| {})
}

#[test]
fn a_finely_sampled_veering_is_followed_along_its_branches() {
    // K1 = 200 … 300 N/m in 41 points: the shapes turn by at most 0.125 rad per step (MAC ≥
    // 0.98), so each tracked mode stays on its branch (closed form, 1e-8) while its shape
    // goes from one mass to the other, and nothing is flagged.
    let r = veering("K1=200:300:41");
    let t = r.tracking();
    assert_eq!(t.labels, vec!["node 2 x 99 %".to_string(), "node 3 x 99 %".to_string()]);
    for k in 0..41 {
        let k1 = r.points[k][0];
        for (j, l) in tracked(&r, k).iter().enumerate() {
            let w = veering_mode(k1, j == 0).0.sqrt();
            assert!((l.im - w).abs() < 1e-8 * w, "K1 = {k1}, mode {}: {l} against {w}", j + 1);
        }
        assert!(t.matches[k].as_ref().unwrap().iter().all(|m| !m.as_ref().unwrap().ambiguous() && !m.as_ref().unwrap().crossing), "K1 = {k1}");
    }
    // Mode 1 (the lower branch) now moves the other mass: its label at the last point.
    let last = r.results[40].as_ref().unwrap();
    assert_eq!(last.modes[t.matches[40].as_ref().unwrap()[0].as_ref().unwrap().candidate].label, "node 3 x 99 %");
}

#[test]
fn a_coarsely_sampled_veering_is_flagged_with_the_mac_of_the_closed_form() {
    // K1 = 200, 225, 250, 275, 300: from 225 to 250 the lower mode's shape turns from
    // 10.9° to 45°, MAC = cos²(34.1°) = 0.686 (closed form) < 0.8: ambiguous, flagged.
    let r = veering("K1=200:300:5");
    let t = r.tracking();
    let m = t.matches[2].as_ref().unwrap()[0].as_ref().unwrap();
    let (a, b) = (veering_mode(225.0, true).1, veering_mode(250.0, true).1);
    let expected = (a[0] * b[0] + a[1] * b[1]).powi(2);
    assert!((m.mac - expected).abs() < 1e-9, "MAC {} against {expected}", m.mac);
    assert!(m.ambiguous());
    let s = r.stacked().unwrap();
    let flags = &s.strings.iter().find(|(n, _)| *n == "mode_flags").unwrap().1;
    assert!(flags[2].contains("mode 1 ambiguous (MAC 0.69"), "{flags:?}");
}

#[test]
fn ordinary_rom_states_are_the_modal_coordinates_their_names_say() {
    // examples/mass_on_springs.mbd, 4 modes kept: before the fix the SVD's basis of E's
    // range permuted the states (the first, named 'mode 1 re', was mode 7's). Each named pair
    // of states must carry its mode's eigenvalues: trace 2 Re λ, determinant |λ|², nothing
    // coupling it to the other states.
    use romdyn::study::{StudySource, Study};
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/mass_on_springs.mbd");
    let study = Study::builder(StudySource::model_file(&path)).reference(Reference::Initial).node_ports(vec!["2:Fx".parse().unwrap(), "3:Fy".parse().unwrap()], vec!["2:x".parse().unwrap(), "3:y".parse().unwrap()]).build().unwrap();
    let rom = study.reduce(&RomRequest::new(ModeSelection::Lowest(4))).unwrap();
    let x = rom.export(&study, RomForm::Ordinary);
    assert_eq!(x.a.nrows(), 8);
    for p in 0..4 {
        let (i, j) = (2 * p, 2 * p + 1);
        assert_eq!((x.state_modes[i], x.states[i].ends_with(" re")), (x.state_modes[j], true));
        let l = study.modal().modes[x.state_modes[i] - 1].lambda;
        let (tr, det) = (x.a[(i, i)] + x.a[(j, j)], x.a[(i, i)] * x.a[(j, j)] - x.a[(i, j)] * x.a[(j, i)]);
        assert!((tr - 2.0 * l.re).abs() < 1e-9 * l.norm() && (det - l.norm_sqr()).abs() < 1e-9 * l.norm_sqr(), "{}: {l}", x.states[i]);
        for k in (0..8).filter(|&k| k != i && k != j) {
            assert!(x.a[(i, k)].abs() + x.a[(j, k)].abs() < 1e-9 * l.norm(), "{} coupled to state {k}", x.states[i]);
        }
    }
}
