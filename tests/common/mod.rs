//! Test helpers shared by the validation tests.
#![allow(dead_code)]

pub mod beam_family;
pub mod beams;
pub mod cli;
pub mod fixtures;
pub mod fuzz;
pub mod mbdyn;
pub mod models;

use faer::Mat;
use romdyn::linear::{Jacobians, LinearDae};

/// Dense matrix from rows.
pub fn mat(rows: &[&[f64]]) -> Mat<f64> {
    Mat::from_fn(rows.len(), rows[0].len(), |i, j| rows[i][j])
}

/// Relative difference `|a − b| / |b|`.
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Two rigidly connected masses of paper §6.1 (Table 1): unknowns [x1, q1, x2, q2, α],
/// force f on mass 2, output x2. `scaled` selects eq. 30 over eq. 29.
pub fn two_masses(r: f64, scaled: bool) -> LinearDae {
    let (m1, m2, k) = (2.0, 8.0, 1000.0);
    let (fyd, fy) = if scaled {
        (
            mat(&[&[m1, 0., 0., 0., 0.], &[r, 1., 0., 0., -1.], &[0., 0., m2, 0., 0.], &[0., 0., 0., 1., 1.], &[-1., 0., 1., 0., 0.]]),
            mat(&[&[0., -1., 0., 0., 0.], &[k, 0., 0., 0., 0.], &[0., 0., 0., -1., 0.], &[0., 0., 0., 0., 0.], &[0., 0., 0., 0., 0.]]),
        )
    } else {
        (
            mat(&[&[m1, 0., 0., 0., 0.], &[r, 1., 0., 0., 0.], &[0., 0., m2, 0., 0.], &[0., 0., 0., 1., 0.], &[0., 0., 0., 0., 0.]]),
            mat(&[&[0., -1., 0., 0., 0.], &[k, 0., 0., 0., -1.], &[0., 0., 0., -1., 0.], &[0., 0., 0., 0., 1.], &[-1., 0., 1., 0., 0.]]),
        )
    };
    LinearDae {
        jacobians: Jacobians::Derivatives { fyd, fy },
        b: mat(&[&[0.], &[0.], &[0.], &[1.], &[0.]]),
        c: mat(&[&[0., 0., 1., 0., 0.]]),
        unknown_names: ["x1", "q1", "x2", "q2", "alpha"].map(String::from).to_vec(),
        input_names: vec!["f".into()],
        output_names: vec!["x2".into()],
        constraint_form: None,
        multipliers: Vec::new(),
        c_rate: None,
    }
}

/// The same system given as J, J* for a coefficient `c` (eqs. 13–14).
pub fn with_coefficient(dae: &LinearDae, c: f64) -> LinearDae {
    let (fyd, fy) = dae.jacobians.derivatives();
    let (j, jstar) = romdyn::linear::coefficient_from_derivatives(&fyd, &fy, c);
    LinearDae { jacobians: Jacobians::Coefficient { j, jstar, dcoef: c }, ..dae.clone() }
}

const CHAIN_N: usize = 50;
const CHAIN_K: f64 = 1000.0;

/// The 50-mass chain of issue 2 (CASES): mass 1 grounded by a 1000 N/m spring, springs
/// between masses i and i+1 for i < 49, x50 − x49 = 0 (form of eq. 29); force on mass 50,
/// output x50. Unknowns [x1..x50, q1..q50, α].
pub fn mass_chain() -> LinearDae {
    const N: usize = CHAIN_N;
    const K: f64 = CHAIN_K;
    let n = 2 * N + 1;
    let (mut fyd, mut fy) = (Mat::<f64>::zeros(n, n), Mat::<f64>::zeros(n, n));
    for i in 0..N {
        fyd[(i, i)] = 1.0; // m ẋ_i − q_i = 0
        fy[(i, N + i)] = -1.0;
        fyd[(N + i, N + i)] = 1.0; // q̇_i + (K x)_i + Φ_/xᵀ α = f_i
    }
    fy[(N, 0)] += K;
    for i in 0..N - 2 {
        let (a, b) = (N + i, N + i + 1);
        fy[(a, i)] += K;
        fy[(b, i + 1)] += K;
        fy[(a, i + 1)] -= K;
        fy[(b, i)] -= K;
    }
    // Φ = x50 − x49.
    fy[(2 * N, N - 1)] = 1.0;
    fy[(2 * N, N - 2)] = -1.0;
    fy[(2 * N - 1, 2 * N)] = 1.0;
    fy[(2 * N - 2, 2 * N)] = -1.0;
    let mut b = Mat::<f64>::zeros(n, 1);
    b[(2 * N - 1, 0)] = 1.0;
    let mut c = Mat::<f64>::zeros(1, n);
    c[(0, N - 1)] = 1.0;
    LinearDae {
        jacobians: Jacobians::Derivatives { fyd, fy },
        b,
        c,
        unknown_names: (0..n).map(|i| format!("y{i}")).collect(),
        input_names: vec!["f50".into()],
        output_names: vec!["x50".into()],
        constraint_form: None,
        multipliers: Vec::new(),
        c_rate: None,
    }
}


/// λ from an MBDyn eigenanalysis file's `alpha` row: Λ = (αr + j αi)/β,
/// λ = (1/dCoef)(Λ − 1)/(Λ + 1) (MBDyn manual, eigenanalysis output): (Re λ, Im λ) [rad/s].
pub fn lambda_of_alpha(row: [f64; 3], dcoef: f64) -> (f64, f64) {
    let (ar, ai, b) = (row[0], row[1], row[2]);
    let d = dcoef * ((ar + b).powi(2) + ai * ai);
    ((ar * ar + ai * ai - b * b) / d, 2.0 * ai * b / d)
}

/// Asserts that `text` is what `serde_json`'s pretty printer gives for the document it holds
/// (each object's keys sorted, the same layout), number tokens aside: serde_json's reader
/// rounds some decimals one unit off in the last place (without its `float_roundtrip`
/// feature), so a number's digits are not compared, only that it is one on both sides.
pub fn assert_canonical_json(text: &str) {
    let value: serde_json::Value = serde_json::from_str(text).unwrap();
    let reprint = serde_json::to_string_pretty(&value).unwrap() + "\n";
    let layout = |t: &str| -> Vec<String> {
        t.lines()
            .map(|l| {
                let (key, value) = l.rsplit_once(": ").map_or(("", l), |(k, v)| (k, v));
                let bare = value.trim().trim_end_matches(',');
                if bare.parse::<f64>().is_ok() { format!("{key}: <number>{}", if value.ends_with(',') { "," } else { "" }) } else { l.to_string() }
            })
            .collect()
    };
    let (a, b) = (layout(text), layout(&reprint));
    assert_eq!(a.len(), b.len(), "lines");
    if let Some(k) = (0..a.len()).find(|&k| a[k] != b[k]) {
        panic!("line {}: {:?} where serde_json prints {:?}", k + 1, a[k], b[k]);
    }
}
