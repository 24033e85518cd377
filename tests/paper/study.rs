//! The ROM workflow as a library type (issue 9, point 11): the same numbers as the CLI.

use romdyn::analysis::Reference;
use romdyn::rom::ModeSelection;
use romdyn::study::{FrequencyGrid, StudySource, Residualization, RomRequest, Study, StudyError};

fn beam() -> Study {
    Study::builder(StudySource::model_file("examples/simply_supported_beam.mbd")).reference(Reference::Static { load_steps: 10 }).node_ports(vec!["5:Fy".parse().unwrap()], vec!["5:y".parse().unwrap()]).build().unwrap()
}

#[test]
fn beam_rom_through_the_study_keeps_the_paper_static_gains() {
    let study = beam();
    assert_eq!(study.dae().dim(), 138);
    // Eq. 73: L³/(48 EJ) + L/(4 GA) = 2.108333e-5 m/N for the example's data, 1e-9 relative.
    let exact = 1.0 / 48e3 + 1.0 / 4e6;
    let first = study.reduce(&RomRequest::new(ModeSelection::Lowest(1))).unwrap();
    let full = first.static_gains.full.as_ref().unwrap()[(0, 0)];
    assert!((full / exact - 1.0).abs() < 1e-9, "{full}");
    // Paper §7.1: one mode loses 1.6 % of the static gain (romdyn −1.570 %, docs/src/cases.md, C4 table).
    let g = first.static_gains.rom.as_ref().unwrap()[(0, 0)];
    assert!((g / exact - 1.0 + 0.01570).abs() < 5e-5, "{g}");
    // Residualizing every dropped mode restores the full static gain (eqs. 57–63), 1e-9.
    let all = study.reduce(&RomRequest::new(ModeSelection::Lowest(1)).residualize(Residualization::Dropped)).unwrap();
    let g = all.static_gains.rom.as_ref().unwrap()[(0, 0)];
    assert!((g / full - 1.0).abs() < 1e-9, "{g} vs {full}");
    let freq = study.frequencies(&FrequencyGrid { fmin_hz: Some(1.0), fmax_hz: Some(100.0), points: 3 }, &[]).unwrap();
    assert_eq!(freq.len(), 3);
    assert!((freq[1] - 10.0).abs() < 1e-12);
}

#[test]
fn a_rom_without_ports_is_a_typed_error() {
    let study = Study::builder(StudySource::model_file("examples/pendulum.mbd")).build().unwrap();
    assert!(matches!(study.reduce(&RomRequest::new(ModeSelection::Lowest(1))), Err(StudyError::NoPorts)));
    let missing = Study::builder(StudySource::model_file("examples/no_such_file.mbd")).build();
    assert!(matches!(missing, Err(StudyError::Model(_))));
}
