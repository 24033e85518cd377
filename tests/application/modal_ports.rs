//! Modal coordinates as ROM outputs (issue 35 point 2): `JOINT:qK`, `JOINT:qK_rate` and the
//! ports file's `"modal coordinate"` on `tests/mbdyn_files/modal_clamped_port.mbd`, against
//! the one-mode closed form written in the file.

use crate::common;

use common::mbdyn::test_file;
use faer::c64;
use romdyn::study::{StudySource, Study};

const K: f64 = 1000.0;
/// Modal mass 0.5 kg plus the 1.5 kg body on FEM node B.
const MASS: f64 = 2.0;

fn study(outputs: &[&str]) -> Study {
    let outputs = outputs.iter().map(|o| o.parse().unwrap_or_else(|e| panic!("{e}"))).collect();
    Study::builder(StudySource::model_file(test_file("modal_clamped_port.mbd"))).node_ports(vec!["2:Fy".parse().unwrap()], outputs).build().unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_modal_coordinate_is_an_output_with_its_closed_form() {
    let s = study(&["10:q1", "10:q1_rate", "2:y"]);
    assert_eq!(s.dae().output_names, ["modal 10 q1 [-]", "modal 10 q1 rate [1/s]", "node 2 y [m]"]);
    // q1 = 1/(k − (m + m₂) ω²) F, q̇1 = jω q1; node 2 moves with FEM node B (mode shape 1 m
    // along y per unit q1): the same as its y. Direct solves on 30-odd unknowns: 1e-12.
    for f in [1.0, 7.0] {
        let w = std::f64::consts::TAU * f;
        let h = s.full_frequency_response(&[f]).unwrap_or_else(|e| panic!("{e}"));
        let q = 1.0 / (K - MASS * w * w);
        let expected = [c64::new(q, 0.0), c64::new(0.0, w * q), c64::new(q, 0.0)];
        for (o, e) in expected.iter().enumerate() {
            let got = h[0][(o, 0)];
            assert!((got - e).norm() < 1e-12 * q.abs().max(1e-3), "f = {f} Hz, output {o}: {got} against {e}");
        }
    }
    // Static gains: 1/k for q1 and y, none for q̇1.
    let gain = s.full_static_gain().unwrap_or_else(|e| panic!("{e}"));
    assert!((gain[(0, 0)] - 1.0 / K).abs() < 1e-15 && gain[(1, 0)].abs() < 1e-15 && (gain[(2, 0)] - 1.0 / K).abs() < 1e-15, "{gain:?}");
    // The ROM of the one mode keeps the output: static gain 1/k.
    let rom = s.reduce(&romdyn::study::RomRequest::new(romdyn::rom::ModeSelection::Lowest(1))).unwrap_or_else(|e| panic!("{e}"));
    let gain = rom.static_gains.rom.as_ref().map(|g| g[(0, 0)]).unwrap_or_else(|e| panic!("{e}"));
    assert!((gain - 1.0 / K).abs() < 1e-14, "{gain}");
}

#[test]
fn the_ports_file_names_modal_coordinates_and_bad_ones_are_refused() {
    let p = romdyn::input::ports_file::parse_ports(r#"{"outputs": [{"name": "q", "type": "modal coordinate", "joint": 10, "mode": 1}, {"type": "modal coordinate rate", "joint": 10, "mode": 1}, "10:q1"]}"#, "p.json".as_ref()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.outputs[0].label(), "q [-]");
    assert_eq!(p.outputs[1].label(), "output 2 [1/s]");
    assert_eq!(p.outputs[0].measurement, p.outputs[2].measurement);
    let refused = |text: &str| romdyn::input::ports_file::parse_ports(text, "p.json".as_ref()).err().expect("refused").to_string();
    assert!(refused(r#"{"outputs": [{"type": "modal coordinate", "joint": 10}]}"#).contains("needs \"mode\""));
    assert!(refused(r#"{"outputs": [{"type": "modal coordinate", "node": 10, "mode": 1}]}"#).contains("takes \"joint\""));
    assert!(refused(r#"{"outputs": [{"type": "displacement", "node": 2, "direction": [0, 1, 0], "mode": 1}]}"#).contains("belong to 'modal coordinate' outputs"));
    // On the model: a joint that is not there, a mode the joint does not use.
    let err = |o: &str| Study::builder(StudySource::model_file(test_file("modal_clamped_port.mbd"))).node_ports(vec![], vec![o.parse().unwrap()]).build().err().expect("refused").to_string();
    assert!(err("11:q1").contains("modal joint 11 is not defined"), "{}", err("11:q1"));
    assert!(err("10:q2").contains("modal joint 10 has no mode 2 (its modes: 1"), "{}", err("10:q2"));
    let syntax = "10:q0".parse::<romdyn::dae::NodeOutput>().err().expect("mode 0 refused").to_string();
    assert!(syntax.contains("qK|qK_rate"), "{syntax}");
}

/// The response at f = 0 against the static gain, dense and sparse, on a model whose
/// linearization is in the form of eq. 30 (constraint rows and multipliers in `F_/ẏ`).
fn assert_zero_frequency_is_static(file: &str, input: &str, outputs: &[&str]) {
    let m = common::mbdyn::read_test_file(file);
    assert_eq!(m.model.constraint_form, romdyn::model::ConstraintForm::Scaled, "{file}: the case is eq. 30's");
    let inputs: Vec<romdyn::dae::NodeInput> = vec![input.parse().unwrap()];
    let outputs: Vec<romdyn::dae::NodeOutput> = outputs.iter().map(|o| o.parse().unwrap()).collect();
    let asm = romdyn::dae::Assembler::new(&m.model);
    let state = romdyn::dae::State::initial(&m.model, &asm.dofs);
    let dense = romdyn::dae::linearize(&m.model, &state, &inputs, &outputs, None).unwrap_or_else(|e| panic!("{e}"));
    let gain = romdyn::rom::full_static_gain(&dense).unwrap_or_else(|e| panic!("{e}"));
    let h = romdyn::rom::full_frequency_response(&dense, &[0.0, 1e-12]);
    let ports = |p: &[romdyn::dae::NodeInput]| p.iter().map(romdyn::dae::NodeInput::port).collect::<Vec<_>>();
    let out_ports: Vec<_> = outputs.iter().map(romdyn::dae::NodeOutput::port).collect();
    let sparse = romdyn::dae::linearize_sparse(&m.model, &state, &ports(&inputs), &out_ports).unwrap_or_else(|e| panic!("{e}"));
    let hs = sparse.frequency_response(&[0.0, 1e-12]).unwrap_or_else(|e| panic!("{file}, sparse: {e}"));
    let scale = (0..gain.nrows()).map(|o| gain[(o, 0)].abs()).fold(0.0, f64::max);
    for (route, h) in [("dense", &h), ("sparse", &hs)] {
        for (k, f) in [0.0, 1e-12].iter().enumerate() {
            for o in 0..gain.nrows() {
                // 1e-10 of the largest gain: one LU each of the same static matrix (at 1e-12 Hz
                // the response differs from the static gain by (ω/ω₁)² ≈ 1e-27, a rate output
                // by ω·gain ≈ 6e-12 of it).
                let got = h[k][(o, 0)];
                assert!((got - c64::new(gain[(o, 0)], 0.0)).norm() <= 1e-10 * scale, "{file} {route} at {f} Hz, output {o}: {got} against the static gain {}", gain[(o, 0)]);
            }
        }
    }
}

#[test]
fn the_response_at_zero_frequency_is_the_static_gain() {
    // Before: NaN at f = 0 on every model in the form of eq. 30 — its constraint rows and
    // multiplier columns sit in F_/ẏ, so jω F_/ẏ + F_/y lost them at ω = 0 (the static gain
    // restored them). The closed form here: q1 = y = F/k = 1e-3 m/N.
    assert_zero_frequency_is_static("modal_clamped_port.mbd", "2:Fy", &["10:q1", "2:y", "10:q1_rate"]);
    let s = Study::builder(StudySource::model_file(test_file("modal_clamped_port.mbd"))).node_ports(vec!["2:Fy".parse().unwrap()], vec!["10:q1".parse().unwrap()]).build().unwrap_or_else(|e| panic!("{e}"));
    let h = s.full_frequency_response(&[0.0]).unwrap_or_else(|e| panic!("{e}"));
    assert!((h[0][(0, 0)] - c64::new(1.0 / K, 0.0)).norm() < 1e-15, "{:?}", h[0][(0, 0)]);
    // A clamped cantilever of beam3 (a clamp's multipliers): the tip's static deflection.
    assert_zero_frequency_is_static("cms_cantilever.mbd", "17:Fy", &["17:y", "13:y", "17:rz"]);
}
