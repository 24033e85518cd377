//! Command-line interface: argument parsing, printing, exit codes.

mod args;
mod bode;
mod check;
mod eig;
mod load;
mod rom;
mod run;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// romdyn: linear reduced-order models from multibody DAEs.
///
/// Units are SI throughout: eigenvalues in rad/s, frequencies in Hz, forces in N,
/// moments in N m, displacements in m, rotations in rad, dCoef in s.
#[derive(Parser, Debug)]
#[command(name = "romdyn", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run an MBDyn input file: initial-value problem and eigenanalyses; writes .out, .mov, .log, .m, .json
    Run(run::RunArgs),
    /// Check every element's Jacobian against finite differences of its residual
    Check(check::CheckArgs),
    /// Eigenanalysis of a linear DAE: modal table with labels and error estimates
    Eig(eig::EigArgs),
    /// Reduced-order model from selected modes; exports E, A, B, C, D (.json/.mat/.npz)
    Rom(rom::RomArgs),
    /// Frequency response of the full model (and of a ROM): CSV table and Bode plot
    Freq(rom::FreqArgs),
}

pub fn run() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run(a) => run::run(a),
        Command::Check(a) => check::run(a),
        Command::Eig(a) => eig::run(a),
        Command::Rom(a) => rom::run(a),
        Command::Freq(a) => rom::run_freq(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("romdyn: error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
