//! Design-point sweeps (issue 15): `set:` overrides at the reader's entry, the pendulum's
//! length and mass swept against closed forms, failed points kept with their values, the
//! stacked arrays' layout, continuation of static solutions.

use std::path::{Path, PathBuf};

use romdyn::analysis::Reference;
use romdyn::input::mbdyn::{read_model_text, SetOverrides};
use romdyn::rom::ModeSelection;
use romdyn::study::{EigenSettings, Ports, RomForm, RomRequest};
use romdyn::sweep::{check_parameters, grid, sweep, Parameter, SweepOptions, SweepResults};

fn example(name: &str) -> (String, PathBuf) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name);
    (std::fs::read_to_string(&path).unwrap(), path)
}

/// ROM of the pendulum: moment about z on node 2 in, its rotation out, one mode.
fn pendulum_options() -> SweepOptions {
    SweepOptions {
        reference: Reference::Initial,
        ports: Ports::Nodes { inputs: vec!["2:Mz".parse().unwrap()], outputs: vec!["2:rz".parse().unwrap()] },
        eigen: EigenSettings::default(),
        rom: RomRequest::new(ModeSelection::Lowest(1)),
        form: RomForm::Ordinary,
        modes: 1,
        continuation: false,
        beam_update: romdyn::input::mbdyn::BeamUpdateChoice::Every(romdyn::element::BeamUpdate::PathIndependent),
    }
}

fn run(name: &str, sets: &[&str], options: &SweepOptions) -> SweepResults {
    let (text, path) = example(name);
    let params: Vec<Parameter> = sets.iter().map(|s| s.parse().unwrap()).collect();
    let names: Vec<String> = params.iter().map(|p| p.name.clone()).collect();
    check_parameters(&text, &path, &names).unwrap();
    sweep(&text, &path, &names, grid(&params).unwrap(), options, &|| {})
}

// examples/pendulum.mbd: M = 1 kg, J = 1e-3 kg m², G = 9.81 m/s².
const M: f64 = 1.0;
const J: f64 = 1e-3;
const G: f64 = 9.81;

/// Closed form of the compound pendulum about its hinge: ω² = M G L / (J + M L²) (paper
/// eq. 82 with the hinge offset L); L = 1 gives 3.130527 rad/s.
fn omega(m: f64, l: f64) -> f64 {
    (m * G * l / (J + m * l * l)).sqrt()
}

#[test]
fn override_replaces_the_files_value_and_unknown_names_are_refused() {
    let (text, path) = example("pendulum.mbd");
    let with = |name: &str, x: f64| read_model_text(&text, &path, &SetOverrides::from([(name.to_string(), x)]));
    // L = 2 m: node 2 hangs at y = -2 (the file's `set: const real L = 1.;` replaced).
    let m = with("L", 2.0).unwrap();
    assert_eq!(m.model.nodes[1].position[1], -2.0);
    let e = with("LENGTH", 2.0).err().unwrap().to_string();
    assert!(e.contains("pendulum.mbd: error: --set LENGTH: the file declares no variable 'LENGTH'") && e.contains("G, J, L, M"), "{e}");
    // An integer variable takes whole numbers only; re-assignments keep the override.
    let src = "set: integer N = 2;\nset: real X = 1.;\nset: X = 3.*X;\nset: real Y = X;\n";
    let doc = |o: SetOverrides| romdyn::input::mbdyn::parse_text_with(src, Path::new("v.mbd"), &o);
    let e = doc(SetOverrides::from([("N".to_string(), 2.5)])).err().unwrap().to_string();
    assert!(e.starts_with("v.mbd:1:14: error: --set N=2.5: 'N' is declared integer here, the value must be a whole number"), "{e}");
    let d = doc(SetOverrides::from([("X".to_string(), 5.0)])).unwrap();
    assert_eq!((d.variables.real("X"), d.variables.real("Y")), (Some(5.0), Some(5.0)));
    let d = doc(SetOverrides::new()).unwrap();
    assert_eq!(d.variables.real("Y"), Some(3.0));
}

#[test]
fn pendulum_length_sweep_matches_the_closed_form() {
    let r = run("pendulum.mbd", &["L=0.5:4:8"], &pendulum_options());
    assert_eq!(r.points.len(), 8);
    for (k, res) in r.results.iter().enumerate() {
        let l = 0.5 + 0.5 * k as f64;
        assert_eq!(r.points[k], vec![l]);
        let res = res.as_ref().unwrap();
        // Closed form ω = sqrt(M G L / (J + M L²)), relative 1e-6.
        let w = res.modes[0].lambda;
        assert!((w.im - omega(M, l)).abs() < 1e-6 * omega(M, l) && w.re.abs() < 1e-9, "L = {l}: {w}");
        // ROM static gain rz/Mz = 1/(M G L) [rad/(N m)] (gravity stiffness M G L), 1e-6.
        let g = res.rom.rom_static_gain.as_ref().unwrap()[(0, 0)];
        assert!((g * M * G * l - 1.0).abs() < 1e-6, "L = {l}: gain {g}");
    }
}

#[test]
fn a_failed_point_is_reported_with_its_values_and_the_others_kept() {
    // M = -1 kg is refused by the reader (file:line:col); L < 0 is not a failure: the
    // pendulum then stands upside down (inverted pendulum, ±sqrt(M G |L| / (J + M L²)) real).
    let r = run("pendulum.mbd", &["M=-1,1,2", "L=-1,1"], &pendulum_options());
    assert_eq!(r.points.len(), 6);
    let failures: Vec<_> = r.failures().collect();
    assert_eq!(failures.len(), 2, "{failures:?}");
    for (k, values, e) in failures {
        assert_eq!(values[0], -1.0);
        assert!(k < 2);
        assert!(e.contains("pendulum.mbd:45:17: error: negative mass -1"), "{e}");
    }
    for k in 2..6 {
        let (m, l) = (r.points[k][0], r.points[k][1]);
        let w = r.results[k].as_ref().unwrap().modes[0].lambda;
        let expected = omega(m, l.abs());
        if l > 0.0 {
            assert!((w.im - expected).abs() < 1e-6 * expected, "M = {m}, L = {l}: {w}");
        } else {
            // The unstable member +a of the ±a pair.
            assert!((w.re - expected).abs() < 1e-6 * expected && w.im == 0.0, "M = {m}, L = {l}: {w}");
        }
    }
    assert_eq!(r.describe_point(0), "M = -1, L = -1");
    let csv = r.modes_csv();
    assert!(csv.lines().nth(1).unwrap().contains("negative mass"), "{csv}");
}

#[test]
fn stacked_arrays_are_point_major_slices_with_failed_points_nan() {
    let r = run("pendulum.mbd", &["M=1,-1,2"], &pendulum_options());
    let s = r.stacked().unwrap();
    let a = s.arrays.iter().find(|a| a.name == "A").unwrap();
    assert_eq!(a.dims, vec![2, 2, 3]);
    // A(:,:,k) is point k's A in the sweep's consistent basis (column-major, point index
    // slowest).
    let consistent = r.consistent_roms();
    for k in [0, 2] {
        let rom = &consistent[k].as_ref().unwrap().rom;
        for j in 0..2 {
            for i in 0..2 {
                assert_eq!(a.data[i + 2 * j + 4 * k], rom.a[(i, j)]);
            }
        }
        // The ordinary ROM of one pair: eigenvalues of A(:,:,k) are ±j ω (closed form).
        let w = omega(r.points[k][0], 1.0);
        let (tr, det) = (a.data[4 * k] + a.data[4 * k + 3], a.data[4 * k] * a.data[4 * k + 3] - a.data[4 * k + 1] * a.data[4 * k + 2]);
        assert!(tr.abs() < 1e-9 && (det - w * w).abs() < 1e-6 * w * w, "point {k}: tr {tr}, det {det}");
    }
    assert!(a.data[4..8].iter().all(|x| x.is_nan()));
    let ok = s.arrays.iter().find(|a| a.name == "point_ok").unwrap();
    assert_eq!(ok.data, vec![1.0, 0.0, 1.0]);
    let p = s.arrays.iter().find(|a| a.name == "parameters").unwrap();
    assert_eq!((p.dims.clone(), p.data.clone()), (vec![3, 1], vec![1.0, -1.0, 2.0]));
    // Both files are written; the .npz stores column-major data with fortran_order.
    let dir = std::env::temp_dir().join(format!("romdyn_sweep_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    r.write_arrays(&dir.join("s.mat")).unwrap();
    r.write_arrays(&dir.join("s.npz")).unwrap();
    let npz = std::fs::read(dir.join("s.npz")).unwrap();
    let text = String::from_utf8_lossy(&npz);
    assert!(text.contains("A.npy") && text.contains("'fortran_order': True, 'shape': (2, 2, 3)"));
    let mat = std::fs::read(dir.join("s.mat")).unwrap();
    assert!(mat.starts_with(b"MATLAB 5.0 MAT-file"));
    assert!(r.write_arrays(&dir.join("s.txt")).is_err());
    let [svg, png] = r.write_plot(&dir.join("plot"), None).unwrap();
    assert!(svg.exists() && png.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn continuation_gives_the_same_static_solutions() {
    // The simply supported beam under an axial compression N (0 to half of the first
    // buckling load of 4 elements), static reference: starting each equilibrium from the
    // previous point's must give the same modes as ramping from the straight shape.
    let options = SweepOptions {
        reference: Reference::Static { load_steps: 10 },
        ports: Ports::Nodes { inputs: vec!["5:Fy".parse().unwrap()], outputs: vec!["5:y".parse().unwrap()] },
        rom: RomRequest::new(ModeSelection::Lowest(1)),
        modes: 2,
        ..pendulum_options()
    };
    let plain = run("simply_supported_beam.mbd", &["N=0:4000:3"], &options);
    let cont = run("simply_supported_beam.mbd", &["N=0:4000:3"], &SweepOptions { continuation: true, ..options });
    for k in 0..3 {
        let (a, b) = (plain.results[k].as_ref().unwrap(), cont.results[k].as_ref().unwrap());
        for (x, y) in a.modes.iter().map(|m| m.lambda).zip(b.modes.iter().map(|m| m.lambda)) {
            assert!((x - y).norm() < 1e-8 * x.norm(), "point {k}: {x} vs {y}");
        }
    }
    // The compression lowers the first bending frequency (paper Fig. 5).
    assert!(plain.results[2].as_ref().unwrap().modes[0].lambda.im < plain.results[0].as_ref().unwrap().modes[0].lambda.im);
}

#[test]
fn cli_sweep_writes_the_others_and_exits_1_on_a_failed_point() {
    let dir = std::env::temp_dir().join(format!("romdyn_sweep_cli_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (_, pendulum) = example("pendulum.mbd");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_romdyn"))
        .args(["sweep".as_ref(), pendulum.as_os_str()])
        .args(["--set", "M=1,-1", "--set", "L=1,4", "--input", "2:Mz", "--output", "2:rz", "--count", "1", "--lowest", "1", "--jobs", "2"])
        .arg("-o")
        .arg(dir.join("p.mat"))
        .arg("--table")
        .arg(dir.join("p.csv"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("design point 3 (M = -1, L = 1) failed:") && stderr.contains("pendulum.mbd:45:17: error: negative mass -1"), "{stderr}");
    assert!(stderr.contains("2 of 4 design points failed"), "{stderr}");
    let csv = std::fs::read_to_string(dir.join("p.csv")).unwrap();
    // Row 2: M = 1, L = 4: ω = sqrt(M G L / (J + M L²)) (12 digits written).
    let row: Vec<&str> = csv.lines().nth(2).unwrap().split(',').collect();
    let w: f64 = row[4].parse().unwrap();
    assert!((w - omega(1.0, 4.0)).abs() < 1e-6 * w, "{csv}");
    assert!(dir.join("p.mat").exists());
    // A name the file does not declare stops before any point runs.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_romdyn")).args(["sweep".as_ref(), pendulum.as_os_str()]).args(["--set", "LEN=1,2", "--count", "1"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(1) && stderr.contains("--set LEN: the file declares no variable 'LEN'"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_sweep_at_a_reference_time_takes_the_beam_update_eig_takes() {
    // examples/cantilever.mbd (ten beam3, tip force P applied at t = 0) swept over P, the
    // reference at t = 2 ms of its time integration. `romdyn eig --at T` on the same file
    // takes MBDyn's incremental beam update (the default `auto`, tests/multibody/beam_incremental.rs);
    // a sweep's point must give the same modes (to round-off, 1e-12 relative: the same
    // computation), and the path-independent update other ones (measured: first mode
    // 1.6e-8 and 4.0e-8 relative apart at P = 500 and 1000 N, above the 1e-10 asserted), or
    // a sweep point and `eig` on the same file would part without a message.
    use romdyn::element::BeamUpdate;
    use romdyn::input::mbdyn::BeamUpdateChoice;
    let options = |beam_update| SweepOptions {
        reference: Reference::At(0.002),
        ports: Ports::Nodes { inputs: vec!["21:Fy".parse().unwrap()], outputs: vec!["21:y".parse().unwrap()] },
        rom: RomRequest::new(ModeSelection::Lowest(1)),
        modes: 2,
        beam_update,
        ..pendulum_options()
    };
    let first = |choice| {
        let r = run("cantilever.mbd", &["P=500,1000"], &options(choice));
        r.results.iter().map(|p| p.as_ref().unwrap().modes[0].lambda).collect::<Vec<_>>()
    };
    let (auto, incremental, independent) = (first(BeamUpdateChoice::Auto), first(BeamUpdateChoice::Every(BeamUpdate::Incremental)), first(BeamUpdateChoice::Every(BeamUpdate::PathIndependent)));
    for k in 0..2 {
        assert!((auto[k] - incremental[k]).norm() < 1e-12 * auto[k].norm(), "point {k}: auto {} vs incremental {}", auto[k], incremental[k]);
        let apart = (auto[k] - independent[k]).norm() / auto[k].norm();
        eprintln!("point {k}: first mode {} rad/s, path independent {apart:e} relative apart", auto[k]);
        assert!(apart > 1e-10, "point {k}: the path-independent update gave the same mode {}", independent[k]);
    }
}

/// A sweep of discrete-time ROMs (issue 37 point 3: `--sample-rate` in every export): each
/// point's stacked `Ad` is `e^{A T}` of the same point's continuous ROM in the same
/// consistent basis (zero-order hold keeps the modal states; the basis change is orthogonal
/// and commutes with the exponential), to 1e-12; balanced reduction and the minimal
/// realization are refused by the library, naming the setting.
#[test]
fn a_sweep_of_discrete_roms_keeps_the_modal_basis_and_refuses_balancing() {
    let fs = 2048.0;
    let continuous = run("pendulum.mbd", &["L=1:2:3"], &pendulum_options());
    let mut options = pendulum_options();
    options.rom.sampling = romdyn::study::sampling(Some(fs), "zoh", None).unwrap();
    let discrete = run("pendulum.mbd", &["L=1:2:3"], &options);
    let (c, d) = (continuous.consistent_roms(), discrete.consistent_roms());
    for k in 0..3 {
        let (c, d) = (&c[k].as_ref().unwrap().rom, &d[k].as_ref().unwrap().rom);
        assert_eq!(d.sample_time, Some(1.0 / fs));
        assert_eq!(c.states, d.states, "point {k}: the same modal states");
        let at = faer::Mat::from_fn(c.a.nrows(), c.a.ncols(), |i, j| c.a[(i, j)] / fs);
        let expected = romdyn::rom::expm(&at);
        for i in 0..expected.nrows() {
            for j in 0..expected.ncols() {
                assert!((d.a[(i, j)] - expected[(i, j)]).abs() < 1e-12, "point {k}: Ad[{i},{j}] {} vs e^(A T) {}", d.a[(i, j)], expected[(i, j)]);
            }
        }
    }
    for (setting, set) in [(romdyn::study::Setting::Balanced, true), (romdyn::study::Setting::Minimal, false)] {
        let mut options = pendulum_options();
        if set {
            options.rom.balanced = romdyn::study::balancing(Some(1), None, false).unwrap();
        } else {
            options.rom.minimal = romdyn::study::minimal_tolerance(Some(1e-9)).unwrap();
        }
        match options.check() {
            Err(romdyn::study::StudyError::Option { option, message }) => assert!(option == setting && message.contains("not available in a sweep"), "{message}"),
            other => panic!("{setting:?}: {other:?}"),
        }
        // A Rust caller that skips the check gets every point refused, not a mixed basis.
        let r = run("pendulum.mbd", &["L=1:2:2"], &options);
        assert_eq!(r.failures().count(), 2);
    }
}
