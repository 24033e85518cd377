//! MBDyn's `modal` joint read from a file (issue 35): `tests/mbdyn_files/modal_spring_mass.mbd`
//! and its FEM file, against the closed form written in the file, and bad cards refused
//! with the file, line and column.

use crate::common;

use common::mbdyn::{assert_refused, test_file};
use romdyn::analysis::Reference;
use romdyn::eigen::ModeKind;
use romdyn::study::{EigenSettings, Linearization, Study};

const FILE: &str = "modal_spring_mass.mbd";

#[test]
fn an_attached_multibody_node_moves_with_its_fem_node() {
    let lin = Linearization { reference: Reference::Initial, inputs: vec![], outputs: vec![] };
    let study = Study::from_model_file(&test_file(FILE), &lin, EigenSettings::default()).unwrap_or_else(|e| panic!("{e}"));
    let im: Vec<f64> = study.modal().modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 1e-6).map(|m| m.lambda.im).collect();
    // The file's closed form: ω² = k (1/(mb + m2) + 1/ma + l²/Jz) with Jz = 0.3 + 0.01 kg m².
    let expected = (1000.0f64 * (1.0 / 2.0 + 1.0 / 2.0 + 0.64 / 0.31)).sqrt();
    assert_eq!(im.len(), 1, "{im:?}");
    // 1e-9 relative: one QZ on 36 unknowns with entries from 1e-2 to 1e3.
    assert!(common::rel(im[0], expected) < 1e-9, "{} rad/s against the closed form {expected} rad/s", im[0]);
}

#[test]
fn bad_modal_joint_cards_are_refused_with_their_place() {
    let original = std::fs::read_to_string(test_file(FILE)).unwrap();
    let with = |from: &str, to: &str| original.replace(from, to);
    assert_refused(
        FILE,
        &original,
        &[
            (with("structural: 1, modal,", "structural: 1, dynamic,"), "is not a 'modal' node"),
            (with("        1,                        # modes", "        2, list, 1, 1,"), "mode number 1: expected"),
            (with("        1,                        # modes", "        2, list, 1, 3,"), "mode 3 asked for, the FEM file"),
            (with("        1,                        # modes", "        2,"), "mode 2 asked for, the FEM file"),
            (with("from file,                # FEM node count", "3,"), "3 FEM nodes given, the FEM file"),
            (with("\"B\", 2, null;", "\"Z\", 2, null;"), "FEM node \"Z\" is not in the FEM file"),
            (with("origin node, \"A\",", "origin node, \"Q\","), "origin node: FEM node \"Q\""),
            (with("\"modal_spring_mass.fem\"", "\"no_such_file.fem\""), "the FEM file cannot be used"),
            (with("no damping,", "diag damping, 1, 2, 0.01,"), "damped mode index 2"),
            (with("\"B\", 2, null;", "\"B\", 2, null, orientation, euler123, 0.1, 0., 0.;"), "an interface orientation other than the identity"),
        ],
    );
}

#[test]
fn a_bad_fem_file_is_refused_with_its_own_place() {
    // The FEM file's error (file:line:col of the .fem) comes through the card's.
    let dir = common::cli::temp_dir("modal-bad-fem");
    let fem = std::fs::read_to_string(test_file("modal_spring_mass.fem")).unwrap().replace("0.5 0.5 0.5 0. 0. 0.", "0.5 0.5 0.5 0. 0. nan");
    common::cli::write_file(&dir, "modal_spring_mass.fem", &fem);
    let mbd = common::cli::write_file(&dir, FILE, &std::fs::read_to_string(test_file(FILE)).unwrap());
    let err = romdyn::input::mbdyn::read_model(std::path::Path::new(&mbd)).err().expect("a NaN in record 11 is refused").to_string();
    assert!(err.contains(&format!("{FILE}:")) && err.contains("modal_spring_mass.fem:28:19:"), "{err}");
    assert!(err.contains("expected a finite real number, found 'nan'"), "{err}");
}
