//! Fixed step file drivers and the `file` drive caller (fixedstep.cc, drive_.cc; issue 12,
//! point 3): `tests/mbdyn_files/file_driver.mbd` against closed forms and MBDyn 1.7.3, and
//! the errors for bad cards and bad data files.

use crate::common::mbdyn::test_file as path;

use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{build, parse_text, read_model};

fn text(name: &str) -> String {
    std::fs::read_to_string(path(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// `∫_a^b (1 − s) ds`: the displacement at t = 1 s of a unit mass from rest under a unit
/// force on [a, b].
fn response(a: f64, b: f64) -> f64 {
    (b - a) - (b * b - a * a) / 2.0
}

#[test]
fn file_driver_channels_give_the_closed_forms_and_mbdyns_motion() {
    let m = read_model(&path("file_driver.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let x = |k: usize| report.final_state.node_frame(&asm.dofs, k).kin.x[0];
    // Closed forms x(1) = ∫₀¹ (1 − s) f(s) ds (file header): 2 N throughout; the ramp t to
    // 0.5 s then zero; twice the ramp's samples held (const) and the last one after 0.5 s.
    let held: f64 = (0..5).map(|k| 0.2 * k as f64 * response(0.1 * k as f64, 0.1 * (k + 1) as f64)).sum::<f64>() + response(0.5, 1.0);
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, 1727489e) on this file with its
    // two data files, `output precision: 16`, x of nodes 1 to 3 in the last row of its .mov.
    let cases = [
        (x(0), 1.0, 1.0000000019986568e+00),
        (x(1), 0.5f64.powi(3) / 6.0 + 0.125 * 0.5, 8.3208234371328876e-02),
        (x(2), held, 2.5535028124977666e-01),
    ];
    for (k, (x, exact, mbdyn)) in cases.into_iter().enumerate() {
        eprintln!("node {}: x(1) = {x:.15e}, closed form {exact:.15e}, MBDyn {mbdyn:.15e}", k + 1);
        // ms (ρ∞ = 0.6, h = 1 ms) across the jumps of the padded and held channels (0.5 N at
        // 0.5 s, 0.2 N every 0.1 s): an error of order h times the jump, below 2e-3 relative.
        assert!((x - exact).abs() < 2e-3 * exact, "node {}: {x} against the closed form {exact}", k + 1);
        // Same method and steps: MBDyn's derivatives phase moves node 1 by f dCoef t = 2e-9 m
        // (its coefficient 1e-6 h, docs/src/mbdyn/integration.md); the others agree to the Newton tolerance.
        let tolerance = if k == 0 { 3e-9 } else { 1e-10 };
        assert!((x - mbdyn).abs() < tolerance, "node {}: {x} against MBDyn {mbdyn}", k + 1);
    }
}

/// The file's text with `old` replaced by `new` (which must occur), read; the error, which
/// must name `file_driver.mbd` at the line of `old` and contain `expected`.
fn refused(old: &str, new: &str, expected: &str) {
    let base = text("file_driver.mbd");
    assert!(base.contains(old), "{old}");
    let line = base.lines().position(|l| l.contains(old)).unwrap() + 1;
    let e = match parse_text(&base.replacen(old, new, 1), &path("file_driver.mbd")).and_then(|d| build(&d)) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("{new} must be refused"),
    };
    assert!(e.contains(&format!("file_driver.mbd:{line}:")) && e.contains(expected), "{new}: {e}");
}

#[test]
fn bad_file_drivers_name_the_card_the_data_file_and_the_problem() {
    let missing = path("no_such_data.dat");
    refused("\"file_driver_header.dat\"", "\"no_such_data.dat\"", &format!("file driver 3: cannot read the data file \"{}\"", missing.display()));
    refused("file: 2, fixed step, 6, 2,", "file: 2, fixed step, 6, 3,", "line 2: expected 3 number(s) (one per channel), found 2");
    refused("file: 2, fixed step, 6, 2,", "file: 2, fixed step, 7, 2,", "expected 7 row(s) of data, found 6");
    refused("file: 2, fixed step, 6, 2,", "file: 2, variable step, 2,", "a 'variable step' file driver is not supported by romdyn (MBDyn 1.7.3 runs it)");
    refused("file: 2, fixed step, 6, 2,", "file: 2, stream, 2,", "a 'stream' file driver is not supported by romdyn (MBDyn 1.7.3 runs it)");
    refused("pad zeros, no, \"file_driver.dat\"", "bailout, upper, \"file_driver.dat\"", "bailout ends the run");
    refused("file, 2, 2;", "file, 2, 3;", "file driver 2 has channels 1 to 2, found 3");
    refused("file, 3, 1, amplitude", "file, 3, amplitude", "expected the channel number before 'amplitude'");
    refused("file, 2, 2;", "file, 4, 2;", "file driver 4 is not defined");
    refused("    file drivers: 3;", "    file drivers: 2;", "control data declares 2 file drivers, the model has 3");
}

#[test]
fn a_data_file_header_gives_the_initial_time_and_step() {
    let base = text("file_driver.mbd");
    // The same driver with the header's values written on the card: the same model.
    let written = base.replace("initial time, from file, time step, from file,", "initial time, 0., time step, 0.1,");
    let read = |t: &str| parse_text(t, &path("file_driver.mbd")).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"));
    let (a, b) = (read(&base), read(&written));
    let (ra, rb) = (run(&a.model, &a.problem, &mut ()).unwrap(), run(&b.model, &b.problem, &mut ()).unwrap());
    assert_eq!(ra.final_state.y, rb.final_state.y);
}
