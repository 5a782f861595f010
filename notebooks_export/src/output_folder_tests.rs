//! Unit tests of [`super::StagedFolder`]: every rule of the module documentation.

use super::*;

/// A fresh, empty scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-staged-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Writes a report folder at `dest` through a staged folder.
fn write_report(dest: &Path, existing: Existing, text: &str) -> Result<(), ReportError> {
    let staged = StagedFolder::create(dest, existing, "fairgrasp report")?;
    std::fs::create_dir_all(staged.path().join("episodes")).unwrap();
    std::fs::write(staged.path().join("report.md"), text).unwrap();
    std::fs::write(staged.path().join("episodes/ep0.json"), "{}").unwrap();
    staged.commit()
}

#[test]
fn a_missing_folder_is_written_whole_with_its_marker_and_no_staging_left() {
    let dir = scratch("missing");
    let dest = dir.join("sub/report");
    write_report(&dest, Existing::Refuse, "# one").unwrap();
    assert_eq!(names(&dest), [MARKER, "episodes", "report.md"]);
    assert_eq!(names(&dir.join("sub")), ["report"]);
    let marker = FolderMarker::read(&dest).unwrap().unwrap();
    assert_eq!(marker.written_by, "fairgrasp report");
    assert_eq!(marker.changes(&dest).unwrap(), []);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_empty_folder_is_written_without_force() {
    let dir = scratch("empty");
    std::fs::create_dir(dir.join("out")).unwrap();
    write_report(&dir.join("out"), Existing::Refuse, "# one").unwrap();
    assert!(dir.join("out/report.md").is_file());
    assert_eq!(names(&dir), ["out"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_folder_fairgrasp_wrote_is_refused_without_force_and_replaced_with_it() {
    let dir = scratch("marked");
    let dest = dir.join("out");
    write_report(&dest, Existing::Refuse, "# old").unwrap();
    std::fs::write(dest.join("episodes/ep0.json"), "{}").unwrap(); // same bytes: unchanged
    let e = write_report(&dest, Existing::Refuse, "# new")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("out") && e.contains("--force") && e.contains("fairgrasp report"),
        "{e}"
    );
    assert_eq!(
        std::fs::read_to_string(dest.join("report.md")).unwrap(),
        "# old"
    );
    write_report(&dest, Existing::Replace, "# new").unwrap();
    assert_eq!(
        std::fs::read_to_string(dest.join("report.md")).unwrap(),
        "# new"
    );
    assert_eq!(
        names(&dir),
        ["out"],
        "staging or the old folder left behind"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn force_refuses_a_folder_with_edited_or_added_files_and_names_them() {
    let dir = scratch("edited");
    let dest = dir.join("out");
    write_report(&dest, Existing::Refuse, "# old").unwrap();
    std::fs::write(dest.join("report.md"), "# my analysis").unwrap();
    std::fs::write(dest.join("notes.txt"), "mine").unwrap();
    let e = write_report(&dest, Existing::Replace, "# new")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("report.md (edited") && e.contains("notes.txt (added since"),
        "{e}"
    );
    assert_eq!(
        std::fs::read_to_string(dest.join("report.md")).unwrap(),
        "# my analysis"
    );
    assert_eq!(names(&dir), ["out"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_folder_fairgrasp_did_not_write_is_refused_even_with_force() {
    let dir = scratch("foreign");
    let dest = dir.join("thesis");
    std::fs::create_dir(&dest).unwrap();
    std::fs::write(dest.join("chapter1.tex"), "mine").unwrap();
    for existing in [Existing::Refuse, Existing::Replace] {
        let e = write_report(&dest, existing, "# new")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("thesis") && e.contains("did not write it") && e.contains("--out"),
            "{e}"
        );
    }
    assert_eq!(names(&dest), ["chapter1.tex"]);
    assert_eq!(names(&dir), ["thesis"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_staged_folder_dropped_midway_leaves_the_destination_untouched() {
    let dir = scratch("dropped");
    let dest = dir.join("out");
    write_report(&dest, Existing::Refuse, "# old").unwrap();
    let before = FolderMarker::of_folder(&dest, "x").unwrap().files;
    let result: Result<(), ReportError> = (|| {
        let staged = StagedFolder::create(&dest, Existing::Replace, "fairgrasp compare")?;
        std::fs::write(staged.path().join("report.md"), "# half").unwrap();
        Err(ReportError::malformed(
            Path::new("episode"),
            "simulated failure",
        ))?;
        staged.commit()
    })();
    assert!(result.is_err());
    assert_eq!(FolderMarker::of_folder(&dest, "x").unwrap().files, before);
    assert_eq!(names(&dir), ["out"], "the staging folder was not removed");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_unwritable_parent_is_reported_when_the_folder_is_created() {
    let dir = scratch("parent");
    std::fs::write(dir.join("a_file"), "x").unwrap();
    for dest in [dir.join("a_file/out"), dir.join("a_file/deeper/out")] {
        let e = StagedFolder::create(&dest, Existing::Refuse, "fairgrasp report")
            .unwrap_err()
            .to_string();
        assert!(e.contains("a_file") && e.contains("parent"), "{e}");
    }
    let e = StagedFolder::create(Path::new("/dev/null/x"), Existing::Refuse, "t")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("/dev/null/x") && e.contains("not a folder"),
        "{e}"
    );
    let e = StagedFolder::create(&dir.join("a_file"), Existing::Replace, "t")
        .unwrap_err()
        .to_string();
    assert!(e.contains("is a file"), "{e}");
    assert_eq!(names(&dir), ["a_file"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_current_folder_and_its_ancestors_are_refused() {
    for dest in [".", "..", "/"] {
        let e = StagedFolder::create(Path::new(dest), Existing::Replace, "t")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("current folder") || e.contains("no parent"),
            "{dest}: {e}"
        );
    }
}

#[test]
fn a_destination_filled_during_the_run_is_not_replaced_and_the_output_is_kept() {
    let dir = scratch("race");
    let dest = dir.join("out");
    let staged = StagedFolder::create(&dest, Existing::Replace, "fairgrasp compare").unwrap();
    let other = StagedFolder::create(&dest, Existing::Replace, "fairgrasp compare").unwrap();
    assert_ne!(staged.path(), other.path());
    drop(other);
    std::fs::write(staged.path().join("report.md"), "# mine").unwrap();
    std::fs::create_dir(&dest).unwrap();
    std::fs::write(dest.join("theirs.txt"), "theirs").unwrap();
    let kept = staged.path().to_path_buf();
    let e = staged.commit().unwrap_err().to_string();
    assert!(
        e.contains(&*kept.to_string_lossy()) && e.contains("kept"),
        "{e}"
    );
    assert_eq!(names(&dest), ["theirs.txt"]);
    assert!(kept.join("report.md").is_file());
    std::fs::remove_dir_all(&dir).ok();
}
