//! The output folders of `fairgrasp compare` and `fairgrasp report`, and `plot --still`: a
//! folder fairgrasp did not write is never written into; an earlier report is replaced only
//! with --force and only while unchanged; an error or a kill leaves the folder as it was; an
//! unwritable place is reported before any work; a still past the episode's end is refused.

use std::path::{Path, PathBuf};
use std::process::Output;

mod common;
use common::{command, fairgrasp_in};

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A shipped training run folder: `report` draws its learning curves in a second.
fn shipped_run(name: &str) -> String {
    repo()
        .join("assets/policies")
        .join(name)
        .display()
        .to_string()
}

/// A fresh, empty folder under cargo's test temp dir.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("folders-{name}"));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Asserts success and returns stdout.
fn ok(out: &Output) -> String {
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Asserts exit status 1 and returns stderr.
fn refused(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(1), "not refused:\n{stderr}");
    stderr
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

/// Every file below `dir` with its content, by relative path.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(d) = pending.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let path = e.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else {
                let bytes = std::fs::read(&path).unwrap();
                out.push((path.strip_prefix(dir).unwrap().to_path_buf(), bytes));
            }
        }
    }
    out.sort();
    out
}

#[test]
fn report_refuses_a_folder_holding_a_users_file_even_with_force_and_keeps_the_file() {
    let dir = scratch("foreign");
    std::fs::create_dir(dir.join("thesis")).unwrap();
    std::fs::write(dir.join("thesis/notes.md"), "my notes").unwrap();
    let run = shipped_run("residual_hard");
    for force in [false, true] {
        let mut args = vec!["report", &run, "--out", "thesis"];
        if force {
            args.push("--force");
        }
        let stderr = refused(&fairgrasp_in(&dir, &args));
        assert!(
            stderr.contains("thesis: is not empty and fairgrasp did not write it")
                && stderr.contains("--out"),
            "{stderr}"
        );
    }
    assert_eq!(names(&dir.join("thesis")), ["notes.md"]);
    assert_eq!(
        std::fs::read_to_string(dir.join("thesis/notes.md")).unwrap(),
        "my notes"
    );
    assert_eq!(names(&dir), ["thesis"], "a staging folder was left behind");
}

#[test]
fn a_second_report_into_the_same_folder_needs_force_which_replaces_it() {
    let dir = scratch("again");
    let (a, b) = (shipped_run("residual_hard"), shipped_run("pure_hard"));
    ok(&fairgrasp_in(&dir, &["report", &a, &b, "--out", "rep"]));
    let first = snapshot(&dir.join("rep"));
    let md = std::fs::read_to_string(dir.join("rep/report.md")).unwrap();
    assert!(md.contains("pure_hard"), "{md}");

    let stderr = refused(&fairgrasp_in(&dir, &["report", &a, "--out", "rep"]));
    assert!(
        stderr.contains("rep: already holds the output of an earlier `fairgrasp report`")
            && stderr.contains("--force"),
        "{stderr}"
    );
    assert_eq!(snapshot(&dir.join("rep")), first, "refused, yet changed");

    ok(&fairgrasp_in(
        &dir,
        &["report", &a, "--out", "rep", "--force"],
    ));
    let md = std::fs::read_to_string(dir.join("rep/report.md")).unwrap();
    assert!(!md.contains("pure_hard"), "the old report is still there");
    assert!(dir.join("rep/.fairgrasp-report").is_file());
    assert_eq!(
        names(&dir),
        ["rep"],
        "staging or the old folder left behind"
    );
}

#[test]
fn force_refuses_a_report_the_user_edited_and_names_the_file() {
    let dir = scratch("edited");
    let run = shipped_run("residual_hard");
    ok(&fairgrasp_in(&dir, &["report", &run, "--out", "rep"]));
    std::fs::write(dir.join("rep/report.md"), "# My analysis\n").unwrap();
    let stderr = refused(&fairgrasp_in(
        &dir,
        &["report", &run, "--out", "rep", "--force"],
    ));
    assert!(stderr.contains("report.md (edited"), "{stderr}");
    assert_eq!(
        std::fs::read_to_string(dir.join("rep/report.md")).unwrap(),
        "# My analysis\n"
    );
    assert_eq!(names(&dir), ["rep"]);
}

#[test]
fn an_unwritable_parent_is_reported_before_any_episode_runs() {
    let dir = scratch("parent");
    std::fs::write(dir.join("a_file"), "x").unwrap();
    let out = fairgrasp_in(
        &dir,
        &[
            "compare",
            "--preset",
            "fixed",
            "--episodes",
            "1",
            "--threads",
            "1",
            "--out",
            "a_file/cmp",
        ],
    );
    let stderr = refused(&out);
    assert!(
        stderr.contains("a_file/cmp: its parent") && stderr.contains("is a file, not a folder"),
        "{stderr}"
    );
    assert!(
        out.stdout.is_empty(),
        "episodes ran before the folder was checked"
    );
    let run = shipped_run("residual_hard");
    let stderr = refused(&fairgrasp_in(
        &dir,
        &["report", &run, "--out", "/dev/null/x"],
    ));
    assert!(
        stderr.contains("/dev/null/x: its parent /dev/null is a file"),
        "{stderr}"
    );
    assert_eq!(names(&dir), ["a_file"]);
}

#[test]
fn compare_keeps_its_folder_until_forced_and_a_kill_leaves_it_whole() {
    let dir = scratch("compare");
    ok(&compare_into_cmp(&dir, &[]));
    let first = snapshot(&dir.join("cmp"));
    assert_a_second_compare_and_a_report_over_it_are_refused(&dir, &first);
    let episode = assert_a_still_past_the_end_is_refused(&dir, &first);
    assert_plot_and_force_keep_the_report_and_an_added_file(&dir, &first, &episode);
    assert_a_killed_compare_leaves_the_folder_whole(&dir, &first);
    assert_force_replaces_the_folder_as_compare_wrote_it(&dir);
}

/// `fairgrasp compare` of one `fixed` episode on two threads into `dir/cmp`, with `extra`
/// arguments.
fn compare_into_cmp(dir: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "compare",
        "--preset",
        "fixed",
        "--episodes",
        "1",
        "--threads",
        "2",
        "--out",
        "cmp",
    ];
    args.extend(extra);
    fairgrasp_in(dir, &args)
}

/// Again without --force, and a report over its own input: refused, nothing touched (`first`
/// is the folder's snapshot).
fn assert_a_second_compare_and_a_report_over_it_are_refused(
    dir: &Path,
    first: &[(PathBuf, Vec<u8>)],
) {
    let stderr = refused(&compare_into_cmp(dir, &[]));
    assert!(
        stderr.contains("cmp: already holds") && stderr.contains("--force"),
        "{stderr}"
    );
    let stderr = refused(&fairgrasp_in(
        dir,
        &["report", "cmp", "--out", "cmp", "--force"],
    ));
    assert!(
        stderr.contains("is (or contains) the input folder"),
        "{stderr}"
    );
    assert_eq!(snapshot(&dir.join("cmp")), first);
}

/// A still past the episode's end is refused before anything is drawn. Returns the recorded
/// episode's path relative to `dir`.
fn assert_a_still_past_the_end_is_refused(dir: &Path, first: &[(PathBuf, Vec<u8>)]) -> String {
    let episode = names(&dir.join("cmp/episodes"))
        .into_iter()
        .find(|n| n.ends_with(".json.gz"))
        .unwrap();
    let episode = format!("cmp/episodes/{episode}");
    let stderr = refused(&fairgrasp_in(dir, &["plot", &episode, "--still", "5000"]));
    assert!(
        stderr.contains("--still 5000") && stderr.contains("recorded steps, numbered 0–"),
        "{stderr}"
    );
    assert_eq!(
        snapshot(&dir.join("cmp")),
        first,
        "plot drew despite the refusal"
    );
    episode
}

/// plot never draws into a report folder; a file put there by other means is one --force
/// would lose: named, kept. The added file is removed again afterwards.
fn assert_plot_and_force_keep_the_report_and_an_added_file(
    dir: &Path,
    first: &[(PathBuf, Vec<u8>)],
    episode: &str,
) {
    let stderr = refused(&fairgrasp_in(dir, &["plot", episode, "--still", "3"]));
    assert!(stderr.contains("inside the report folder"), "{stderr}");
    assert_eq!(
        snapshot(&dir.join("cmp")),
        first,
        "plot drew into the report"
    );
    let added = dir.join(episode.replace(".json.gz", "_step3.png"));
    std::fs::write(&added, b"a still copied in by hand").unwrap();
    let stderr = refused(&compare_into_cmp(dir, &["--force"]));
    assert!(stderr.contains("_step3.png (added since"), "{stderr}");
    assert!(added.is_file());
    std::fs::remove_file(&added).unwrap();
}

/// A kill while the episodes run leaves the folder as it was (and the staging folder, named
/// after the process, visible next to it; removed here).
fn assert_a_killed_compare_leaves_the_folder_whole(dir: &Path, first: &[(PathBuf, Vec<u8>)]) {
    assert_eq!(snapshot(&dir.join("cmp")), first);
    let mut child = command()
        .args(["compare", "--preset", "fixed", "--episodes", "400"])
        .args(["--threads", "1", "--out", "cmp", "--force"])
        .current_dir(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let staging = dir.join(format!("cmp.partial-{}", child.id()));
    for _ in 0..1200 {
        if staging.is_dir() || child.try_wait().unwrap().is_some() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    assert!(staging.is_dir(), "no staging folder while compare runs");
    child.kill().unwrap();
    child.wait().unwrap();
    assert_eq!(
        snapshot(&dir.join("cmp")),
        first,
        "a killed run changed the folder"
    );
    std::fs::remove_dir_all(&staging).unwrap();
}

/// With --force and the folder as compare wrote it: replaced, nothing else left in `dir`.
fn assert_force_replaces_the_folder_as_compare_wrote_it(dir: &Path) {
    let table = ok(&compare_into_cmp(dir, &["--force", "--seed", "7"]));
    assert!(table.contains("Written to cmp"), "{table}");
    let json = std::fs::read_to_string(dir.join("cmp/compare.json")).unwrap();
    assert!(json.contains("--seed 7"), "not the new comparison");
    assert_eq!(names(dir), ["cmp"], "staging or the old folder left behind");
}
