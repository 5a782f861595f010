//! `.fairgrasp-report`: the file by which fairgrasp recognises an output folder it wrote. It
//! lists every file written there with its size and FNV-1a hash, so that `--force` can tell a
//! folder left as written from one whose files the user has edited or added to.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{ReportError, read_text, write_file};

/// The marker's file name, at the top of the output folder.
pub const MARKER: &str = ".fairgrasp-report";

/// Sub-folders deeper than this are not searched: what lies below counts as not written by
/// fairgrasp (fairgrasp writes at most one level, `episodes/`).
const MAX_DEPTH: usize = 8;

/// What the marker says about its folder.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FolderMarker {
    /// The command that wrote the folder, e.g. `fairgrasp compare`.
    pub written_by: String,
    /// For the user who opens the file.
    #[serde(default)]
    pub note: String,
    /// Every file written, by path relative to the folder (`/`-separated).
    pub files: BTreeMap<String, FileStamp>,
}

/// A file's size and content hash when fairgrasp wrote it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileStamp {
    pub bytes: u64,
    /// FNV-1a (64 bit) of the content, 16 hex digits: detects edits, not tampering.
    pub fnv1a64: String,
}

/// Something in a marked folder that fairgrasp did not write as it is now.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Change {
    /// A listed file whose content differs.
    Edited(String),
    /// A file (or link, or anything else) the marker does not list.
    Added(String),
}

impl std::fmt::Display for Change {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Edited(p) => write!(f, "{p} (edited since fairgrasp wrote it)"),
            Self::Added(p) => write!(f, "{p} (added since fairgrasp wrote the folder)"),
        }
    }
}

/// One entry found by [`walk`]: relative name, full path, and whether it is a regular file.
struct Entry {
    name: String,
    path: std::path::PathBuf,
    is_file: bool,
}

impl FolderMarker {
    /// The marker of `dir` as it is now: every regular file below it (the marker excepted).
    pub fn of_folder(dir: &Path, written_by: &str) -> Result<Self, ReportError> {
        let mut files = BTreeMap::new();
        for entry in walk(dir)? {
            if !entry.is_file {
                return Err(ReportError::malformed(
                    &entry.path,
                    "not a regular file or folder: fairgrasp writes neither links nor devices",
                ));
            }
            files.insert(entry.name, stamp(&entry.path)?);
        }
        Ok(Self {
            written_by: written_by.to_string(),
            note: format!(
                "Written by `{written_by}`. `--force` replaces this folder only while every file \
                 in it is listed here, unchanged. Delete this file and fairgrasp will never \
                 replace the folder."
            ),
            files,
        })
    }

    /// Writes the marker into `dir`.
    pub fn write(&self, dir: &Path) -> Result<(), ReportError> {
        let json = serde_json::to_string_pretty(self).expect("a marker serialises");
        write_file(&dir.join(MARKER), json.as_bytes())
    }

    /// The marker of `dir`: `None` if it has none; an error if the file is unreadable or not
    /// a marker.
    pub fn read(dir: &Path) -> Result<Option<Self>, ReportError> {
        let path = dir.join(MARKER);
        if std::fs::symlink_metadata(&path).is_err() {
            return Ok(None);
        }
        let text = read_text(&path)?;
        serde_json::from_str(&text)
            .map(Some)
            .map_err(|e| ReportError::malformed(&path, format!("not a fairgrasp marker: {e}")))
    }

    /// What in `dir` differs from the marker: edited and added files, in path order. Listed
    /// files that are gone do not count (deleting loses nothing).
    pub fn changes(&self, dir: &Path) -> Result<Vec<Change>, ReportError> {
        let mut changes = Vec::new();
        for entry in walk(dir)? {
            match self.files.get(&entry.name) {
                Some(listed) if entry.is_file => {
                    if stamp(&entry.path)? != *listed {
                        changes.push(Change::Edited(entry.name));
                    }
                }
                _ => changes.push(Change::Added(entry.name)),
            }
        }
        Ok(changes)
    }
}

/// Every entry below `dir` that is not a folder (the top-level marker excepted), in name order.
/// Sub-folders are searched, links are not followed; a name that is not UTF-8, or a folder
/// deeper than [`MAX_DEPTH`], is reported as an entry that is not a regular file.
fn walk(dir: &Path) -> Result<Vec<Entry>, ReportError> {
    let mut out = Vec::new();
    let mut pending = vec![(dir.to_path_buf(), String::new(), 0usize)];
    while let Some((folder, prefix, depth)) = pending.pop() {
        let mut children: Vec<_> = std::fs::read_dir(&folder)
            .map_err(|e| ReportError::io(&folder, e))?
            .collect::<Result<_, _>>()
            .map_err(|e| ReportError::io(&folder, e))?;
        children.sort_by_key(|c| c.file_name());
        for child in children {
            let path = child.path();
            let file_name = child.file_name();
            let name = format!("{prefix}{}", file_name.to_string_lossy());
            if depth == 0 && file_name == MARKER {
                continue;
            }
            let kind = child.file_type().map_err(|e| ReportError::io(&path, e))?;
            let utf8 = file_name.to_str().is_some();
            if kind.is_dir() && utf8 && depth < MAX_DEPTH {
                pending.push((path, format!("{name}/"), depth + 1));
            } else {
                out.push(Entry {
                    name: if kind.is_dir() {
                        format!("{name}/")
                    } else {
                        name
                    },
                    path,
                    is_file: kind.is_file() && utf8,
                });
            }
        }
    }
    out.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(out)
}

/// The size and FNV-1a hash of a file, read in blocks.
fn stamp(path: &Path) -> Result<FileStamp, ReportError> {
    let mut file = std::fs::File::open(path).map_err(|e| ReportError::io(path, e))?;
    let mut hash = fairgrasp_types::checksum::Fnv1a64::default();
    let mut bytes = 0u64;
    let mut block = vec![0u8; 1 << 16];
    loop {
        let n = file
            .read(&mut block)
            .map_err(|e| ReportError::io(path, e))?;
        if n == 0 {
            break;
        }
        bytes += n as u64;
        hash.update(&block[..n]);
    }
    Ok(FileStamp {
        bytes,
        fnv1a64: format!("{:016x}", hash.value()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir =
            std::env::temp_dir().join(format!("fairgrasp-marker-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(dir.join("episodes")).unwrap();
        std::fs::write(dir.join("report.md"), "# report\n").unwrap();
        std::fs::write(dir.join("episodes/ep0.json"), "{}").unwrap();
        dir
    }

    #[test]
    fn fnv1a_matches_the_published_test_vectors() {
        let dir = scratch("fnv");
        std::fs::write(dir.join("a"), "a").unwrap();
        std::fs::write(dir.join("empty"), "").unwrap();
        assert_eq!(stamp(&dir.join("a")).unwrap().fnv1a64, "af63dc4c8601ec8c");
        assert_eq!(
            stamp(&dir.join("empty")).unwrap().fnv1a64,
            "cbf29ce484222325"
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_folder_as_written_has_no_changes_and_reads_back() {
        let dir = scratch("same");
        let marker = FolderMarker::of_folder(&dir, "fairgrasp report").unwrap();
        assert_eq!(
            marker.files.keys().collect::<Vec<_>>(),
            ["episodes/ep0.json", "report.md"]
        );
        marker.write(&dir).unwrap();
        assert_eq!(FolderMarker::read(&dir).unwrap(), Some(marker.clone()));
        assert_eq!(marker.changes(&dir).unwrap(), []);
        // Deleting a listed file is not a change that --force could lose.
        std::fs::remove_file(dir.join("episodes/ep0.json")).unwrap();
        assert_eq!(marker.changes(&dir).unwrap(), []);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn edits_and_added_files_and_links_are_changes() {
        let dir = scratch("changed");
        let marker = FolderMarker::of_folder(&dir, "fairgrasp compare").unwrap();
        marker.write(&dir).unwrap();
        std::fs::write(dir.join("report.md"), "# my analysis\n").unwrap();
        std::fs::write(dir.join("episodes/notes.txt"), "mine").unwrap();
        std::fs::create_dir_all(dir.join("mine/deeper")).unwrap();
        std::os::unix::fs::symlink("/etc", dir.join("link")).unwrap();
        assert_eq!(
            marker.changes(&dir).unwrap(),
            [
                Change::Added("episodes/notes.txt".into()),
                Change::Added("link".into()),
                Change::Edited("report.md".into()),
            ],
            "an empty folder holds nothing to lose"
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_folder_without_marker_reads_none_and_a_broken_one_is_an_error() {
        let dir = scratch("none");
        assert_eq!(FolderMarker::read(&dir).unwrap(), None);
        std::fs::write(dir.join(MARKER), "not json").unwrap();
        let e = FolderMarker::read(&dir).unwrap_err().to_string();
        assert!(
            e.contains(MARKER) && e.contains("not a fairgrasp marker"),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
