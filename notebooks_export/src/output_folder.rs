//! The output folder of `fairgrasp compare` and `fairgrasp report`, written as a whole or not
//! at all.
//!
//! [`StagedFolder::create`] checks the destination and creates a temporary sibling,
//! `<name>.partial-<pid>` (same parent, so the final rename is atomic), before any work: an
//! unwritable place fails at once, not after minutes of episodes. The caller writes every file
//! into [`StagedFolder::path`]; [`StagedFolder::commit`] adds the marker
//! ([`crate::folder_marker`]) and moves the folder into place. Dropped without a commit (an
//! error, a panic), the temporary folder is deleted and the destination is untouched. Only a
//! killed process leaves `<name>.partial-<pid>` behind, next to an untouched destination.
//!
//! The destination may be:
//! - missing, or an empty folder: written;
//! - a folder an earlier `compare` or `report` wrote (it holds `.fairgrasp-report`): replaced
//!   only with [`Existing::Replace`] (`--force`), and only while every file in it is one
//!   fairgrasp wrote, unchanged. An edited `report.md` or an added file stops it, named. The
//!   old folder is renamed aside (`<name>.replaced-<pid>`), the new one moved in, then the old
//!   one deleted;
//! - anything else (a file, a folder fairgrasp did not write, the current folder): refused,
//!   `--force` or not.

use std::path::{Path, PathBuf};

use crate::error::ReportError;
use crate::folder_marker::{FolderMarker, MARKER};

/// What to do when the destination is a folder fairgrasp wrote before.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Existing {
    /// Refuse (the default).
    Refuse,
    /// Replace it if nothing in it was edited or added (`--force`).
    Replace,
}

impl Existing {
    /// [`Existing::Replace`] with `--force` (`force = True` in Python), else
    /// [`Existing::Refuse`].
    pub fn from_force(force: bool) -> Self {
        if force {
            Existing::Replace
        } else {
            Existing::Refuse
        }
    }
}

/// How the destination was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Destination {
    Missing,
    Empty,
    /// A folder fairgrasp wrote, unchanged, and `Existing::Replace` was given.
    Replaceable,
}

/// An output folder being written (see the module documentation).
#[derive(Debug)]
pub struct StagedFolder {
    /// The destination as the user named it (for messages).
    shown: PathBuf,
    /// The destination as an absolute path, links resolved.
    target: PathBuf,
    staging: PathBuf,
    existing: Existing,
    written_by: String,
    /// Whether dropping leaves the staging folder in place (committed, or kept for the user).
    keep: bool,
}

impl StagedFolder {
    /// Checks `dest` (see the module documentation) and creates the staging folder next to it
    /// (and `dest`'s parent folders if needed). `written_by` names the command in the marker.
    pub fn create(dest: &Path, existing: Existing, written_by: &str) -> Result<Self, ReportError> {
        let err = |what: String| ReportError::OutputFolder {
            path: dest.to_path_buf(),
            what,
        };
        let target = resolve(dest).map_err(|e| err(e.to_string()))?;
        let (Some(parent), Some(name)) = (target.parent(), target.file_name()) else {
            return Err(err("has no parent folder to write it in".into()));
        };
        check(dest, &target, existing)?;
        if parent.exists() && !parent.is_dir() {
            return Err(err(format!(
                "its parent {} is a file, not a folder",
                parent.display()
            )));
        }
        std::fs::create_dir_all(parent).map_err(|e| {
            err(format!(
                "cannot create its parent folder {}: {e}",
                parent.display()
            ))
        })?;
        let staging =
            unused_sibling(parent, name, "partial", |p| std::fs::create_dir(p)).map_err(|e| {
                err(format!(
                    "cannot write in its parent folder {}: {e}",
                    parent.display()
                ))
            })?;
        Ok(Self {
            shown: dest.to_path_buf(),
            target,
            staging,
            existing,
            written_by: written_by.to_string(),
            keep: false,
        })
    }

    /// The folder to write every file into (the staging folder).
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// The destination as the user named it.
    pub fn destination(&self) -> &Path {
        &self.shown
    }

    /// Writes the marker and moves the staging folder into place. The destination is checked
    /// again first: if it changed while the files were written (another run filled it, a file
    /// in it was edited), nothing is replaced and the new folder is kept where it is, named in
    /// the error.
    pub fn commit(mut self) -> Result<(), ReportError> {
        FolderMarker::of_folder(&self.staging, &self.written_by)?.write(&self.staging)?;
        let kept = |e: ReportError, staging: &Path| ReportError::OutputFolder {
            path: staging.to_path_buf(),
            what: format!("this run's complete output is kept here, because: {e}"),
        };
        let state = match check(&self.shown, &self.target, self.existing) {
            Ok(state) => state,
            Err(e) => {
                self.keep = true;
                return Err(kept(e, &self.staging));
            }
        };
        let moved = match state {
            Destination::Missing | Destination::Empty => self.move_in(state),
            Destination::Replaceable => self.replace(),
        };
        match moved {
            Ok(()) => {
                self.keep = true;
                Ok(())
            }
            Err(e) => {
                self.keep = true;
                Err(kept(e, &self.staging))
            }
        }
    }

    /// Renames the staging folder onto a missing or empty destination.
    fn move_in(&self, state: Destination) -> Result<(), ReportError> {
        let renamed = std::fs::rename(&self.staging, &self.target);
        if renamed.is_err() && state == Destination::Empty {
            // Where a rename cannot replace an empty folder: remove it first.
            std::fs::remove_dir(&self.target).map_err(|e| self.io(e))?;
            return std::fs::rename(&self.staging, &self.target).map_err(|e| self.io(e));
        }
        renamed.map_err(|e| self.io(e))
    }

    /// Moves the old folder aside, the new one in, then deletes the old one; on failure the
    /// old folder is moved back.
    fn replace(&self) -> Result<(), ReportError> {
        let parent = self.target.parent().unwrap_or(Path::new("."));
        let name = self.target.file_name().unwrap_or_default();
        let aside = unused_sibling(parent, name, "replaced", |p| {
            std::fs::rename(&self.target, p)
        })
        .map_err(|e| self.io(e))?;
        if let Err(e) = std::fs::rename(&self.staging, &self.target) {
            std::fs::rename(&aside, &self.target).ok();
            return Err(self.io(e));
        }
        // The new folder is in place; a failure to delete the old one leaves it visible as
        // `<name>.replaced-<pid>`, with nothing lost.
        std::fs::remove_dir_all(&aside).ok();
        Ok(())
    }

    fn io(&self, e: std::io::Error) -> ReportError {
        ReportError::OutputFolder {
            path: self.shown.clone(),
            what: format!("cannot move the new folder into place: {e}"),
        }
    }
}

impl Drop for StagedFolder {
    fn drop(&mut self) {
        if !self.keep {
            std::fs::remove_dir_all(&self.staging).ok();
        }
    }
}

/// `dest` as an absolute path, links resolved when it exists.
fn resolve(dest: &Path) -> std::io::Result<PathBuf> {
    if std::fs::symlink_metadata(dest).is_ok() {
        dest.canonicalize()
    } else {
        std::path::absolute(dest)
    }
}

/// Creates (with `make`) the first free `<name>.<tag>-<pid>[-<n>]` in `parent` and returns it.
fn unused_sibling(
    parent: &Path,
    name: &std::ffi::OsStr,
    tag: &str,
    make: impl Fn(&Path) -> std::io::Result<()>,
) -> std::io::Result<PathBuf> {
    let pid = std::process::id();
    let mut last = None;
    for n in 0..100 {
        let mut sibling = name.to_os_string();
        sibling.push(if n == 0 {
            format!(".{tag}-{pid}")
        } else {
            format!(".{tag}-{pid}-{n}")
        });
        let path = parent.join(sibling);
        if std::fs::symlink_metadata(&path).is_ok() {
            continue;
        }
        match make(&path) {
            Ok(()) => return Ok(path),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| std::io::Error::other("100 candidate names taken")))
}

/// What the destination is, or why it may not be written.
fn check(shown: &Path, target: &Path, existing: Existing) -> Result<Destination, ReportError> {
    let err = |what: String| ReportError::OutputFolder {
        path: shown.to_path_buf(),
        what,
    };
    let Ok(meta) = std::fs::metadata(target) else {
        return Ok(Destination::Missing);
    };
    if !meta.is_dir() {
        return Err(err(
            "is a file, not a folder: --out names the folder to write into".into(),
        ));
    }
    if let Ok(cwd) = std::env::current_dir().and_then(|d| d.canonicalize())
        && cwd.starts_with(target)
    {
        return Err(err(
            "is the current folder (or contains it): choose a folder inside it, such as \
             --out report"
                .into(),
        ));
    }
    let mut entries = std::fs::read_dir(target).map_err(|e| ReportError::io(shown, e))?;
    if entries.next().is_none() {
        return Ok(Destination::Empty);
    }
    let marker = match FolderMarker::read(target) {
        Ok(Some(marker)) => marker,
        Ok(None) => {
            return Err(err(format!(
                "is not empty and fairgrasp did not write it (it has no {MARKER} file): \
                 fairgrasp writes only into a new or empty folder, or replaces, with --force, \
                 a folder it wrote itself; choose another --out"
            )));
        }
        Err(e) => {
            return Err(err(format!(
                "is not empty and its {MARKER} cannot be read ({e}); choose another --out"
            )));
        }
    };
    if existing == Existing::Refuse {
        return Err(err(format!(
            "already holds the output of an earlier `{}`: pass --force to replace it, or \
             choose another --out",
            marker.written_by
        )));
    }
    let changes = marker.changes(target)?;
    if !changes.is_empty() {
        const SHOWN: usize = 5;
        let mut list: Vec<String> = changes.iter().take(SHOWN).map(|c| c.to_string()).collect();
        if changes.len() > SHOWN {
            list.push(format!("and {} more", changes.len() - SHOWN));
        }
        return Err(err(format!(
            "--force replaces only what fairgrasp wrote, unchanged, and this folder holds {}: \
             move them out (or delete them) first, or choose another --out",
            list.join(", ")
        )));
    }
    Ok(Destination::Replaceable)
}

#[cfg(test)]
#[path = "output_folder_tests.rs"]
mod tests;
