//! What the run that reaches a reference warns about reaches every linearization made there
//! (issue 30, "Python hears no warning"; issue 31, the library does the work): a study at
//! the initial time or `--at` carries the run's warnings on its initial state, and a
//! linearization at a point where an element is not differentiable, or depends on reaction
//! multipliers, says so as `romdyn run`'s eigenanalyses did. `romdyn eig` prints them.

use std::path::Path;

use romdyn::analysis::{Reference, RunWarning};
use romdyn::input::mbdyn::{read_model_text, SetOverrides};
use romdyn::study::{Study, StudySource, Warning};

use crate::common::cli::{romdyn, temp_dir, write_file};

fn study_warnings(text: &str, reference: Reference, set: &[(&str, f64)]) -> Vec<Warning> {
    let overrides: SetOverrides = set.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    let m = read_model_text(text, Path::new("reference_warnings.mbd"), &overrides).unwrap_or_else(|e| panic!("{e}"));
    let study = Study::builder(StudySource::model(m.model, m.problem)).reference(reference).build().unwrap_or_else(|e| panic!("{e}"));
    study.warnings().to_vec()
}

/// A 5 kg block on a line along x with MBDyn's modlugre friction (σ₀ = 2000 1/m, σ₁ = 2.5
/// s/m, κ = 0.71, μ = 0.4), pressed by gravity (N = M g = 49.05 N) and pulled by F.
const BLOCK: &str = "
begin: data; problem: initial value; end: data;
set: real F = 10.;
begin: initial value;
  initial time: 0.; final time: 2.; time step: 1.e-3;
  tolerance: 1e-8; max iterations: 50;
  derivatives coefficient: 1e-7; derivatives max iterations: 10; derivatives tolerance: 1e-3;
end: initial value;
begin: control data; structural nodes: 2; rigid bodies: 1; joints: 2; forces: 1; gravity; end: control data;
begin: nodes;
  structural: 1, static, null, eye, null, null;
  structural: 2, dynamic, null, eye, null, null;
end: nodes;
scalar function: \"mu\", const, .4;
begin: elements;
  joint: 1, clamp, 1, node, node;
  joint: 2, in line, 1, position, reference, node, null, orientation, 1, 0., 0., 1., 3, 1., 0., 0.,
    2, friction, preload, 1e-10, modlugre, 2000., 2.5, 0., .71, \"mu\", simple;
  body: 2, 2, 5., null, diag, 1., 1., 1.;
  force: 1, absolute, 2, position, null, 1., 0., 0., const, F;
  gravity: uniform, 0., 0., -1., const, 9.81;
end: elements;
";

#[test]
fn a_linearization_at_stick_past_breakaway_says_it_is_one_sided() {
    // Closed form: at rest the bristles carry F, z = F/(σ₀ N); the state equation has a kink
    // in v once z exceeds the breakaway deflection κ μ/σ₀ = 1.42e-4 m, i.e. F > κ μ N =
    // 13.93 N (and the block sticks while F < μ N = 19.62 N). F = 16 N: one-sided; F = 10
    // N: smooth. Both: the friction force scales with the reaction (N as integrated).
    let (sigma0, n) = (2000.0, 5.0 * 9.81);
    for (force, one_sided) in [(16.0, true), (10.0, false)] {
        let warnings = study_warnings(BLOCK, Reference::At(1.9), &[("F", force)]);
        let sided: Vec<&String> = warnings.iter().filter_map(|w| if let Warning::OneSided { why } = w { Some(why) } else { None }).collect();
        assert_eq!(sided.len(), usize::from(one_sided), "F = {force} N: {warnings:?}");
        if let Some(why) = sided.first() {
            // "in line 2: its friction state z = 1.63…e-4 m is past the breakaway …"
            let z: f64 = why.split("z = ").nth(1).and_then(|r| r.split(' ').next()).and_then(|z| z.parse().ok()).unwrap_or_else(|| panic!("{why}"));
            let expected = force / (sigma0 * n);
            assert!((z.abs() - expected).abs() < 1e-6 * expected, "z = {z} against F/(σ₀ N) = {expected}");
            assert!(why.starts_with("in line 2: ") && warnings.iter().any(|w| w.to_string().contains("one-sided derivative")), "{why}");
        }
        assert!(warnings.iter().any(|w| matches!(w, Warning::ReactionDependent { why } if why.starts_with("in line 2: its friction force and stiffness scale with the normal force"))), "{warnings:?}");
    }
    // The CLI prints them as `romdyn run`'s eigenanalysis does.
    let dir = temp_dir("reference-warnings-block");
    let file = write_file(&dir, "block.mbd", BLOCK);
    let (ok, _, err) = romdyn(&["eig", &file, "--at", "1.9", "--set", "F=16"]);
    assert!(ok, "{err}");
    assert!(err.contains("warning: in line 2: its friction state z = ") && err.contains("one-sided derivative"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A 2 kg body thrown in gravity whose derivatives cannot meet a tolerance of 1e-30: with
/// `derivatives coefficient: …, auto` MBDyn accepts the coefficient of the smallest residual.
const THROWN: &str = "
begin: data; problem: initial value; end: data;
begin: initial value;
  initial time: 0.; final time: .1; time step: 1.e-3; method: ms, .6;
  tolerance: 1e-10; max iterations: 10;
  derivatives tolerance: 1e-30; derivatives max iterations: 2;
  derivatives coefficient: 1e-4, auto;
end: initial value;
begin: control data; structural nodes: 1; rigid bodies: 1; gravity; end: control data;
begin: nodes; structural: 1, dynamic, 0., 0., 0., eye, 1., 0., 2., null; end: nodes;
begin: elements;
  body: 1, 1, 2., null, diag, 1., 1., 1.;
  gravity: uniform, 0., 0., -1., const, 9.81;
end: elements;
";

/// tests/mbdyn_files/velocity_along_the_rod.mbd: a point on a rod pinned by a spherical
/// hinge, its velocity written along the rod (0.3 m/s), the initial assembly skipped.
fn along_the_rod() -> String {
    std::fs::read_to_string(crate::common::mbdyn::test_file("velocity_along_the_rod.mbd")).unwrap()
}

#[test]
fn a_study_at_the_initial_state_carries_the_runs_warnings() {
    let warnings = study_warnings(THROWN, Reference::Initial, &[]);
    let raised: Vec<(f64, f64)> = warnings.iter().filter_map(|w| if let Warning::Run { warning: RunWarning::DerivativesToleranceRaised { dcoef, tolerance } } = w { Some((*dcoef, *tolerance)) } else { None }).collect();
    assert_eq!(raised.len(), 1, "{warnings:?}");
    // As `romdyn run` and MBDyn 1.7.3 do on tests/mbdyn_files/derivatives_last_chance.mbd
    // (tests/mbdyn/mbdyn_runs.rs: MBDyn prints coef=1e-09 tol=2.80241e-11 for `1e-3, auto`
    // with a 1 ms step): the smallest coefficient tried, 1e-6 times the written one, times
    // the step, 1e-4 · 1e-6 · 1e-3 s = 1e-13 s; the tolerance 1.01 times the residual the
    // momenta leave, √2 dCoef m g (2.80241e-11 = 1.01 √2 · 1e-12 · 2 · 9.81 there).
    let (dcoef, tolerance) = raised[0];
    assert!((dcoef - 1e-13).abs() <= 1e-9 * 1e-13, "dCoef {dcoef:e} s");
    let expected = 1.01 * 2f64.sqrt() * dcoef * 2.0 * 9.81;
    // 1e-4: measured 7e-6 (the residual also carries rounding of Newton's last increment).
    assert!((tolerance - expected).abs() < 1e-4 * expected, "tolerance {tolerance:e}, expected {expected:e}");

    let warnings = study_warnings(&along_the_rod(), Reference::Initial, &[]);
    let rates: Vec<f64> = warnings.iter().filter_map(|w| if let Warning::Run { warning: RunWarning::InconsistentVelocity { rate, .. } } = w { Some(*rate) } else { None }).collect();
    assert_eq!(rates.len(), 1, "{warnings:?}");
    // 1e-10: the file's tolerance (the rate is taken after the derivatives phase; 2.5e-12 measured).
    assert!((rates[0].abs() - 0.3).abs() < 1e-10, "the constraint's rate {} against the written 0.3 m/s along the rod", rates[0]);

    // `romdyn eig` prints them, `romdyn run` as before.
    let dir = temp_dir("reference-warnings-initial");
    let file = write_file(&dir, "rod.mbd", &along_the_rod());
    let (ok, _, err) = romdyn(&["eig", &file]);
    assert!(ok, "{err}");
    assert!(err.contains("warning: reference solution: the initial velocities do not satisfy the joints"), "{err}");
    let (ok, _, err) = romdyn(&["run", &file, "-o", &dir.join("rod").to_string_lossy()]);
    assert!(ok, "{err}");
    assert!(err.contains("warning: the initial velocities do not satisfy the joints"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A scalar node clamped to a ramp satisfies its clamp: a differential one's value moves with
/// its derivative, an algebraic one follows the drive at every instant. The rate check moved
/// only structural positions, and a pressure ramped at
/// 1e9 Pa/s (tests/mbdyn_files/hydraulic_dynamic_pipe.mbd) read as "the initial velocities
/// do not satisfy the joints (genel clamp 1 … changes at -1.000e9 per s)": a hydraulic node
/// is algebraic (its value has no derivative to move with, and the clamp holds it at every
/// instant). The same for differential and algebraic abstract nodes; a structural violation
/// is still reported (the rod test above).
#[test]
fn a_scalar_node_clamped_to_a_ramp_is_not_reported_as_violating_its_clamp() {
    let pipe = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/hydraulic_dynamic_pipe.mbd")).unwrap();
    let abstract_ramp = "
begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 0.01; time step: 1.e-3; tolerance: 1.e-9; end: initial value;
begin: control data; abstract nodes: 3; genels: 3; end: control data;
begin: nodes; abstract: 1, differential, value, 0., derivative, 250.; abstract: 2, differential; abstract: 3, algebraic, value, 1.; end: nodes;
begin: elements;
  genel: 1, clamp, 1, abstract, algebraic, ramp, 250., 0., forever, 0.;
  genel: 3, clamp, 3, abstract, ramp, 40., 0., forever, 1.;
  genel: 2, spring support, 2, abstract, algebraic, linear elastic, 4.;
end: elements;
";
    for (name, text) in [("dynamic pipe", pipe.as_str()), ("abstract ramp", abstract_ramp)] {
        let warnings = study_warnings(text, Reference::Initial, &[]);
        let rates: Vec<String> = warnings.iter().filter_map(|w| if let Warning::Run { warning: RunWarning::InconsistentVelocity { equation, rate } } = w { Some(format!("{equation}: {rate:e}")) } else { None }).collect();
        assert!(rates.is_empty(), "{name}: {rates:?}");
    }
    // With the differential node's derivative written as 0, its clamp Φ = x − 250 t changes
    // at ẋ − 250 = −250 per s (closed form): a true violation, still reported.
    let written_zero = abstract_ramp.replace("derivative, 250.", "derivative, 0.");
    let warnings = study_warnings(&written_zero, Reference::Initial, &[]);
    let rates: Vec<f64> = warnings.iter().filter_map(|w| if let Warning::Run { warning: RunWarning::InconsistentVelocity { rate, .. } } = w { Some(*rate) } else { None }).collect();
    assert_eq!(rates.len(), 1, "{warnings:?}");
    // 1e-9 relative: the rate's third-order difference is exact on a linear drive.
    assert!((rates[0] + 250.0).abs() < 1e-9 * 250.0, "rate {}", rates[0]);
}

/// A drive that changes within microseconds: node 1 follows `x = A (1 − cos ωt)` by a drive
/// displacement pin and abstract node 2 is clamped to `B (1 − cos ωt)`, half cosines over
/// 1 ms (ω = π / 1 ms, A = 5 cm, B = 50), both written at rest, as the drives start. The
/// rates at t = 0 are 0 (closed form). A fixed difference in time read the drives' own
/// curvature as rates: the initial assembly gave node 1 a velocity of A ω⁴ ε³ / 4 =
/// 1.2e-6 m/s (second order at ε = 1e-6 s; MBDyn 1.7.3 writes 0 on this file, its drives'
/// derivatives being analytic), and the check of written velocities reported "genel clamp 2
/// … changes at 1.622 per s" (third order at 1e-5 s), a violation that is not there.
#[test]
fn a_drive_that_changes_within_microseconds_is_not_read_as_a_velocity() {
    let fast = "
begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 2.e-4; time step: 1.e-5; tolerance: 1.e-6; max iterations: 20; end: initial value;
begin: control data; structural nodes: 1; rigid bodies: 1; joints: 1; abstract nodes: 1; genels: 1; end: control data;
begin: nodes;
  structural: 1, dynamic, null, eye, null, null;
  abstract: 2, differential, value, 0., derivative, 0.;
end: nodes;
begin: elements;
  body: 1, 1, 2., null, diag, 1., 1., 1.;
  joint: 1, drive displacement pin, 1, null, null, single, 1., 0., 0., cosine, 0., pi/1.e-3, 0.05, half, 0.;
  genel: 2, clamp, 2, abstract, algebraic, cosine, 0., pi/1.e-3, 50., half, 0.;
end: elements;
";
    let m = read_model_text(fast, Path::new("fast_drives.mbd"), &SetOverrides::default()).unwrap_or_else(|e| panic!("{e}"));
    let report = romdyn::analysis::run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    // 1e-12 m/s: the drive's rate is 0 exactly; the extrapolated difference leaves rounding.
    assert!(report.assembly.moved_velocity < 1e-12, "{:?}", report.assembly);
    assert!(report.inconsistent_velocity.is_none(), "{:?}", report.inconsistent_velocity);

    // With the abstract node's derivative written as 3, its clamp Φ = x − B (1 − cos ωt)
    // changes at ẋ − 0 = 3 per s (closed form): a true violation, still reported.
    let written = fast.replace("derivative, 0.", "derivative, 3.");
    let warnings = study_warnings(&written, Reference::Initial, &[]);
    let rates: Vec<f64> = warnings.iter().filter_map(|w| if let Warning::Run { warning: RunWarning::InconsistentVelocity { rate, .. } } = w { Some(*rate) } else { None }).collect();
    assert_eq!(rates.len(), 1, "{warnings:?}");
    // 1e-7 per s: B (1 − cos ωh) is rounded to B · 1.1e-16, 1e-7 per s at h = 5e-8 s
    // (measured 5.3e-9).
    assert!((rates[0] - 3.0).abs() < 1e-7, "rate {}", rates[0]);
}
