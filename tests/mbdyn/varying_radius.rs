//! An integration method whose asymptotic spectral radius is a drive that varies: MBDyn
//! evaluates it before every step at the step's time with the last solution (stepsol.cc,
//! `MultistepSolver::SetCoef`); romdyn took its value at the initial time.

use std::path::Path;

use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{read_model, read_model_text, SetOverrides};

/// Node 1's x [m] and ẋ [m/s] at the end of the run of `text` (read as `name` in tests/mbdyn_files).
fn end_of(name: &str, text: Option<String>) -> (f64, f64) {
    let path = Path::new("tests/mbdyn_files").join(name);
    let m = match text {
        Some(t) => read_model_text(&t, &path, &SetOverrides::default()).unwrap(),
        None => read_model(&path).unwrap(),
    };
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let k = report.final_state.node_frame(&asm.dofs, 1).kin;
    (k.x[0], k.xdot[0])
}

#[test]
fn a_radius_of_time_is_evaluated_before_every_step_as_mbdyn() {
    // varying_radius.mbd: `method: ms, linear, 0., 0.5;` (ρ = t/2), a 10 rad/s oscillator in
    // steps of 50 ms to t = 2 s. MBDyn 1.7.3 (1727489e) on the same file, its .mov at t = 2 s:
    // x = 8.0613618506868309e-02 m, ẋ = -4.9957481479476784e-01 m/s (measured 1.4e-17 m).
    let (x, v) = end_of("varying_radius.mbd", None);
    assert!((x - 8.0613618506868309e-02).abs() < 1e-12, "x = {x} m against MBDyn's");
    assert!((v - -4.9957481479476784e-01).abs() < 1e-11, "ẋ = {v} m/s against MBDyn's");
    // The radius frozen at its initial value 0 (romdyn before) ends 1.2e-2 m away: the test
    // tells the two apart.
    let text = std::fs::read_to_string("tests/mbdyn_files/varying_radius.mbd").unwrap();
    let (x0, _) = end_of("varying_radius.mbd", Some(text.replace("method: ms, linear, 0., 0.5;", "method: ms, 0.;")));
    assert!((x0 - x).abs() > 1e-3, "frozen radius {x0} m, varying {x} m");
}

#[test]
fn a_radius_reading_the_state_is_evaluated_with_the_last_solution_as_mbdyn() {
    // state_radius.mbd: `method: ms, postponed, 99;` with drive caller 99 = 0.5 + 2 x of the
    // mass (a node drive). MBDyn 1.7.3 (1727489e), .mov at t = 2 s: x =
    // 7.9908357739968891e-02 m, ẋ = -5.5213028341895720e-01 m/s (measured 1.4e-17 m).
    let (x, v) = end_of("state_radius.mbd", None);
    assert!((x - 7.9908357739968891e-02).abs() < 1e-12, "x = {x} m against MBDyn's");
    assert!((v - -5.5213028341895720e-01).abs() < 1e-11, "ẋ = {v} m/s against MBDyn's");
}

#[test]
fn a_radius_leaving_zero_to_one_stops_the_run_with_its_time_and_value() {
    let text = std::fs::read_to_string("tests/mbdyn_files/varying_radius.mbd").unwrap();
    let m = read_model_text(&text.replace("method: ms, linear, 0., 0.5;", "method: ms, linear, 0., 1.;"), Path::new("tests/mbdyn_files/varying_radius.mbd"), &SetOverrides::default()).unwrap();
    let e = run(&m.model, &m.problem, &mut ()).unwrap_err().to_string();
    assert!(e.contains("asymptotic spectral radius is 1.05") && e.contains("at t = 1.05"), "{e}");
}
