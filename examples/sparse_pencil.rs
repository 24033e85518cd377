//! The hanging N-link chain's pencil for side-by-side eigensolver timings
//! (scripts/bench_eigen.py, issue 13 acceptance):
//!
//! ```text
//! cargo run --release --example sparse_pencil -- export N DIR
//!     writes DIR/E.mtx and DIR/K.mtx: the pencil λ E + K of eq. 29 that
//!     eigen::krylov::sparse_modes factors and iterates on (the chain of the tests and of
//!     benches/sparse_eigen.rs linearized at rest in MBDyn's form, eq. 30, then mapped to
//!     eq. 29), Matrix Market coordinate real general, 17 N + 12 rows.
//! cargo run --release --example sparse_pencil -- export-mbdyn FILE DIR
//!     the same for an MBDyn file, linearized at its initial state (scripts/bench_sparse_run.py:
//!     the pencil `romdyn run FILE` solves when the file asks for `use arpack` at the
//!     initial time of a model at rest there).
//! cargo run --release --example sparse_pencil -- solve DIR COUNT [REPEAT] [--right-only]
//!     reads DIR/E.mtx, DIR/K.mtx, runs sparse_modes(Lowest(COUNT)) REPEAT times on
//!     E ẏ + K y = 0 and prints the fastest wall time [s] and the eigenvalues [rad/s]
//!     (Im λ ≥ 0 of each pair), one "re im" line each; with SPARSE_PENCIL_PROGRESS set,
//!     the solver's progress lines (operator applications, restarts) on stderr.
//!     `--right-only`: right vectors only (`SparseEigenSettings::left_vectors = false`, the
//!     work scipy's eigs does: no adjoint run, so the result is not certified).
//! ```
//!
//! The files are written and read by romdyn's Matrix Market code
//! (`output::matrix_market::write_sparse_matrix`, `input::matrix_market::read_sparse_matrix`).

#[allow(dead_code)]
#[path = "../tests/common/models.rs"]
mod models;

use std::io::Write;
use std::path::Path;

use anyhow::{bail, Context, Result};
use faer::Mat;
use romdyn::dae::{linearize_sparse, Assembler, State};
use romdyn::eigen::krylov::{shift_invert_pencil, sparse_modes_with_progress, ModeTarget, SparseEigenSettings};
use romdyn::input::matrix_market::read_sparse_matrix;
use romdyn::linear::SparseLinearDae;
use romdyn::model::ConstraintForm;
use romdyn::output::matrix_market::write_sparse_matrix;
use romdyn::solve::{static_solution, NewtonSettings};

fn main() -> Result<()> {
    match run() {
        // `| head`: the reader went away; what it took is complete lines.
        Err(e) if e.downcast_ref::<std::io::Error>().is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe) => Ok(()),
        other => other,
    }
}

fn run() -> Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let right_only = args.iter().any(|a| a == "--right-only");
    args.retain(|a| a != "--right-only");
    let settings = SparseEigenSettings { left_vectors: !right_only, ..Default::default() };
    match args.iter().map(String::as_str).collect::<Vec<_>>().as_slice() {
        ["export", n, dir] => export(n.parse().context("N: a number of links")?, Path::new(dir)),
        ["export-mbdyn", file, dir] => export_mbdyn(Path::new(file), Path::new(dir)),
        ["solve", dir, count] => solve(Path::new(dir), count.parse().context("COUNT: a number of modes")?, 1, &settings),
        ["solve", dir, count, repeat] => solve(Path::new(dir), count.parse().context("COUNT: a number of modes")?, repeat.parse().context("REPEAT: a number of runs")?, &settings),
        _ => bail!("usage: sparse_pencil export N DIR | sparse_pencil export-mbdyn FILE DIR | sparse_pencil solve DIR COUNT [REPEAT] [--right-only]"),
    }
}

fn export(n: u32, dir: &Path) -> Result<()> {
    let model = models::hanging_chain(n, ConstraintForm::Scaled);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings::default())?;
    write_pencil(&linearize_sparse(&model, &st, &[], &[])?, dir)
}

fn export_mbdyn(file: &Path, dir: &Path) -> Result<()> {
    let read = romdyn::input::mbdyn::read_model(file)?;
    let asm = Assembler::new(&read.model);
    let st = State::initial(&read.model, &asm.dofs);
    write_pencil(&linearize_sparse(&read.model, &st, &[], &[])?, dir)
}

fn write_pencil(dae: &SparseLinearDae, dir: &Path) -> Result<()> {
    let (e, k) = shift_invert_pencil(dae)?;
    std::fs::create_dir_all(dir)?;
    write_sparse_matrix(&dir.join("E.mtx"), &e)?;
    write_sparse_matrix(&dir.join("K.mtx"), &k)?;
    println!("{} equations, nnz(E) = {}, nnz(K) = {}", e.nrows(), e.nnz(), k.nnz());
    Ok(())
}

fn solve(dir: &Path, count: usize, repeat: usize, settings: &SparseEigenSettings) -> Result<()> {
    let (e, k) = (read_sparse_matrix(&dir.join("E.mtx"))?, read_sparse_matrix(&dir.join("K.mtx"))?);
    let n = e.nrows();
    if k.nrows() != n || e.ncols() != n || k.ncols() != n {
        bail!("E.mtx and K.mtx must be square and of one size");
    }
    let dae = SparseLinearDae {
        fyd: e,
        fy: k,
        b: Mat::zeros(n, 0),
        c: Mat::zeros(0, n),
        c_rate: None,
        unknown_names: (0..n).map(|i| format!("y{i}")).collect(),
        input_names: Vec::new(),
        output_names: Vec::new(),
        constraint_form: None,
        multipliers: Vec::new(),
    };
    let mut best = f64::INFINITY;
    let mut result = None;
    for _ in 0..repeat.max(1) {
        // The previous run's modes go before the next run starts: the peak memory the
        // script reports is then that of one run.
        drop(result.take());
        let start = std::time::Instant::now();
        let verbose = std::env::var_os("SPARSE_PENCIL_PROGRESS").is_some();
        let r = sparse_modes_with_progress(&dae, ModeTarget::Lowest(count), settings, &|line| {
            if verbose {
                eprintln!("{line}");
            }
        })?;
        best = best.min(start.elapsed().as_secs_f64());
        result = Some(r);
    }
    let Some(r) = result else { unreachable!("at least one run") };
    let out = std::io::stdout();
    let mut out = out.lock();
    writeln!(out, "time {best:.6} s, certified {}, max residual {:.2e}", r.certified, r.max_residual)?;
    for m in r.modal.modes.iter().filter(|m| m.lambda.im >= 0.0) {
        writeln!(out, "{:.17e} {:.17e}", m.lambda.re, m.lambda.im)?;
    }
    Ok(())
}
