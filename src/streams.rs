//! Streams as Unix tools treat them. A closed pipe (`fairgrasp … | head -1`) ends a command
//! quietly, by SIGPIPE's default action, which Rust's runtime turns off; a stdout that cannot
//! be written (a full disk, `> /dev/full`) is a one-line error with exit code 1. A command that
//! writes files finishes them first: its stdout goes through a [`Relay`], so a closed pipe
//! drops what it prints and the command ends quietly only once its files are whole.

use std::io::{Read, Write};
use std::os::fd::{AsFd, AsRawFd};
use std::process::ExitCode;

/// Restores SIGPIPE's default action, and turns the panic `println!` raises when stdout cannot
/// be written into a one-line error with exit code 1 (every other panic goes to the default
/// hook).
pub fn as_unix_tools() {
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

/// What became of the output a [`Relay`] carried.
#[derive(Debug)]
enum Delivery {
    /// All of it reached stdout.
    Whole,
    /// The reader closed the pipe; the rest was dropped.
    Closed,
    /// Writing failed otherwise; the rest was dropped.
    Failed(std::io::Error),
}

/// The process's stdout replaced by a pipe that a thread copies to the real one: a write to
/// the real stdout that fails (the reader gone) never reaches the command, which runs on.
pub struct Relay {
    copier: std::thread::JoinHandle<Delivery>,
}

impl Relay {
    /// Relays stdout when it is a pipe (the only stdout a reader can close); None otherwise,
    /// or when the pipe cannot be made (the output then goes straight to stdout).
    pub fn start() -> Option<Relay> {
        let stdout = std::io::stdout();
        if !is_pipe(stdout.as_fd().as_raw_fd()) {
            return None;
        }
        let original = std::fs::File::from(stdout.as_fd().try_clone_to_owned().ok()?);
        let (reader, writer) = std::io::pipe().ok()?;
        // SAFETY: both descriptors are open; dup2 replaces fd 1 atomically. SIGPIPE ignored
        // makes a write to a closed pipe an EPIPE error the copier sees, not the process's end.
        unsafe {
            libc::signal(libc::SIGPIPE, libc::SIG_IGN);
            if libc::dup2(writer.as_raw_fd(), 1) < 0 {
                libc::signal(libc::SIGPIPE, libc::SIG_DFL);
                return None;
            }
        }
        drop(writer);
        let copier = std::thread::spawn(move || copy(reader, original));
        Some(Relay { copier })
    }

    /// Ends the relay once the command is done (`succeeded` as it returned): everything it
    /// printed is copied, then a closed pipe ends the process as it ends a short command (by
    /// SIGPIPE, quietly) if the command succeeded, and a failed write is a one-line error.
    pub fn finish(self, code: ExitCode, succeeded: bool) -> ExitCode {
        std::io::stdout().flush().ok();
        // fd 1 onto /dev/null closes the pipe's last write end: the copier reads its end.
        if let Ok(null) = std::fs::OpenOptions::new().write(true).open("/dev/null") {
            // SAFETY: both descriptors are open.
            unsafe {
                libc::dup2(null.as_raw_fd(), 1);
            }
        }
        let delivery = self.copier.join().unwrap_or(Delivery::Whole);
        match delivery {
            Delivery::Whole => code,
            Delivery::Closed if succeeded => {
                // SAFETY: restoring the default action, then raising the signal it ends on.
                unsafe {
                    libc::signal(libc::SIGPIPE, libc::SIG_DFL);
                    libc::raise(libc::SIGPIPE);
                }
                code
            }
            Delivery::Closed => code,
            Delivery::Failed(e) => {
                eprintln!("error: cannot write the output to stdout: {e}");
                ExitCode::FAILURE
            }
        }
    }
}

/// Whether `fd` is a pipe (or FIFO).
fn is_pipe(fd: i32) -> bool {
    // SAFETY: fstat writes into a zeroed `stat` it owns for the call.
    let mut st: libc::stat = unsafe { std::mem::zeroed() };
    (unsafe { libc::fstat(fd, &mut st) } == 0) && (st.st_mode & libc::S_IFMT) == libc::S_IFIFO
}

/// Copies `from` to `to` until `from` ends; after a failed write it reads on and drops.
fn copy(mut from: std::io::PipeReader, mut to: std::fs::File) -> Delivery {
    let mut state = Delivery::Whole;
    let mut buffer = [0u8; 8192];
    loop {
        let n = match from.read(&mut buffer) {
            Ok(0) => return state,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(_) => return state,
        };
        if matches!(state, Delivery::Whole)
            && let Err(e) = to.write_all(&buffer[..n])
        {
            state = match e.kind() {
                std::io::ErrorKind::BrokenPipe => Delivery::Closed,
                _ => Delivery::Failed(e),
            };
        }
    }
}
