//! Every door into a study runs the same checks (issue 31): the reference checked against
//! the file's problem (a `--at` time after its final time is refused, naming the setting),
//! an unrestrained model named (a static reference of a model with a free rigid-body
//! motion says which), and the beams' incremental update warned about at a static
//! reference. `Study::from_application` skipped all three.

use std::path::Path;

use romdyn::analysis::Reference;
use romdyn::dae::{NodeInput, NodeOutput};
use romdyn::input::mbdyn::MbdynModel;
use romdyn::input::mbdyn::{BeamUpdateChoice, ReadOptions};
use romdyn::study::{Application, Setting, Study, StudyError, StudySource, Warning};

use crate::common::cli::{pendulum_variant, romdyn, temp_dir, write_file};

fn model(relative: &str, replace: &[(&str, &str)]) -> MbdynModel {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(relative);
    let mut text = std::fs::read_to_string(&path).unwrap();
    for (a, b) in replace {
        assert!(text.contains(a), "{a}");
        text = text.replace(a, b);
    }
    romdyn::input::mbdyn::parse_text(&text, &path).and_then(|d| romdyn::input::mbdyn::build(&d)).unwrap_or_else(|e| panic!("{e}"))
}

/// The library's doors (the builder with node ports, the application door), each on the same model, reference and node ports.
fn every_door(make: &dyn Fn() -> MbdynModel, reference: Reference, input: &str, output: &str) -> Vec<(&'static str, Result<Study, StudyError>)> {
    let inputs = vec![input.parse::<NodeInput>().unwrap()];
    let outputs = vec![output.parse::<NodeOutput>().unwrap()];
    let app = Application { inputs: inputs.iter().map(NodeInput::port).collect(), outputs: outputs.iter().map(NodeOutput::port).collect(), names: Default::default(), remove_springs: Vec::new(), imposed: None, cuts: Vec::new() };
    let (a, b) = (make(), make());
    vec![
        ("builder (node ports)", Study::builder(StudySource::model(a.model, a.problem)).reference(reference).node_ports(inputs, outputs).build()),
        ("builder (application)", Study::builder(StudySource::model(b.model, b.problem)).reference(reference).application(app).build()),
    ]
}

#[test]
fn a_reference_time_after_the_problem_is_refused_at_every_door() {
    // examples/pendulum.mbd integrates to 2 s.
    let make = || model("examples/pendulum.mbd", &[]);
    for (door, result) in every_door(&make, Reference::At(5.0), "2:Mz", "2:rz") {
        match result {
            Err(StudyError::Option { option: Setting::ReferenceTime, message }) => assert!(message.contains("after the file's final time 2 s"), "{door}: {message}"),
            Err(e) => panic!("{door}: {e}"),
            Ok(_) => panic!("{door}: accepted a reference time after the final time"),
        }
    }
}

#[test]
fn an_unrestrained_model_is_named_at_every_door() {
    // The pendulum with its clamp removed and the hinge replaced by a 6-D spring: the two
    // nodes float together (tests/paper/rom_trust.rs has the CLI's message).
    let spring = "joint: 2, deformable joint,\n        1, null, hinge, reference, node, eye,\n        2, 0., L, 0., hinge, reference, node, eye,\n        linear elastic generic, diag, 1.e4, 1.e4, 1.e4, 1.e4, 1.e4, 1.e4;";
    let make = || model("examples/pendulum.mbd", &[("    joint: 1, clamp, 1, node, node;\n", ""), ("joint: 2, revolute hinge,\n        1, position, null,\n        2, position, 0., L, 0.;", spring), ("joints: 2;", "joints: 1;")]);
    for (door, result) in every_door(&make, Reference::Static { load_steps: 1 }, "2:Fx", "2:x") {
        match result {
            Err(StudyError::Unrestrained { motion, .. }) => assert!(motion.contains("rigid-body motion of the whole model"), "{door}: {motion}"),
            Err(e) => panic!("{door}: {e}"),
            Ok(_) => panic!("{door}: a floating model found a static equilibrium"),
        }
    }
}

#[test]
fn incremental_beams_at_a_static_reference_are_warned_at_every_door() {
    let make = || {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/beam3_tip_couple.mbd");
        let overrides = romdyn::input::mbdyn::SetOverrides::new();
        let options = ReadOptions::new(&overrides, BeamUpdateChoice::Every(romdyn::element::BeamUpdate::Incremental), false);
        romdyn::input::mbdyn::read_model_with(&path, options).unwrap_or_else(|e| panic!("{e}"))
    };
    let last = make().model.nodes.last().unwrap().label;
    for (door, result) in every_door(&make, Reference::Static { load_steps: 10 }, &format!("{last}:Fy"), &format!("{last}:y")) {
        let study = result.unwrap_or_else(|e| panic!("{door}: {e}"));
        assert!(study.warnings().iter().any(|w| matches!(w, Warning::IncrementalBeamsStatic { beams: 2 })), "{door}: {:?}", study.warnings());
    }
}

/// The CLI's door runs the same three checks through the same builder: `--at` after the
/// file's final time refused naming the flag, the floating model's motion named, the
/// incremental beams at `--static` warned about.
#[test]
fn the_command_line_door_runs_the_same_checks() {
    let (ok, _, err) = romdyn(&["eig", "examples/pendulum.mbd", "--at", "5"]);
    assert!(!ok && err.contains("--at: TIME 5 s is after the file's final time 2 s"), "{err}");

    let dir = temp_dir("study-doors-cli");
    let spring = "joint: 2, deformable joint,\n        1, null, hinge, reference, node, eye,\n        2, 0., L, 0., hinge, reference, node, eye,\n        linear elastic generic, diag, 1.e4, 1.e4, 1.e4, 1.e4, 1.e4, 1.e4;";
    let floating = pendulum_variant(&[("    joint: 1, clamp, 1, node, node;\n", ""), ("joint: 2, revolute hinge,\n        1, position, null,\n        2, position, 0., L, 0.;", spring), ("joints: 2;", "joints: 1;")]);
    let file = write_file(dir.as_ref(), "floating.mbd", &floating);
    let (ok, _, err) = romdyn(&["eig", &file, "--static", "--load-steps", "1"]);
    assert!(!ok && err.contains("unrestrained") && err.contains("rigid-body motion of the whole model"), "{err}");

    let (ok, _, err) = romdyn(&["eig", "tests/mbdyn_files/beam3_tip_couple.mbd", "--static", "--beam-update", "incremental"]);
    assert!(ok && err.contains("warning: 2 beam(s) use MBDyn's incremental update"), "{err}");
}

/// The eigen settings are checked once, by the builder, before any work: a sparse target of
/// no mode or an empty band is refused naming its setting (the CLI's `--count 0` and
/// `--band 3:3` stop earlier, in clap, with the library's words: tests/cli/cli.rs).
#[test]
fn the_builder_checks_the_eigen_settings_once() {
    use romdyn::eigen::krylov::ModeTarget;
    use romdyn::study::EigenSettings;
    for (target, setting) in [(ModeTarget::Lowest(0), Setting::Count), (ModeTarget::Band { fmin_hz: 3.0, fmax_hz: 3.0 }, Setting::Band)] {
        let eigen = EigenSettings { target: Some(target), ..EigenSettings::default() };
        match Study::builder(StudySource::model_file("examples/pendulum.mbd")).eigen(eigen).build() {
            Err(StudyError::Option { option, .. }) => assert_eq!(option, setting),
            Err(e) => panic!("{target:?}: {e}"),
            Ok(_) => panic!("{target:?} accepted"),
        }
    }
}

/// The beams' `auto` update at a reference from a time integration: a driven beam3 cannot
/// take MBDyn's incremental update and keeps the path-independent one; the builder makes that
/// note a study warning, which the CLI prints with its flag (pytest: with the keyword).
#[test]
fn a_beam_the_auto_update_leaves_path_independent_is_a_study_warning() {
    let dir = temp_dir("study-doors-driven-beam");
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mbdyn_files/beam3_tip_couple.mbd")).unwrap();
    assert!(text.contains("    beam3: 2, 3, null"));
    let driven = write_file(dir.as_ref(), "driven.mbd", &text.replace("    beam3: 2, 3, null", "    driven: 2, const, 1., beam3: 2, 3, null"));
    let (ok, _, err) = romdyn(&["eig", &driven, "--at", "0.5"]);
    assert!(ok, "{err}");
    assert_eq!(err.matches("warning: beam3").count(), 1, "{err}");
    assert!(err.contains("warning: beam3 2") && err.contains("keeps the path-independent update") && err.contains("(--beam-update path-independent silences this)"), "{err}");
}

/// The beams' update is a reader option: the builder reads a model file with the update asked
/// for, and refuses one for a model read already (it would be silently ignored).
#[test]
fn the_beam_update_of_a_model_read_already_is_refused() {
    let m = model("tests/mbdyn_files/beam3_tip_couple.mbd", &[]);
    let path = Path::new("beam3_tip_couple.mbd");
    match Study::builder(StudySource::read(m, path)).beam_update(BeamUpdateChoice::Auto).build() {
        Err(StudyError::Option { option, message }) => assert!(option == Setting::BeamUpdate && message.contains("when the file is read"), "{message}"),
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("a beam update on a model read already was accepted"),
    }
    let study = Study::builder(StudySource::model_file("tests/mbdyn_files/beam3_tip_couple.mbd")).beam_update(BeamUpdateChoice::Every(romdyn::element::BeamUpdate::Incremental)).reference(Reference::Static { load_steps: 10 }).build().unwrap_or_else(|e| panic!("{e}"));
    assert!(study.warnings().iter().any(|w| matches!(w, Warning::IncrementalBeamsStatic { beams: 2 })), "{:?}", study.warnings());
}
