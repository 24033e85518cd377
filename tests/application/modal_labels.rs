//! Mode labels that name a flexible body's modes (issue 35 point 2): a modal joint's modal
//! coordinates carry the kinetic energy `½ q̇ᵀ M q̇` of its modes, shared out beside the
//! nodes' in the modal table, its JSON and Python.

use crate::common;

use common::mbdyn::test_file;
use romdyn::eigen::ModeKind;
use romdyn::study::{Study, StudySource};

fn study_of(name: &str) -> Study {
    Study::builder(StudySource::model_file(&test_file(name))).build().unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_clamped_components_mode_shares_its_energy_with_the_mass_it_carries() {
    // tests/mbdyn_files/modal_clamped_port.mbd: the one mode of modal_spring_mass.fem
    // (modal mass 0.5 kg) moves FEM node B, which carries node 2's 1.5 kg body, by q₁ along
    // y. Closed form: the kinetic energies ½ 0.5 |λ q₁|² and ½ 1.5 |λ q₁|², so the mode is
    // 25 % the modal joint's mode 1 and 75 % node 2 y (1e-10), at ω = √(1000/2) rad/s.
    let study = study_of("modal_clamped_port.mbd");
    let energy = study.energy();
    let (i, mode) = study.modal().modes.iter().enumerate().find(|(_, m)| m.kind == ModeKind::Dynamic).unwrap();
    assert!((mode.lambda.norm() - 500f64.sqrt()).abs() < 1e-10 * 500f64.sqrt(), "{}", mode.lambda);
    let share = |who: &str| energy[i].iter().find(|s| s.who() == who).map_or(0.0, |s| s.share);
    assert!((share("modal joint 10 mode 1") - 0.25).abs() < 1e-10, "{:?}", energy[i]);
    assert!((share("node 2 y") - 0.75).abs() < 1e-10, "{:?}", energy[i]);
    let modal = energy[i].iter().find(|s| s.element.is_some()).unwrap();
    assert_eq!((modal.node, modal.element.as_deref(), modal.mode), (10, Some("modal joint"), Some(1)));
    assert_eq!(romdyn::eigen::describe(&energy[i]), "node 2 y 75 %, modal joint 10 mode 1 25 %");
}

#[test]
fn a_floating_bodys_rigid_modes_go_to_its_modal_node_and_its_flexible_ones_to_its_modes() {
    // tests/mbdyn_files/modal_floating_soft.mbd: the two-mode point-mass body of
    // modal_point_masses.fem on a modal node held by soft springs, a 0.5 kg body at FEM node B.
    // The six rigid-body modes (below 0.1 Hz) move the modal node and the body rigidly: their
    // energy is the nodes' (the FEM modes' share below 1e-3); the two flexible modes (3.2 and
    // 4.6 Hz, the FEM file's modes coupled to the frame) have each its own FEM mode as the
    // largest share.
    let study = study_of("modal_floating_soft.mbd");
    let energy = study.energy();
    let dynamic: Vec<usize> = study.modal().modes.iter().enumerate().filter(|(_, m)| m.kind == ModeKind::Dynamic && m.lambda.im >= 0.0).map(|(i, _)| i).collect();
    assert_eq!(dynamic.len(), 8);
    let in_modes = |i: usize| energy[i].iter().filter(|s| s.element.as_deref() == Some("modal joint")).map(|s| s.share).sum::<f64>();
    for &i in &dynamic {
        let f = study.modal().modes[i].freq_hz();
        if f < 1.0 {
            assert!(in_modes(i) < 1e-3, "{f} Hz: {:?}", energy[i]);
        } else {
            let top = &energy[i][0];
            assert_eq!(top.element.as_deref(), Some("modal joint"), "{f} Hz: {:?}", energy[i]);
            assert!(top.share > 0.4, "{f} Hz: {:?}", energy[i]);
        }
    }
    let flexible: Vec<Option<usize>> = dynamic.iter().filter(|&&i| study.modal().modes[i].freq_hz() > 1.0).map(|&i| energy[i][0].mode).collect();
    assert_eq!(flexible, [Some(1), Some(2)]);
}

#[test]
fn the_eigen_json_carries_the_modal_joints_mode() {
    let (ok, stdout, stderr) = common::cli::romdyn(&["eig", test_file("modal_clamped_port.mbd").to_str().unwrap(), "--json"]);
    assert!(ok, "{stdout}\n{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("{e}: {stdout}"));
    let energy = &v["eigenvalues"][0]["energy"];
    let modal = energy.as_array().unwrap().iter().find(|s| s["element"] == "modal joint").unwrap_or_else(|| panic!("{energy}"));
    assert_eq!((modal["node"].as_u64(), modal["mode"].as_u64(), modal["state"].as_str()), (Some(10), Some(1), Some("mode 1")));
    assert!((modal["share"].as_f64().unwrap() - 0.25).abs() < 1e-10, "{modal}");
}
