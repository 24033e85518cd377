//! `romdyn validate` (issue 33): the H1 estimate of the nonlinear run against closed forms,
//! the paper's Fig. 7 beam, a ROM wrong on purpose, and measured responses.

use std::path::Path;

use faer::c64;
use romdyn::analysis::Reference;
use romdyn::dae::{NodeInput, NodeOutput};
use romdyn::input::mbdyn::read_model;
use romdyn::rom::ModeSelection;
use romdyn::study::{Ports, Residualization, RomRequest, Study, StudySource};
use romdyn::validate::welch::magnitude_random_error;
use romdyn::validate::{read_measured, validate, validate_roms, ValidateOptions, Validation};

fn validated(file: &str, reference: Reference, input: &str, output: &str, request: RomRequest, options: &ValidateOptions) -> Validation {
    let m = read_model(Path::new(file)).unwrap();
    let ports = Ports::Nodes { inputs: vec![input.parse::<NodeInput>().unwrap()], outputs: vec![output.parse::<NodeOutput>().unwrap()] };
    let mut study = Study::builder(StudySource::model(m.model, m.problem)).reference(reference).ports(ports.clone()).build().unwrap();
    let (state, problem) = study.reference_and_problem().unwrap();
    let rom = study.reduce(&request).unwrap();
    validate(&mut study, &problem, &state, &ports, &rom, options, &mut |_, _| {}).unwrap()
}

const MASSES: &str = "examples/mass_on_springs.mbd";

/// Mass 3 of mass_on_springs.mbd along x validated with `options`: each bin with coherence
/// >= 0.9 as (frequency [Hz], |H1 - H| / |H|, coherence), H(jω) = 1/(K − M ω² + j C ω) the
/// closed form (M = 2 kg, K = 100 N/m, C = 1 N s/m, the file's values), the number of bins,
/// the estimate's independent averages and the validation.
fn oscillator(options: &ValidateOptions) -> (Vec<(f64, f64, f64)>, usize, f64, Validation) {
    let v = validated(MASSES, Reference::Initial, "3:Fx", "3:x", RomRequest::new(ModeSelection::Indices(vec![3])), options);
    let c = &v.runs[0].channels[0];
    let (m, k, damping) = (2.0, 100.0, 1.0);
    let coherent = (0..c.estimate.freq_hz.len())
        .filter(|&i| c.estimate.coherence[i] >= 0.9)
        .map(|i| {
            let f = c.estimate.freq_hz[i];
            let w = 2.0 * std::f64::consts::PI * f;
            let exact = c64::new(1.0, 0.0) / c64::new(k - m * w * w, damping * w);
            (f, (c.estimate.h[i] - exact).norm() / exact.norm(), c.estimate.coherence[i])
        })
        .collect();
    let (bins, averages) = (c.estimate.freq_hz.len(), c.estimate.independent);
    (coherent, bins, averages, v)
}

/// The oscillator's H1 estimate agrees with the closed form at every bin with coherence
/// ≥ 0.9 within three times Bendat and Piersol's random error `√(1 − γ²)/(|γ| √(2 n_d))`
/// plus 1 % (the window's resolution bias at the 0.08 Hz wide peak with 0.011 Hz bins,
/// (1/3)(Δf/B_r)² ≈ 0.7 %, and the input's interpolation).
#[test]
fn mass_spring_damper_estimate_matches_the_closed_form() {
    let (coherent, bins, averages, v) = oscillator(&ValidateOptions { resolution_hz: Some(0.011), averages: 16, ..ValidateOptions::default() });
    for &(f, err, g) in &coherent {
        let allowed = 3.0 * magnitude_random_error(g, averages) + 0.01;
        assert!(err <= allowed, "{f} Hz: |H1 - H| / |H| = {err:.4} > {allowed:.4} (coherence {g})");
    }
    assert!(coherent.len() > bins / 2, "{} of {bins} bins coherent", coherent.len());
    // The ROM keeps that oscillator: it represents the model (the linear spring, tiny motion).
    assert!(v.represents, "{}", v.summary());
}

/// The same oscillator and closed form excited by the two other signals of `--signal`: a
/// Schroeder-phased multisine at the estimator's bins and a linear chirp repeated every Welch
/// segment. Both are periodic in the segment, so the estimator takes no window (Hann's mixed
/// each bin with its neighbours, whose deterministic phases do not average out: 1.3 % from
/// 0.8 to 1.07 Hz and 3.6 % at the peak, whatever the step, before) and has no random
/// error once the fade-in's transient (decay time 2M/C = 4 s against 91 s segments) has
/// died. What is left is the integrator's period error (ms, ρ∞ = 0.6), which the peak
/// magnifies by 1/ζ (ζ = 0.035): measured 0.43 % at 1.132 Hz with the default step (5.6
/// ms) and 0.028 % with a step four times smaller (h², checked by `romdyn validate
/// --time-step 1.4e-3`). Bounds: 0.6 % at every coherent bin, 0.2 % below 1.05 Hz (0.11 % measured at 1.02 Hz).
#[test]
fn multisine_and_chirp_estimates_match_the_closed_form() {
    use romdyn::validate::signal::SignalKind;
    for signal in [SignalKind::Multisine, SignalKind::Chirp] {
        let (coherent, bins, _, v) = oscillator(&ValidateOptions { signal, resolution_hz: Some(0.011), averages: 8, ..ValidateOptions::default() });
        for &(f, err, g) in &coherent {
            let allowed = if f < 1.05 { 2e-3 } else { 6e-3 };
            assert!(err <= allowed, "{signal:?}, {f} Hz: |H1 - H| / |H| = {err:.5} > {allowed} (coherence {g})");
        }
        assert!(coherent.len() > bins / 2, "{signal:?}: {} of {bins} bins coherent", coherent.len());
        assert!(v.represents, "{signal:?}: {}", v.summary());
    }
}

/// The paper's Fig. 7 (§7.1): the simply supported beam's mid-span response to a mid-span
/// force, the 1-mode, the 2-mode (modes 1 and 7, the third bending) and the 1-mode with mode
/// 7 statically residualized ROMs (the README's command) compared with one nonlinear run
/// (band 0–100 Hz, 64 averages), as the figure overlays them on one direct response.
///
/// Reference: the full linear model's response (the modal sum, computed by direct solves).
/// The beam is undamped: the response to each segment's input rings beyond the segment, and
/// the H1 estimate's error is that leakage, random from segment to segment and tied to the
/// coherence by Bendat and Piersol's `√(1 − γ²)/(γ √(2 n_d))` (2.5 % at γ² = 0.99 with 8
/// averages: measured 4.3 % at 63.6 Hz with the defaults). With 64 averages (Hann, three
/// quarters overlap, the input 4 bins past the band, the step 6.6e-5 s that keeps the
/// integrator's phase drift at 49 Hz within 0.3 rad over the 17 s record) the largest error
/// where γ² > 0.99 is measured 1.25 % (72.4 Hz); 2 % asserted. At the band's step (1.25e-4
/// s, 4096-sample segments): 1.53 % with 64 averages, 2.08 % with 32, 2.71 % with 16.
#[test]
fn simply_supported_beam_fig7() {
    let m = read_model(Path::new("examples/simply_supported_beam.mbd")).unwrap();
    let ports = Ports::Nodes { inputs: vec!["5:Fy".parse().unwrap()], outputs: vec!["5:y".parse().unwrap()] };
    let mut study = Study::builder(StudySource::model(m.model, m.problem)).reference(Reference::Static { load_steps: 10 }).ports(ports.clone()).build().unwrap();
    let (state, problem) = study.reference_and_problem().unwrap();
    let roms = [
        RomRequest::new(ModeSelection::Lowest(1)),
        RomRequest::new(ModeSelection::Indices(vec![1, 7])),
        RomRequest::new(ModeSelection::Lowest(1)).residualize(Residualization::Modes(vec![7])),
        // The paper's third curve: the two-mode ROM with the modes it drops residualized.
        RomRequest::new(ModeSelection::Indices(vec![1, 7])).residualize(Residualization::Dropped),
    ]
    .map(|r| study.reduce(&r).unwrap());
    let options = ValidateOptions { band_hz: Some((0.0, 100.0)), averages: 64, ..ValidateOptions::default() };
    let v = validate_roms(&mut study, &problem, &state, &ports, &roms, &options, &mut |_, _| {}).unwrap();
    let [one, two, residualized, two_residualized] = [&v[0], &v[1], &v[2], &v[3]].map(|v| &v.runs[0].channels[0]);
    let mut compared = 0;
    for (i, f) in one.estimate.freq_hz.iter().enumerate() {
        if one.estimate.coherence[i] > 0.99 {
            let err = (one.estimate.h[i] - one.full[i]).norm() / one.full[i].norm();
            assert!(err < 0.02, "{f} Hz: estimate vs full {err}\n{}", v[0].summary());
            compared += 1;
        }
    }
    // Most of the 53 bins; the first mode's neighbourhood left out.
    assert!(compared >= 30, "{compared} bins with coherence > 0.99");
    // The 1-mode ROM departs from the full model above the first mode (static error 1.6 %,
    // paper §7.1; 5.5 % at 100 Hz in closed form), the reduction's error, not the estimate's:
    // the validation reports it as its largest ROM-vs-estimate error (coherence >= 0.95),
    // above 60 Hz (measured 5.6 % at 98.3 Hz). The residualized and the 2-mode ROMs depart
    // from the full model by 0.8 % and 2.6e-4 at the band's top; their largest error against
    // the estimate is the estimate's own (measured 2.6 % at 63.1 Hz, where the estimate is
    // 2.7 % from the full model at coherence 0.95–0.99): below 3 % and half the 1-mode's.
    let (e1, f1) = one.rom_error.unwrap();
    assert!(e1 > 0.04 && f1 > 60.0, "{e1} at {f1} Hz\n{}", v[0].summary());
    for c in [two, residualized, two_residualized] {
        let (e, f) = c.rom_error.unwrap();
        assert!(e < 0.03 && e < e1 / 2.0, "{e} at {f} Hz");
    }
    assert!(v[0].summary().contains(&format!("ROM vs estimate {:.3} % at {f1:.4} Hz", 100.0 * e1)));
    assert!(v.iter().all(|v| v.represents), "{}", v[0].summary());
}

/// A ROM wrong on purpose: mass 3's y response (2.25 Hz) by a ROM that keeps its x mode
/// (1.125 Hz, modes 3,4) instead, which the port does not see, is flagged; the ROM keeping
/// the y mode (modes 7,8: mass 2's undamped y mode has the same |λ| and comes first, the
/// table's tie broken by Re λ) is not. Same band (0–4 Hz) and signal for both.
#[test]
fn a_rom_without_the_mode_the_port_sees_is_flagged() {
    // 0.4 N RMS on K = 400 N/m: 1 mm static (the wrong ROM has no static gain to size it by).
    let options = ValidateOptions { band_hz: Some((0.0, 4.0)), resolution_hz: Some(0.05), amplitudes: vec![0.4], ..ValidateOptions::default() };
    let wrong = validated(MASSES, Reference::Initial, "3:Fy", "3:y", RomRequest::new(ModeSelection::Indices(vec![3])), &options);
    let right = validated(MASSES, Reference::Initial, "3:Fy", "3:y", RomRequest::new(ModeSelection::Indices(vec![7])), &options);
    assert!(!wrong.represents && wrong.verdict().contains("does NOT represent"), "{}", wrong.summary());
    assert!(right.represents && !right.verdict().contains("NOT"), "{}", right.summary());
}

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("h-validate-tests-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// A CSV written from the full model's own response (re/im, Rust's shortest round-trip
/// formatting) is compared with the full model within 1e-12; the mag/phase form within
/// the round-off of the polar conversion.
#[test]
fn measured_round_trip() {
    let m = read_model(Path::new(MASSES)).unwrap();
    let ports = Ports::Nodes { inputs: vec!["3:Fx".parse().unwrap()], outputs: vec!["3:x".parse().unwrap()] };
    let study = Study::builder(StudySource::model(m.model, m.problem)).ports(ports).build().unwrap();
    let freq: Vec<f64> = (1..=50).map(|k| 0.07 * k as f64).collect();
    let h = study.full_frequency_response(&freq).unwrap();
    let mut text = String::from("# written from the full model\nfrequency [Hz],1/1 re [m/N],1/1 im [m/N],1/1 mag [m/N],1/1 phase [deg]\n");
    for (f, h) in freq.iter().zip(&h) {
        let v = h[(0, 0)];
        text += &format!("{f},{},{},{},{}\n", v.re, v.im, v.norm(), v.arg().to_degrees());
    }
    let path = tmp("round_trip.csv");
    std::fs::write(&path, text).unwrap();
    let options = ValidateOptions { measured: Some(path.clone()), band_hz: Some((0.0, 3.0)), resolution_hz: Some(0.1), averages: 4, ..ValidateOptions::default() };
    let v = validated(MASSES, Reference::Initial, "3:Fx", "3:x", RomRequest::new(ModeSelection::Indices(vec![3])), &options);
    // Two channels of the file, the same pair: re/im exactly, mag/phase to round-off.
    assert_eq!(v.measured.len(), 2);
    assert!(v.measured[0].full_error <= 1e-12, "{}", v.measured[0].full_error);
    assert!(v.measured[1].full_error <= 1e-12, "{}", v.measured[1].full_error);
}

/// Malformed files are refused with FILE:LINE:COLUMN.
#[test]
fn malformed_measurements_are_refused_with_their_place() {
    let cases = [
        ("frequency [Hz],1/1 re [m/N],1/1 im [m/N]\n1.0,2.0,x\n", ":2:9: 'x' is not a finite number"),
        ("frequency [Hz],1/1 re [m/N]\n1.0,2.0\n", ":1:16: 2 columns"),
        ("freq [s],1/1 re [m/N],1/1 im [m/N]\n", ":1:1: the first column must be 'frequency [Hz]'"),
        ("frequency [Hz],1/1 re [m/N],1/1 im [m/s]\n", ":1:29:"),
        ("frequency [Hz],0/1 re [m/N],0/1 im [m/N]\n", ":1:16: '0/1 re [m/N]': expected a channel"),
        ("frequency [Hz],1/1 re [m/N],1/1 im [m/N]\n2.0,1,1\n1.0,1,1\n", ":3:1: frequency 1 Hz"),
        ("frequency [Hz],1/1 re [m/N],1/1 im [m/N]\n1.0,1\n", ":2:5: 2 columns, the header has 3"),
        ("# only a comment\n", ":1:1: no header line"),
    ];
    for (k, (text, expected)) in cases.iter().enumerate() {
        let path = tmp(&format!("bad{k}.csv"));
        std::fs::write(&path, text).unwrap();
        let e = read_measured(&path).unwrap_err().to_string();
        assert!(e.starts_with(&path.display().to_string()) && e.contains(expected), "case {k}: {e}");
    }
}

/// The complete elliptic integral of the first kind, `K(k) = π / (2 AGM(1, √(1 − k²)))`.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    while (a - b).abs() > 1e-15 * a {
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// The pendulum of pendulum.mbd (m = 1 kg, L = 1 m, J = 1e-3 kg m², undamped) at growing
/// random moment amplitudes: the linearity limit lies where its period, by the closed form
/// `T = 4 √(L/g) K(sin(θ₀/2))` (T/T₀ = (2/π) K), departs from the small-angle one by about
/// what the fit threshold allows. Model of that threshold: the output is the ringing of the
/// mode, a relative period error `D` turns its phase by `2π f₀ D t`, so over the compared
/// record `T_r` the NRMSE falls by about the phase's RMS, `2π f₀ D T_r / √3`: the fit 0.5
/// allows `D* = √3 · 0.5 / (2π f₀ T_r)`. A random response of RMS angle `σ` swings with
/// RMS envelope `θ₀ = √2 σ`. The last amplitude described has `D(θ₀) < D*`; the first not
/// described `D(θ₀) > D*/3` (the model ignores how the envelope varies: measured 1.1e-3
/// against D* = 1.2e-3).
#[test]
fn pendulum_linearity_limit_matches_the_period_closed_form() {
    // K(0) = π/2 and K(sin 45°) = 1.854075 (Abramowitz and Stegun, table 17.1): the AGM.
    assert!((elliptic_k(0.0) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    assert!((elliptic_k(std::f64::consts::FRAC_1_SQRT_2) - 1.854_074_677).abs() < 1e-8);
    let options = ValidateOptions { amplitudes: vec![0.002, 0.02, 0.06, 0.1, 0.3], ..ValidateOptions::default() };
    let v = validated("examples/pendulum.mbd", Reference::Initial, "2:Mz", "2:rz", RomRequest::new(ModeSelection::Lowest(1)), &options);
    let (Some(ok), bad) = v.linearity_limit.expect("a linearity limit within 0.002..0.3 N m") else { panic!("{}", v.summary()) };
    let sigma = |a: f64| v.runs.iter().find(|r| r.amplitude[0] == a).unwrap().channels[0].output_rms;
    let departure = |sigma: f64| 2.0 / std::f64::consts::PI * elliptic_k((std::f64::consts::SQRT_2 * sigma / 2.0).sin()) - 1.0;
    let f0 = (9.81f64 / 1.001).sqrt() / (2.0 * std::f64::consts::PI);
    let record = (v.plan.samples - v.plan.lead_in) as f64 * v.plan.dt;
    let allowed = 3f64.sqrt() * (1.0 - v.plan.fit) / (2.0 * std::f64::consts::PI * f0 * record);
    let (d_ok, d_bad) = (departure(sigma(ok)), departure(sigma(bad)));
    assert!(d_ok < allowed && d_bad > allowed / 3.0, "limit {ok}..{bad} N m: D = {d_ok:.3e}, {d_bad:.3e} against D* = {allowed:.3e}\n{}", v.summary());
    assert!(v.represents, "the smallest amplitude is described");
}

/// `romdyn validate --amplitudes A1,A2` writes every amplitude's estimate and time series
/// (issue 33: the CSVs held only the smallest amplitude's): on the linear oscillator (mass 3
/// of mass_on_springs.mbd along x) both estimates equal the closed form H = 1/(K − M ω² +
/// j C ω) and each run's input has the RMS asked for (its definition, over the samples).
#[test]
fn every_amplitude_is_written() {
    let dir = crate::common::cli::temp_dir("validate-amplitudes");
    let prefix = dir.join("v").to_string_lossy().into_owned();
    let (ok, _, err) = crate::common::cli::romdyn(&["validate", MASSES, "--input", "3:Fx", "--output", "3:x", "--modes", "3", "--signal", "multisine", "--validation-band", "0:2", "--resolution", "0.05", "--averages", "2", "--amplitudes", "0.5,2", "-o", &prefix]);
    assert!(ok, "{err}");
    let table = |name: &str| -> (Vec<String>, Vec<Vec<f64>>) {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        let mut lines = text.lines();
        let header = lines.next().unwrap().split(',').map(str::to_string).collect();
        (header, lines.map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect())
    };
    let (header, rows) = table("v.csv");
    let column = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name:?} in {header:?}"));
    for a in ["5.000000e-1", "2.000000e0"] {
        let n = "node 3 x [m] / node 3 Fx [N]";
        let (re, im, coherence) = (column(&format!("{n} estimate re [m/N] at {a} RMS [N]")), column(&format!("{n} estimate im [m/N] at {a} RMS [N]")), column(&format!("{n} coherence [1] at {a} RMS [N]")));
        for r in rows.iter().filter(|r| r[coherence] >= 0.99 && r[0] < 1.05) {
            let w = 2.0 * std::f64::consts::PI * r[0];
            let exact = c64::new(1.0, 0.0) / c64::new(100.0 - 2.0 * w * w, w);
            // 0.3 %: the integrator's period error below the peak (the multisine test above)
            // and, with 2 averages, what is left of the fade-in's transient (decay time 4 s
            // against a 12 s lead-in): measured 0.20 % at 0.944 Hz.
            assert!((c64::new(r[re], r[im]) - exact).norm() < 3e-3 * exact.norm(), "{a} N RMS, {} Hz", r[0]);
        }
    }
    let (header, rows) = table("v.time.csv");
    for (a, rms) in [("5.000000e-1", 0.5), ("2.000000e0", 2.0)] {
        let k = header.iter().position(|h| h == &format!("input node 3 Fx [N] at {a} RMS [N]")).unwrap_or_else(|| panic!("{header:?}"));
        let got = (rows.iter().map(|r| r[k] * r[k]).sum::<f64>() / rows.len() as f64).sqrt();
        assert!((got - rms).abs() < 1e-9 * rms, "input RMS {got}, asked {rms}");
    }
}

/// A multisine on the undamped Fig. 7 beam: the fade-in's ringing at 49.3 Hz never decays and,
/// with no window, leaks into every bin, so no bin reaches the coherence threshold (0 of 51
/// measured). The verdict says the ROM could not be judged, not that it departs: the same ROM
/// is within 2 % of the full model over the band (closed form, `rom` vs full).
#[test]
fn an_estimate_with_no_coherent_bin_is_not_a_departure() {
    use romdyn::validate::signal::SignalKind;
    let options = ValidateOptions { signal: SignalKind::Multisine, ..ValidateOptions::default() };
    let request = RomRequest::new(ModeSelection::Lowest(1)).residualize(Residualization::Modes(vec![7]));
    let v = validated("examples/simply_supported_beam.mbd", Reference::Static { load_steps: 10 }, "5:Fy", "5:y", request, &options);
    let c = &v.runs[0].channels[0];
    assert!(c.rom_error.is_none(), "{}", v.summary());
    assert!(v.verdict().contains("NOT KNOWN") && !v.verdict().contains("does NOT represent"), "{}", v.verdict());
    assert!(v.warning().unwrap().contains("could not be judged"));
    let worst = c.rom.iter().zip(&c.full).map(|(r, f)| (r - f).norm() / f.norm()).fold(0.0, f64::max);
    assert!(worst < 0.02, "ROM vs full {worst}");
}

/// `romdyn validate --report DIR` (issue 37 point 6: the report's "validation plots"): the
/// page of `romdyn rom --report` with the validation's summary and figure in it, the
/// validation's files beside it equal to `-o`'s.
#[test]
fn the_report_carries_the_validation() {
    let dir = crate::common::cli::temp_dir("validate-report");
    let prefix = dir.join("v").to_string_lossy().into_owned();
    let report = dir.join("report").to_string_lossy().into_owned();
    let (ok, _, err) = crate::common::cli::romdyn(&["validate", MASSES, "--input", "3:Fx", "--output", "3:x", "--modes", "3", "--signal", "multisine", "--validation-band", "0:2", "--resolution", "0.05", "--averages", "2", "-o", &prefix, "--report", &report]);
    assert!(ok, "{err}");
    let page = std::fs::read_to_string(dir.join("report/index.html")).unwrap();
    assert!(page.contains("<h2>Validation against the nonlinear model</h2>") && page.contains("<img src=\"validation.svg\""), "{page}");
    assert!(page.contains("id=\"romdyn-geometry\"") && page.contains("<img src=\"bode.svg\""), "{page}");
    assert_eq!(std::fs::read_to_string(dir.join("report/validation.csv")).unwrap(), std::fs::read_to_string(dir.join("v.csv")).unwrap());
    for f in ["validation.svg", "validation.png", "bode.svg", "bode.png"] {
        assert!(dir.join("report").join(f).metadata().map(|m| m.len() > 0).unwrap_or(false), "{f}");
    }
}

/// A cut loop (`--cut`) is refused by validate, naming the flag, as dummy-spring removal and
/// imposed motion are: the nonlinear model keeps the cut element, so the ROM of the cut
/// model has no nonlinear run to be compared with (it failed on a port count before).
#[test]
fn a_cut_loop_is_refused_by_validate_with_its_reason() {
    let dir = crate::common::cli::temp_dir("validate-cut");
    let prefix = dir.join("v").to_string_lossy().into_owned();
    let (ok, _, err) = crate::common::cli::romdyn(&["validate", "examples/pid_mass.mbd", "--input", "1:abstract", "--output", "1:abstract", "--count", "2", "--cut", "genel:4", "--validation-band", "0:2", "--averages", "2", "-o", &prefix]);
    assert!(!ok && err.contains("--cut: a cut loop has no nonlinear counterpart to run"), "{err}");
}
