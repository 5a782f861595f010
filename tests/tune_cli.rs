//! `fairgrasp tune` on bad input (issue 60, item 6) and resumed from another folder (item 1):
//! every flag's bad value is refused in one line naming the flag, the value and what it may be
//! (exit code 2, a usage error, as clap's own); a folder or file the command did not write is
//! never written into; a fragment `baseline --tuned` cannot use is refused naming the file and
//! what is wrong; and a tuning of a preset file resumed from another working directory goes on
//! with the preset its folder recorded.

use std::path::{Path, PathBuf};
use std::process::Output;

mod common;
use common::{fairgrasp, fairgrasp_in, stderr};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("tune-cli-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `tune` on `place_fixture_error` into `out` with `extra` flags: of the force search, 4
/// episodes a trial, a budget of 1 000 env steps, 1 thread and its 2 best trials validated on 2
/// episodes unless `extra` sets them.
fn tune_args<'a>(out: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec!["tune", "--preset", "place_fixture_error", "--out", out];
    for (flag, value) in [
        ("--control", "force_search"),
        ("--episodes", "4"),
        ("--budget", "1000"),
        ("--threads", "1"),
        ("--validation-episodes", "2"),
        ("--finalists", "2"),
    ] {
        if !extra.contains(&flag) {
            args.extend([flag, value]);
        }
    }
    args.extend(extra);
    args
}

/// Refused with `code` in one line of error that names every needle.
fn refused(o: &Output, code: i32, needles: &[&str], what: &str) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(code), "{what}: {e}");
    assert!(!e.contains("panicked"), "{what}: {e}");
    let errors: Vec<&str> = e.lines().filter(|l| l.starts_with("error")).collect();
    let [line] = errors[..] else {
        panic!("{what}: one line of error: {e}");
    };
    for n in needles {
        assert!(line.contains(n), "{what}: `{n}` not in {line}");
    }
}

#[test]
fn every_bad_flag_of_tune_is_a_usage_error_naming_the_flag_the_value_and_its_range() {
    let dir = scratch("flags");
    let out = dir.join("t");
    let out = out.to_str().unwrap();
    let cases: [(&[&str], &[&str]); 23] = [
        (
            &["--validation-seed", "7"],
            &["--validation-seed 7", "reported"],
        ),
        (
            &["--validation-seed", "11"],
            &["--validation-seed 11", "--seed 11"],
        ),
        (
            &["--seed", "5", "--validation-seed", "5"],
            &["--validation-seed 5", "--seed 5"],
        ),
        (&["--finalists", "0"], &["--finalists", "1..=100"]),
        (
            &["--validation-episodes", "0"],
            &["--validation-episodes", "1..=100000"],
        ),
        (
            &["--param", "check_floor=0.2:0.8"],
            &["check_floor=0.2:0.8", "switch", "1:1"],
        ),
        (
            &["--param", "wobble"],
            &["--param wobble", "pitch", "speed"],
        ),
        (
            &["--param", "pitch=0.004:0.002"],
            &[
                "pitch=0.004:0.002",
                "low below high",
                "accepts, [",
                "m per turn",
            ],
        ),
        (
            &["--param", "contact_force=0.05:3"],
            &["contact_force=0.05:3", "[0.1, 30] N"],
        ),
        (
            &["--param", "pitch=nan:0.002"],
            &["--param", "`nan` is not a finite number"],
        ),
        (
            &["--param", "pitch=0.001:inf"],
            &["--param", "`inf` is not a finite number"],
        ),
        (&["--param", "pitch=0.001"], &["--param", "NAME=LOW:HIGH"]),
        (
            &["--param", "pitch=a:0.002"],
            &["--param", "`a` is not a finite number"],
        ),
        (
            &["--param", "pitch=0.001:0.002:0.003"],
            &["--param", "`0.002:0.003` is not a finite number"],
        ),
        (
            &["--param", "=0.001:0.002"],
            &["--param", "not a parameter"],
        ),
        (
            &["--param", "pitch", "--param", "pitch"],
            &["--param pitch", "named twice"],
        ),
        (&["--budget", "0"], &["--budget", "1..=1000000000"]),
        (&["--budget", "2000000000"], &["--budget", "1..=1000000000"]),
        (
            &["--budget", "lots"],
            &["--budget", "\"lots\"", "1..=1000000000"],
        ),
        (&["--episodes", "0"], &["--episodes", "1..=100000"]),
        (&["--threads", "0"], &["--threads", "1..=256"]),
        (&["--seed", "-1"], &["--seed", "0..=9007199254740991"]),
        (
            &["--control", "spiral"],
            &["--control spiral", "force_search"],
        ),
    ];
    for (extra, needles) in cases {
        let o = fairgrasp(&tune_args(out, extra));
        refused(&o, 2, needles, &format!("{extra:?}"));
        assert!(
            !Path::new(out).exists(),
            "{extra:?}: the refused tuning wrote {out}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn tune_never_writes_into_a_file_or_a_folder_it_did_not_make() {
    let dir = scratch("out");
    let file = dir.join("notes.txt");
    std::fs::write(&file, "mine").unwrap();
    let o = fairgrasp(&tune_args(file.to_str().unwrap(), &[]));
    refused(&o, 1, &["notes.txt", "not a folder"], "--out FILE");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine");
    let folder = dir.join("mine");
    std::fs::create_dir_all(&folder).unwrap();
    std::fs::write(folder.join("results.csv"), "a,b\n").unwrap();
    let o = fairgrasp(&tune_args(folder.to_str().unwrap(), &[]));
    refused(&o, 1, &["mine", "not a tuning folder"], "--out FOLDER");
    let names: Vec<_> = std::fs::read_dir(&folder).unwrap().flatten().collect();
    assert_eq!(names.len(), 1, "only the user's file");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_fragment_baseline_cannot_use_is_refused_naming_the_file_and_what_is_wrong() {
    let dir = scratch("fragment");
    let out = dir.join("t");
    let ok = fairgrasp(&tune_args(out.to_str().unwrap(), &["--param", "pitch"]));
    assert!(ok.status.success(), "{}", stderr(&ok));
    let text = std::fs::read_to_string(out.join("tuned.toml")).unwrap();
    let pitch_line = text.lines().find(|l| l.starts_with("pitch =")).unwrap();
    let cases = [
        (
            "not_toml.toml",
            "[task.place.search\n".to_string(),
            vec!["not TOML"],
        ),
        (
            "no_note.toml",
            "[task.place.search]\npitch = 0.002\n".to_string(),
            vec!["[control.tuned.<control>]"],
        ),
        (
            "foreign.toml",
            format!("{text}\n[task]\nmax_steps = 50\n"),
            vec!["task.max_steps", "[task.place.search]"],
        ),
        (
            "too_coarse.toml",
            text.replace(pitch_line, "pitch = 0.5"),
            vec!["task.place.search.pitch", "0.5"],
        ),
        (
            "unknown_control.toml",
            text.replace("[control.tuned.force_search]", "[control.tuned.wobble]"),
            vec!["control.tuned.wobble", "not a control"],
        ),
    ];
    for (name, body, needles) in cases {
        let path = dir.join(name);
        std::fs::write(&path, &body).unwrap();
        let p = path.to_str().unwrap();
        let o = fairgrasp(&[
            "baseline",
            "--preset",
            "place_fixture_error",
            "--script",
            "force_search",
            "--tuned",
            p,
            "--episodes",
            "1",
        ]);
        let mut all = vec![name];
        all.extend(needles);
        refused(&o, 1, &all, name);
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            body,
            "{name} was rewritten"
        );
    }
    // Tuned on one preset, read into another.
    let o = fairgrasp(&[
        "baseline",
        "--preset",
        "place_tilted",
        "--script",
        "force_search",
        "--tuned",
        out.join("tuned.toml").to_str().unwrap(),
        "--episodes",
        "1",
    ]);
    refused(
        &o,
        1,
        &["tuned.toml", "place_fixture_error", "place_tilted"],
        "other preset",
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_tuning_of_a_preset_file_resumed_from_another_folder_goes_on_with_its_recorded_preset() {
    let dir = scratch("cwd");
    let (a, b) = (dir.join("a"), dir.join("b"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    let original = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/configs/place_fixture_error.toml"
    ))
    .unwrap();
    std::fs::write(a.join("cell.toml"), &original).unwrap();
    // Another cell of that name in `b`: its fixture is known less well.
    let other = original.replace(
        "observed_position_noise = 0.003",
        "observed_position_noise = 0.004",
    );
    assert_ne!(other, original);
    std::fs::write(b.join("cell.toml"), other).unwrap();
    let out = dir.join("t");
    let args = |budget: &'static str| {
        vec![
            "tune".to_string(),
            "--preset".into(),
            "cell.toml".into(),
            "--control".into(),
            "force_search".into(),
            "--param".into(),
            "pitch".into(),
            "--episodes".into(),
            "4".into(),
            "--budget".into(),
            budget.into(),
            "--threads".into(),
            "1".into(),
            "--validation-episodes".into(),
            "2".into(),
            "--finalists".into(),
            "2".into(),
            "--out".into(),
            out.to_str().unwrap().into(),
        ]
    };
    let run = |cwd: &Path, budget| {
        let a = args(budget);
        let refs: Vec<&str> = a.iter().map(String::as_str).collect();
        fairgrasp_in(cwd, &refs)
    };
    let first = run(&a, "1000");
    assert!(first.status.success(), "{}", stderr(&first));
    let before = std::fs::read_to_string(out.join("trials.csv")).unwrap();
    let resumed = run(&b, "3000");
    assert!(resumed.status.success(), "{}", stderr(&resumed));
    let e = stderr(&resumed);
    assert!(
        e.contains("goes on with the preset it started on")
            && e.contains("task.place.observed_position_noise: 0.003 → 0.004"),
        "{e}"
    );
    let after = std::fs::read_to_string(out.join("trials.csv")).unwrap();
    assert!(
        after.len() > before.len() && after.starts_with(&before),
        "{after}"
    );
    // The same, uninterrupted, from `a`: the very same trials (the walls of `b` never ran).
    let whole = dir.join("whole");
    let mut a_args = args("3000");
    *a_args.last_mut().unwrap() = whole.to_str().unwrap().into();
    let refs: Vec<&str> = a_args.iter().map(String::as_str).collect();
    let o = fairgrasp_in(&a, &refs);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(whole.join("trials.csv")).unwrap(),
        after
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A start that fails (here: no file may grow past 0 bytes, as on a full disk) leaves no
/// `--out` behind: not an empty folder that a rerun would take for a new tuning's.
#[test]
fn a_failed_start_leaves_no_out_folder() {
    let dir = scratch("full");
    let out = dir.join("t");
    let args = tune_args(out.to_str().unwrap(), &[]);
    let o = std::process::Command::new("sh")
        .arg("-c")
        // The signal ignored, a write past the limit fails with EFBIG instead of killing.
        .arg("trap '' XFSZ; ulimit -f 0; exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_fairgrasp"))
        .args(&args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.lines().any(|l| l.starts_with("error")), "{e}");
    assert!(!out.exists(), "a failed start left {}: {e}", out.display());
    // With room again, the same command starts the tuning.
    let o = fairgrasp(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).ok();
}

/// The tuning says what it chose and on what: the trial's score, the validation's, and the
/// env steps of both in the unit that fits; the fragment reads into its own preset through
/// `baseline`, and two fragments of one control for one preset are refused by `compare`.
#[test]
fn tune_reports_its_validation_and_two_fragments_of_one_control_are_refused() {
    let dir = scratch("report");
    let out = dir.join("t");
    let o = fairgrasp(&tune_args(out.to_str().unwrap(), &["--param", "pitch"]));
    assert!(o.status.success(), "{}", stderr(&o));
    let printed = common::stdout(&o);
    assert!(printed.contains("on validation"), "{printed}");
    assert!(
        printed.contains("on the validation = ") && !printed.contains(" M env steps"),
        "{printed}"
    );
    assert!(out.join("finalists.csv").is_file());
    let fragment = out.join("tuned.toml");
    let o = fairgrasp(&[
        "baseline",
        "--preset",
        "place_fixture_error",
        "--script",
        "force_search",
        "--tuned",
        fragment.to_str().unwrap(),
        "--episodes",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let copy = dir.join("copy.toml");
    std::fs::copy(&fragment, &copy).unwrap();
    let report = dir.join("report");
    let o = fairgrasp(&[
        "compare",
        "--preset",
        "place_fixture_error",
        "--tuned",
        fragment.to_str().unwrap(),
        "--tuned",
        copy.to_str().unwrap(),
        "--episodes",
        "1",
        "--out",
        report.to_str().unwrap(),
    ]);
    refused(
        &o,
        1,
        &[
            "copy.toml",
            "a second fragment of `force_search`",
            "place_fixture_error",
        ],
        "two fragments",
    );
    assert!(!report.exists());
    std::fs::remove_dir_all(&dir).ok();
}
