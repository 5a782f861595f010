//! `fairgrasp`: the command line. It parses arguments, calls the library crates and prints.

mod cli;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    streams_as_unix_tools();
    let args = cli::Cli::parse();
    match cli::run(args) {
        Ok(code) => code,
        Err(err) => {
            eprintln!("error: {err:#}");
            ExitCode::FAILURE
        }
    }
}

/// Streams as Unix tools treat them: a closed pipe (`fairgrasp … | head -1`) ends the command
/// quietly (SIGPIPE's default action, which Rust's runtime turns off), and a stdout that cannot
/// be written (a full disk, `> /dev/full`) is a one-line error with exit code 1. `println!`
/// panics when a write fails; the hook turns exactly that panic into the error and leaves every
/// other panic to the default hook.
fn streams_as_unix_tools() {
    // SAFETY: called first in `main`, before any thread exists; SIG_DFL is a valid disposition.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let message = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("");
        if let Some(reason) = message.strip_prefix("failed printing to stdout: ") {
            eprintln!("error: cannot write the output to stdout: {reason}");
            std::process::exit(1);
        }
        default(info);
    }));
}
