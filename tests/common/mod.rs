//! Test helpers shared by the validation tests.
#![allow(dead_code)]

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
