//! The one way a command's error becomes its message: its causes once each (a cause already
//! quoted by the message before it is not repeated), a full disk named with where it is mounted
//! and how much room it has, a path through a dangling symbolic link named as such with its
//! target, and the whole bounded ([`fairgrasp_types::text::bounded_message`]).

use std::path::{Path, PathBuf};

use fairgrasp_types::text::bounded_message;

/// The message `error: …` prints for `err`.
pub fn render(err: &anyhow::Error) -> String {
    let mut message = String::new();
    for cause in err.chain() {
        let cause = cause.to_string();
        if message.ends_with(&cause) {
            continue;
        }
        if !message.is_empty() {
            message.push_str(": ");
        }
        message.push_str(&cause);
    }
    with_notes(without_repeated_paths(&message))
}

/// The message `error: …` prints when the output cannot be written to stdout: `reason` as
/// the OS gave it, with the file stdout goes to (`target`, a regular file: `> out.json`) and,
/// on a full disk, which disk it is, as every other full disk is named. A device (`/dev/full`)
/// or a pipe is no disk: only the reason is given.
pub fn stdout_failure(target: Option<&Path>, reason: &str) -> String {
    match target {
        Some(file) => with_notes(format!(
            "cannot write the output to stdout, {}: {reason}",
            file.display()
        )),
        None => bounded_message(&format!("cannot write the output to stdout: {reason}")),
    }
}

/// `message` with the notes it calls for (a full disk, a dangling link), bounded.
fn with_notes(mut message: String) -> String {
    for note in [full_disk_note(&message), dangling_link_note(&message)]
        .into_iter()
        .flatten()
    {
        message.push_str("; ");
        message.push_str(&note);
    }
    bounded_message(&message)
}

/// `message` without a `PATH: ` that the part after it repeats or names a file under
/// (`…/episodes: …/episodes/a.json.gz: No space left…` says the folder once): an error that
/// names its file, wrapped by one that names the file's folder, reads as one.
fn without_repeated_paths(message: &str) -> String {
    let parts: Vec<&str> = message.split(": ").collect();
    let mut kept: Vec<&str> = Vec::with_capacity(parts.len());
    for (i, part) in parts.iter().enumerate() {
        let repeated = parts.get(i + 1).is_some_and(|next| {
            part.contains('/')
                && (next == part
                    || next
                        .strip_prefix(part)
                        .is_some_and(|rest| rest.starts_with('/')))
        });
        if !repeated {
            kept.push(part);
        }
    }
    kept.join(": ")
}

/// The paths a message names: its words that hold a `/` or end in `:` (a file named first),
/// without the punctuation around them; at most the first 32.
fn named_paths(message: &str) -> impl Iterator<Item = &Path> {
    message
        .split_whitespace()
        .filter(|w| w.contains('/') || w.ends_with(':'))
        .map(|w| w.trim_matches(|c: char| "`'\",;:()".contains(c)))
        .filter(|w| !w.is_empty())
        .take(32)
        .map(Path::new)
}

/// For a message that names a path which is, or lies under, a symbolic link to nothing: the
/// link and where it points (the OS says only "No such file or directory" or "File exists").
pub fn dangling_link_note(message: &str) -> Option<String> {
    named_paths(message)
        .flat_map(Path::ancestors)
        .filter(|p| !p.as_os_str().is_empty())
        .find_map(|p| {
            let target = std::fs::read_link(p).ok()?;
            let missing =
                std::fs::metadata(p).is_err_and(|e| e.kind() == std::io::ErrorKind::NotFound);
            missing.then(|| {
                format!(
                    "{} is a dangling symbolic link: it points to {}, which does not exist \
                     (remove the link or give another path)",
                    p.display(),
                    target.display()
                )
            })
        })
}

/// What the OS says of a full disk (ENOSPC) and of a full quota (EDQUOT).
const FULL: [&str; 2] = ["(os error 28)", "(os error 122)"];

/// For a message that reports a full disk: which disk holds the file it names (the word before
/// the OS's reason that has a `/`; the working folder otherwise), where that disk is mounted,
/// its size and its free space.
pub fn full_disk_note(message: &str) -> Option<String> {
    let at = FULL.iter().filter_map(|f| message.find(f)).min()?;
    let reason_start = message[..at].rfind(": ").unwrap_or(0);
    let named = message[..reason_start]
        .split_whitespace()
        .rev()
        .map(|w| w.trim_end_matches(':'))
        .find(|w| w.contains('/'))
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("."));
    let existing = named
        .ancestors()
        .find(|p| !p.as_os_str().is_empty() && p.exists())
        .unwrap_or(Path::new("."));
    let place = std::fs::canonicalize(existing).ok()?;
    let (mount_point, source) = mount_of(&place).unwrap_or_else(|| ("?".into(), "?".into()));
    let room = match room_of(&place) {
        Some((free, size)) => format!("{} in all, {} free now", bytes(size), bytes(free)),
        None => "its size unknown".into(),
    };
    Some(format!(
        "the disk holding {} ran out of space ({source} mounted on {mount_point}: {room}): \
         free space there or write the output to another disk",
        existing.display()
    ))
}

/// The mount point and source (device) of the file system holding `path` (canonical), from
/// `/proc/self/mountinfo`: the longest mount point that contains it.
fn mount_of(path: &Path) -> Option<(String, String)> {
    let table = std::fs::read_to_string("/proc/self/mountinfo").ok()?;
    table
        .lines()
        .filter_map(|line| {
            let fields: Vec<&str> = line.split(' ').collect();
            let mount_point = unescape(fields.get(4)?);
            let dash = fields.iter().position(|f| *f == "-")?;
            let source = unescape(fields.get(dash + 2)?);
            path.starts_with(&mount_point)
                .then_some((mount_point, source))
        })
        .max_by_key(|(mount_point, _)| mount_point.len())
}

/// mountinfo's octal escapes (`\040` for a space) undone.
fn unescape(field: &str) -> String {
    let mut out = String::new();
    let mut rest = field;
    while let Some(i) = rest.find('\\') {
        out.push_str(&rest[..i]);
        match u8::from_str_radix(rest.get(i + 1..i + 4).unwrap_or(""), 8) {
            Ok(b) => {
                out.push(b as char);
                rest = &rest[i + 4..];
            }
            Err(_) => {
                out.push('\\');
                rest = &rest[i + 1..];
            }
        }
    }
    out.push_str(rest);
    out
}

/// The free bytes (for an unprivileged user) and the size of the file system holding `path`.
fn room_of(path: &Path) -> Option<(u64, u64)> {
    use std::os::unix::ffi::OsStrExt;
    let c_path = std::ffi::CString::new(path.as_os_str().as_bytes()).ok()?;
    // SAFETY: a NUL-terminated path and a zeroed statvfs the call fills.
    let mut st: libc::statvfs = unsafe { std::mem::zeroed() };
    if unsafe { libc::statvfs(c_path.as_ptr(), &mut st) } != 0 {
        return None;
    }
    let unit = st.f_frsize as u64;
    Some((st.f_bavail as u64 * unit, st.f_blocks as u64 * unit))
}

/// A byte count in the largest binary unit that keeps it at 1 or more (`1.0 MiB`, `0 B`).
fn bytes(n: u64) -> String {
    let units = ["KiB", "MiB", "GiB", "TiB"];
    let mut value = n as f64;
    let mut unit = "B";
    for u in units {
        if value < 1024.0 {
            break;
        }
        value /= 1024.0;
        unit = u;
    }
    if unit == "B" {
        format!("{n} B")
    } else {
        format!("{value:.1} {unit}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_disk_is_named_by_its_mount_point_size_and_free_space() {
        let message = "/tmp/x.partial-1/replay.gif: No space left on device (os error 28)";
        let note = full_disk_note(message).expect("a full disk");
        let tmp = std::fs::canonicalize("/tmp").unwrap();
        let (mount_point, _) = mount_of(&tmp).unwrap();
        assert!(
            note.starts_with("the disk holding /tmp ran out of space ("),
            "{note}"
        );
        assert!(
            note.contains(&format!("mounted on {mount_point}: ")),
            "{note}"
        );
        assert!(
            note.contains(" in all, ") && note.contains(" free now"),
            "{note}"
        );
        // A quota, a relative path, no path at all.
        assert!(full_disk_note("runs/a/model.bpk: Disk quota exceeded (os error 122)").is_some());
        assert!(
            full_disk_note("write failed: No space left on device (os error 28)")
                .is_some_and(|n| n.starts_with("the disk holding . ran out of space"))
        );
        assert_eq!(
            full_disk_note("x.csv: Permission denied (os error 13)"),
            None
        );
    }

    /// An error that quotes its cause, as `#[error("{path}: {source}")]` does.
    #[derive(Debug)]
    struct Quoting(std::io::Error);

    impl std::fmt::Display for Quoting {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            write!(f, "a.csv: {}", self.0)
        }
    }

    impl std::error::Error for Quoting {
        fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
            Some(&self.0)
        }
    }

    #[test]
    fn a_cause_the_message_already_quotes_is_not_repeated() {
        let io = std::io::Error::from_raw_os_error(13);
        let shown = io.to_string();
        let err = anyhow::Error::new(Quoting(io)).context("writing the report");
        assert_eq!(
            format!("{err:#}"),
            format!("writing the report: a.csv: {shown}: {shown}")
        );
        assert_eq!(render(&err), format!("writing the report: a.csv: {shown}"));
    }

    #[test]
    fn a_path_under_a_dangling_link_names_the_link_and_its_target() {
        let dir = std::env::temp_dir().join(format!("fairgrasp-dangling-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let link = dir.join("out");
        std::fs::remove_file(&link).ok();
        std::os::unix::fs::symlink("/nonexistent/target", &link).unwrap();
        let message = format!(
            "{}/episode_0000.png: File exists (os error 17)",
            link.display()
        );
        let note = dangling_link_note(&message).expect("a dangling link");
        assert_eq!(
            note,
            format!(
                "{} is a dangling symbolic link: it points to /nonexistent/target, which does not \
                 exist (remove the link or give another path)",
                link.display()
            )
        );
        // A link to something that exists is no matter.
        std::fs::remove_file(&link).unwrap();
        std::os::unix::fs::symlink(&dir, &link).unwrap();
        assert_eq!(dangling_link_note(&message), None);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_folder_named_before_a_file_in_it_is_said_once() {
        let full = "No space left on device (os error 28)";
        assert_eq!(
            without_repeated_paths(&format!(
                "/d/r.partial-1/episodes: /d/r.partial-1/episodes: {full}"
            )),
            format!("/d/r.partial-1/episodes: {full}")
        );
        assert_eq!(
            without_repeated_paths(&format!("/d/episodes: /d/episodes/a.json.gz: {full}")),
            format!("/d/episodes/a.json.gz: {full}")
        );
        // A sibling whose name starts alike, a word that is no path, a wrapping context: kept.
        for kept in [
            format!("/d/episodes: /d/episodes_old/a.csv: {full}"),
            format!("preset `fixed`: preset `fixed`: {full}"),
            format!("--out /d/r: /d/r/a.md: {full}"),
        ] {
            assert_eq!(without_repeated_paths(&kept), kept);
        }
    }

    #[test]
    fn stdout_onto_a_full_disk_names_the_file_and_the_disk_but_a_device_is_no_disk() {
        let reason = "No space left on device (os error 28)";
        let tmp = std::fs::canonicalize("/tmp").unwrap();
        let file = tmp.join("out.json");
        let message = stdout_failure(Some(&file), reason);
        assert!(
            message.starts_with(&format!(
                "cannot write the output to stdout, {}: {reason}; the disk holding {} ran out of space (",
                file.display(),
                tmp.display()
            )),
            "{message}"
        );
        assert_eq!(
            stdout_failure(None, reason),
            format!("cannot write the output to stdout: {reason}")
        );
    }

    #[test]
    fn sizes_are_shown_in_binary_units() {
        assert_eq!(bytes(0), "0 B");
        assert_eq!(bytes(1023), "1023 B");
        assert_eq!(bytes(1 << 20), "1.0 MiB");
        assert_eq!(bytes(3 << 29), "1.5 GiB");
        assert_eq!(unescape("/mnt/a\\040b"), "/mnt/a b");
    }
}
