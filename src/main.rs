//! The `romdyn` command: maps subcommands to library calls and prints. All work lives in
//! the `romdyn` library.

mod cli;

/// Exit status of a process ended by SIGPIPE (128 + 13), as a shell reports it.
const SIGPIPE_STATUS: i32 = 141;

/// A closed output pipe (`romdyn eig … | head -1`) ends the command quietly with the
/// SIGPIPE status, as other Unix tools do; any other panic keeps Rust's report.
fn quiet_broken_pipe() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info.payload().downcast_ref::<String>().map(String::as_str).or_else(|| info.payload().downcast_ref::<&str>().copied()).unwrap_or("");
        if message.starts_with("failed printing to std") && message.contains("Broken pipe") {
            std::process::exit(SIGPIPE_STATUS);
        }
        default(info);
    }));
}

fn main() -> std::process::ExitCode {
    quiet_broken_pipe();
    // SIGINT/SIGTERM remove the temporary files of outputs being written.
    if let Err(e) = romdyn::output::cleanup::remove_temporaries_on_signal() {
        eprintln!("romdyn: warning: cannot watch for SIGINT/SIGTERM ({e}): an interrupted run may leave temporary files");
    }
    cli::run()
}
