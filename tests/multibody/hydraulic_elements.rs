//! MBDyn's `dynamic pipe`, `accumulator`, `tank` and `orifice` hydraulic elements (issue
//! 34) on tests/mbdyn_files/hydraulic_{dynamic_pipe,accumulator,tank,orifice}.mbd: their
//! Jacobians against finite differences in both constraint forms, closed forms (the
//! dynamic pipe's acoustic mode, the accumulator's gas spring, the tank's level), and MBDyn
//! 1.7.3's rows of `.hyd` on the same files (`output precision: 16` added to control data).

use crate::common;
use common::mbdyn::test_file;
use faer::c64;
use romdyn::input::mbdyn::{read_model_text, ReadOptions};
use romdyn::study::{Study, StudySource};

use super::hydraulic_output::{assert_instant, hyd_rows};

fn text(name: &str) -> String {
    std::fs::read_to_string(test_file(name)).unwrap()
}

fn model_of(name: &'static str, text: String) -> impl Fn(romdyn::model::ConstraintForm) -> romdyn::model::Model {
    move |form| {
        let mut model = read_model_text(&text, &test_file(name), ReadOptions::default()).unwrap_or_else(|e| panic!("{e}")).model;
        model.constraint_form = form;
        model
    }
}

#[test]
fn dynamic_pipe_accumulator_tank_orifice_jacobians_match_finite_differences() {
    // Central differences at states moved by noise (amplitude 0.5 on every unknown and
    // rate: the pipes' flows turbulent, the accumulator's stroke past its stops), 1e-7.
    // The tank starts at a level of 0.7 m here, so that the noise leaves it positive.
    let tank = text("hydraulic_tank.mbd").replace("set: real S0 = 4.e-4;", "set: real S0 = 0.7;").replace("set: real SMAX = 1.e-3;", "set: real SMAX = 2.;");
    for (name, text, seed, elements) in [
        ("hydraulic_dynamic_pipe.mbd", text("hydraulic_dynamic_pipe.mbd"), 47, 2),
        ("hydraulic_accumulator.mbd", text("hydraulic_accumulator.mbd"), 48, 3),
        ("hydraulic_tank.mbd", tank, 49, 3),
        ("hydraulic_orifice.mbd", text("hydraulic_orifice.mbd"), 50, 8),
    ] {
        let compared = common::mbdyn::assert_model_jacobians(model_of(name, text), seed, 1e-7);
        assert_eq!(compared, elements, "{name}");
    }
}

/// The dynamic eigenvalues of the file `name` at its initial state.
fn eigenvalues(name: &str) -> Vec<c64> {
    let m = read_model_text(&text(name), &test_file(name), ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let study = Study::builder(StudySource::model(m.model, m.problem)).node_ports(vec!["1:hydraulic".parse().unwrap()], vec!["2:hydraulic".parse().unwrap()]).build().unwrap_or_else(|e| panic!("{e}"));
    study.modal().modes.iter().filter(|m| m.kind == romdyn::eigen::ModeKind::Dynamic).map(|m| m.lambda).collect()
}

#[test]
fn dynamic_pipe_acoustic_mode_is_the_closed_form_and_mbdyns() {
    // The file's numbers: β = 1e9 Pa, ρ = 850 kg/m³, μ = 1e-3 Pa s, D = 0.01 m, L = 1 m.
    let (beta, rho, mu, d, l) = (1e9, 850.0, 1e-3, 0.01, 1.0);
    let k = 16.0 * l * mu / (d * d * rho);
    let omega2 = 8.0 * beta / (3.0 * rho * l * l);
    // Closed form (the module doc of hydraulic_pipe_dynamic.rs): λ² + (2K/L) λ + 8β/(3ρL²)
    // = 0 and λ = −2K/L, to 1e-10 relative.
    let acoustic = c64::new(-k / l, (omega2 - (k / l).powi(2)).sqrt());
    let lambdas = eigenvalues("hydraulic_dynamic_pipe.mbd");
    let near = |want: c64| lambdas.iter().any(|l| (l - want).norm() < 1e-10 * want.norm());
    assert!(near(acoustic) && near(acoustic.conj()) && near(c64::new(-2.0 * k / l, 0.0)), "{lambdas:?} vs {acoustic}, {}", -2.0 * k / l);
    // The continuous pipe's quarter wave π c/(2L) = 1703.8 rad/s: 4.0 % below the two
    // half-pipes' √(8/3) c/L = 1771.2 rad/s.
    let quarter_wave = std::f64::consts::PI * (beta / rho).sqrt() / (2.0 * l);
    assert!((acoustic.im / quarter_wave - 1.0 - 0.0396).abs() < 1e-3, "{}", acoustic.im / quarter_wave);
    // MBDyn 1.7.3 on the same file (`eigenanalysis: 0., parameter, 1.e-4, use lapack`,
    // `results output precision, 16`; λ = (Λ − 1)/(dCoef (Λ + 1)) of its .m file):
    // −0.18823501599533635 ± 1771.2297552007149j and −0.37647058822840490: 3.3e-9 and
    // 1.8e-11 from romdyn's and the closed form's (MBDyn's Cayley transform at dCoef 5e-5
    // and its printed digits), asserted to 1e-8.
    for want in [c64::new(-0.18823501599533635, 1771.2297552007149), c64::new(-0.37647058822840490, 0.0)] {
        assert!(lambdas.iter().any(|l| (l - want).norm() < 1e-8 * want.norm()), "{lambdas:?} vs MBDyn {want}");
    }
}

#[test]
fn dynamic_pipe_run_writes_mbdyns_rows() {
    // MBDyn 1.7.3's `.hyd` rows at t = 3 ms (the wave turbulent, Re 6308) and at the end:
    // p₁, p₂, ṗ₁, ṗ₂, q₁, q₂, q̇₁, q̇₂, ρ₁, ρ₀, ρ₂, ρ' twice, Re, the regime. Tolerance
    // 1e-8 relative plus 1e-4 (ṗ₁, the rate of the held end's pressure, is noise about zero
    // in both programs: 4.5e-5 Pa/s against ṗ₂'s 2e9).
    let name = "hydraulic_dynamic_pipe.mbd";
    let rows = hyd_rows(name, &text(name));
    assert_eq!(rows.len(), 1002);
    let mid: &[f64] = &[1.0, 2.0e6, 2.3269829612784805e+06, -1.7865810415810244e-05, -1.9789340637135861e+09, -4.9541749740057907e-02, -4.9541762929180236e-02, -2.5615971502439145e+01, -2.5615992770109930e+01, 8.5085000000000002e+02, 8.5098896775854337e+02, 8.5112793551708671e+02, 8.5e-07, 8.5e-07, 6.3078523280870750e+03, 1.0];
    let last: &[f64] = &[1.0, 2.0e6, 2.4886400151267736e+06, 5.4849593844334753e-05, -1.8622269991575186e+09, -4.6620041549098171e-02, -4.6620049592576276e-02, -3.8319062207472456e+01, -3.8319090806049239e+01, 8.5085000000000002e+02, 8.5105767200642890e+02, 8.5126534401285778e+02, 8.5e-07, 8.5e-07, 5.9358485598145335e+03, 1.0];
    assert_instant(name, &rows, 1, 300, &[mid], 1e-4);
    assert_instant(name, &rows, 1, 1001, &[last], 1e-4);
}

#[test]
fn accumulator_is_a_mass_on_its_gas_spring_and_runs_as_mbdyn() {
    // The file's numbers. Closed form at rest: M λ² + c λ + k = 0, k = κ A² PS/V (the gas
    // spring, V = A (S − S0) the gas's volume), c = ρ A² k_lam (the pipe's laminar loss, k_lam = 32 LP μ/(DP² AP ρ)),
    // to 1e-10 relative. MBDyn 1.7.3's eigenanalysis of this file stops on a segmentation
    // fault (the `eigenanalysis` card as in the dynamic pipe's test): no MBDyn eigenvalue.
    let (rho, mu, s, s0, a, m, pg, kappa, dp, lp) = (850.0_f64, 1e-3, 0.1_f64, 0.02_f64, 1e-2, 1.0, 1e7, 1.4, 1e-2, 0.1);
    let ps = pg * (s / (s - s0)).powf(kappa);
    let k = kappa * a * a * ps / (a * (s - s0));
    let pipe_area = std::f64::consts::FRAC_PI_4 * dp * dp;
    let c = rho * a * a * 32.0 * lp * mu / (dp * dp * pipe_area * rho);
    let root = c64::new(-c / (2.0 * m), (k / m - (c / (2.0 * m)).powi(2)).sqrt());
    let lambdas = eigenvalues("hydraulic_accumulator.mbd");
    assert!(lambdas.iter().any(|l| (l - root).norm() < 1e-10 * root.norm()), "{lambdas:?} vs {root}");
    assert!(lambdas.iter().any(|l| (l - root.conj()).norm() < 1e-10 * root.norm()), "{lambdas:?} vs {root}");
    // MBDyn 1.7.3's `.hyd` rows, the pipe (velocity, flow, Re) and the accumulator (s, v, v̇,
    // the gas pressure, the flow into the node, MBDyn's unset density column: 0), at t =
    // 0.015 s (filling, turbulent pipe) and at the end (0.1 s). Over the run: 8.2e-10 of
    // each column's largest value (measured; the file's tolerance 1e-8).
    let name = "hydraulic_accumulator.mbd";
    let rows = hyd_rows(name, &text(name));
    assert_eq!(rows.len(), 2 * 1001);
    let mid: [&[f64]; 2] = [&[1.0, 9.3033603216213082e-02, 6.2108157935221583e-03, 7.9078562733781132e+02], &[2.0, 2.0003747770981052e-02, 7.3068421100260688e-04, 9.8338003683173336e-01, 1.3667922340139473e+07, -6.2108157935221592e-03, 0.0]];
    let last: [&[f64]; 2] = [&[1.0, -1.3966837386169134e-02, -9.3240991668328466e-04, 1.1871811778243764e+02], &[2.0, 2.0008293738498641e-02, -1.0969528431568055e-04, 1.6587769612506401e-01, 1.3669009809030315e+07, 9.3240991668328476e-04, 0.0]];
    assert_instant(name, &rows, 2, 150, &mid, 1e-9);
    assert_instant(name, &rows, 2, 1000, &last, 1e-9);
}

#[test]
fn tank_level_follows_its_orifices_and_mbdyn() {
    // Closed form: constant flows q₁ = AP √(2ρ(P1 − PT)), q₂ = AP √(2ρ(PT − P2)/0.5), ρ =
    // ρ(P1 + P2/2) = RHO (1 + (P1 + P2/2 − PR)/BETA), level S0 + (q₁ − q₂) t/(ρ AT): the
    // rate and the flows to 1e-10 relative (measured 1.1e-12), the level to 1e-11 m (both
    // programs' levels are 9e-12 m above the closed form from the first step on: the start
    // of the multistep method from the derivatives phase's rate).
    let (rho0, beta, pr, pt, p1, p2, ap, at, s0) = (850.0_f64, 1e9, 1e5, 2e5_f64, 6e5_f64, 1e5_f64, 1e-6, 1e-2, 4e-4);
    let rho = rho0 * (1.0 + (p1 + 0.5 * p2 - pr) / beta);
    let (q1, q2) = (ap * (2.0 * rho * (p1 - pt)).sqrt(), ap * (2.0 * rho * (pt - p2) / 0.5).sqrt());
    let name = "hydraulic_tank.mbd";
    let rows = hyd_rows(name, &text(name));
    assert_eq!(rows.len(), 51);
    for (k, row) in rows.iter().enumerate().skip(1) {
        let t = 0.01 * k as f64;
        let want = [s0 + (q1 - q2) * t / (rho * at), (q1 - q2) / (rho * at), -q1, q2];
        for j in 0..4 {
            let tolerance = if j == 0 { 1e-11 } else { 1e-10 * want[j].abs() };
            assert!((row[1 + j] - want[j]).abs() < tolerance, "t = {t}, column {j}: {} vs {}", row[1 + j], want[j]);
        }
    }
    // MBDyn 1.7.3's last row (t = 0.5 s): level, rate, flows into nodes 1 and 2.
    let last: &[f64] = &[1.0, 8.4915419716175499e-04, 8.9830837635736943e-04, -2.6083979757698019e-02, 1.8444158967000909e-02];
    assert_instant(name, &rows, 1, 50, &[last], 1e-11);
    // With orifices of 1e-4 m² and a step of 1 ms the tank is full at step 7, and MBDyn
    // 1.7.3 stops there ("Max iterations number 20 has been reached during Step=7,
    // Time=0.007"): full, its tank cuts the inflow and pulls the level back, empty again it
    // lets the inflow in, and Newton's iterates go back and forth between the two. romdyn
    // stops at the same step.
    let full = text(name).replace("set: real AP = 1.e-6;", "set: real AP = 1.e-4;").replace("time step: 1.e-2;", "time step: 1.e-3;");
    let m = read_model_text(&full, &test_file(name), ReadOptions::default()).unwrap();
    let error = romdyn::analysis::run(&m.model, &m.problem, &mut ()).err().expect("the full tank's step fails").to_string();
    assert!(error.contains("step 7 of") && error.contains("t = 0.007 s"), "{error}");
}

#[test]
fn orifice_runs_through_both_regimes_as_mbdyn() {
    // MBDyn 1.7.3's `.hyd` rows of the actuator (1) and the orifice (2: velocity in the pipe,
    // flow, Re, regime) at t = 1 ms (the supply ramping) and at the end: romdyn's rows over
    // the run differ by at most 1.7e-14 kg/s on the closed chamber's flow (zero in both).
    let name = "hydraulic_orifice.mbd";
    let rows = hyd_rows(name, &text(name));
    assert_eq!(rows.len(), 2 * 1002);
    let mid: [&[f64]; 2] = [
        &[1.0, 1.6791146469897180e-02, -1.2931877790833824e-14, 1.1208702933299497e+06, 1.0146545750603203e+06, 1.4918093283678737e+08, 4.8355353326491453e+07, 1.0000146543602424e-04, 9.9998534563975767e-05, 8.5010273974933045e+02, 8.5001245638880130e+02],
        &[2.0, 6.2911751479440374e+00, 1.6791146469862635e-02, 1.0694997751504861e+03, 1.0],
    ];
    let last: [&[f64]; 2] = [
        &[1.0, 5.5348415679358342e-03, -1.1102230246251566e-19, 1.9588056644059555e+06, 1.9248004793334715e+06, 7.2125592024430290e+07, -7.0827527011456033e+06, 1.0009239460136657e-04, 9.9907605398633450e-05, 8.5081498481474512e+02, 8.5078608040743347e+02],
        &[2.0, 2.0737510558021111e+00, 5.5348415679358342e-03, 3.5253767948635885e+02, 1.0],
    ];
    assert_instant(name, &rows, 2, 100, &mid, 1e-11);
    assert_instant(name, &rows, 2, 1001, &last, 1e-11);
}
