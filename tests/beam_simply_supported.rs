//! CASES C4: the simply supported beam of paper §6.2 and §7.1 (Table 3).

mod common;

use common::beams::{node_label, simply_supported, TABLE3};
use romdyn::dae::{linearize, Assembler, State};
use romdyn::linear::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::solve::{static_solution, NewtonSettings};

fn first_bending(elements: usize, n_axial: f64) -> f64 {
    let model = simply_supported(&TABLE3, elements, n_axial);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    let mid = node_label(elements);
    let dae = linearize(&model, &st, &[format!("{mid}:Fy").parse().unwrap()], &[format!("{mid}:y").parse().unwrap()], None).unwrap();
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Lambda).unwrap();
    let mut w: Vec<f64> = modal.of_kind(ModeKind::Dynamic).map(|i| modal.modes[i].lambda.im.abs()).collect();
    w.sort_by(f64::total_cmp);
    eprintln!("{elements} el, N = {n_axial}: {:?}", &w[..w.len().min(8)]);
    w[0]
}

#[test]
fn explore() {
    for ne in [2, 4] {
        first_bending(ne, 0.0);
    }
}

#[test]
fn explore_load() {
    let ncr = std::f64::consts::PI.powi(2) * 1e3;
    for ne in [2, 4] {
        for r in [0.0, 0.2, 0.4, 0.6, 0.8, 0.9] {
            let w = first_bending(ne, r * ncr);
            let exact = std::f64::consts::PI.powi(2) * (1e3f64).sqrt() * (1.0 - r as f64).sqrt();
            eprintln!("ne {ne} r {r}: {w} exact {exact} err {:.4}%", 100.0 * (w - exact) / exact);
        }
    }
}

#[test]
fn explore_one() {
    let ncr = std::f64::consts::PI.powi(2) * 1e3;
    let model = simply_supported(&TABLE3, 4, 0.6 * ncr);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    let it = static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    eprintln!("iterations {it}");
    let dae = linearize(&model, &st, &["5:Fy".parse().unwrap()], &["5:y".parse().unwrap()], None).unwrap();
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Lambda).unwrap();
    for (i, m) in modal.modes.iter().enumerate() {
        eprintln!("{i} {:?} {} {:e}", m.kind, m.lambda, m.error);
    }
}

#[test]
fn dump_one() {
    let ncr = std::f64::consts::PI.powi(2) * 1e3;
    let model = simply_supported(&TABLE3, 4, 0.6 * ncr);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
    let dae = linearize(&model, &st, &["5:Fy".parse().unwrap()], &["5:y".parse().unwrap()], None).unwrap();
    let (fyd, fy) = dae.jacobians.derivatives();
    romdyn::output::matrix_market::write_matrix(std::path::Path::new("/tmp/fyd.mtx"), &fyd).unwrap();
    romdyn::output::matrix_market::write_matrix(std::path::Path::new("/tmp/fy.mtx"), &fy).unwrap();
}

#[test]
fn explore_convergence() {
    let ncr = std::f64::consts::PI.powi(2) * 1e3;
    for ne in [8] {
        let w0 = first_bending(ne, 0.0);
        let w9 = first_bending(ne, 0.9 * ncr);
        let rho = 0.9 / (1.0 - (w9 / w0).powi(2));
        eprintln!("ne {ne}: Ncr_d/Ncr_E = {rho:.6}  w0 {w0}");
    }
}

#[test]
fn dump_stiffness() {
    for ga in [1e4, 1e5] {
        for ne in [2, 4, 8, 16, 32] {
            for n in [0.0, 1000.0] {
                let d = common::beams::BeamData { ga, ..TABLE3 };
                let model = simply_supported(&d, ne, n);
                let asm = Assembler::new(&model);
                let mut st = State::initial(&model, &asm.dofs);
                static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
                let fy = asm.jacobian(&st, romdyn::dae::Coefficients::static_analysis()).to_dense();
                romdyn::output::matrix_market::write_matrix(std::path::Path::new(&format!("/tmp/k_{ga:e}_{ne}_{n}.mtx")), &fy).unwrap();
            }
        }
    }
}

#[test]
fn explore_time() {
    let ncr = std::f64::consts::PI.powi(2) * 1e3;
    for r in [0.0, 0.9] {
        let model = simply_supported(&TABLE3, 8, r * ncr);
        let asm = Assembler::new(&model);
        let mut st = State::initial(&model, &asm.dofs);
        static_solution(&asm, &mut st, 1, &NewtonSettings::default()).unwrap();
        let dae = linearize(&model, &st, &["9:Fy".parse().unwrap()], &["9:y".parse().unwrap()], None).unwrap();
        let t = std::time::Instant::now();
        let _modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Direct).unwrap();
        eprintln!("r {r} n {} eigen {:?}", dae.dim(), t.elapsed());
    }
}
