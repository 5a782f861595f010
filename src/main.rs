//! `fairgrasp`: the command line. It parses arguments, calls the library crates and prints.

mod cli;
mod error_message;
mod streams;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use std::io::Write;
use std::process::ExitCode;

use fairgrasp_types::text::cut_long_words;

fn main() -> ExitCode {
    streams::as_unix_tools();
    let args = match cli::Cli::try_parse_from_args(std::env::args_os().collect()) {
        Ok(args) => args,
        // Help and version print as clap prints them; usage errors with long values cut.
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => {
            eprint!("{}", cut_long_words(&e.render().to_string()));
            return ExitCode::from(2);
        }
    };
    // A command that writes files finishes them even when nobody reads its stdout.
    let relay = args.writes_files().then(streams::Relay::start).flatten();
    // A panic still delivers what the command printed before it.
    let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| cli::run(args)));
    let run = match (run, relay) {
        (Ok(run), relay) => (run, relay),
        (Err(panic), Some(relay)) => {
            relay.finish(ExitCode::FAILURE, false);
            std::panic::resume_unwind(panic)
        }
        (Err(panic), None) => std::panic::resume_unwind(panic),
    };
    let (run, relay) = run;
    let (code, succeeded) = match run {
        Ok(code) => (code, true),
        Err(err) => {
            // Never a panic: a stderr that cannot be written (a full disk) stays empty, and
            // the exit code still says the command failed.
            let _ = writeln!(std::io::stderr(), "error: {}", error_message::render(&err));
            // A usage error found after parsing exits as clap's own do.
            if err.downcast_ref::<cli::UsageError>().is_some() {
                (ExitCode::from(2), false)
            } else {
                (ExitCode::FAILURE, false)
            }
        }
    };
    match relay {
        Some(relay) => relay.finish(code, succeeded),
        None => code,
    }
}
