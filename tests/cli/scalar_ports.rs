//! ROM ports on hydraulic nodes through the command line (issue 34): `romdyn rom` on
//! tests/mbdyn_files/hydraulic_actuator_mass.mbd at rest (`--set F0=0`), a force on the piston in, the chambers'
//! pressures out, and the ROM's static gains against the hydraulic spring's closed form.

use crate::common;
use common::cli::{romdyn, temp_dir};

#[test]
fn actuator_rom_gains_from_piston_force_to_chamber_pressures_are_the_closed_form() {
    let dir = temp_dir("actuator-rom");
    let out = dir.join("actuator_rom.json");
    let args = ["rom", "tests/mbdyn_files/hydraulic_actuator_mass.mbd", "--input", "2:Fz", "--output", "1:hydraulic", "--output", "2:hydraulic", "--count", "1", "--set", "F0=0", "-o", out.to_str().unwrap()];
    let (ok, stdout, stderr) = romdyn(&args);
    assert!(ok, "{stdout}\n{stderr}");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(v["output_units"], serde_json::json!(["Pa", "Pa"]));
    assert_eq!(v["input_units"], serde_json::json!(["N"]));
    // Closed form (the file's header): a force F on the piston moves it by F/k, k = β A²
    // (1/V₁ + 1/V₂), and changes the chambers' pressures by ∓β A (F/k)/V: with V₁ = V₂ = V,
    // dp₁/dF = −1/(2A) = −500 Pa/N, dp₂/dF = +500 Pa/N. The full model has no static gain
    // (the chambers' masses are conserved: its F_/y is singular); the ROM of the piston's
    // mode has this one, 1e-10 relative.
    let (beta, area, volume) = (1e9, 1e-3, 1e-4);
    let k = beta * area * area * 2.0 / volume;
    let want = [-beta * area / (volume * k), beta * area / (volume * k)];
    for (row, w) in want.into_iter().enumerate() {
        let got = v["rom_static_gain"][row][0].as_f64().unwrap();
        assert!((got - w).abs() < 1e-10 * w.abs(), "dp{}/dF = {got}, closed form {w}", row + 1);
    }
    assert!(v["full_static_gain"].is_null());
    // With -o the report goes to stderr; at rest (F0 = 0) it warns of nothing.
    assert!(stderr.contains("full model: not available (the static matrix of the full model is singular"), "{stderr}");
    assert!(!stderr.contains("warning"), "{stderr}");
}

#[test]
fn actuator_rom_with_metres_and_pascals_out_judges_each_output_on_its_own_scale() {
    // Issue 34: with the piston's displacement [m] beside the chambers' pressures [Pa] (1e10
    // Pa per metre), the port check said "output node 2 z responds to no input", and the
    // mode's error column read 2.2e-2 rad/s. Now each output is judged against the largest
    // response in its own units and the eigenvalue's error is componentwise.
    let dir = temp_dir("actuator-rom-units");
    let out = dir.join("actuator_rom.json");
    let args = ["rom", "tests/mbdyn_files/hydraulic_actuator_mass.mbd", "--input", "2:Fz", "--output", "2:z", "--output", "1:hydraulic", "--output", "2:hydraulic", "--count", "1", "--set", "F0=0", "-o", out.to_str().unwrap()];
    let (ok, stdout, stderr) = romdyn(&args);
    assert!(ok, "{stdout}\n{stderr}");
    assert!(!stderr.contains("responds to no input") && !stderr.contains("warning"), "{stderr}");
    // The closed form: the ROM's static gain of the piston is 1/k, k = β A² (1/V₁ + 1/V₂)
    // = 2e7 N/m, 1e-10 relative.
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let k = 1e9 * 1e-6 * 2.0 / 1e-4;
    let got = v["rom_static_gain"][0][0].as_f64().unwrap();
    assert!((got - 1.0 / k).abs() < 1e-10 / k, "dz/dF = {got}, closed form {}", 1.0 / k);
    // The modal table's error column: below 1e-8 rad/s (the eigenvalue ±j √(k/M) is right to
    // 1e-10 relative, tests/multibody/hydraulic.rs).
    let (ok, stdout, stderr) = romdyn(&["eig", "tests/mbdyn_files/hydraulic_actuator_mass.mbd", "--set", "F0=0"]);
    assert!(ok, "{stderr}");
    let row = stdout.lines().find(|l| l.trim_start().starts_with("1,2")).unwrap_or_else(|| panic!("{stdout}"));
    let error: f64 = row.split_whitespace().nth(7).and_then(|e| e.parse().ok()).unwrap_or_else(|| panic!("{row}"));
    assert!(error < 1e-8, "{row}");
}
