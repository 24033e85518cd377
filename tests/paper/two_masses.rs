//! CASES C1: two rigidly connected masses (paper §6.1, Tables 1–2, eqs. 24–31).

use crate::common;

use common::{rel, two_masses, with_coefficient};
use romdyn::c64;
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::rom::{full_frequency_response, select_modes, DescriptorRom, ModeSelection};

const DCOEFS: [f64; 5] = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5];
const ROUTES: [EigenRoute; 2] = [EigenRoute::Direct, EigenRoute::Lambda];

/// Closed form: one mass m1 + m2 on spring k with damper r: λ = −r/(2M) ± j sqrt(k/M − (r/2M)²).
fn exact_lambda(r: f64) -> c64 {
    let (m, k) = (10.0, 1000.0);
    c64::new(-r / (2.0 * m), (k / m - (r / (2.0 * m)).powi(2)).sqrt())
}

#[test]
fn eigenvalues_and_labels_in_both_forms_for_every_dcoef() {
    for scaled in [false, true] {
        for r in [0.0, 10.0] {
            for c in DCOEFS {
                let dae = with_coefficient(&two_masses(r, scaled), c);
                for route in ROUTES {
                    let modal = ModalAnalysis::compute(&dae.jacobians, route).unwrap();
                    let ctx = format!("scaled={scaled} r={r} c={c:e} {route:?}");
                    // Paper Table 2: eq. 29 gives 2 dynamic + 3 infinite; eq. 30 gives 2 dynamic + 2 zero + 1 infinite.
                    let (zero, inf) = if scaled { (2, 1) } else { (0, 3) };
                    assert_eq!(modal.count(ModeKind::Dynamic), 2, "{ctx}");
                    assert_eq!(modal.count(ModeKind::Zero), zero, "{ctx}");
                    assert_eq!(modal.count(ModeKind::Infinite), inf, "{ctx}");
                    // Exact ±10 j (r = 0) and −0.5 ± 9.987492 j (r = 10), eq. 31. Tolerance 1e-8 relative:
                    // the Λ route loses accuracy as |λ| c shrinks (eq. 33), about 1e-10 at c = 1e-5.
                    let want = exact_lambda(r);
                    let got = modal.modes[0].lambda;
                    assert!((got - want).norm() / want.norm() < 1e-8, "{ctx}: {got} vs {want}");
                    assert_eq!(modal.modes[1].lambda, got.conj(), "{ctx}");
                }
            }
        }
    }
}

#[test]
fn error_estimate_covers_the_actual_error() {
    // Matrices given exactly (F_yd, F_y): the estimate of eqs. 32–35 must bound |λ − λ_exact|.
    for scaled in [false, true] {
        for r in [0.0, 10.0] {
            let dae = two_masses(r, scaled);
            for route in ROUTES {
                let modal = ModalAnalysis::compute(&dae.jacobians, route).unwrap();
                let err = (modal.modes[0].lambda - exact_lambda(r)).norm();
                assert!(err <= modal.modes[0].error, "scaled={scaled} r={r} {route:?}: {err:e} > {:e}", modal.modes[0].error);
            }
        }
    }
}

#[test]
fn damped_eigenvalue_matches_paper_eq_31() {
    // Paper eq. 31: λ = −0.5 ± j 9.9875; CASES C1: −0.5 ± 9.987492 j (computed), to 1e-6 absolute.
    let modal = ModalAnalysis::compute(&two_masses(10.0, false).jacobians, EigenRoute::Direct).unwrap();
    assert!((modal.modes[0].lambda - c64::new(-0.5, 9.987492)).norm() < 1e-6);
}

#[test]
fn two_state_rom_reproduces_eigenvalues_static_gain_and_response() {
    let (m, k) = (10.0, 1000.0);
    for scaled in [false, true] {
        for r in [0.0, 10.0] {
            for c in [1e-1, 1e-3, 1e-5] {
                for given_j in [false, true] {
                    let base = two_masses(r, scaled);
                    let dae = if given_j { with_coefficient(&base, c) } else { base };
                    for route in ROUTES {
                        let ctx = format!("scaled={scaled} r={r} c={c:e} J given={given_j} {route:?}");
                        let modal = ModalAnalysis::compute(&dae.jacobians, route).unwrap();
                        let sel = select_modes(&modal, &ModeSelection::Lowest(1)).unwrap();
                        let rom = DescriptorRom::project(&dae, &modal, &sel, false).unwrap();
                        assert_eq!(rom.e.nrows(), 2, "{ctx}");
                        let ord = rom.to_ordinary().unwrap();
                        // Eigenvalues of the ordinary ROM's A equal the selected ones (1e-8 relative, see above).
                        let ev = ord.a.eigenvalues().unwrap();
                        let want = exact_lambda(r);
                        assert!(ev.iter().any(|l| (l - want).norm() / want.norm() < 1e-8), "{ctx}: {ev:?}");
                        assert!(ev.iter().any(|l| (l - want.conj()).norm() / want.norm() < 1e-8), "{ctx}: {ev:?}");
                        // Static gain 1/k = 1e-3 m/N (CASES C1), to 1e-9 relative.
                        let g = ord.static_gain().unwrap()[(0, 0)];
                        assert!(rel(g, 1.0 / k) < 1e-9, "{ctx}: static gain {g}");
                        // Response equals 1/(k − M ω² + j r ω) at 1, 5, 20 rad/s to 1e-9 relative (CASES C1).
                        let w = [1.0, 5.0, 20.0];
                        let f: Vec<f64> = w.iter().map(|w| w / (2.0 * std::f64::consts::PI)).collect();
                        let (hd, ho) = (rom.frequency_response(&f), ord.frequency_response(&f));
                        for (i, w) in w.iter().enumerate() {
                            let exact = c64::new(1.0, 0.0) / c64::new(k - m * w * w, r * w);
                            for h in [hd[i][(0, 0)], ho[i][(0, 0)]] {
                                assert!((h - exact).norm() / exact.norm() < 1e-9, "{ctx}: w={w} {h} vs {exact}");
                            }
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn full_model_response_matches_closed_form() {
    // The full DAE's C̃ (jω F_yd + F_y)⁻¹ B̃ equals 1/(k − M ω² + j r ω) to 1e-12 relative, both forms.
    for scaled in [false, true] {
        let dae = two_masses(10.0, scaled);
        let w = 5.0;
        let h = full_frequency_response(&dae, &[w / (2.0 * std::f64::consts::PI)])[0][(0, 0)];
        let exact = c64::new(1.0, 0.0) / c64::new(1000.0 - 10.0 * w * w, 10.0 * w);
        assert!((h - exact).norm() / exact.norm() < 1e-12);
    }
}

#[test]
fn full_static_gain_in_the_form_of_eq_30_restores_the_constraint() {
    // Eq. 30: the constraint row and the multiplier column live in F_yd, so F_y is singular;
    // with the multiplier known, the static matrix is eq. 29's F_y and the gain is 1/k =
    // 1e-3 m/N (CASES C1), to rounding. Without that knowledge there is no static gain.
    use romdyn::model::ConstraintForm;
    use romdyn::rom::full_static_gain;
    let mut dae = two_masses(10.0, true);
    assert!(full_static_gain(&dae).is_err());
    dae.constraint_form = Some(ConstraintForm::Scaled);
    dae.multipliers = vec![4];
    let g = full_static_gain(&dae).unwrap()[(0, 0)];
    assert!(rel(g, 1e-3) < 1e-12, "{g}");
    assert!(rel(full_static_gain(&two_masses(10.0, false)).unwrap()[(0, 0)], 1e-3) < 1e-12);
}
