//! ROMs from the sparse modes (issue 13 point 3): projection by sparse products
//! (`DescriptorRom::project_sparse`) on the shift-invert modes, with the static correction
//! of the truncated modes from one sparse static solve, against the same ROM from the dense
//! route (`ModalAnalysis::of_dae`, dense projection, dense static gain): same static gain and
//! frequency response at 5 frequencies to 1e-8.

use crate::common;

use common::beams::{simply_supported, TABLE3};
use common::models::hanging_chain;
use romdyn::dae::{linearize, linearize_sparse, Assembler, NodeInput, NodeOutput, State};
use romdyn::eigen::krylov::{sparse_modes, ModeTarget, SparseEigenSettings};
use romdyn::eigen::{EigenRoute, ModalAnalysis};
use romdyn::model::ConstraintForm;
use romdyn::model::Model;
use romdyn::rom::{full_static_gain, select_modes, with_static_correction, DescriptorRom, ModeSelection};
use romdyn::solve::{static_solution, NewtonSettings};

fn at_rest(model: &Model) -> State {
    let asm = Assembler::new(model);
    let mut st = State::initial(model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    st
}

/// The `keep` lowest modes' ROM, statically corrected, from both routes; `freqs` [Hz] sit
/// between the modes (a response at a resonance would compare the routes' rounding of Re λ).
fn compare(what: &str, model: &Model, input: &str, output: &str, keep: usize, freqs: &[f64]) {
    let st = at_rest(model);
    let (i, o): (NodeInput, NodeOutput) = (input.parse().unwrap(), output.parse().unwrap());
    let dense = linearize(model, &st, &[i], &[o], None).unwrap();
    let sparse = linearize_sparse(model, &st, &[i.port()], &[o.port()]).unwrap();
    let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
    let rom_dense = {
        let sel = select_modes(&modal, &ModeSelection::Lowest(keep)).unwrap();
        let rom = DescriptorRom::project(&dense, &modal, &sel, false).unwrap().to_ordinary().unwrap();
        with_static_correction(&rom, &full_static_gain(&dense).unwrap()).unwrap()
    };
    let sm = sparse_modes(&sparse, ModeTarget::Lowest(keep), &SparseEigenSettings::default()).unwrap();
    assert!(sm.certified, "{what}: {:?}", sm.note);
    let rom_sparse = {
        let sel = select_modes(&sm.modal, &ModeSelection::Lowest(keep)).unwrap();
        let rom = DescriptorRom::project_sparse(&sparse, &sm.modal, &sel, false).unwrap().to_ordinary().unwrap();
        with_static_correction(&rom, &sparse.static_gain().unwrap()).unwrap()
    };
    assert_eq!(rom_sparse.a.nrows(), 2 * keep, "{what}: two states per kept pair");
    // Same static gain (the full model's, by the dense and by the sparse static solve).
    let (gd, gs) = (rom_dense.static_gain().unwrap(), rom_sparse.static_gain().unwrap());
    assert!((&gd - &gs).norm_l2() <= 1e-8 * gd.norm_l2(), "{what}: static gain {gd:?} vs {gs:?}");
    let (hd, hs) = (rom_dense.frequency_response(freqs), rom_sparse.frequency_response(freqs));
    for ((a, b), f) in hd.iter().zip(hs.iter()).zip(freqs) {
        let d = (a - b).norm_l2() / a.norm_l2();
        // Issue 13 acceptance: 1e-8 relative.
        assert!(d <= 1e-8, "{what}: response at {f} Hz differs by {d:e}: {a:?} vs {b:?}");
    }
}

/// 5 frequencies between the lowest modes of `model` (midpoints of the first gaps).
fn between_modes(model: &Model) -> Vec<f64> {
    let dense = linearize(model, &at_rest(model), &[], &[], None).unwrap();
    let modal = ModalAnalysis::of_dae(&dense, EigenRoute::Lambda, None).unwrap();
    let f: Vec<f64> = modal.of_kind(romdyn::eigen::ModeKind::Dynamic).filter(|&k| modal.modes[k].lambda.im > 0.0).map(|k| modal.modes[k].freq_hz()).collect();
    let mut out = vec![0.5 * f[0]];
    out.extend((0..4).map(|k| 0.5 * (f[k] + f[k + 1])));
    out
}

#[test]
fn twenty_mode_rom_of_the_1712_equation_chain_is_the_dense_one() {
    let model = hanging_chain(100, ConstraintForm::Scaled);
    let freqs = between_modes(&model);
    compare("chain N = 100", &model, "100:Fx", "100:x", 20, &freqs);
}

#[test]
fn rom_of_the_4_element_beam_is_the_dense_one() {
    // 4-element simply supported beam (paper §6.2): 9 nodes, load and deflection at
    // mid-span (the 5th node).
    let model = simply_supported(&TABLE3, 4, 0.0, 0.0);
    let freqs = between_modes(&model);
    let mid = common::beams::node_label(4);
    compare("beam", &model, &format!("{mid}:Fy"), &format!("{mid}:y"), 6, &freqs);
}

#[test]
fn three_sparse_modes_of_the_mass_chain_with_static_correction_give_0_049() {
    // CASES (issue 2): 50 unit masses, 49 springs of 1000 N/m in series to x50: 0.049 m/N.
    let sparse = romdyn::linear::SparseLinearDae::from_dense(&common::mass_chain());
    let sm = sparse_modes(&sparse, ModeTarget::Lowest(3), &SparseEigenSettings::default()).unwrap();
    assert!(sm.certified, "{:?}", sm.note);
    let sel = select_modes(&sm.modal, &ModeSelection::Lowest(3)).unwrap();
    let rom = DescriptorRom::project_sparse(&sparse, &sm.modal, &sel, false).unwrap().to_ordinary().unwrap();
    assert_eq!(rom.a.nrows(), 6);
    let corrected = with_static_correction(&rom, &sparse.static_gain().unwrap()).unwrap();
    let g = corrected.static_gain().unwrap()[(0, 0)];
    // Issue 13 acceptance: 0.049 to 1e-9.
    assert!((g - 0.049).abs() <= 1e-9 * 0.049, "{g}");
}
