//! The sparse linear model (issue 13 points 1 and 3): the same numbers as the dense one,
//! static gain by one sparse solve, and the sparse static correction of a truncated ROM.

use crate::common;

use std::path::Path;

use common::rel;
use romdyn::analysis::{reference_state, Reference};
use romdyn::dae::{linearize, linearize_sparse};
use romdyn::input::mbdyn::{read_model, read_model_text, SetOverrides};
use romdyn::eigen::{EigenRoute, ModalAnalysis};
use romdyn::linear::SparseLinearDae;
use romdyn::rom::{full_frequency_response, full_static_gain, select_modes, with_static_correction, DescriptorRom, ModeSelection};

fn beam() -> romdyn::input::mbdyn::MbdynModel {
    read_model(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join("simply_supported_beam.mbd")).unwrap()
}

#[test]
fn sparse_linearization_is_the_dense_one() {
    let m = beam();
    let st = reference_state(&m.model, &m.problem, Reference::Static { load_steps: 1 }).unwrap();
    let (i, o): (romdyn::dae::NodeInput, romdyn::dae::NodeOutput) = ("5:Fy".parse().unwrap(), "5:y".parse().unwrap());
    let dense = linearize(&m.model, &st, &[i], &[o], None).unwrap();
    let sparse = linearize_sparse(&m.model, &st, &[i.port()], &[o.port()]).unwrap();
    let (fyd, fy) = dense.jacobians.derivatives();
    // Same assembly, same entries: exact.
    assert_eq!(sparse.fyd.to_dense(), fyd);
    assert_eq!(sparse.fy.to_dense(), fy);
    assert!(sparse.nnz() < fy.nrows() * fy.ncols() / 10, "{} non-zeros of {}²", sparse.nnz(), fy.nrows());
    // Paper eq. 73: L³/(48 EJ) + L/(4 GA) in the form of eq. 30, to 1e-9 relative.
    let d = common::beams::TABLE3;
    let exact = d.length.powi(3) / (48.0 * d.ej) + d.length / (4.0 * d.ga);
    let g = sparse.static_gain().unwrap()[(0, 0)];
    assert!(rel(g, exact) < 1e-9, "{g:e}");
    // Frequency response by sparse solves: the dense solves' numbers to 1e-10.
    let f = [0.1, 1.0, 10.0, 40.0, 200.0];
    let (hs, hd) = (sparse.frequency_response(&f).unwrap(), full_frequency_response(&dense, &f));
    for (a, b) in hs.iter().zip(hd.iter()) {
        assert!((a - b).norm_l2() <= 1e-10 * b.norm_l2(), "{a:?} {b:?}");
    }
}

#[test]
fn three_mode_rom_of_the_mass_chain_gets_the_static_gain_0_049() {
    // CASES (issue 2): 50 unit masses, 49 springs of 1000 N/m in series to x50: 0.049 m/N.
    let dae = common::mass_chain();
    let sparse = SparseLinearDae::from_dense(&dae);
    let full = sparse.static_gain().unwrap();
    assert!(rel(full[(0, 0)], 0.049) < 1e-12, "{:?}", full);
    assert!(rel(full[(0, 0)], full_static_gain(&dae).unwrap()[(0, 0)]) < 1e-12);
    let modal = ModalAnalysis::of_dae(&dae, EigenRoute::Direct, None).unwrap();
    let sel = select_modes(&modal, &ModeSelection::Lowest(3)).unwrap();
    let rom = DescriptorRom::project(&dae, &modal, &sel, false).unwrap().to_ordinary().unwrap();
    let truncated = rom.static_gain().unwrap()[(0, 0)];
    // Without correction three modes miss part of the compliance.
    assert!(rel(truncated, 0.049) > 1e-3, "{truncated}");
    let corrected = with_static_correction(&rom, &full).unwrap();
    // Issue 13 acceptance: 0.049 to 1e-9, same eigenvalues.
    let g = corrected.static_gain().unwrap()[(0, 0)];
    assert!(rel(g, 0.049) < 1e-9, "{g}");
    assert_eq!(corrected.eigenvalues, rom.eigenvalues);
}

/// `linearize_sparse`'s `F_/ẏ` and `F_/y` are the dense route's (`linearize` without
/// dcoef: the same triplets accumulated entry by entry, `Triplets::to_dense`) bit for
/// bit, on a string of masses whose parameters are not round (masses 1.3 kg and up,
/// rods of EA 900.7 N and rest lengths 0.93 m, nodes 1.07 m apart, moved sideways), so
/// that a node's diagonal sums the terms of its body, two rods and itself with rounding.
#[test]
fn sparse_derivatives_are_the_dense_ones_bit_for_bit() {
    let n = 12;
    let mut text = format!(
        "begin: data; problem: initial value; end: data;\nbegin: initial value; initial time: 0.; final time: 0.; time step: 1.e-3; end: initial value;\n\
         begin: control data; skip initial joint assembly; structural nodes: {}; rigid bodies: {n}; joints: {}; end: control data;\nbegin: nodes;\n\
         structural: 0, static, null, eye, null, null;\nstructural: {}, static, {:?}, 0., 0., eye, null, null;\n",
        n + 2,
        n + 3,
        n + 1,
        1.07 * (n + 1) as f64
    );
    for i in 1..=n {
        text += &format!("structural: {i}, dynamic displacement, {:?}, {:?}, 0.01, null;\n", 1.07 * i as f64, 0.013 * (i % 3) as f64);
    }
    text += &format!("end: nodes;\nbegin: elements;\njoint: 0, clamp, 0, node, node;\njoint: {}, clamp, {}, node, node;\n", n + 2, n + 1);
    for i in 1..=n + 1 {
        if i <= n {
            text += &format!("body: {i}, {i}, {:?};\n", 1.3 + 0.1 * i as f64);
        }
        text += &format!("joint: {i}, rod, {}, {i}, 0.93, linear elastic, 900.7;\n", i - 1);
    }
    text += "end: elements;\n";
    let m = read_model_text(&text, Path::new("string.mbd"), &SetOverrides::new()).unwrap();
    let st = reference_state(&m.model, &m.problem, Reference::Initial).unwrap();
    let dense = linearize(&m.model, &st, &[], &[], None).unwrap();
    let sparse = linearize_sparse(&m.model, &st, &[], &[]).unwrap();
    let (fyd, fy) = dense.jacobians.derivatives();
    for (s, d) in [(&sparse.fyd, fyd), (&sparse.fy, fy)] {
        let s = s.to_dense();
        for i in 0..d.nrows() {
            for j in 0..d.ncols() {
                // A sum of exactly zero is not stored (it may be −0 in the dense sum).
                assert!(s[(i, j)].to_bits() == d[(i, j)].to_bits() || (s[(i, j)] == 0.0 && d[(i, j)] == 0.0), "({i}, {j}): {:e} against {:e}", s[(i, j)], d[(i, j)]);
            }
        }
    }
    assert!(sparse.fy.nnz() > 10 * n, "{} non-zeros in F_y", sparse.fy.nnz());
}
