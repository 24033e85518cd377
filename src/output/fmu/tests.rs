//! The FMU of a mass–spring–damper ROM, its C source compiled with a small driver that
//! calls the FMI 2.0 functions as an importer does: the co-simulation step response equals
//! the exact one (closed form through the matrix exponential) to rounding, model exchange's
//! derivatives are `A x + B u`, the discrete ROM samples as `x[k+1] = A x[k] + B u[k]`.

use super::*;
use crate::output::zip::stored_members;
use crate::rom::expm;

/// m = 2 kg, c = 0.3 N s/m, k = 50 N/m; input a force [N], outputs the position [m] and the
/// force itself (D = 1): x = (position, velocity).
fn mass_spring_damper(sample_time: Option<f64>) -> RomExport {
    let (m, c, k) = (2.0, 0.3, 50.0);
    let a = Mat::from_fn(2, 2, |i, j| [[0.0, 1.0], [-k / m, -c / m]][i][j]);
    let b = Mat::from_fn(2, 1, |i, _| [0.0, 1.0 / m][i]);
    let (a, b) = match sample_time {
        // Zero-order hold: [[Ad, Bd], [0, I]] = exp([[A, B], [0, 0]] T).
        Some(t) => {
            let z = Mat::from_fn(3, 3, |i, j| if i < 2 { if j < 2 { a[(i, j)] * t } else { b[(i, 0)] * t } } else { 0.0 });
            let e = expm(&z);
            (Mat::from_fn(2, 2, |i, j| e[(i, j)]), Mat::from_fn(2, 1, |i, _| e[(i, 2)]))
        }
        None => (a, b),
    };
    RomExport {
        kind: "ordinary",
        e: Mat::identity(2, 2),
        a,
        b,
        c: Mat::from_fn(2, 2, |i, j| if i == 0 && j == 0 { 1.0 } else { 0.0 }),
        d: Mat::from_fn(2, 1, |i, _| if i == 1 { 1.0 } else { 0.0 }),
        eigenvalues: Vec::new(),
        full_eigenvalues: Vec::new(),
        inputs: vec!["2:Fx".into()],
        outputs: vec!["2:x".into(), "force <echo>".into()],
        states: vec!["q1".into(), "q1'".into()],
        input_units: vec!["N".into()],
        output_units: vec!["m".into(), "N".into()],
        state_units: vec!["m".into(), "m/s".into()],
        state_modes: vec![1, 1],
        state_freq_hz: vec![0.8, 0.8],
        reference_time: Some(0.0),
        dcoef: 1.0,
        full_static_gain: None,
        rom_static_gain: None,
        sample_time,
        discretization: if sample_time.is_some() { "zoh".into() } else { "continuous".into() },
        hankel_singular_values: Vec::new(),
        error_bound: None,
    }
}

/// An importer: instantiates the FMU as co-simulation (or model exchange with `me`), applies
/// a unit force and prints `t position force` at every communication point of step `h`
/// (model exchange: `t der(position) der(velocity)` at x = (0.1, -0.2)).
const DRIVER: &str = r#"
#include <stdio.h>
#include <stdlib.h>
typedef void *fmi2Component;
typedef struct { void *l, *a, *f, *s, *e; } Callbacks;
fmi2Component fmi2Instantiate(const char *, int, const char *, const char *, const Callbacks *, int, int);
int fmi2SetupExperiment(fmi2Component, int, double, double, int, double);
int fmi2EnterInitializationMode(fmi2Component);
int fmi2ExitInitializationMode(fmi2Component);
int fmi2SetReal(fmi2Component, const unsigned *, size_t, const double *);
int fmi2GetReal(fmi2Component, const unsigned *, size_t, double *);
int fmi2DoStep(fmi2Component, double, double, int);
int fmi2SetContinuousStates(fmi2Component, const double *, size_t);
int fmi2GetDerivatives(fmi2Component, double *, size_t);
int main(int argc, char **argv) {
    Callbacks cb = {0};
    int me = argc > 3;
    fmi2Component c = fmi2Instantiate("rom", me ? 0 : 1, argv[1], "", &cb, 0, 0);
    if (!c) { printf("refused\n"); return 0; }
    double h = atof(argv[2]), one = 1.0, y[2];
    unsigned u = 0, outs[2] = {1, 2};
    fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0);
    fmi2EnterInitializationMode(c);
    fmi2ExitInitializationMode(c);
    fmi2SetReal(c, &u, 1, &one);
    if (me) {
        double x[2] = {0.1, -0.2}, dx[2];
        fmi2SetContinuousStates(c, x, 2);
        fmi2GetDerivatives(c, dx, 2);
        printf("%.17e %.17e\n", dx[0], dx[1]);
        return 0;
    }
    for (int k = 0; k <= 200; k++) {
        fmi2GetReal(c, outs, 2, y);
        printf("%.17e %.17e %.17e\n", k * h, y[0], y[1]);
        fmi2DoStep(c, k * h, h, 1);
    }
    return 0;
}
"#;

/// Builds the FMU, compiles its source with [`DRIVER`] and runs it with `args`.
fn run_driver(export: &RomExport, tag: &str, args: &[&str]) -> Vec<Vec<f64>> {
    let bytes = fmu_bytes(export, "msd").unwrap_or_else(|e| panic!("{e}"));
    let members = stored_members(&bytes).expect("a readable archive");
    let names: Vec<&str> = members.iter().map(|(n, _)| n.as_str()).collect();
    assert!(names.contains(&"modelDescription.xml") && names.contains(&"sources/msd.c") && names.iter().any(|n| n.starts_with("binaries/")), "{names:?}");
    let source = &members.iter().find(|(n, _)| n == "sources/msd.c").unwrap().1;
    let dir = std::env::temp_dir().join(format!("romdyn-fmu-test-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("msd.c"), source).unwrap();
    std::fs::write(dir.join("driver.c"), DRIVER).unwrap();
    let exe = dir.join("driver");
    let ok = Command::new("cc").arg("-O2").arg("-o").arg(&exe).arg(dir.join("driver.c")).arg(dir.join("msd.c")).arg("-lm").status().unwrap().success();
    assert!(ok, "the FMU's source compiles with a driver");
    let out = Command::new(&exe).arg(guid(export)).args(args).output().unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    String::from_utf8(out.stdout).unwrap().lines().map(|l| l.split_whitespace().map(|w| w.parse().unwrap_or(f64::NAN)).collect()).collect()
}

#[test]
fn co_simulation_steps_give_the_exact_step_response() {
    let export = mass_spring_damper(None);
    let rows = run_driver(&export, "cs", &["0.01"]);
    assert_eq!(rows.len(), 201);
    // Exact response to a unit step: x(t) = ∫₀ᵗ e^{As} ds B, the upper right block of
    // exp([[A, B], [0, 0]] t); position = x₁, the force output = u = 1 (D).
    let mut worst: f64 = 0.0;
    for row in &rows {
        let t = row[0];
        let z = Mat::from_fn(3, 3, |i, j| if i < 2 { if j < 2 { export.a[(i, j)] * t } else { export.b[(i, 0)] * t } } else { 0.0 });
        let exact = expm(&z)[(0, 2)];
        worst = worst.max((row[1] - exact).abs());
        assert_eq!(row[2], 1.0, "D u at t = {t}");
    }
    // Static deflection 1/k = 0.02 m; the steps are exact to rounding (measured 3e-18 m).
    assert!(worst < 1e-12 * 0.02, "largest difference {worst:e} m");
}

#[test]
fn model_exchange_derivatives_are_a_x_plus_b_u() {
    let export = mass_spring_damper(None);
    let rows = run_driver(&export, "me", &["0.01", "me"]);
    let (x, u) = ([0.1, -0.2], 1.0);
    for i in 0..2 {
        let expected = export.a[(i, 0)] * x[0] + export.a[(i, 1)] * x[1] + export.b[(i, 0)] * u;
        assert!((rows[0][i] - expected).abs() <= 1e-15 * expected.abs().max(1.0), "der x{}: {} vs {expected}", i + 1, rows[0][i]);
    }
}

#[test]
fn a_discrete_rom_samples_at_its_sampling_time() {
    let t = 1.0 / 2048.0;
    let export = mass_spring_damper(Some(t));
    // Communication step 4 samples: each step applies x ← Ad x + Bd u four times.
    let rows = run_driver(&export, "zoh", &[&format!("{:.17e}", 4.0 * t)]);
    let mut x = [0.0, 0.0];
    for (k, row) in rows.iter().enumerate().take(50) {
        assert!((row[1] - x[0]).abs() <= 1e-15, "sample {}: {} vs {}", 4 * k, row[1], x[0]);
        for _ in 0..4 {
            x = [export.a[(0, 0)] * x[0] + export.a[(0, 1)] * x[1] + export.b[(0, 0)], export.a[(1, 0)] * x[0] + export.a[(1, 1)] * x[1] + export.b[(1, 0)]];
        }
    }
    let xml = String::from_utf8(stored_members(&fmu_bytes(&export, "msd").unwrap()).unwrap().remove(0).1).unwrap();
    // Model exchange too (time events at the samples: python/tests/test_fmu.py runs it in
    // FMPy); its states are discrete and there are no derivatives.
    assert!(xml.contains("<ModelExchange") && xml.contains("<CoSimulation") && xml.contains("stepSize=\"4.8828125e-4\""), "{xml}");
    assert!(xml.contains("variability=\"discrete\" initial=\"exact\"") && !xml.contains("<Derivatives>"), "{xml}");
}

#[test]
fn the_model_description_names_every_variable_with_its_unit() {
    let export = mass_spring_damper(None);
    let xml = model_description::xml(&export, "msd", &guid(&export));
    for needle in [
        "fmiVersion=\"2.0\"",
        "<ModelExchange modelIdentifier=\"msd\"",
        "<CoSimulation modelIdentifier=\"msd\"",
        "name=\"2:Fx\" valueReference=\"0\" causality=\"input\"",
        "name=\"force &lt;echo&gt;\" valueReference=\"2\" causality=\"output\"",
        "name=\"der(q1&apos;)\" valueReference=\"6\"",
        "derivative=\"4\"",
        "<Unit name=\"N\"/>",
        "description=\"state 2: m/s\"",
    ] {
        assert!(xml.contains(needle), "{needle} missing in\n{xml}");
    }
    assert_ne!(guid(&export), guid(&mass_spring_damper(Some(0.001))));
}

#[test]
fn a_descriptor_rom_and_odd_file_names_are_handled() {
    let mut export = mass_spring_damper(None);
    export.e[(1, 1)] = 0.0;
    assert!(matches!(fmu_bytes(&export, "x"), Err(FmuError::Descriptor)));
    assert_eq!(model_identifier(Path::new("out/2nd rom-v1.fmu")), "rom_2nd_rom_v1");
    assert_eq!(model_identifier(Path::new("plant.fmu")), "plant");
}
