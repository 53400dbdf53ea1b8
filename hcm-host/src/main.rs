//! `hcm`: hybrid contact modeling from the command line.

mod cli;

fn main() -> std::process::ExitCode {
    // Before any output is started: an interrupted run then leaves no temporary behind.
    if let Err(error) = hcm_host::output::remove_temporaries_on_signals() {
        eprintln!("warning: interrupting hcm may leave temporary files behind: {error}");
    }
    cli::main()
}
