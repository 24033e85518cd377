//! Issue 30, findings 5 and 7 (ROM messages): every ROM output is checked against the full
//! model on the response grid, transmissibility included, and the messages say what holds:
//! rate outputs are not "exactly zero", a clamped node's rounding is not a static-gain
//! difference, rounding of an ill-conditioned static matrix is not a warning, and the advice
//! checks what the user already asked for.

use crate::common;

use common::cli::{romdyn, temp_dir, write_file};
use faer::c64;
use romdyn::analysis::Reference;
use romdyn::rom::ModeSelection;
use romdyn::study::{StudySource, Residualization, RomRequest, StaticGains, Study, Warning};

const ISOLATOR: &str = "tests/mbdyn_files/isolator_imposed.mbd";
// tests/mbdyn_files/isolator_imposed.mbd: payload M on spring K, damper C over base MB, base
// on the dummy spring K0 to the ground.
const M: f64 = 10.0;
const K: f64 = 3553.0575843;
const C: f64 = 18.849555921;
const MB: f64 = 1.0;
const K0: f64 = 1.0;

/// Closed-form transmissibility of the base-excited oscillator (Den Hartog, Mechanical
/// Vibrations, §2.7): x/x_base = (K + jωC) / (K − Mω² + jωC).
fn closed_form_t(f_hz: f64) -> c64 {
    let w = 2.0 * std::f64::consts::PI * f_hz;
    c64::new(K, w * C) / c64::new(K - M * w * w, w * C)
}

/// A response CSV (`output::response_csv` layout): the frequencies and, for the curve whose
/// header starts with `label`, (re, im, mag, phase_deg) per row.
fn csv_curve(text: &str, label: &str) -> Vec<(f64, [f64; 4])> {
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|h| h.trim_matches('"').starts_with(label) && h.ends_with(" re")).unwrap_or_else(|| panic!("no column {label}: {header:?}"));
    assert!(header[col + 3].trim_matches('"').ends_with("phase_deg"), "{header:?}");
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (v[0], [v[col], v[col + 1], v[col + 2], v[col + 3]])
        })
        .collect()
}

/// Finding 5: with imposed base motion, `--band 1:30` drops the base (dummy-spring) mode at
/// 0.048 Hz; the ROM's transmissibility is then wrong and must be warned about, with the
/// dropped mode named. Keeping it, the ROM's transmissibility, magnitude and phase, is the
/// closed form.
#[test]
fn isolator_transmissibility_is_checked_and_written_with_phase() {
    let dir = temp_dir("rom-checks-isolator");
    let prefix = dir.join("t").to_string_lossy().into_owned();
    let out = dir.join("rom.json").to_string_lossy().into_owned();
    let args = |band: &'static str| vec!["rom", ISOLATOR, "--input", "3:Fx", "--output", "3:x", "--imposed", "2:x", "--band", band, "--transmissibility", &prefix, "-o", &out].into_iter().map(String::from).collect::<Vec<_>>();
    let run = |band| {
        let a = args(band);
        let (ok, _, err) = romdyn(&a.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(ok, "{err}");
        (err, std::fs::read_to_string(format!("{prefix}.csv")).unwrap())
    };

    // The base mode dropped: warned, naming it (sqrt(K0/(M + MB))/2π = 0.0480 Hz).
    let (err, csv) = run("1:30");
    let base_hz = (K0 / (M + MB)).sqrt() / (2.0 * std::f64::consts::PI);
    assert!((base_hz - 0.04798).abs() < 1e-5, "{base_hz}");
    assert!(err.contains("warning: the ROM's transmissibility (eq. 100) node 3 x [m] / node 2 x [m] departs from the full model's"), "{err}");
    assert!(err.contains("mode(s) 1 (0.0480 Hz) below the kept ones are neither kept nor residualized"), "{err}");
    assert!(err.contains("transmissibility z/z_e (eq. 100) on"), "{err}");
    // Not vacuous: the CSV's ROM is far from the closed form in the band (measured 0.91 at
    // 1 Hz, relative), while its full model is the closed form (1e-9).
    let (full, rom) = (csv_curve(&csv, "full model: node 3 x [m] / node 2 x [m]"), csv_curve(&csv, "ROM: node 3 x [m] / node 2 x [m]"));
    let worst_rom = rom.iter().filter(|(f, _)| *f <= 30.0).map(|(f, v)| (c64::new(v[0], v[1]) - closed_form_t(*f)).norm() / closed_form_t(*f).norm()).fold(0.0, f64::max);
    assert!(worst_rom > 0.5, "{worst_rom}");
    for (f, v) in &full {
        let t = closed_form_t(*f);
        assert!((c64::new(v[0], v[1]) - t).norm() <= 1e-9 * t.norm(), "full model at {f} Hz: {v:?} vs {t}");
    }

    // The base mode kept: no departure, and the ROM's complex transmissibility is the closed
    // form to 1e-9 (relative), its magnitude column |T| and its phase column arg T in degrees
    // to 1e-6 (printed with 6 decimals; modulo 360 for the unwrapping).
    let (err, csv) = run("0:30");
    assert!(!err.contains("departs"), "{err}");
    let rom = csv_curve(&csv, "ROM: node 3 x [m] / node 2 x [m]");
    assert!(rom.len() >= 100 && rom[0].0 < 1.0 && rom[rom.len() - 1].0 > 9.0, "{}", rom.len());
    for (f, v) in &rom {
        let t = closed_form_t(*f);
        assert!((c64::new(v[0], v[1]) - t).norm() <= 1e-9 * t.norm(), "ROM at {f} Hz: {v:?} vs {t}");
        assert!((v[2] - t.norm()).abs() <= 1e-9 * t.norm(), "|T| at {f} Hz: {} vs {}", v[2], t.norm());
        let dphase = (v[3] - t.arg().to_degrees()).rem_euclid(360.0);
        assert!(dphase.min(360.0 - dphase) <= 1e-6, "phase at {f} Hz: {} vs {}", v[3], t.arg().to_degrees());
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Finding 7: a velocity output (`z = C̃_v Δẏ`: its C̃ row is zero) is not "responds to no
/// input": its response is jω times the displacement's, which the two-mass closed form
/// gives: [K − ω² M + jω D]⁻¹ with M = diag(MB, M), K = [[K0 + K, −K], [−K, K]],
/// D = [[C, −C], [−C, C]] (hand-built), force on the payload.
#[test]
fn a_velocity_output_is_not_reported_zero_and_its_response_is_the_closed_form() {
    let dir = temp_dir("rom-checks-velocity");
    let ports = write_file(
        &dir,
        "ports.json",
        r#"{ "inputs": [ { "name": "F", "type": "force", "node": 3, "direction": [1, 0, 0] } ],
             "outputs": [ { "name": "v3", "type": "velocity", "node": 3, "direction": [1, 0, 0] } ] }"#,
    );
    let bode = dir.join("b").to_string_lossy().into_owned();
    let out = dir.join("rom.json").to_string_lossy().into_owned();
    let (ok, _, err) = romdyn(&["rom", ISOLATOR, "--ports", &ports, "--count", "2", "--bode", &bode, "-o", &out]);
    assert!(ok, "{err}");
    assert!(!err.contains("responds to no input") && !err.contains("no output responds"), "{err}");
    let csv = std::fs::read_to_string(format!("{bode}.csv")).unwrap();
    let full = csv_curve(&csv, "full model: v3 [m/s] / F [N]");
    for (f, v) in &full {
        let w = 2.0 * std::f64::consts::PI * f;
        let jw = c64::new(0.0, w);
        // Dynamic stiffness Z = K − ω² M + jω D; payload displacement per payload force is
        // Z₁₁ / det Z (row/column 0: base, 1: payload).
        let z00 = c64::new(K0 + K - w * w * MB, w * C);
        let z01 = c64::new(-K, -w * C);
        let z11 = c64::new(K - w * w * M, w * C);
        let x = z00 / (z00 * z11 - z01 * z01);
        let h = jw * x;
        assert!((c64::new(v[0], v[1]) - h).norm() <= 1e-9 * h.norm(), "v3/F at {f} Hz: {v:?} vs {h}");
        assert!(h.norm() > 1e-6, "{h}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Finding 7: a force on the clamped ground node of examples/cantilever.mbd moves nothing
/// (the clamp takes it: closed form zero); its static gain reads 2e-22 m/N of rounding. It
/// must be reported as such ("(rounding)", an input that moves nothing), never as a static
/// gain that differs by 1.4e8 ("keep more modes"), nor as a response that departs; the real
/// channel beside it (tip force) is still compared.
#[test]
fn a_force_on_the_clamped_ground_node_is_rounding_not_a_difference() {
    let (ok, _, err) = romdyn(&["rom", "examples/cantilever.mbd", "--static", "--input", "1:Fy", "--input", "21:Fy", "--output", "21:y", "--count", "1", "--residualize"]);
    assert!(ok, "{err}");
    assert!(err.contains("warning: no output responds to input node 1 Fy [N]"), "{err}");
    assert!(!err.contains("static gain differs") && !err.contains("departs"), "{err}");
    let row = err.lines().skip_while(|l| !l.starts_with("node 21 y [m]")).find(|l| l.contains("relative difference")).unwrap_or_else(|| panic!("{err}"));
    let cells: Vec<&str> = row.split_whitespace().collect();
    assert_eq!(cells[2], "(rounding)", "{row}");
    // The tip channel: a number, the ROM with every dropped mode residualized within the
    // rounding level of this model (StaticGains::rounding_of: 1.7e-7).
    let diff: f64 = cells[3].parse().unwrap_or_else(|_| panic!("{row}"));
    assert!(diff.abs() <= 1.7e-7, "{row}");
}

/// Finding 7: a static-gain difference at the rounding of the static matrix is no warning.
/// examples/cantilever.mbd (EA/EJ = 1e5 m⁻²): its modes span 119 to 1.03e6 rad/s, so an LU
/// of its static matrix loses up to about ε (ω_max/ω_min)² = 1.7e-8; every dropped mode
/// residualized gives the same difference as the ROM that keeps every dynamic mode (the
/// independent reference: no mode is truncated there, so the difference is rounding).
#[test]
fn static_gain_rounding_of_a_stiff_beam_is_not_a_warning() {
    let study = Study::builder(StudySource::model_file("examples/cantilever.mbd")).reference(Reference::Static { load_steps: 10 }).node_ports(vec!["21:Fy".parse().unwrap()], vec!["21:y".parse().unwrap()]).build().unwrap();
    let lambdas: Vec<f64> = study.modal().modes.iter().filter(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).map(|m| m.lambda.norm()).collect();
    let spread = lambdas.iter().fold(0.0f64, |a, &b| a.max(b)) / lambdas.iter().fold(f64::INFINITY, |a, &b| a.min(b));
    assert!((5e3..5e4).contains(&spread), "{spread}");
    let every = study.reduce(&RomRequest::new(ModeSelection::Band { fmin_hz: 0.0, fmax_hz: 1e9 })).unwrap();
    let residualized = study.reduce(&RomRequest::new(ModeSelection::Lowest(1)).residualize(Residualization::Dropped)).unwrap();
    let (rel_every, _) = every.static_gains.largest_relative_difference().unwrap();
    let (rel_res, _) = residualized.static_gains.largest_relative_difference().unwrap();
    let level = StaticGains::rounding_of(spread);
    assert!((level - 10.0 * f64::EPSILON * spread * spread).abs() <= 1e-12 * level, "{level}");
    // Both at rounding, below the level, and the same to 10 %: measured 3.2e-8 each with
    // the dense route's dCoef from the matrix norms, 1.32e-10 each (2e-4 apart) with the
    // dCoef from the spectrum (2026-12-06).
    assert!(rel_every <= level && rel_res <= level, "{rel_every:e} {rel_res:e} {level:e}");
    assert!(rel_every > 1e-13 && (rel_res - rel_every).abs() <= 0.1 * rel_every, "{rel_every:e} {rel_res:e}");
    assert!(!residualized.warnings.iter().any(|w| matches!(w, Warning::StaticGain { .. })), "{:?}", residualized.warnings);

    // Node 2, beside the clamp, reads 1e-6 m/N of the tip force against the tip's 3e-4: the
    // same absolute rounding is a larger part of it, in the ROM with every mode kept as
    // with every dropped mode residualized: no warning, and a tolerance scaled by the static
    // solution's size only (below 1e-3: a real difference of 0.1 % would still be one).
    let study = Study::builder(StudySource::model_file("examples/cantilever.mbd")).reference(Reference::Static { load_steps: 10 }).node_ports(vec!["21:Fy".parse().unwrap()], vec!["2:y".parse().unwrap()]).build().unwrap();
    let every = study.reduce(&RomRequest::new(ModeSelection::Band { fmin_hz: 0.0, fmax_hz: 1e9 })).unwrap();
    let residualized = study.reduce(&RomRequest::new(ModeSelection::Lowest(1)).residualize(Residualization::Dropped)).unwrap();
    let (rel_every, _) = every.static_gains.largest_relative_difference().unwrap();
    let (rel_res, _) = residualized.static_gains.largest_relative_difference().unwrap();
    // Measured 2.8e-6 each with the dCoef from the norms, 1.86e-10 each with the dCoef from
    // the spectrum (2026-12-06).
    assert!(rel_every > 1e-13 && (rel_res - rel_every).abs() <= 0.1 * rel_every, "{rel_every:e} {rel_res:e}");
    let tolerance = residualized.static_gains.tolerance(0, 0);
    assert!(rel_res <= tolerance && tolerance <= 1e-3, "{rel_res:e} {tolerance:e}");
    assert!(!residualized.warnings.iter().any(|w| matches!(w, Warning::StaticGain { .. })), "{:?}", residualized.warnings);
}

/// Finding 7: the departure's advice checks what was asked: with --residualize it does not
/// advise --residualize. examples/cantilever.mbd's tip channel with the modes up to 100 Hz
/// (the first) departs near the full model's antiresonance at 80.7 Hz (measured 30,
/// relative), within the band.
#[test]
fn a_departure_advises_residualize_only_when_it_was_not_given() {
    let base = ["rom", "examples/cantilever.mbd", "--static", "--input", "21:Fy", "--output", "21:y", "--band", "0:100"];
    let (ok, _, err) = romdyn(&base);
    assert!(ok, "{err}");
    let line = err.lines().find(|l| l.contains("departs")).unwrap_or_else(|| panic!("{err}"));
    assert!(line.contains("--residualize (folds"), "{line}");
    let (ok, _, err) = romdyn(&[&base[..], &["--residualize"]].concat());
    assert!(ok, "{err}");
    let line = err.lines().find(|l| l.contains("departs")).unwrap_or_else(|| panic!("{err}"));
    assert!(line.contains("already residualized (--residualize was given)") && !line.contains("--residualize (folds"), "{line}");
    // Above the band a truncated ROM is not meant to follow: --band 0:60 checks up to 60 Hz.
    let (ok, _, err) = romdyn(&["rom", "examples/cantilever.mbd", "--static", "--input", "21:Fy", "--output", "21:y", "--band", "0:60", "--residualize"]);
    assert!(ok, "{err}");
    assert!(!err.contains("departs"), "{err}");
}

/// A pair the full model holds at zero by symmetry (rounding, 1e-14, next to responses of
/// order 1 in its row and column) has no scale of its own: a ROM's 2e-3 there is a small
/// coupling against the responses around it, not a departure of 2e11 (README's HAM-SAS
/// transmissibility command warned on such a pair, table x / node 1 y, at 3.13e10). Its
/// error is measured on the smaller of its output's and input's largest responses; a pair
/// of its own small scale (1e-7 in a row of 1e-7) keeps its own. By hand, from the matrices.
#[test]
fn a_pair_zero_by_symmetry_is_measured_against_its_row_and_column() {
    use romdyn::linear::{FrequencyResponse, Port};
    use romdyn::study::ChannelError;
    let m = |a: [[f64; 3]; 2]| faer::Mat::from_fn(2, 3, |i, j| c64::new(a[i][j], 0.0));
    // Output 0 sees input 0 (1.0) and input 2 (1e-7, a weak but real coupling); output 1
    // sees input 1 (2.0); the pairs (0, 1) and (1, 0) are zero but for rounding.
    let full = m([[1.0, 1e-14, 1e-7], [3e-14, 2.0, 0.0]]);
    let ports = |n: usize| (0..n).map(|k| Port::from_label(&format!("p{k} [m]"))).collect::<Vec<_>>();
    let compare = |rom: [[f64; 3]; 2]| FrequencyResponse::new(vec![1.0], ports(3), ports(2), vec![full.clone()]).with_reduced("ROM", vec![m(rom)]).accuracy().worst_channel.unwrap();
    // The ROM couples (0, 1) by 2e-3: 2e-3 / min(row 0's 1.0, column 1's 2.0) = 2e-3.
    let w = compare([[1.0, 2e-3, 1e-7], [0.0, 2.0, 0.0]]);
    assert_eq!((w.output, w.input), (0, 1));
    assert!((w.relative - 2e-3).abs() < 1e-13, "{w:?}");
    assert!(w.relative < ChannelError::WARN);
    // An invented coupling as large as the responses around it is a departure: 1.5 / 1.0.
    let w = compare([[1.0, 1.5, 1e-7], [0.0, 2.0, 0.0]]);
    assert!((w.output, w.input) == (0, 1) && (w.relative - 1.5).abs() < 1e-13 && w.relative > ChannelError::WARN, "{w:?}");
    // The weak pair (0, 2) keeps its own scale: 2e-7 against 1e-7 is off by 1.0.
    let w = compare([[1.0, 0.0, 2e-7], [0.0, 2.0, 0.0]]);
    assert!((w.output, w.input) == (0, 2) && (w.relative - 1.0).abs() < 1e-9, "{w:?}");
}
