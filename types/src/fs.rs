//! Writing result files so that a crash or an interrupt never leaves a half-written one, and
//! reading input files so that a FIFO, a device or a huge file never hangs or exhausts memory.

use std::io::{Read, Write};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

/// A name no other call of this process (any thread) or other live process uses:
/// `<stem>.tmp<pid>-<n>` with `n` counted across the process.
fn temporary_name(path: &Path) -> std::path::PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(format!(".tmp{}-{n}", std::process::id()));
    path.with_file_name(name)
}

/// Writes `bytes` to `path` through a temporary file in the same folder (named after the file,
/// this process and a per-process counter, so two threads writing the same path never share
/// one) and a rename, creating the parent folder if needed. On failure the temporary file is
/// removed and `path` is left as it was.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let tmp = temporary_name(path);
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        std::fs::remove_file(&tmp).ok();
    }
    result
}

/// The largest config, `meta.json` or other small text input read \[bytes\] (1 MiB: the largest
/// shipped config is 4 KB).
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;
/// The largest data file read whole (`metrics.csv`, `compare.json`, a network's weights) \[bytes\]
/// (1 GiB: the largest network the trainer allows is about 1 GB of f32 weights).
pub const MAX_DATA_BYTES: u64 = 1 << 30;

/// Reads a regular file of at most `max_bytes`. Anything else is refused before it is opened
/// (a FIFO would block, `/dev/zero` never ends, a folder is not a file) and a larger file before
/// it is read, each with an `InvalidInput` error that says why; a file that grows past the cap
/// while read is refused too.
pub fn read_bounded(path: &Path, max_bytes: u64) -> std::io::Result<Vec<u8>> {
    let refuse = |why: String| std::io::Error::new(std::io::ErrorKind::InvalidInput, why);
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(refuse(
            "not a regular file (a folder, FIFO or device is never read)".into(),
        ));
    }
    if meta.len() > max_bytes {
        return Err(refuse(format!(
            "{} bytes, more than the {max_bytes} this file may have",
            meta.len()
        )));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::fs::File::open(path)?
        .take(max_bytes + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(refuse(format!(
            "grew past the {max_bytes} bytes this file may have while it was read"
        )));
    }
    Ok(bytes)
}

/// [`read_bounded`] as UTF-8 text (invalid UTF-8 is an `InvalidData` error).
pub fn read_text_bounded(path: &Path, max_bytes: u64) -> std::io::Result<String> {
    String::from_utf8(read_bounded(path, max_bytes)?).map_err(|e| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()),
        )
    })
}

/// The system's folder for temporary files: `TMPDIR` when it names an absolute folder, else
/// `/tmp` (an empty or relative `TMPDIR` would put them in the working directory).
pub fn system_temp_dir() -> std::path::PathBuf {
    let dir = std::env::temp_dir();
    if dir.is_absolute() {
        dir
    } else {
        std::path::PathBuf::from("/tmp")
    }
}

/// A file name fragment from a method or preset name: lowercase ASCII letters, digits and single
/// `_` between them (`"residual PPO: run_1"` → `"residual_ppo_run_1"`).
pub fn slug(s: &str) -> String {
    let mut out = String::new();
    for c in s.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    out.trim_matches('_').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_regular_files_within_the_cap_are_read() {
        let dir = std::env::temp_dir().join(format!("fairgrasp-bounded-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let small = dir.join("small.toml");
        std::fs::write(&small, "a = 1\n").unwrap();
        assert_eq!(read_text_bounded(&small, 100).unwrap(), "a = 1\n");
        let big = read_bounded(&small, 3).unwrap_err();
        assert!(big.to_string().contains("more than the 3"), "{big}");
        // A FIFO is refused before it is opened (opening it would block until a writer came).
        let fifo = dir.join("fifo.toml");
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(made.success());
        let e = read_bounded(&fifo, 100).unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
        // A device that never ends, and a folder.
        for path in [Path::new("/dev/zero"), dir.as_path()] {
            let e = read_bounded(path, MAX_CONFIG_BYTES).unwrap_err();
            assert!(
                e.to_string().contains("not a regular file"),
                "{}: {e}",
                path.display()
            );
        }
        std::fs::write(&small, [b'a', 0xff, b'b']).unwrap();
        let e = read_text_bounded(&small, 100).unwrap_err();
        assert!(e.to_string().contains("not UTF-8"), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn slug_keeps_letters_and_digits_and_squeezes_the_rest() {
        assert_eq!(slug("residual PPO: run_1"), "residual_ppo_run_1");
        assert_eq!(slug("  scripted   baseline (2) "), "scripted_baseline_2");
        assert_eq!(slug("../etc/passwd"), "etc_passwd");
    }

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir =
            std::env::temp_dir().join(format!("fairgrasp-types-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        dir
    }

    #[test]
    fn write_atomic_creates_the_folder_replaces_the_file_and_leaves_no_temporary() {
        let dir = scratch("replace");
        let path = dir.join("sub/result.json");
        write_atomic(&path, b"first").unwrap();
        write_atomic(&path, b"second").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        let names: Vec<_> = std::fs::read_dir(dir.join("sub"))
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("result.json")]);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn threads_writing_one_path_at_once_all_succeed_and_leave_one_whole_file() {
        let dir = scratch("threads");
        let path = dir.join("shared.bin");
        let payloads: Vec<Vec<u8>> = (0..8u8).map(|k| vec![k; 64 * 1024]).collect();
        std::thread::scope(|s| {
            for p in &payloads {
                let path = &path;
                s.spawn(move || {
                    for _ in 0..20 {
                        write_atomic(path, p).unwrap();
                    }
                });
            }
        });
        let bytes = std::fs::read(&path).unwrap();
        assert!(payloads.contains(&bytes), "a torn or mixed file");
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "temporaries left"
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn write_atomic_into_a_folder_path_fails_and_keeps_the_folder() {
        let dir = scratch("folder");
        std::fs::create_dir_all(dir.join("taken")).unwrap();
        assert!(write_atomic(&dir.join("taken"), b"x").is_err());
        assert!(dir.join("taken").is_dir());
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "temporary left behind"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}

/// One process per folder: an advisory lock (`flock`) on a lock file inside it, which holds the
/// pid of the process working there. The kernel releases the lock when that process ends,
/// however it ends, so a lock file left by a killed process is stale and is taken over
/// ([`FolderLock::stale_pid`] names it). `train` (its run folder) and `tune` (its `--out`)
/// both take it.
#[derive(Debug)]
pub struct FolderLock {
    file: std::fs::File,
    /// The pid a stale lock file named (a killed process), if any.
    pub stale_pid: Option<String>,
}

/// Why a [`FolderLock`] was not taken.
#[derive(Debug)]
pub enum LockRefused {
    /// Another live process holds it: the message names it, what it does and `flag`.
    InUse(String),
    /// The lock file is not a regular file: the message says what to do.
    NotAFile(String),
    /// Creating the folder or the lock file failed (the path and the error).
    Io(std::path::PathBuf, std::io::Error),
}

impl FolderLock {
    /// Takes the lock file `lock_name` of `dir` (both created if missing), or refuses naming
    /// the process that holds it, what it is `doing` there (`training`, `tuning`) and the
    /// `flag` that chooses another folder.
    pub fn acquire(
        dir: &Path,
        lock_name: &str,
        doing: &str,
        flag: &str,
    ) -> Result<FolderLock, LockRefused> {
        use std::fs::{OpenOptions, TryLockError};
        use std::io::Seek;
        std::fs::create_dir_all(dir).map_err(|e| LockRefused::Io(dir.to_path_buf(), e))?;
        let path = dir.join(lock_name);
        if path.exists() && !path.is_file() {
            return Err(LockRefused::NotAFile(format!(
                "{} is not a regular file: remove it to work in {}",
                path.display(),
                dir.display()
            )));
        }
        let io = |e| LockRefused::Io(path.clone(), e);
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(io)?;
        let mut holder = String::new();
        // Best effort: the pid is only for the message.
        let _ = (&file).take(64).read_to_string(&mut holder);
        let holder = holder.trim().to_string();
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                let who = if holder.is_empty() {
                    "another process".to_string()
                } else {
                    format!("process {holder}")
                };
                return Err(LockRefused::InUse(format!(
                    "{} is in use: {who} is {doing} in it ({}); wait for it to end, or choose another {flag}",
                    dir.display(),
                    path.display()
                )));
            }
            Err(TryLockError::Error(e)) => return Err(io(e)),
        }
        let write_pid = |f: &mut std::fs::File| -> std::io::Result<()> {
            f.set_len(0)?;
            f.rewind()?;
            writeln!(f, "{}", std::process::id())?;
            f.sync_data()
        };
        write_pid(&mut file).map_err(io)?;
        Ok(FolderLock {
            file,
            stale_pid: (!holder.is_empty()).then_some(holder),
        })
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        // Emptied first, so a later reader never takes a finished process's pid for a holder.
        let _ = self.file.set_len(0);
        let _ = self.file.unlock();
    }
}
