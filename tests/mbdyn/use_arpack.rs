//! MBDyn's `use arpack, NEV, NCV, TOL` (input manual, "Eigenanalysis"; solver.cc
//! `eig_arpack`: the NEV eigenvalues of `Aplus⁻¹ Aminus − I` of smallest magnitude, Λ
//! nearest 1, λ nearest 0) runs romdyn's sparse route for the NEV lowest dynamic modes, and
//! `use lapack` the dense one, refused before allocating when it exceeds the dense budget.
//!
//! The model: a string of N point masses (1 kg, `dynamic displacement` nodes 1 m apart)
//! between two clamped walls, on rods of EA = 900 N and rest length 0.9 m: tension
//! T = EA (1 − 0.9)/0.9 = 100 N, axial stiffness k_a = EA/0.9 = 1000 N/m, lateral stiffness
//! T/1 m = 100 N/m. Its modes are those of a fixed-fixed spring-mass chain (closed form):
//! `ω_j = 2 sqrt(k/m) sin(jπ/(2(N+1)))`, j = 1..N, with k = 100 N/m twice (y and z) and
//! k = 1000 N/m once (x). The rods' linearization holds the tension's lateral stiffness
//! exactly (`displacement_nodes.rs` checks one such mass against MBDyn 1.7.3).

use crate::common;

use common::cli::{romdyn_at, temp_dir, write_file};
use common::lambda_of_alpha;
use common::mbdyn::string_of_masses;
use std::path::Path;

use faer::c64;
use romdyn::analysis::Eigenanalysis;
use romdyn::dae::{Assembler, State};
use romdyn::eigen::ModeKind;
use romdyn::input::mbdyn::{build, parse_text};
use romdyn::model::EigenSolverRequest;
use serde_json::Value;

/// The closed form's `count` lowest natural frequencies [rad/s] of the string of `n`
/// masses, each repeated as often as it occurs (lateral ones twice), ascending.
fn closed_form(n: usize, count: usize) -> Vec<f64> {
    let mode = |k: f64, j: usize| 2.0 * k.sqrt() * (j as f64 * std::f64::consts::PI / (2.0 * (n + 1) as f64)).sin();
    let mut all: Vec<f64> = (1..=n).flat_map(|j| [mode(100.0, j), mode(100.0, j), mode(1000.0, j)]).collect();
    all.sort_by(f64::total_cmp);
    all.truncate(count);
    all
}

/// On a string of 600 masses (7224 equations: one 7224 x 7224 matrix is over the dense
/// budget of 5e7 entries), `use lapack` is refused before the run with the size and the
/// sparse request to make, and writes nothing; `use arpack, 10, 30, 0.` writes the 10
/// lowest modes and the second copy of the 10th (lateral j = 5, degenerate: a cluster is
/// returned whole), 22 eigenvalues equal to the closed form's to 1e-9 relative, and the
/// pencil as sparse
/// triplets, whose entries with the written vectors give `Aminus v = Λ Aplus v` (relative
/// residual below 1e-10, the sparse route's tolerance).
#[test]
fn use_arpack_on_a_model_too_large_for_the_dense_route_writes_the_lowest_modes_and_a_sparse_pencil() {
    let n = 600;
    let equations = 12 * n + 24;
    let dir = temp_dir("use-arpack-large");
    let dense = write_file(&dir, "dense.mbd", &string_of_masses(n, "output sparse matrices, parameter, 1.e-3, use lapack"));
    let (ok, _, err) = romdyn_at(&dir, &["run", &dense]);
    assert!(!ok);
    assert!(err.contains(&format!("({equations} equations) is {equations} x {equations} = {} entries, more than romdyn's budget", equations * equations)), "{err}");
    assert!(err.contains("'use arpack, NEV, NCV, TOL'"), "{err}");
    assert!(!dir.join("dense_0.m").exists() && !dir.join("dense.out").exists());

    let sparse = write_file(&dir, "sparse.mbd", &string_of_masses(n, "output sparse matrices, output eigenvectors, parameter, 1.e-3, use arpack, 10, 30, 0."));
    let (ok, out, err) = romdyn_at(&dir, &["run", &sparse]);
    assert!(ok, "{err}");
    assert!(out.contains("22 dynamic eigenvalues, the 10 lowest dynamic modes (use arpack), sparse shift-invert Krylov-Schur route: certified"), "{out}");
    let text = std::fs::read_to_string(dir.join("sparse_0.json")).unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    // Streamed part by part (src/output/eigen_json.rs), laid out as serde_json prints the
    // whole document (sparse triplets, vectors, energy shares).
    common::assert_canonical_json(&text);
    let dcoef = json["dCoef"].as_f64().unwrap();
    assert_eq!(dcoef, 5e-4);
    let alpha: Vec<[f64; 3]> = json["alpha"].as_array().unwrap().iter().map(|r| [0, 1, 2].map(|k| r[k].as_f64().unwrap())).collect();
    let mut omega: Vec<f64> = alpha.iter().map(|&r| lambda_of_alpha(r, dcoef)).filter(|l| l.1 > 0.0).map(|l| l.0.hypot(l.1)).collect();
    omega.sort_by(f64::total_cmp);
    let want = closed_form(n, 11);
    assert_eq!(omega.len(), want.len(), "{omega:?}");
    for (got, want) in omega.iter().zip(&want) {
        assert!((got - want).abs() <= 1e-9 * want, "{got} against the closed form {want}");
    }

    // The pencil as triplets (1-based), a few per row: no n x n matrix was written.
    let triplets = |name: &str| -> Vec<(usize, usize, f64)> {
        assert_eq!(json[name]["size"], serde_json::json!([equations, equations]));
        json[name]["entries"].as_array().unwrap().iter().map(|e| (e[0].as_u64().unwrap() as usize - 1, e[1].as_u64().unwrap() as usize - 1, e[2].as_f64().unwrap())).collect()
    };
    let (aplus, aminus) = (triplets("Aplus"), triplets("Aminus"));
    assert!(aplus.len() < 20 * equations && aminus.len() < 20 * equations, "{} entries", aplus.len());
    let vr = json["VR"].as_array().unwrap();
    let product = |m: &[(usize, usize, f64)], v: &[c64]| {
        let mut y = vec![c64::new(0.0, 0.0); equations];
        m.iter().for_each(|&(i, j, a)| y[i] += v[j] * a);
        y
    };
    let norm = |v: &[c64]| v.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
    for (k, row) in alpha.iter().enumerate() {
        let big_lambda = c64::new(row[0], row[1]) / row[2];
        let v: Vec<c64> = vr.iter().map(|r| c64::new(r[k]["re"].as_f64().unwrap(), r[k]["im"].as_f64().unwrap())).collect();
        let (am, ap) = (product(&aminus, &v), product(&aplus, &v));
        let residual: Vec<c64> = am.iter().zip(&ap).map(|(a, b)| a - big_lambda * b).collect();
        let relative = norm(&residual) / (norm(&am) + big_lambda.norm() * norm(&ap));
        assert!(relative < 1e-10, "mode {k}: residual {relative:e}");
    }
}

/// The sparse route's modes equal the dense route's on a string of 30 masses (384
/// equations): `use arpack, 8, …` gives the 8 lowest modes and the second copy of the 8th
/// (lateral j = 4, degenerate), each eigenvalue the dense route's to 1e-9 relative and the closed
/// form's to 1e-9, each right vector in the span of the dense route's vectors of its
/// eigenvalue (the lateral pairs are degenerate: the basis is the solver's choice) to 1e-9;
/// and MBDyn 1.7.3's ARPACK eigenvalues of the same file to 1e-9.
#[test]
fn use_arpack_modes_equal_the_dense_routes_on_a_smaller_model() {
    let n = 30;
    let m = common::mbdyn::read(&string_of_masses(n, "parameter, 1.e-3, use arpack, 8, 20, 0."));
    let request = m.problem.eigenanalysis.clone().unwrap();
    assert_eq!(request.solver, EigenSolverRequest::Lowest { modes: 8, card: "use arpack" });
    let state = State::initial(&m.model, &Assembler::new(&m.model).dofs);
    let sparse = Eigenanalysis::at(&m.model, &state, 0, &request).unwrap();
    let dense = Eigenanalysis::at(&m.model, &state, 0, &romdyn::model::EigenRequest { solver: EigenSolverRequest::Dense, ..request.clone() }).unwrap();
    assert!(sparse.not_certified.is_none(), "{}", sparse.solver);
    // MBDyn 1.7.3 (built here with ARPACK) on this file with final time 1e-3 (it does no
    // eigenanalysis when the final time is the initial one) and `eigenanalysis: 0., output
    // eigenvectors, results output precision, 16, parameter, 1.e-3, use arpack, 16, 40, 0.`:
    // 14 of 16 Ritz values converged (INFO=1), the lateral j = 1, 2 pairs (these alpha rows,
    // λ by MBDyn's formula) and 6 eigenvalues at λ ≈ 0 (its constrained variables', which
    // romdyn's route removes). romdyn's sparse modes hold MBDyn's pairs to 1e-9 relative
    // (MBDyn's own distance to the closed form: 1.1e-10).
    let mbdyn_alpha = [[9.9999948693270690e-01, 1.0129831169994549e-03, 1.0], [9.9999948693217133e-01, 1.0129831168012313e-03, 1.0], [9.9999795299655692e-01, 2.0233643688835159e-03, 1.0], [9.9999795299597960e-01, 2.0233643687599724e-03, 1.0]];
    for row in mbdyn_alpha {
        let (re, im) = lambda_of_alpha(row, 5e-4);
        let l = c64::new(re, im);
        let nearest = sparse.modal.modes.iter().map(|m| m.lambda).min_by(|a, b| (a - l).norm().total_cmp(&(b - l).norm())).unwrap();
        assert!((nearest - l).norm() <= 1e-9 * l.norm(), "MBDyn's {l} against romdyn's {nearest}");
    }
    let upper = |a: &Eigenanalysis| -> Vec<usize> { (0..a.modal.modes.len()).filter(|&k| a.modal.modes[k].kind == ModeKind::Dynamic && a.modal.modes[k].lambda.im > 0.0).collect() };
    let (s, d) = (upper(&sparse), upper(&dense));
    // 8 modes asked: lateral j = 1, 2, 3 (twice each), axial j = 1 (3.2 rad/s) and the
    // first of lateral j = 4's pair, whose second copy comes with it.
    assert_eq!(s.len(), 9);
    let want = closed_form(n, 9);
    for (i, &k) in s.iter().enumerate() {
        let l = sparse.modal.modes[k].lambda;
        let nearest = d.iter().map(|&j| dense.modal.modes[j].lambda).min_by(|a, b| (a - l).norm().total_cmp(&(b - l).norm())).unwrap();
        assert!((l - nearest).norm() <= 1e-9 * l.norm(), "mode {i}: sparse {l} against dense {nearest}");
        assert!((l.norm() - want[i]).abs() <= 1e-9 * want[i], "mode {i}: {l} against the closed form {}", want[i]);
        // The dense route's vectors of this eigenvalue, orthonormalized; the sparse vector's
        // part outside their span.
        let mut basis: Vec<Vec<c64>> = Vec::new();
        for &j in d.iter().filter(|&&j| (dense.modal.modes[j].lambda - l).norm() <= 1e-7 * l.norm()) {
            let mut v: Vec<c64> = dense.modal.modes[j].right.as_ref().unwrap().iter().copied().collect();
            for b in &basis {
                let p: c64 = b.iter().zip(&v).map(|(x, y)| x.conj() * y).sum();
                v.iter_mut().zip(b).for_each(|(y, x)| *y -= p * x);
            }
            let nv = v.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
            basis.push(v.into_iter().map(|z| z / nv).collect());
        }
        let mut v: Vec<c64> = sparse.modal.modes[k].right.as_ref().unwrap().iter().copied().collect();
        let nv = v.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
        for b in &basis {
            let p: c64 = b.iter().zip(&v).map(|(x, y)| x.conj() * y).sum();
            v.iter_mut().zip(b).for_each(|(y, x)| *y -= p * x);
        }
        let outside = v.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt() / nv;
        assert!(outside <= 1e-9, "mode {i}: {outside:e} of the sparse vector outside the dense route's eigenspace");
    }
}

/// `J(±c)` are assembled on the sparse route only when the file writes them: without `output
/// sparse matrices` (or full) the analysis holds no pencil and its `.m`/JSON carry no
/// `Aplus`/`Aminus`; with it, the written `Aplus`/`Aminus` are `J(±c)` assembled
/// independently at the same state (`sparse_jacobian_pair`, eqs. 13–14), entry for entry. A
/// file that asks for matrices the analysis does not hold is an error, never a file without
/// them.
#[test]
fn use_arpack_assembles_the_written_pencil_only_when_the_file_asks_for_it() {
    use romdyn::output::eigen_file::MatrixLayout;
    use romdyn::output::eigen_json::write_eigen_json;
    use romdyn::output::eigen_m::write_eigen_m;
    let n = 30;
    let analysis = |card: &str| {
        let m = common::mbdyn::read(&string_of_masses(n, card));
        let state = State::initial(&m.model, &Assembler::new(&m.model).dofs);
        let request = m.problem.eigenanalysis.clone().unwrap();
        let a = Eigenanalysis::at(&m.model, &state, 0, &request).unwrap();
        (m, state, a)
    };
    let m_text = |a: &Eigenanalysis| {
        let mut text = Vec::new();
        write_eigen_m(&mut text, "string.mbd", &a.file()).unwrap();
        String::from_utf8(text).unwrap()
    };
    let (_, _, plain) = analysis("parameter, 1.e-3, use arpack, 8, 20, 0.");
    assert!(!plain.pencil.is_assembled());
    assert_eq!(plain.pencil.dim(), 12 * n + 24);
    let text = m_text(&plain);
    assert!(text.contains("dCoef = ") && !text.contains("Aplus") && !text.contains("Aminus"), "{text}");
    // Asked for anyway (not by `Eigenanalysis::file`): an error from both writers.
    let mut file = plain.file();
    file.matrices = Some(MatrixLayout::Sparse);
    assert!(write_eigen_m(&mut Vec::new(), "string.mbd", &file).is_err());
    assert!(write_eigen_json(&mut Vec::new(), "string.mbd", &file).is_err());

    let (m, state, with) = analysis("output sparse matrices, parameter, 1.e-3, use arpack, 8, 20, 0.");
    assert!(with.pencil.is_assembled());
    // The same modes either way (the pencil is only written).
    let lambdas = |a: &Eigenanalysis| a.modal.modes.iter().map(|m| m.lambda).collect::<Vec<_>>();
    assert_eq!(lambdas(&plain), lambdas(&with));
    let (aplus, aminus) = romdyn::dae::sparse_jacobian_pair(&m.model, &state, with.dcoef).unwrap();
    for (plus, independent) in [(true, &aplus), (false, &aminus)] {
        let mut want: Vec<(usize, usize, f64)> = independent.triplets().filter(|e| e.2 != 0.0).collect();
        want.sort_by_key(|&(i, j, _)| (j, i));
        assert_eq!(with.pencil.nonzeros(plus).unwrap(), want);
    }
    let text = m_text(&with);
    assert!(text.contains("Aplus = spconvert(Aplus);") && text.contains("Aminus = spconvert(Aminus);"), "{text}");
}

/// The card's arguments are checked as MBDyn 1.7.3 checks them (solver.cc `ReadData`),
/// each refusal at its file:line:column.
#[test]
fn use_arpack_and_use_jdqz_arguments_are_checked_as_mbdyn_checks_them() {
    for (options, at, what) in [
        ("use arpack, 0, 20, 0.", ":3:36:", "the number of eigenvalues must be positive, found 0"),
        ("use arpack, 5, 7, 0.", ":3:39:", "the number of Arnoldi vectors must be more than NEV + 2 = 7, found 7"),
        ("use jdqz, 12, 20, 0.", ":3:38:", "at least 2 NEV = 24, found 20"),
        ("use lapack, use arpack, 5, 20, 0.", ":3:36:", "the solver is already selected"),
    ] {
        let e = parse_text(&string_of_masses(2, options), Path::new("m.mbd")).and_then(|d| build(&d)).err().expect("refused").to_string();
        assert!(e.contains(at) && e.contains(what), "{options}: {e}");
    }
    let m = common::mbdyn::read(&string_of_masses(2, "use jdqz, 3, 20, 1e-9"));
    assert_eq!(m.problem.eigenanalysis.unwrap().solver, EigenSolverRequest::Lowest { modes: 3, card: "use jdqz" });
}
