//! Streams as Unix tools treat them. A closed pipe (`fairgrasp … | head -1`) ends a command
//! quietly, by SIGPIPE's default action, which Rust's runtime turns off; a stdout that cannot
//! be written (a full disk, `> /dev/full`) is a one-line error with exit code 1.
//!
//! A command that writes files finishes them first, whatever becomes of its streams: its stdout
//! (unless a terminal) and its stderr when a reader can close it (a pipe or socket, or the same
//! file as stdout: `2>&1`) go through a [`Relay`], a pipe a thread copies to the real stream.
//! A write the real stream refuses (its reader gone, its disk full) is the relay's to drop, so
//! a closed pipe or a full log never stops the command mid-way (`println!`/`eprintln!` would
//! panic; a progress line to a closed stderr used to end `compare` and `tune` with nothing
//! written); once its files are whole, the command ends as a short one would.

use std::io::{Read, Write};
use std::os::fd::{AsRawFd, FromRawFd, OwnedFd, RawFd};
use std::path::PathBuf;
use std::process::ExitCode;

use crate::error_message;

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
            let message = error_message::stdout_failure(file_behind(1).as_deref(), reason);
            // Never a second panic: a stderr that cannot be written either stays empty.
            let _ = writeln!(std::io::stderr(), "error: {message}");
            std::process::exit(1);
        }
        default(info);
    }));
}

/// What became of the output a relay carried.
#[derive(Debug)]
enum Delivery {
    /// All of it reached the real stream.
    Whole,
    /// The reader closed the pipe; the rest was dropped.
    Closed,
    /// Writing failed otherwise (a full disk); the rest was dropped.
    Failed(std::io::Error),
}

/// One relayed stream: the descriptors it stands in for (1, 2, or both when they are one
/// file), the real stream they pointed to, and the thread copying into it.
struct Route {
    fds: Vec<RawFd>,
    original: OwnedFd,
    copier: std::thread::JoinHandle<Delivery>,
}

/// The process's stdout and stderr, where a reader can close them or a disk refuse them,
/// replaced by pipes that threads copy to the real ones: a write the real stream refuses
/// never reaches the command, which runs on.
pub struct Relay {
    routes: Vec<Route>,
}

/// How a descriptor is connected.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Sink {
    /// A terminal (never relayed: progress bars ask whether stderr is one).
    Terminal,
    /// A pipe or socket: its reader can go away.
    Pipe,
    /// A file or device: its writes can fail (a full disk, `/dev/full`).
    File,
    /// Not open.
    Closed,
}

/// What `fd` is connected to, and its device and inode (to tell whether two are one file).
fn sink_of(fd: RawFd) -> (Sink, (u64, u64)) {
    // SAFETY: fstat writes into a zeroed `stat` it owns for the call; isatty only reads `fd`.
    let mut st: libc::stat = unsafe { std::mem::zeroed() };
    if unsafe { libc::fstat(fd, &mut st) } != 0 {
        return (Sink::Closed, (0, 0));
    }
    let kind = st.st_mode & libc::S_IFMT;
    let sink = if unsafe { libc::isatty(fd) } == 1 {
        Sink::Terminal
    } else if kind == libc::S_IFIFO || kind == libc::S_IFSOCK {
        Sink::Pipe
    } else {
        Sink::File
    };
    (sink, (st.st_dev as u64, st.st_ino as u64))
}

impl Relay {
    /// Relays stdout unless it is a terminal, and stderr when it is a pipe or socket or the
    /// same file as stdout (then both share one relay, so their lines keep their order); None
    /// when neither is relayed or a pipe cannot be made (the output then goes straight out).
    pub fn start() -> Option<Relay> {
        let (out, out_file) = sink_of(1);
        let (err, err_file) = sink_of(2);
        let relay_out = matches!(out, Sink::Pipe | Sink::File);
        let shared = relay_out && err != Sink::Closed && out_file == err_file;
        let mut plan: Vec<Vec<RawFd>> = Vec::new();
        if relay_out {
            plan.push(if shared { vec![1, 2] } else { vec![1] });
        }
        if !shared && err == Sink::Pipe {
            plan.push(vec![2]);
        }
        if plan.is_empty() {
            return None;
        }
        // SAFETY: SIGPIPE ignored makes a write to a closed pipe an EPIPE error the copier
        // sees, not the process's end.
        unsafe {
            libc::signal(libc::SIGPIPE, libc::SIG_IGN);
        }
        let mut relay = Relay { routes: Vec::new() };
        for fds in plan {
            match Route::start(fds) {
                Some(route) => relay.routes.push(route),
                None if relay.routes.is_empty() => {
                    // SAFETY: restoring the default action; nothing is relayed.
                    unsafe {
                        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
                    }
                    return None;
                }
                None => {}
            }
        }
        Some(relay)
    }

    /// Ends the relay once the command is done (`succeeded` as it returned): the real streams
    /// are put back, everything the command printed is copied, then a closed stdout ends the
    /// process as it ends a short command (by SIGPIPE, quietly) if the command succeeded, and
    /// a stdout that refused the output is a one-line error with exit code 1.
    pub fn finish(self, code: ExitCode, succeeded: bool) -> ExitCode {
        std::io::stdout().flush().ok();
        // The real streams back on 1 and 2 close the relays' last write ends: each copier
        // reads its pipe to the end.
        for route in &self.routes {
            for fd in &route.fds {
                // SAFETY: both descriptors are open; dup2 replaces `fd` atomically.
                unsafe {
                    libc::dup2(route.original.as_raw_fd(), *fd);
                }
            }
        }
        let mut stdout = Delivery::Whole;
        let mut stderr = Delivery::Whole;
        for route in self.routes {
            let delivery = route.copier.join().unwrap_or(Delivery::Whole);
            if route.fds.contains(&1) {
                stdout = delivery;
            } else {
                stderr = delivery;
            }
        }
        match (stdout, stderr) {
            (Delivery::Failed(e), _) => {
                let message =
                    error_message::stdout_failure(file_behind(1).as_deref(), &e.to_string());
                let _ = writeln!(std::io::stderr(), "error: {message}");
                ExitCode::FAILURE
            }
            (Delivery::Closed, _) if succeeded => {
                // SAFETY: restoring the default action, then raising the signal it ends on.
                unsafe {
                    libc::signal(libc::SIGPIPE, libc::SIG_DFL);
                    libc::raise(libc::SIGPIPE);
                }
                code
            }
            // A log that could not be written (a full disk): nothing can say so.
            (_, Delivery::Failed(_)) if succeeded => ExitCode::FAILURE,
            _ => code,
        }
    }
}

impl Route {
    /// Points every descriptor of `fds` (1, 2 or both) at a new pipe whose other end a thread
    /// copies to the stream `fds[0]` pointed to; None (nothing changed) if it cannot.
    fn start(fds: Vec<RawFd>) -> Option<Route> {
        // SAFETY: dup of an open descriptor; the new one is owned here.
        let original = unsafe { libc::fcntl(fds[0], libc::F_DUPFD_CLOEXEC, 3) };
        if original < 0 {
            return None;
        }
        // SAFETY: `original` is a descriptor this function just made and owns.
        let original = unsafe { OwnedFd::from_raw_fd(original) };
        let (reader, writer) = std::io::pipe().ok()?;
        for (i, fd) in fds.iter().enumerate() {
            // SAFETY: both descriptors are open; dup2 replaces `fd` atomically.
            if unsafe { libc::dup2(writer.as_raw_fd(), *fd) } < 0 {
                for done in &fds[..i] {
                    // SAFETY: putting back the stream this route had replaced.
                    unsafe {
                        libc::dup2(original.as_raw_fd(), *done);
                    }
                }
                return None;
            }
        }
        drop(writer);
        let target = std::fs::File::from(original.try_clone().ok()?);
        let copier = std::thread::spawn(move || copy(reader, target));
        Some(Route {
            fds,
            original,
            copier,
        })
    }
}

/// The regular file `fd` writes to (for a message about a full disk), if it is one.
fn file_behind(fd: RawFd) -> Option<PathBuf> {
    if sink_of(fd).0 != Sink::File {
        return None;
    }
    let path = std::fs::read_link(format!("/proc/self/fd/{fd}")).ok()?;
    std::fs::metadata(&path)
        .is_ok_and(|m| m.is_file())
        .then_some(path)
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
