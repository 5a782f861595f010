//! Writing result files so that a crash or an interrupt never leaves a half-written one.

use std::io::Write;
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
