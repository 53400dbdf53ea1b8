//! `hcm`: hybrid contact modeling from the command line.

// The CLI's doc comments are its `--help` text, where `<law>` and `<example>` are
// placeholders a reader fills in, not HTML.
#[allow(rustdoc::invalid_html_tags)]
mod cli;

/// Exit status of a process ended by SIGPIPE (128 + 13), as a shell reports it.
const BROKEN_PIPE_STATUS: i32 = 141;

fn main() -> std::process::ExitCode {
    quiet_on_broken_pipe();
    // Before any output is started: an interrupted run then leaves no temporary behind.
    if let Err(error) = hcm_host::output::remove_temporaries_on_signals() {
        eprintln!("warning: interrupting hcm may leave temporary files behind: {error}");
    }
    cli::main()
}

/// `hcm … | head` closes the pipe early; Rust ignores SIGPIPE, so the next `println!`
/// panics. Like any Unix tool, end quietly instead (status 141); other panics keep the
/// default report.
fn quiet_on_broken_pipe() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("os error 32") {
            std::process::exit(BROKEN_PIPE_STATUS);
        }
        default(info);
    }));
}
