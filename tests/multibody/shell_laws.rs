//! MBDyn 1.7.3's `plane stress orthotropic` shell law (shell.cc; the input manual writes
//! such a law as a `matr`): with equal moduli it is the isotropic law, and an orthotropic
//! simply supported plate has the modes of Kirchhoff's orthotropic plate and MBDyn's.
//!
//! MBDyn 1.7.3 (built by shared/tools/build-mbdyn.sh): `mbdyn -f tests/mbdyn_files/FILE.mbd
//! -o out`; eigenvalues from `out_0.m` (`alpha`, `dCoef` = 0.5 s: `λ = (z − 1)/((z + 1)
//! dCoef)`, `z = (αr + i αi)/β`).

use romdyn::study::StudySource;

use super::shell::{frequencies, frequencies_of};
use crate::common::mbdyn::test_file;

#[test]
fn the_orthotropic_law_with_equal_moduli_is_the_isotropic_law() {
    // shell4eas_plate.mbd as written and with its law replaced by the orthotropic one with
    // E_l = E_t = E, nu_lt = NU, G = E/(2 (1 + NU)): C E_l = E h/(1 − ν²) and the rest term by
    // term, up to the order of the products (1 ulp): the same modes to 1e-12 relative.
    let file = test_file("shell4eas_plate.mbd");
    let text = std::fs::read_to_string(&file).unwrap();
    let isotropic = "isotropic, E, E, nu, NU, thickness, H;";
    assert!(text.contains(isotropic));
    let changed = text.replace(isotropic, "plane stress orthotropic, E_l, E, E_t, E, nu_lt, NU, G, E/(2.*(1. + NU)), thickness, H;");
    let m = romdyn::input::mbdyn::read_model_text(&changed, &file, &Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let orthotropic = frequencies_of(StudySource::read(m, &file));
    let reference = frequencies("shell4eas_plate.mbd");
    assert_eq!(orthotropic.len(), reference.len());
    for (k, (o, i)) in orthotropic.iter().zip(&reference).enumerate() {
        assert!((o - i).abs() < 1e-12 * i, "mode {k}: orthotropic {o} against isotropic {i}");
    }
}

#[test]
fn an_orthotropic_plate_has_kirchhoff_s_modes_and_mbdyn_s() {
    // tests/mbdyn_files/shell4eas_orthotropic_plate.mbd: a = 1 m, h = 0.01 m, E_l = 70 GPa
    // along x, E_t = 17.5 GPa, ν_lt = 0.3, G = 10 GPa, ρ = 2700 kg/m³, 4 × 4 shell4eas.
    let w = frequencies("shell4eas_orthotropic_plate.mbd");
    // Kirchhoff's orthotropic plate: ω_mn² = π⁴/(ρ h) (D₁₁ m⁴ + 2 (D₁₂ + 2 D₆₆) m² n² + D₂₂ n⁴)
    // (a = 1 m), D₁₁ = E_l h³/(12 (1 − ν_lt ν_tl)), D₂₂ = E_t h³/(12 (1 − ν_lt ν_tl)), D₁₂ =
    // ν_lt D₂₂, D₆₆ = G h³/12: ω_11 = 205.35, ω_12 = 410.69, ω_21 = 641.00 rad/s. Measured on
    // this mesh: 195.11 (−5.0 %, as the isotropic plate's −5.6 %), 407.84 (−0.7 %), 674.68
    // rad/s (+5.3 %): asserted within the measured errors.
    let (h, el, et, nu, g) = (0.01_f64, 70e9, 17.5e9, 0.3, 10e9);
    let factor = 1.0 - nu * nu * et / el;
    let (d11, d22, d66) = (el * h.powi(3) / (12.0 * factor), et * h.powi(3) / (12.0 * factor), g * h.powi(3) / 12.0);
    let d12 = nu * d22;
    let omega = |m: f64, n: f64| (std::f64::consts::PI.powi(4) / (2700.0 * h) * (d11 * m.powi(4) + 2.0 * (d12 + 2.0 * d66) * m * m * n * n + d22 * n.powi(4))).sqrt();
    for (k, (ours, (m, n), error)) in [(w[0], (1.0, 1.0), 0.055), (w[1], (1.0, 2.0), 0.01), (w[2], (2.0, 1.0), 0.06)].into_iter().enumerate() {
        assert!((ours / omega(m, n) - 1.0).abs() < error, "mode {k}: {ours} against Kirchhoff's ω_{m}{n} {}", omega(m, n));
    }
    // MBDyn 1.7.3 on the same file (its LAPACK eigenanalysis, dCoef 0.5 s): 195.10752601476784,
    // 407.8362904124036, 674.6838640063517, 757.2942576856418 rad/s. Same element and law,
    // same discretization: 1e-6 relative.
    for (k, (ours, theirs)) in w.iter().zip([195.10752601476784, 407.8362904124036, 674.6838640063517, 757.2942576856418]).enumerate() {
        assert!((ours - theirs).abs() < 1e-6 * theirs, "mode {k}: {ours} against MBDyn's {theirs}");
    }
}
