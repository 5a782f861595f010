//! `fairgrasp wrench-probe` end to end: it reports the sensor's pre-check on a place preset,
//! refuses a preset without a wrist sensor and a CSV that exists, writing nothing.

mod common;

use std::path::{Path, PathBuf};

use common::{fairgrasp_in, stderr, stdout};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("wrench-probe-cli-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_probe_reports_each_family_and_writes_its_rows() {
    let dir = scratch("report");
    let out = fairgrasp_in(
        &dir,
        &[
            "wrench-probe",
            "--preset",
            "place_cell",
            "--episodes",
            "6",
            "--csv",
            "t.csv",
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("tilt's sign right"), "{text}");
    assert!(text.contains("6 scenarios from seed 11"), "{text}");
    let csv = std::fs::read_to_string(dir.join("t.csv")).unwrap();
    assert_eq!(csv.lines().count(), 7, "{csv}");
    assert!(
        csv.starts_with("seed,family,step,true_wall,read_wall"),
        "{csv}"
    );
}

#[test]
fn a_preset_without_a_wrist_sensor_or_an_existing_csv_is_refused_and_nothing_written() {
    let dir = scratch("refused");
    let lift = fairgrasp_in(
        &dir,
        &["wrench-probe", "--preset", "sector", "--csv", "a.csv"],
    );
    assert!(!lift.status.success());
    let err = stderr(&lift);
    assert!(
        err.contains("--preset sector") && err.contains("no wrist sensor"),
        "{err}"
    );
    assert!(!dir.join("a.csv").exists());
    std::fs::write(dir.join("b.csv"), "mine").unwrap();
    let taken = fairgrasp_in(&dir, &["wrench-probe", "--episodes", "2", "--csv", "b.csv"]);
    assert!(!taken.status.success());
    assert!(stderr(&taken).contains("b.csv"), "{}", stderr(&taken));
    assert_eq!(std::fs::read_to_string(dir.join("b.csv")).unwrap(), "mine");
}
