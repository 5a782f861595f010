//! The one rule for writing an output file over an existing path: a command replaces only a
//! regular file that fairgrasp wrote, recognised by the mark every generated chart, replay and
//! page carries near its start ([`GENERATOR`]). It never replaces an input (a CSV, a model, a
//! config carries no mark), a folder, a device or a pipe, nor any file inside a report folder
//! (those are `compare`'s and `report`'s, replaced whole or not at all).

use std::io::Read;
use std::path::{Path, PathBuf};

/// The mark of a generated file: a PNG's `Software` text chunk, a GIF's comment, an HTML page's
/// `generator` meta tag.
pub const GENERATOR: &str = "fairgrasp";

/// The file a report folder holds that lists what `compare` / `report` wrote into it.
pub const REPORT_MARKER: &str = ".fairgrasp-report";

/// How far into a file its mark is looked for \[bytes\].
const HEAD_BYTES: u64 = 64 * 1024;

/// PNG's signature.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

/// The start of a file, if it is a regular file (nothing else is opened).
pub fn head(path: &Path) -> Option<Vec<u8>> {
    if !std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        return None;
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .ok()?
        .take(HEAD_BYTES)
        .read_to_end(&mut bytes)
        .ok()?;
    Some(bytes)
}

fn contains(haystack: &[u8], needle: &[u8]) -> bool {
    haystack.windows(needle.len()).any(|w| w == needle)
}

/// Whether `head` starts a PNG fairgrasp wrote (its `tEXt` chunk `Software` = [`GENERATOR`]).
pub fn png_is_ours(head: &[u8]) -> bool {
    head.starts_with(PNG_SIGNATURE) && contains(head, b"tEXtSoftware\0fairgrasp")
}

/// Whether `head` starts a GIF fairgrasp wrote (a comment extension holding [`GENERATOR`]).
pub fn gif_is_ours(head: &[u8]) -> bool {
    head.starts_with(b"GIF89a") && contains(head, b"\x21\xfe\x09fairgrasp")
}

/// The report folder (holding [`REPORT_MARKER`]) that `path` lies inside, if any.
pub fn report_folder_around(path: &Path) -> Option<PathBuf> {
    let absolute = std::path::absolute(path).ok()?;
    absolute
        .ancestors()
        .skip(1)
        .find(|dir| dir.join(REPORT_MARKER).exists())
        .map(Path::to_path_buf)
}

/// Checks that `path` may be written by a command whose files of this kind `is_ours`
/// recognises (`what` names the kind, e.g. "chart"). Missing paths are fine; an existing one
/// must be a regular file that `is_ours`; nothing inside a report folder is. The message names
/// the path and says what to do.
pub fn check_replaceable(
    path: &Path,
    what: &str,
    is_ours: impl Fn(&[u8]) -> bool,
) -> Result<(), String> {
    let shown = path.display();
    if let Some(report) = report_folder_around(path) {
        return Err(format!(
            "{shown} is inside the report folder {}, which only `fairgrasp compare` and \
             `fairgrasp report` write (replaced whole, with --force): choose a path outside it",
            report.display()
        ));
    }
    match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(format!("{shown}: {e}")),
        Ok(_) => {}
    }
    match head(path) {
        None => Err(format!(
            "{shown} exists and is not a regular file (a folder, a device or a pipe): it is never \
             written over; choose a file name"
        )),
        Some(bytes) if is_ours(&bytes) => Ok(()),
        Some(_) => Err(format!(
            "{shown} exists and is not a {what} fairgrasp wrote: it is never replaced; choose \
             another name, or move the file away first"
        )),
    }
}

/// Whether `name` is a file an episode recording writes (`episode_NNNN.csv` / `.json`, and the
/// `.png`, `.gif` and `_stepN.png` that `plot` draws beside it).
pub fn is_episode_file(name: &str) -> bool {
    let Some(rest) = name.strip_prefix("episode_") else {
        return false;
    };
    let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
    let tail = &rest[digits..];
    let step_png = tail
        .strip_prefix("_step")
        .and_then(|t| t.strip_suffix(".png"))
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()));
    digits > 0 && ([".csv", ".json", ".png", ".gif"].contains(&tail) || step_png)
}

/// Checks a folder episodes are recorded into (`--record DIR`): new or empty, and not inside a
/// report folder. A folder holding earlier recordings is refused too: a new recording would
/// leave its `episode_*` files beside the earlier ones (a shorter run leaves the earlier
/// run's later episodes) with nothing to tell the two runs apart.
pub fn check_record_folder(dir: &Path) -> Result<(), String> {
    let shown = dir.display();
    if let Some(report) = report_folder_around(&dir.join("episode_0000.json")) {
        return Err(format!(
            "{shown} is inside the report folder {}, which only `fairgrasp compare` and \
             `fairgrasp report` write: record elsewhere",
            report.display()
        ));
    }
    let entries = match std::fs::read_dir(dir) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(_) if dir.exists() => {
            return Err(format!(
                "{shown} exists and is not a folder: record into a folder"
            ));
        }
        Err(e) => return Err(format!("{shown}: {e}")),
        Ok(entries) => entries,
    };
    let mut episodes = Vec::new();
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if !is_episode_file(&name) {
            return Err(format!(
                "{shown} holds {name}, which is not an episode recording: episodes are recorded \
                 only into a new or empty folder; choose another folder"
            ));
        }
        episodes.push(name);
    }
    if !episodes.is_empty() {
        episodes.sort();
        return Err(format!(
            "{shown} holds {} episode files of an earlier recording ({}): a new recording would \
             mix with them; record into a new or empty folder (or delete them first)",
            episodes.len(),
            crate::text::first_few(&episodes, 3)
        ));
    }
    Ok(())
}

/// A recording made whole or not at all: its episodes are written into a staging folder beside
/// the recording's folder (`DIR.recording-PID`), which takes its place only once every episode
/// is written ([`StagedRecording::finish`]). A recording that fails (a full disk, an error, a
/// panic) removes the staging folder when dropped and leaves `DIR` as it was.
#[derive(Debug)]
pub struct StagedRecording {
    target: PathBuf,
    staging: PathBuf,
    finished: bool,
}

impl StagedRecording {
    /// Checks `dir` ([`check_record_folder`]) and makes the staging folder beside it.
    pub fn start(dir: &Path) -> Result<StagedRecording, String> {
        check_record_folder(dir)?;
        // An existing folder by its real name (`.`, a link): the staging folder goes beside it.
        let dir = &std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
        let Some(name) = dir.file_name() else {
            return Err(format!("{}: record into a named folder", dir.display()));
        };
        let mut name = name.to_os_string();
        name.push(format!(".recording-{}", std::process::id()));
        let staging = dir.with_file_name(name);
        let _ = std::fs::remove_dir_all(&staging);
        std::fs::create_dir_all(&staging).map_err(|e| format!("{}: {e}", staging.display()))?;
        Ok(StagedRecording {
            target: dir.to_path_buf(),
            staging,
            finished: false,
        })
    }

    /// The folder the episodes are written into meanwhile.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// Puts the recording in its place: the staging folder becomes `DIR` (an empty `DIR` is
    /// replaced by it).
    pub fn finish(mut self) -> Result<(), String> {
        std::fs::rename(&self.staging, &self.target).map_err(|e| {
            format!(
                "{}: {e} (moving the finished recording from {})",
                self.target.display(),
                self.staging.display()
            )
        })?;
        self.finished = true;
        Ok(())
    }
}

impl Drop for StagedRecording {
    fn drop(&mut self) {
        if !self.finished {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_staged_recording_appears_whole_or_leaves_the_folder_as_it_was() {
        let dir = std::env::temp_dir().join(format!("fairgrasp-staged-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let target = dir.join("rec");
        // Dropped before it finishes: nothing is left, not even the staging folder.
        let staged = StagedRecording::start(&target).unwrap();
        std::fs::write(staged.path().join("episode_0000.csv"), "t\n").unwrap();
        drop(staged);
        assert!(!target.exists());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        // Finished into an empty folder the user made: it holds the episodes.
        std::fs::create_dir(&target).unwrap();
        let staged = StagedRecording::start(&target).unwrap();
        std::fs::write(staged.path().join("episode_0000.csv"), "t\n").unwrap();
        staged.finish().unwrap();
        assert!(target.join("episode_0000.csv").is_file());
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "no staging folder left"
        );
        // A folder that holds a recording is refused before anything is written.
        assert!(StagedRecording::start(&target).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn only_marked_regular_files_outside_report_folders_are_replaced() {
        let dir = std::env::temp_dir().join(format!("fairgrasp-output-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("report")).unwrap();
        let ours = dir.join("chart.png");
        std::fs::write(&ours, b"\x89PNG\r\n\x1a\n....tEXtSoftware\0fairgrasp").unwrap();
        let theirs = dir.join("photo.png");
        std::fs::write(&theirs, b"\x89PNG\r\n\x1a\n....tEXtSoftware\0GIMP").unwrap();
        let csv = dir.join("metrics.csv");
        std::fs::write(&csv, b"update,success\n1,0.5\n").unwrap();
        assert_eq!(check_replaceable(&ours, "chart", png_is_ours), Ok(()));
        assert_eq!(
            check_replaceable(&dir.join("new.png"), "chart", png_is_ours),
            Ok(())
        );
        for (path, words) in [
            (&theirs, "not a chart fairgrasp wrote"),
            (&csv, "not a chart fairgrasp wrote"),
            (&dir, "not a regular file"),
            (&PathBuf::from("/dev/null"), "not a regular file"),
        ] {
            let e = check_replaceable(path, "chart", png_is_ours).unwrap_err();
            assert!(e.contains(words), "{}: {e}", path.display());
        }
        std::fs::write(dir.join("report").join(REPORT_MARKER), "").unwrap();
        let inside = dir.join("report/sub/new.png");
        let e = check_replaceable(&inside, "chart", png_is_ours).unwrap_err();
        assert!(e.contains("inside the report folder"), "{e}");
        assert!(gif_is_ours(b"GIF89a......\x21\xfe\x09fairgrasp\x00"));
        assert!(!gif_is_ours(b"GIF89a......\x21\xfe\x05hello\x00"));
        for name in [
            "episode_0001.csv",
            "episode_12.json",
            "episode_0003_step40.png",
        ] {
            assert!(is_episode_file(name), "{name}");
        }
        for name in [
            "episode_.csv",
            "episode_0001.toml",
            "episode_1_step.png",
            "notes.md",
        ] {
            assert!(!is_episode_file(name), "{name}");
        }
        std::fs::write(dir.join("report/episode_0001.csv"), "").unwrap();
        assert!(check_record_folder(&dir.join("report")).is_err());
        let record = dir.join("record");
        assert_eq!(check_record_folder(&record), Ok(()));
        std::fs::create_dir_all(&record).unwrap();
        assert_eq!(check_record_folder(&record), Ok(()));
        for i in 0..5 {
            std::fs::write(record.join(format!("episode_{i:04}.csv")), "").unwrap();
        }
        let e = check_record_folder(&record).unwrap_err();
        assert!(
            e.contains("holds 5 episode files")
                && e.contains("episode_0000.csv, episode_0001.csv, episode_0002.csv and 2 more")
                && e.contains("new or empty folder"),
            "{e}"
        );
        std::fs::write(record.join("thesis.tex"), "").unwrap();
        assert!(
            check_record_folder(&record)
                .unwrap_err()
                .contains("thesis.tex")
        );
        assert!(
            check_record_folder(&csv)
                .unwrap_err()
                .contains("not a folder")
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
