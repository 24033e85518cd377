//! The beam examples in MBDyn format (`examples/simply_supported_beam.mbd`,
//! `examples/cantilever.mbd`) give the numbers of the same models built through the Rust API
//! (CASES C4, C5), including under a load set by a driver file before `include:`.

use crate::common;

use std::path::Path;

use common::beams::{simply_supported, TABLE3};
use common::rel;
use romdyn::analysis::{reference_state, Reference};
use romdyn::dae::{linearize, Assembler, State};
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::model::Model;
use romdyn::solve::{static_solution, NewtonSettings};

fn example(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)
}

/// The example read through a driver file that sets `variables` first (`set: ifndef` in the
/// example keeps them).
fn with_variables(name: &str, variables: &str) -> MbdynModel {
    let text = format!("{variables}\ninclude: \"{name}\";\n");
    build(&parse_text(&text, &example("driver.mbd")).unwrap()).unwrap()
}

fn lowest_frequency(model: &Model, st: &State) -> f64 {
    let dae = linearize(model, st, &[], &[], None).unwrap();
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Lambda).unwrap();
    modal.of_kind(ModeKind::Dynamic).map(|i| modal.modes[i].lambda.norm()).fold(f64::INFINITY, f64::min)
}

fn api_frequency(n_axial: f64) -> f64 {
    let model = simply_supported(&TABLE3, 4, n_axial, 0.0);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings { tolerance: 1e-10, ..NewtonSettings::default() }).unwrap();
    lowest_frequency(&model, &st)
}

#[test]
fn simply_supported_beam_file_matches_the_api_model() {
    let n_crit = std::f64::consts::PI.powi(2) * TABLE3.ej;
    for (set, n) in [("", 0.0), ("set: real N = 0.5*pi^2*1.e3;", 0.5 * n_crit)] {
        let m = with_variables("simply_supported_beam.mbd", set);
        assert_eq!(Assembler::new(&m.model).dofs.len, 138, "9 dynamic nodes (108), joints 5 + 7 x 3 + 4");
        let st = reference_state(&m.model, &m.problem, Reference::Static { load_steps: 1 }).unwrap();
        let (file, api) = (lowest_frequency(&m.model, &st), api_frequency(n));
        eprintln!("N = {n}: file {file} rad/s, API {api} rad/s");
        // Same model two ways: to rounding (1e-9).
        assert!(rel(file, api) < 1e-9);
    }
}

#[test]
fn cantilever_file_reproduces_the_elastica() {
    // CASES C5: tip 0.30172 L down and 0.05643 L back for P L²/EJ = 1, within 0.5 %.
    let m = with_variables("cantilever.mbd", "");
    let st = reference_state(&m.model, &m.problem, Reference::Static { load_steps: 10 }).unwrap();
    let asm = Assembler::new(&m.model);
    let tip = asm.dofs.node_first[m.model.node_index(21).unwrap()];
    let (down, back) = (-st.y[tip + 1], 1.0 - st.y[tip]);
    assert!(rel(down, 0.30172) < 0.005 && rel(back, 0.05643) < 0.005, "{down} {back}");
}

#[test]
fn full_model_static_gain_is_eq_73_in_the_form_of_eq_30() {
    // The file's model uses MBDyn's constraint form (eq. 30), where F_y alone is singular;
    // the static matrix restores the constraint rows and multiplier columns. Paper eq. 73:
    // L³/(48 EJ) + L/(4 GA), to 1e-9 relative.
    let m = with_variables("simply_supported_beam.mbd", "");
    let st = reference_state(&m.model, &m.problem, Reference::Static { load_steps: 1 }).unwrap();
    let dae = linearize(&m.model, &st, &["5:Fy".parse().unwrap()], &["5:y".parse().unwrap()], None).unwrap();
    let gain = romdyn::rom::full_static_gain(&dae).unwrap()[(0, 0)];
    let exact = TABLE3.length.powi(3) / (48.0 * TABLE3.ej) + TABLE3.length / (4.0 * TABLE3.ga);
    assert!(rel(gain, exact) < 1e-9, "{gain:e}");
}

#[test]
fn rom_command_keeps_the_first_bending_mode_and_residualizes_the_third() {
    // Paper §7.1 / Fig. 7 through the CLI: the first pair kept, modal-table mode 7 (the third
    // bending pair) residualized; the static gain is the two-mode ROM's, 2.104747e-5 m/N
    // (tests/paper/beam_simply_supported.rs: −0.170 % from eq. 73's 2.108333e-5).
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_romdyn"))
        .args(["rom", "examples/simply_supported_beam.mbd", "--static", "--input", "5:Fy", "--output", "5:y", "--count", "1", "--residualize-modes", "7", "--form", "descriptor"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("ROM: 2 states from 1 kept mode(s), 2 statically residualized state(s)"), "{err}");
    // The kept pair: 309.927752 rad/s = 49.326534 Hz (tests/paper/beam_simply_supported.rs).
    assert!(err.lines().any(|l| l.trim_start().starts_with("1,2") && l.contains("49.326534")), "{err}");
    let row = |name: &str| err.lines().find(|l| l.trim_start().starts_with(name)).map(|l| l.split_whitespace().last().unwrap_or("").to_string());
    assert_eq!(row("full model").as_deref(), Some("2.108333e-5"), "{err}");
    assert_eq!(row("ROM ").as_deref(), Some("2.104747e-5"), "{err}");
}
