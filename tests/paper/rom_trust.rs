//! Issue 9 ("ROMs a control engineer can trust"): each finding reproduced, and what
//! happens now. Numbers are checked against closed forms or the full model on the same
//! file; sources next to the assertions.

use crate::common::cli::{romdyn, temp_dir};
use std::path::PathBuf;

use faer::Mat;
use romdyn::analysis::Reference;
use romdyn::eigen::EigenRoute;
use romdyn::linear::{Jacobians, LinearDae};
use romdyn::rom::{full_frequency_response, ModalDamping, ModeSelection, Ranking};
use romdyn::study::{BelowBand, EigenSettings, StudySource, Residualization, RomRequest, Study, StudyError, Warning};

/// `M v' + D v + K x = B u`, `x' = v` as a first-order DAE `y = (x, v)`:
/// `F = [x' − v; M v' + D v + K x − B u]`, so `F_yd = diag(I, M)`, `F_y = [[0, −I], [K, D]]`
/// and `−ΔF = B̃ u` with `B̃ = [0; B]`; `z = C x`.
fn mechanical(m: &Mat<f64>, d: &Mat<f64>, k: &Mat<f64>, b: &Mat<f64>, c: &Mat<f64>) -> LinearDae {
    let n = m.nrows();
    let fyd = Mat::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) { (true, true) => if i == j { 1.0 } else { 0.0 }, (false, false) => m[(i - n, j - n)], _ => 0.0 });
    let fy = Mat::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) { (true, false) => if i == j - n { -1.0 } else { 0.0 }, (false, true) => k[(i - n, j)], (false, false) => d[(i - n, j - n)], _ => 0.0 });
    LinearDae {
        jacobians: Jacobians::Derivatives { fyd, fy },
        b: Mat::from_fn(2 * n, b.ncols(), |i, j| if i >= n { b[(i - n, j)] } else { 0.0 }),
        c: Mat::from_fn(c.nrows(), 2 * n, |i, j| if j < n { c[(i, j)] } else { 0.0 }),
        unknown_names: (0..2 * n).map(|i| format!("y{i}")).collect(),
        input_names: (0..b.ncols()).map(|j| format!("f{j} [N]")).collect(),
        output_names: (0..c.nrows()).map(|i| format!("x{i} [m]")).collect(),
        constraint_form: None,
        multipliers: vec![],
        c_rate: None,
    }
}

/// A chain of unit masses: ground –k[0]– m1 –k[1]– m2 –k[2]– m3 …
fn chain_stiffness(k: &[f64]) -> Mat<f64> {
    let n = k.len();
    Mat::from_fn(n, n, |i, j| {
        if i == j {
            k[i] + if i + 1 < n { k[i + 1] } else { 0.0 }
        } else if j == i + 1 {
            -k[j]
        } else if i == j + 1 {
            -k[i]
        } else {
            0.0
        }
    })
}

fn direct(dae: LinearDae) -> Study {
    Study::builder(StudySource::dae(dae)).eigen(EigenSettings { route: EigenRoute::Direct, ..EigenSettings::default() }).build().unwrap()
}

/// A 3-mass chain, input and output at the last mass, modes near 0.38, 3.2 and 6 Hz.
fn three_mass_chain(damping: f64) -> Study {
    let k = chain_stiffness(&[17.0, 400.0, 400.0]);
    let m = Mat::<f64>::identity(3, 3);
    let d = Mat::from_fn(3, 3, |i, j| damping * k[(i, j)]);
    let b = Mat::from_fn(3, 1, |i, _| if i == 2 { 1.0 } else { 0.0 });
    direct(mechanical(&m, &d, &k, &b, &b.transpose().to_owned()))
}

fn hz(study: &Study, i: usize) -> f64 {
    study.modal().modes[i].freq_hz()
}

/// Point 1: `--band 1:100 --residualize` used to fold the 0.38 Hz mode into D (a flat line
/// far above the full model at 10 Hz). Now the mode below the band is dropped with a
/// warning (default), kept on request, or refused.
#[test]
fn modes_below_the_band_are_not_statically_residualized() {
    let study = three_mass_chain(0.0);
    let f0 = hz(&study, 0);
    assert!((0.3..0.45).contains(&f0), "{f0}");
    let band = ModeSelection::Band { fmin_hz: 1.0, fmax_hz: 100.0 };
    let rom = study.reduce(&RomRequest::new(band.clone()).residualize(Residualization::Dropped)).unwrap();
    assert!(matches!(&rom.warnings[0], Warning::BelowBandDropped { modes, .. } if modes.len() == 1 && modes[0].0 == 1), "{:?}", rom.warnings);
    assert_eq!(rom.descriptor.static_states, 0);
    // At 10 Hz the old ROM (the 0.38 Hz mode folded into D as its static response
    // 1/(m ω₀²)) is many times the full response; the ROM without it is within 40 % (the
    // dropped mode's own 1/(m (ω² − ω₀²)) share at 10 Hz): wrong by what is missing, not by a
    // feedthrough that grows relative to the response as ω².
    let f = [10.0];
    let full = full_frequency_response(study.dae(), &f)[0][(0, 0)];
    let r = rom.ordinary.frequency_response(&f)[0][(0, 0)];
    let new_error = (r - full).norm() / full.norm();
    let old_sel = romdyn::rom::Selection { kept: rom.selection.kept.clone(), dropped: vec![0, 1] };
    let old = romdyn::rom::DescriptorRom::project(study.dae(), study.modal(), &old_sel, true).unwrap().to_ordinary().unwrap();
    let old_error = (old.frequency_response(&f)[0][(0, 0)] - full).norm() / full.norm();
    assert!(new_error < 0.4 && old_error > 10.0, "new {new_error}, old {old_error}");
    let kept = study.reduce(&RomRequest { below_band: BelowBand::Keep, ..RomRequest::new(band.clone()).residualize(Residualization::Dropped) }).unwrap();
    assert_eq!(kept.kept_modes.len(), 3);
    // Keeping every mode gives back the full static gain 1/k_1 + 1/k_2 + 1/k_3 (closed form), 1e-9.
    let g = kept.static_gains.rom.as_ref().unwrap()[(0, 0)];
    assert!((g / (1.0 / 17.0 + 2.0 / 400.0) - 1.0).abs() < 1e-9, "{g}");
    let refused = study.reduce(&RomRequest { below_band: BelowBand::Refuse, ..RomRequest::new(band).residualize(Residualization::Dropped) });
    assert!(matches!(refused, Err(StudyError::ResidualizedBelowBand { .. })));
}

/// Point 2: a mode the output cannot see. Two equal masses on equal springs, coupled:
/// the in-phase mode (√(k/m)) is the lowest, the output x1 − x2 sees only the
/// anti-phase one (√((k + 2κ)/m)). `--count 1` keeps the invisible mode (warning, gain
/// 0); `--count 1 --by dominance` keeps the one that matters, with the full static gain.
#[test]
fn count_and_dominance_differ_on_a_mode_the_output_cannot_see() {
    let (k, kappa) = (100.0, 50.0);
    let kk = Mat::from_fn(2, 2, |i, j| if i == j { k + kappa } else { -kappa });
    let m = Mat::<f64>::identity(2, 2);
    let b = Mat::from_fn(2, 1, |i, _| if i == 0 { 1.0 } else { 0.0 });
    let c = Mat::from_fn(1, 2, |_, j| if j == 0 { 1.0 } else { -1.0 });
    let study = direct(mechanical(&m, &Mat::zeros(2, 2), &kk, &b, &c));
    let by_count = study.reduce(&RomRequest::new(ModeSelection::Lowest(1))).unwrap();
    // In-phase mode: ω = √(k/m) = 10 rad/s (closed form), 1e-9.
    assert!((by_count.kept_modes[0].lambda.im.abs() - 10.0).abs() < 1e-9);
    assert!(by_count.warnings.iter().any(|w| matches!(w, Warning::Invisible { .. })), "{:?}", by_count.warnings);
    let dominant = study.reduce(&RomRequest::new(ModeSelection::Lowest(1)).ranked_by(Ranking::Dominance)).unwrap();
    // Anti-phase mode: ω = √((k + 2κ)/m) = √200 rad/s (closed form), 1e-9.
    assert!((dominant.kept_modes[0].lambda.im.abs() - 200f64.sqrt()).abs() < 1e-9);
    // x1 − x2 under f1: (K⁻¹)₁₁ − (K⁻¹)₂₁ = 1/(k + 2κ) = 5e-3 m/N (closed form), 1e-9.
    let g = dominant.static_gains.rom.as_ref().unwrap()[(0, 0)];
    assert!((g - 1.0 / (k + 2.0 * kappa)).abs() < 1e-9 * g, "{g}");
    assert!(dominant.warnings.is_empty(), "{:?}", dominant.warnings);
    assert!(study.reduce(&RomRequest::new(ModeSelection::Lowest(2)).ranked_by(Ranking::Dominance)).is_err());
}

/// Acceptance: where the lowest modes are the dominant ones, `--count N` and
/// `--count N --by dominance` keep the same modes (3-mass chain with its end force and
/// displacement; pendulum; inverted pendulum; the README beam at N = 1), and on the beam at
/// N = 2 they differ: the second-lowest pair is an axial mode the mid-span y output cannot see.
#[test]
fn count_and_dominance_agree_where_the_lowest_modes_dominate() {
    let chain = three_mass_chain(0.0);
    for n in 1..=3 {
        let a = chain.reduce(&RomRequest::new(ModeSelection::Lowest(n))).unwrap();
        let b = chain.reduce(&RomRequest::new(ModeSelection::Lowest(n)).ranked_by(Ranking::Dominance)).unwrap();
        assert_eq!(a.selection.kept, b.selection.kept, "chain, N = {n}");
    }
    let model = |file: &str, input: &str, output: &str, reference| {
        Study::builder(StudySource::model_file(file)).reference(reference).node_ports(vec![input.parse().unwrap()], vec![output.parse().unwrap()]).build().unwrap()
    };
    for study in [model("examples/pendulum.mbd", "2:Mz", "2:rz", Reference::Initial), model("examples/inverted_pendulum.mbd", "2:Mz", "2:rz", Reference::Initial)] {
        let a = study.reduce(&RomRequest::new(ModeSelection::Lowest(1))).unwrap();
        let b = study.reduce(&RomRequest::new(ModeSelection::Lowest(1)).ranked_by(Ranking::Dominance)).unwrap();
        assert_eq!(a.selection.kept, b.selection.kept);
    }
    let beam = model("examples/simply_supported_beam.mbd", "5:Fy", "5:y", Reference::Static { load_steps: 1 });
    let one = |r| beam.reduce(&RomRequest::new(ModeSelection::Lowest(1)).ranked_by(r)).unwrap().selection.kept;
    assert_eq!(one(Ranking::Frequency), one(Ranking::Dominance));
    let two = |r| beam.reduce(&RomRequest::new(ModeSelection::Lowest(2)).ranked_by(r)).unwrap();
    let (f, d) = (two(Ranking::Frequency), two(Ranking::Dominance));
    assert_ne!(f.selection.kept, d.selection.kept);
    assert!(f.warnings.iter().any(|w| matches!(w, Warning::Invisible { .. })));
    // Dominance keeps the first and third bending pairs: 309.93 and 2659.17 rad/s (docs/src/cases.md, C4 table; paper §7.1 Fig. 7), 1e-3 relative.
    let w: Vec<f64> = d.kept_modes.iter().map(|k| k.lambda.im.abs()).collect();
    assert!((w[0] / 309.928 - 1.0).abs() < 1e-3 && (w[1] / 2659.169 - 1.0).abs() < 1e-3, "{w:?}");
    // … whose ROM keeps the static gain to −0.170 % (docs/src/cases.md, C4 table; paper 0.2 %).
    let g = d.static_gains.rom.as_ref().unwrap()[(0, 0)] / (1.0 / 48e3 + 1.0 / 4e6) - 1.0;
    assert!((g + 0.0017).abs() < 1e-4, "{g}");
}

/// Point 3: the inverted pendulum's ±3.13 rad/s real pair is one mode: `--count 1` keeps
/// both eigenvalues and the full static gain −1/(m g L) = −0.1019368 rad/(N m) (CASES C3).
#[test]
fn inverted_pendulum_count_one_keeps_the_real_pair_and_the_static_gain() {
    let (ok, out, err) = romdyn(&["rom", "examples/inverted_pendulum.mbd", "--input", "2:Mz", "--output", "2:rz", "--count", "1"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["A"].as_array().unwrap().len(), 2);
    let g = v["rom_static_gain"][0][0].as_f64().unwrap();
    let full = v["full_static_gain"][0][0].as_f64().unwrap();
    // 1/(m g L) with m = 1 kg, g = 9.81 m/s², L = 1 m; the ROM of the pair is exact (1e-9).
    assert!((full + 1.0 / 9.81).abs() < 1e-9 && (g / full - 1.0).abs() < 1e-9, "{g} {full}");
    let ev = v["eigenvalues"].as_array().unwrap();
    // λ = ±√(g/L) = ±3.130495 rad/s for a point mass; with J = 1e-3 kg m²: ±√(m g L/(m L² + J)) = ±3.130527 (CASES C3), 1e-6.
    let mut re: Vec<f64> = ev.iter().map(|e| e["re"].as_f64().unwrap()).collect();
    re.sort_by(f64::total_cmp);
    let w = (9.81f64 / 1.001).sqrt();
    assert!((re[0] + w).abs() < 1e-6 && (re[1] - w).abs() < 1e-6, "{re:?}");
}

fn write_model(dir: &PathBuf, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Point 7: a pendulum released horizontally is not in equilibrium at its initial time: the
/// warning names the size (m g = 9.81 N) and the equation. A free body under gravity with
/// `--static` names the unrestrained rigid-body motion and the node.
#[test]
fn reference_out_of_equilibrium_and_unrestrained_motion_are_reported() {
    let dir = temp_dir("equilibrium");
    let pendulum = std::fs::read_to_string("examples/pendulum.mbd").unwrap();
    let horizontal = pendulum.replace("structural: 2, dynamic, 0., -L, 0.,", "structural: 2, dynamic, L, 0., 0.,").replace("2, position, 0., L, 0.;", "2, position, -L, 0., 0.;");
    assert_ne!(horizontal, pendulum);
    let file = write_model(&dir, "horizontal.mbd", &horizontal);
    // Released horizontally at rest, the rod carries no tension and gravity's moment has zero
    // derivative (m g L cos 90°), so the linear model has no restoring stiffness: its swing
    // eigenvalues are zero (MBDyn's derivatives phase keeps the written velocities, as here)
    // and `eig` is the command that still succeeds and warns.
    let (ok, _, err) = romdyn(&["eig", file.to_str().unwrap()]);
    assert!(ok, "{err}");
    // Unbalanced weight: m g less the hinge reaction at release m g J/(m L² + J) (rigid
    // pendulum, closed form) = 9.81 (1 − 0.001/1.001) = 9.8002 N on node 2 in y.
    assert!(err.contains("warning: the reference solution is neither an equilibrium nor a steady motion: with its velocities held and its accelerations set to zero the residual is 9.800e0"), "{err}");
    assert!(err.contains("node 2 force y equilibrium") || err.contains("node 2 linear momentum y"), "{err}");
    let free = pendulum.replace("    joint: 1, clamp, 1, node, node;\n", "").replace("joint: 2, revolute hinge,\n        1, position, null,\n        2, position, 0., L, 0.;", "").replace("joints: 2;", "");
    let file = write_model(&dir, "free.mbd", &free);
    let (ok, _, err) = romdyn(&["eig", file.to_str().unwrap(), "--static"]);
    assert!(!ok);
    // Two unconnected free nodes: no rigid motion of the whole model, so the components.
    assert!(err.contains("unrestrained rigid-body motion along node"), "{err}");
    // The two nodes held together by a 6-D spring and nothing else: the free direction is a
    // rigid motion of both nodes together, named as such rather than as node components.
    let spring = "joint: 2, deformable joint,\n        1, null, hinge, reference, node, eye,\n        2, 0., L, 0., hinge, reference, node, eye,\n        linear elastic generic, diag, 1.e4, 1.e4, 1.e4, 1.e4, 1.e4, 1.e4;";
    let floating = pendulum.replace("    joint: 1, clamp, 1, node, node;\n", "").replace("joint: 2, revolute hinge,\n        1, position, null,\n        2, position, 0., L, 0.;", spring).replace("joints: 2;", "joints: 1;");
    assert!(floating.contains("deformable joint") && !floating.contains("clamp, 1"));
    let file = write_model(&dir, "floating.mbd", &floating);
    let (ok, _, err) = romdyn(&["eig", file.to_str().unwrap(), "--static"]);
    assert!(!ok);
    assert!(err.contains("unrestrained rigid-body motion of the whole model (its 2 nodes move together)"), "{err}");
    // The solver's failure is told once (it was repeated as the error's source too).
    assert_eq!(err.matches("Newton failed").count(), 1, "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Point 8: modal damping ζ = 0.02 on the README beam's ROM moves its poles to
/// −ζω ± jω√(1 − ζ²), keeps the static gain, is reported, and leaves the full model alone.
#[test]
fn modal_damping_applies_to_the_rom_only_and_keeps_the_static_gain() {
    let study = Study::builder(StudySource::model_file("examples/simply_supported_beam.mbd")).reference(Reference::Static { load_steps: 1 }).node_ports(vec!["5:Fy".parse().unwrap()], vec!["5:y".parse().unwrap()]).build().unwrap();
    let plain = study.reduce(&RomRequest::new(ModeSelection::Lowest(1))).unwrap();
    let damped = study.reduce(&RomRequest::new(ModeSelection::Lowest(1)).damped(ModalDamping::Uniform(0.02))).unwrap();
    assert_eq!(damped.damping.len(), 1);
    let w = plain.kept_modes[0].lambda.norm();
    for l in damped.eigenvalues() {
        // The SDOF poles with ζ = 0.02 and the same |λ| (closed form), 1e-9 relative.
        assert!((l.re + 0.02 * w).abs() < 1e-9 * w && (l.im.abs() - w * (1.0f64 - 4e-4).sqrt()).abs() < 1e-9 * w, "{l:?}");
    }
    let (g0, g1) = (plain.static_gains.rom.as_ref().unwrap()[(0, 0)], damped.static_gains.rom.as_ref().unwrap()[(0, 0)]);
    assert!((g1 / g0 - 1.0).abs() < 1e-9, "{g0} {g1}");
    // The full model's first pair is still undamped (|Re λ| at rounding: the modal table of docs/src/guide/getting-started.md).
    assert!(study.modal().modes[0].lambda.re.abs() < 1e-6);
    // At resonance the damped ROM's magnitude is its static gain / (2ζ) = 25 × static (SDOF closed form), 1 %.
    let f = w / (2.0 * std::f64::consts::PI);
    let h = damped.ordinary.frequency_response(&[f])[0][(0, 0)].norm();
    assert!((h / (g1 / 0.04) - 1.0).abs() < 0.01, "{h} vs {}", g1 / 0.04);
    let (ok, _, err) = romdyn(&["rom", "examples/simply_supported_beam.mbd", "--static", "--input", "5:Fy", "--output", "5:y", "--count", "1", "--damping", "0.02"]);
    assert!(ok, "{err}");
    assert!(err.contains("modal damping (ROM only): mode 1: ζ 0.0000 -> 0.0200"), "{err}");
}

/// A small deterministic generator (no dependency): xorshift64*.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545F4914F6CDD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn matrix(&mut self, r: usize, c: usize) -> Mat<f64> {
        Mat::from_fn(r, c, |_, _| 2.0 * self.next() - 1.0)
    }
}

/// Acceptance property: for random stable mechanical pencils (M, K positive definite,
/// D = a M + b K + a random positive semidefinite part) with random inputs and outputs,
/// every ROM with `--residualize` either matches the full static gain to 1e-9 or carries a
/// warning that says why not.
#[test]
fn random_stable_pencils_residualized_roms_keep_the_static_gain_or_warn() {
    let mut rng = Rng(0x9E3779B97F4A7C15);
    let mut checked = 0;
    for case in 0..40 {
        let n = 2 + case % 6;
        let (ni, no) = (1 + case % 3, 1 + (case / 3) % 3);
        let spd = |rng: &mut Rng, shift: f64| {
            let a = rng.matrix(n, n);
            &a * a.transpose() + Mat::<f64>::identity(n, n) * faer::Scale(shift)
        };
        let m = spd(&mut rng, 0.5);
        let k = spd(&mut rng, 1.0) * faer::Scale(100.0);
        let r = rng.matrix(n, n);
        let d = &m * faer::Scale(0.1 * rng.next()) + &k * faer::Scale(1e-3 * rng.next()) + &r * r.transpose() * faer::Scale(0.05 * rng.next());
        let (b, c) = (rng.matrix(n, ni), rng.matrix(no, n));
        let study = direct(mechanical(&m, &d, &k, &b, &c));
        let units = romdyn::rom::mode_units(study.modal()).len();
        let keep = 1 + case % units.max(1);
        let selection = if case % 2 == 0 { ModeSelection::Lowest(keep.min(units)) } else { ModeSelection::Band { fmin_hz: hz(&study, 0) * 1.5, fmax_hz: 1e9 } };
        let Ok(rom) = study.reduce(&RomRequest::new(selection).residualize(Residualization::Dropped)) else { continue };
        let (rel, _) = rom.static_gains.largest_relative_difference().unwrap();
        let warned = rom.warnings.iter().any(|w| matches!(w, Warning::StaticGain { .. }));
        // Exact to rounding: 1e-9, or 10 ε (|λ|max/|λ|min)² on a badly spread model, times
        // the channel's cancellation (StaticGains::tolerance, its measurements written there).
        let g = &rom.static_gains;
        assert!((1e-9..1e-6).contains(&g.rounding), "case {case}: rounding level {:e}", g.rounding);
        assert!(g.beyond_rounding().is_none() || warned, "case {case}: static gain off by {rel:e} without a warning: {:?}", rom.warnings);
        // The tolerance never swallows a real difference: in absolute terms it stays below
        // 1e-6 of the gain matrix's largest entry.
        let full = g.full.as_ref().unwrap();
        for i in 0..full.nrows() {
            for j in 0..full.ncols() {
                assert!(g.tolerance(i, j) * full[(i, j)].abs() <= 1e-6 * full.norm_max(), "case {case}: ({i}, {j}) tolerance {:e}", g.tolerance(i, j));
            }
        }
        checked += 1;
    }
    assert!(checked >= 30, "{checked}");
}

/// Point 4 and acceptance: the phases of the full model and of a ROM, unwrapped from a
/// common reference as the Bode plot and CSV draw them, agree within 1° wherever their
/// magnitudes agree within 1 % — on the README main command (first bending mode, third
/// residualized) and on the three ROMs of paper Fig. 7 (`examples/beam_rom.rs`).
#[test]
fn full_model_and_rom_phases_agree_where_magnitudes_agree() {
    use romdyn::output::bode::{common_reference_phases, response_curves};
    let study = Study::builder(StudySource::model_file("examples/simply_supported_beam.mbd")).reference(Reference::Static { load_steps: 10 }).node_ports(vec!["5:Fy".parse().unwrap()], vec!["5:y".parse().unwrap()]).build().unwrap();
    let dominant = RomRequest::new(ModeSelection::Lowest(2)).ranked_by(Ranking::Dominance);
    let third = study.reduce(&dominant).unwrap().kept_modes[1].indices[0];
    let requests = [
        RomRequest::new(ModeSelection::Lowest(1)).residualize(Residualization::Modes(vec![third])),
        RomRequest::new(ModeSelection::Lowest(1)),
        dominant,
        RomRequest::new(ModeSelection::Lowest(1)).residualize(Residualization::Dropped),
    ];
    let freq = romdyn::rom::log_frequencies(1.0, 2000.0, 800);
    for request in requests {
        let rom = study.reduce(&request).unwrap();
        let c = study.compare(&rom, freq.clone()).unwrap();
        let curves = response_curves(&c, &[(0, 0)]);
        let (full, reduced) = (&curves[0], &curves[1]);
        assert_eq!((full.label, reduced.label), ("full model", "ROM"));
        let p = common_reference_phases(&[full, reduced]);
        let mut compared = 0;
        let agree = |k: usize| {
            let (a, b) = (full.values[k].norm(), reduced.values[k].norm());
            ((b - a) / a).abs() <= 0.01
        };
        // Agreement at a grid point and both neighbours: where the curves merely cross (full
        // past an antiresonance, the ROM before its own: equal magnitudes, opposite signs,
        // e.g. 318.9 Hz on the README ROM) the responses do not agree and the phases differ by 180°.
        for k in 1..freq.len() - 1 {
            if agree(k - 1) && agree(k) && agree(k + 1) {
                assert!((p[0][k] - p[1][k]).abs() <= 1.0, "{request:?}: at {} Hz full {}°, ROM {}°", freq[k], p[0][k], p[1][k]);
                compared += 1;
            }
        }
        // Not vacuous: the first-mode ROM (1.6 % low statically) agrees within 1 % only
        // around its resonance (75 of 800 points), the others below ~100 Hz (> 400 points).
        assert!(compared >= 50, "{compared}");
    }
}

/// One input and one output: the summary's normwise line is the pair's own error, so no
/// second "worst port pair" line nor its warning (the README main command: the full model's
/// antiresonance at 293 Hz, outside the ROM, gives the 1.1e2 of the normwise line).
#[test]
fn a_siso_rom_summary_reports_its_one_pair_once() {
    let (ok, out, err) = romdyn(&["rom", "examples/simply_supported_beam.mbd", "--static", "--input", "5:Fy", "--output", "5:y", "--count", "1", "--residualize-modes", "7"]);
    assert!(ok, "{err}");
    // Without -o the ROM goes to stdout as JSON and the summary to stderr.
    let all = format!("{out}{err}");
    assert!(all.contains("largest relative error 1.10e2 at 293.4382 Hz"), "{all}");
    assert!(!all.contains("worst port pair") && !all.contains("on its own scale"), "{all}");
}

/// Point 9: one modal-table row per pair (`--all`: every eigenvalue), the frequency column
/// as MBDyn's |Im λ|/2π next to the undamped |λ|/2π, zero and infinite rows without
/// damping or energy.
#[test]
fn modal_table_has_one_row_per_pair_and_both_frequencies() {
    let (ok, out, err) = romdyn(&["eig", "--pencil", "examples/two_masses.json"]);
    assert!(ok, "{err}");
    // C1: λ = −0.5 ± 9.987492 j rad/s: |Im λ|/2π = 1.589559 Hz, |λ|/2π = 10/2π = 1.591549 Hz (closed form).
    let row = out.lines().find(|l| l.trim_start().starts_with("1,2")).unwrap_or_else(|| panic!("{out}"));
    assert!(row.contains("±9.987492e0") && row.contains("1.589559") && row.contains("1.591549") && row.contains("0.0500"), "{row}");
    assert!(out.contains("modes 3–5: 3 infinite eigenvalues"), "{out}");
    let (ok, all, _) = romdyn(&["eig", "--pencil", "examples/two_masses.json", "--all"]);
    assert!(ok);
    let infinite: Vec<&str> = all.lines().filter(|l| l.contains("infinite") && !l.starts_with('#')).collect();
    assert_eq!(infinite.len(), 3, "{all}");
    // No damping on an infinite row: the column is blank between the frequencies and the kind.
    assert!(infinite.iter().all(|l| !l.contains("0.0500")), "{all}");
    // The inverted pendulum's ±3.13 rad/s real pair is one row with ±Re λ (CASES C3).
    let (ok, out, _) = romdyn(&["eig", "examples/inverted_pendulum.mbd"]);
    assert!(ok);
    assert!(out.lines().any(|l| l.trim_start().starts_with("1,2") && l.contains("±3.130527e0")), "{out}");
}

/// Point 6: nonsense options are refused before any computation, naming the option.
#[test]
fn nonsense_options_are_refused_with_the_option_named() {
    let pencil = |extra: &[&str]| {
        let mut a = vec!["rom", "--pencil", "examples/two_masses.json", "--count", "1"];
        a.extend_from_slice(extra);
        romdyn(&a)
    };
    for (extra, expect) in [
        (&["--fmin", "10", "--fmax", "1"][..], "--fmin: need FMIN < FMAX"),
        (&["--fmin", "1", "--fmax", "1"][..], "--fmin: need FMIN < FMAX"),
        (&["--fmin", "0"][..], "--fmin: a frequency of a log-spaced grid must be positive"),
        (&["--points", "1"][..], "--points: a frequency grid needs at least 2 points"),
        (&["--points", "0"][..], "--points: a frequency grid needs at least 2 points"),
        (&["--dcoef", "0"][..], "--dcoef: dCoef must be a positive finite"),
        (&["--dcoef", "nan"][..], "--dcoef: dCoef must be a positive finite"),
        (&["--dcoef", "inf"][..], "--dcoef: dCoef must be a positive finite"),
        (&["--dcoef", "-1"][..], "--dcoef: dCoef must be a positive finite"),
        (&["-o", "/tmp"][..], "is a directory"),
        (&["-o", "x.txt"][..], "unknown ROM file format"),
        (&["--damping", "1.5"][..], "outside [0, 1)"),
    ] {
        let (ok, _, err) = pencil(extra);
        assert!(!ok && err.contains(expect), "{extra:?}: {err}");
    }
    let (ok, _, err) = romdyn(&["rom", "--pencil", "examples/two_masses.json", "--count", "0"]);
    assert!(!ok && err.contains("at least 1 mode"), "{err}");
    let model = |extra: &[&str]| {
        let mut a = vec!["rom", "examples/pendulum.mbd", "--input", "2:Mz", "--output", "2:rz", "--count", "1"];
        a.extend_from_slice(extra);
        romdyn(&a)
    };
    for (extra, expect) in [
        (&["--at", "-1"][..], "--at: TIME -1 s is before the file's initial time 0 s"),
        (&["--at", "1e9"][..], "--at: TIME 1000000000 s is after the file's final time 2 s"),
        (&["--at", "inf"][..], "--at: TIME must be a finite time"),
        (&["--at", "nan"][..], "--at: TIME must be a finite time"),
        (&["--static", "--load-steps", "0"][..], "--load-steps: need at least 1 load increment"),
        (&["--input", "2:Mz"][..], "--input: node 2 Mz [N m] is given twice"),
        // The library's Setting, rendered as the flag (Python: "imposed: '2:q': …", pytest).
        (&["--imposed", "2:q"][..], "--imposed: '2:q': expected NODE or NODE:COMPONENTS"),
    ] {
        let (ok, _, err) = model(extra);
        assert!(!ok && err.contains(expect), "{extra:?}: {err}");
    }
    // An input on the clamped node 1: accepted, with a warning that no output responds.
    let (ok, _, err) = romdyn(&["rom", "examples/pendulum.mbd", "--input", "1:Fx", "--input", "2:Mz", "--output", "2:rz", "--count", "1"]);
    assert!(ok, "{err}");
    assert!(err.contains("warning: no output responds to input node 1 Fx [N]"), "{err}");
    // `--modes K` on a zero eigenvalue says what it is.
    let (ok, _, err) = romdyn(&["rom", "examples/pendulum.mbd", "--input", "2:Mz", "--output", "2:rz", "--modes", "3"]);
    assert!(!ok && err.contains("mode 3 is zero (not a dynamic mode)"), "{err}");
}

/// Point 10: every export carries the ROM's own eigenvalues next to the full model's kept
/// ones, names, units, each state's mode and frequency, the reference time, dCoef and both
/// static gains.
#[test]
fn exports_carry_eigenvalues_units_states_reference_and_static_gains() {
    let dir = temp_dir("export");
    let json = dir.join("rom.json");
    let (ok, _, err) = romdyn(&["rom", "examples/pendulum.mbd", "--input", "2:Mz", "--output", "2:rz", "--count", "1", "-o", json.to_str().unwrap()]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    // The ROM's own eigenvalues equal the full model's kept ±3.130527 j rad/s (C2), 1e-6.
    for key in ["eigenvalues", "full_eigenvalues"] {
        let im: Vec<f64> = v[key].as_array().unwrap().iter().map(|e| e["im"].as_f64().unwrap().abs()).collect();
        assert!(im.len() == 2 && im.iter().all(|x| (x - 3.130527).abs() < 1e-6), "{key}: {im:?}");
    }
    assert_eq!(v["input_units"][0], "N m");
    assert_eq!(v["output_units"][0], "rad");
    assert_eq!(v["state_modes"], serde_json::json!([1, 1]));
    // 3.130527/2π = 0.498239 Hz.
    assert!((v["state_freq_hz"][0].as_f64().unwrap() - 0.498239).abs() < 1e-6);
    assert_eq!(v["reference_time"], 0.0);
    assert!(v["dcoef"].as_f64().unwrap() > 0.0);
    // 1/(m g L) = 0.1019368 rad/(N m) (C2), both gains.
    assert!((v["full_static_gain"][0][0].as_f64().unwrap() - 0.1019368).abs() < 1e-7);
    assert!((v["rom_static_gain"][0][0].as_f64().unwrap() - 0.1019368).abs() < 1e-7);
    for ext in ["mat", "npz"] {
        let path = dir.join(format!("rom.{ext}"));
        let (ok, _, err) = romdyn(&["rom", "examples/pendulum.mbd", "--input", "2:Mz", "--output", "2:rz", "--count", "1", "-o", path.to_str().unwrap()]);
        assert!(ok, "{err}");
        let bytes = std::fs::read(&path).unwrap();
        let text = String::from_utf8_lossy(&bytes);
        for name in ["full_eigenvalues", "input_units", "output_units", "state_modes", "state_freq_hz", "reference_time", "dcoef", "full_static_gain", "rom_static_gain", "states"] {
            assert!(text.contains(name), "{ext}: {name}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Point 6, `romdyn run`: an empty file is refused with no output written; `-o DIR` of an
/// existing directory writes DIR/NAME.* inside it, not DIR.out beside it.
#[test]
fn run_refuses_an_empty_model_and_writes_into_an_output_directory() {
    let dir = temp_dir("run");
    let empty = write_model(&dir, "empty.mbd", "");
    let (ok, _, err) = romdyn(&["run", empty.to_str().unwrap()]);
    assert!(!ok, "{err}");
    assert!(std::fs::read_dir(&dir).unwrap().count() == 1, "an output file was written");
    let out = dir.join("results");
    std::fs::create_dir_all(&out).unwrap();
    let (ok, _, err) = romdyn(&["run", "examples/pendulum.mbd", "-o", out.to_str().unwrap()]);
    assert!(ok, "{err}");
    assert!(out.join("pendulum.out").exists() && out.join("pendulum.mov").exists());
    assert!(!dir.join("results.out").exists());
    std::fs::remove_dir_all(&dir).ok();
}
