//! The `romdyn` command: maps subcommands to library calls and prints. All work lives in
//! the `romdyn` library.

mod cli;

fn main() -> std::process::ExitCode {
    cli::run()
}
