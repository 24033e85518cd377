//! A chain of 50 unit masses (issue 2 acceptance): mass 1 grounded by a 1000 N/m spring,
//! springs between masses i and i+1 for i < 49, a rigid constraint x50 − x49 = 0 (form of
//! eq. 29); force on mass 50, output x50.

use crate::common;

use common::{rel, with_coefficient};
use romdyn::c64;
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::linear::LinearDae;
use romdyn::rom::{full_static_gain, select_modes, DescriptorRom, ModeSelection};

fn chain() -> LinearDae {
    common::mass_chain()
}

/// Three lowest natural frequencies [rad/s] of the 49-DOF reduced chain, from
/// scipy.linalg.eigh on K_r, M_r (computed while writing this test).
const LOWEST: [f64; 3] = [0.98360177, 2.95030034, 4.91544096];

#[test]
fn exact_static_gain_is_0_049() {
    // 49 springs in series: 49/1000 m/N (closed form), to 1e-12 relative.
    let g = full_static_gain(&chain()).unwrap()[(0, 0)];
    assert!(rel(g, 0.049) < 1e-12, "{g}");
}

#[test]
fn spectrum_has_49_pairs_and_three_infinite() {
    let modal = ModalAnalysis::compute(&chain().jacobians, EigenRoute::Direct).unwrap();
    assert_eq!(modal.count(ModeKind::Dynamic), 98);
    assert_eq!(modal.count(ModeKind::Infinite), 3);
    for (k, w) in LOWEST.iter().enumerate() {
        // scipy values are printed to 8 decimals: 1e-8 absolute.
        assert!((modal.modes[2 * k].lambda - c64::new(0.0, *w)).norm() < 1e-8, "{}", modal.modes[2 * k].lambda);
    }
}

#[test]
fn three_pair_rom_truncated_and_residualized() {
    for given_j in [false, true] {
        let dae = if given_j { with_coefficient(&chain(), 1e-3) } else { chain() };
        for route in [EigenRoute::Direct, EigenRoute::Lambda] {
            let ctx = format!("J given={given_j} {route:?}");
            let modal = ModalAnalysis::compute(&dae.jacobians, route).unwrap();
            let sel = select_modes(&modal, &ModeSelection::Lowest(3)).unwrap();
            assert_eq!(sel.kept.len(), 6, "{ctx}");

            let truncated = DescriptorRom::project(&dae, &modal, &sel, false).unwrap().to_ordinary().unwrap();
            assert_eq!(truncated.a.nrows(), 6, "{ctx}");
            // Sum of the 3 lowest modal contributions: 0.0468697888 m/N (issue 2; scipy check
            // gives 0.04686978880021), to 1e-9 relative.
            let g = truncated.static_gain().unwrap()[(0, 0)];
            assert!(rel(g, 0.0468697888) < 1e-9, "{ctx}: {g}");
            let ev = truncated.a.eigenvalues().unwrap();
            for w in LOWEST {
                assert!(ev.iter().any(|l| (l - c64::new(0.0, w)).norm() < 1e-8), "{ctx}: {ev:?}");
            }

            let residualized = DescriptorRom::project(&dae, &modal, &sel, true).unwrap();
            assert_eq!(residualized.static_states, 92, "{ctx}");
            let ord = residualized.to_ordinary().unwrap();
            assert_eq!(ord.a.nrows(), 6, "{ctx}");
            // All 46 other pairs statically residualized: the exact 0.049 m/N to 1e-9 relative.
            let g = ord.static_gain().unwrap()[(0, 0)];
            assert!(rel(g, 0.049) < 1e-9, "{ctx}: {g}");
            // Same eigenvalues as the truncated ROM (residualization adds no dynamics).
            let ev = ord.a.eigenvalues().unwrap();
            for w in LOWEST {
                assert!(ev.iter().any(|l| (l - c64::new(0.0, w)).norm() < 1e-8), "{ctx}: {ev:?}");
            }
        }
    }
}

#[test]
fn band_count_and_index_selections_agree() {
    let modal = ModalAnalysis::compute(&chain().jacobians, EigenRoute::Direct).unwrap();
    let by_count = select_modes(&modal, &ModeSelection::Lowest(3)).unwrap();
    // Natural frequencies 0.1565, 0.4696, 0.7823 Hz for the 3 lowest pairs (LOWEST / 2π);
    // the 4th pair is above 0.9 Hz.
    let by_band = select_modes(&modal, &ModeSelection::Band { fmin_hz: 0.0, fmax_hz: 0.9 }).unwrap();
    // Table indices are 1-based; either member of a pair selects the pair.
    let by_index = select_modes(&modal, &ModeSelection::Indices(vec![2, 3, 6])).unwrap();
    assert_eq!(by_count.kept, [0, 1, 2, 3, 4, 5]);
    assert_eq!(by_band, by_count);
    assert_eq!(by_index, by_count);
    assert_eq!(by_count.dropped.len(), 92);
    let infinite = modal.of_kind(ModeKind::Infinite).next().unwrap() + 1;
    assert!(select_modes(&modal, &ModeSelection::Indices(vec![infinite])).is_err());
    assert!(select_modes(&modal, &ModeSelection::Indices(vec![102])).is_err());
    assert!(select_modes(&modal, &ModeSelection::Band { fmin_hz: 100.0, fmax_hz: 200.0 }).is_err());
}
