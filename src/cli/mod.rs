//! Command-line interface: argument parsing, printing, exit codes.

mod allocator;
mod args;
mod check;
mod cms;
mod eig;
mod rom;
mod run;
mod sweep;
mod validate;

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
    /// Run an MBDyn input file: initial-value problem and eigenanalyses; writes .out, .mov, .log, .m, .json (.act, .bst with beams, .pla with shells)
    ///
    /// Consistent initial derivatives, then fixed steps of the file's method from the initial to the
    /// final time [s]; at each 'eigenanalysis' time J(+c) and J(-c) (c = the file's 'parameter', else
    /// 0.5 s as MBDyn) and their eigenvalues λ [rad/s]. Files (MBDyn layouts, SI units): PREFIX.out
    /// step log, PREFIX.mov node motion (m, deg, m/s, rad/s), PREFIX.log model log, and per
    /// eigenanalysis K (0, 1, …) PREFIX_K.m (Octave: dTime, dCoef, Aplus, Aminus, alpha, VR, VL,
    /// geometry) and PREFIX_K.json, K as the file's 'suffix width'/'suffix format' say. Files appear only when the run succeeds; a Newton failure names the step, the
    /// residual norm and the worst equation, and exits with status 1.
    Run(run::RunArgs),
    /// Check every element's Jacobian against finite differences of its residual
    ///
    /// At the model's reference solution, compares each element's J(c) = F/y' + c F/y (c = b0 of the
    /// file's method and time step [s], the coefficient Newton uses) with central finite differences
    /// of the element's residual: y' is perturbed by ±h and y by ±c h (multipliers as Newton moves
    /// them), h = 1e-6 max(1 + |y'_j|, (1 + |y_j|)/c), so y moves by about 1e-6 (1 + |y_j|). Prints
    /// each element's worst entry (equation,
    /// unknown, analytic and finite-difference values); an element fails when
    /// max |analytic - fd| / max(max |J_element|, 1) exceeds the tolerance (default 1e-6), and any
    /// failure gives exit status 1.
    Check(check::CheckArgs),
    /// Eigenanalysis of a linear DAE: modal table with labels and error estimates
    Eig(eig::EigArgs),
    /// Reduced-order model from selected modes; exports E, A, B, C, D (.json/.mat/.npz/.m), balanced, minimal or discrete-time on request
    Rom(rom::RomArgs),
    /// Frequency response of the full model (and of a ROM): CSV table and Bode plot
    Freq(rom::FreqArgs),
    /// ROMs of an MBDyn file over design points of its set: variables (--set NAME=A:B:N): stacked arrays, table and plot of the lowest modes
    ///
    /// At each design point the file is read with the swept variables replaced, then the reference
    /// solution, linearization, eigenanalysis and ROM exactly as 'romdyn rom' with the same options
    /// and ports. Points run in parallel (--jobs); a failed point is reported with its values and
    /// error and the others are kept (exit status 1). Units: the file's (SI); frequencies in Hz,
    /// eigenvalues in rad/s.
    Sweep(sweep::SweepArgs),
    /// Validate a ROM against the nonlinear model (and measurements): H1 estimate of the direct response to a band-limited input, full model, ROM, time-domain fit and a verdict
    ///
    /// Excites the model through each ROM input with a small low-pass filtered random signal (or a
    /// multisine or chirp) from the ROM's reference solution, integrates it with the file's method
    /// at a step of 1/(80 x the band's top), measures each output as the nonlinear quantity its
    /// row of C linearizes, and estimates each input/output pair by H1 with Welch averaging (Hann
    /// windows, half overlap) and coherence. Prints per channel the largest ROM-vs-estimate error
    /// where coherence is high, the ROM's time-domain fit (NRMSE) and a verdict; with several
    /// --amplitudes the linearity limit. Units: SI (inputs N or N m, outputs m, rad, m/s, rad/s;
    /// frequencies Hz, times s).
    Validate(validate::ValidateArgs),
    /// Reduce a substructure (MBDyn file: nodes, bodies, beams, springs) to MBDyn's modal-joint FEM file with Craig–Bampton modes: PREFIX.fem
    ///
    /// Linearizes the substructure at rest at its reference (initial by default, --static, --at),
    /// takes the mass and stiffness of its nodes' displacements [m] and rotations [rad], and keeps
    /// --modes fixed-interface normal modes (interface nodes held, unit modal mass) and six static
    /// constraint modes per --interface node. The FEM file lists every structural node at its
    /// reference position, in the global frame; attach it with a clamped modal joint (the card is
    /// printed). Frequencies in rad/s and Hz.
    Cms(cms::CmsArgs),
}

/// `romdyn help --help` (or `-h`) as `romdyn help help`, and `romdyn help eig --help` as
/// `romdyn help eig`: clap's `help` subcommand takes no flags and exited 2 (issue 32).
fn help_flags_of_help(mut args: Vec<std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    if args.get(1).is_some_and(|a| a == "help") {
        let flag = |a: &std::ffi::OsString| a == "--help" || a == "-h";
        if args[2..].iter().any(flag) {
            args.retain(|a| !flag(a));
            if args.len() == 2 {
                args.push("help".into());
            }
        }
    }
    args
}

pub fn run() -> ExitCode {
    let cli = Cli::parse_from(help_flags_of_help(std::env::args_os().collect()));
    // `ROMDYN_PARSE_ONLY=1 romdyn …` stops once the arguments parse (a usage error still exits
    // 2): tests/cli/docs_commands.rs checks the book's command lines against this parser.
    if std::env::var_os("ROMDYN_PARSE_ONLY").is_some() {
        return ExitCode::SUCCESS;
    }
    let result = match cli.command {
        Command::Run(a) => run::run(a),
        Command::Check(a) => check::run(a),
        Command::Eig(a) => eig::run(a),
        Command::Rom(a) => rom::run(a),
        Command::Freq(a) => rom::run_freq(a),
        Command::Sweep(a) => sweep::run(a),
        Command::Validate(a) => validate::run(a),
        Command::Cms(a) => cms::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // Input errors already read "FILE:LINE:COLUMN: error: …" with the line and a caret.
        Err(e) if e.downcast_ref::<romdyn::input::mbdyn::MbdynError>().is_some() || matches!(e.downcast_ref(), Some(romdyn::study::StudyError::Model(_))) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("romdyn: error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
