//! `fairgrasp`: the command line. It parses arguments, calls the library crates and prints.

mod cli;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use std::process::ExitCode;

fn main() -> ExitCode {
    streams_as_unix_tools();
    let args = match cli::Cli::try_parse_from_args(std::env::args_os().collect()) {
        Ok(args) => args,
        // Help and version print as clap prints them; usage errors with long values cut.
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => {
            eprint!("{}", excerpt_long_words(&e.render().to_string()));
            return ExitCode::from(2);
        }
    };
    match cli::run(args) {
        Ok(code) => code,
        Err(err) => {
            eprintln!("error: {}", excerpt_long_words(&format!("{err:#}")));
            // A usage error found after parsing exits as clap's own do.
            if err.downcast_ref::<cli::UsageError>().is_some() {
                ExitCode::from(2)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}

/// The longest word an error message quotes whole \[characters\]: a longer one (a pasted value
/// of megabytes, a TOML line quoted by the parser) is cut to its start and its length.
const MAX_QUOTED_WORD: usize = 120;

/// `message` with every word longer than [`MAX_QUOTED_WORD`] cut to its first 60 characters
/// and a note of its length, so a bad value never floods the terminal.
fn excerpt_long_words(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(1 << 16));
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        let n = word.chars().count();
        if n > MAX_QUOTED_WORD {
            out.extend(word.chars().take(60));
            out.push_str(&format!("… ({n} characters)"));
        } else {
            out.push_str(word);
        }
        word.clear();
    };
    for c in message.chars() {
        if c.is_whitespace() {
            flush(&mut word, &mut out);
            out.push(c);
        } else {
            word.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
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
