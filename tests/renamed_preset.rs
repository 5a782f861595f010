//! A renamed preset's old name (`seed`, now `sector`) still works on the command line and in a
//! training recipe: the command says so in one line on stderr, and every output carries the
//! current name.

use serde_json::Value;

mod common;
use common::{fairgrasp, stderr, stdout, tiny_recipe, train};

const NOTE: &str =
    "note: preset \"seed\" is now called \"sector\"; the old name still works for now";

/// A fresh, empty temporary folder for one test.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-renamed-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn baseline_with_the_old_name_notes_the_rename_and_reports_the_current_one() {
    let args = |preset| ["baseline", "--preset", preset, "--episodes", "2", "--json"];
    let old = fairgrasp(&args("seed"));
    let new = fairgrasp(&args("sector"));
    assert_eq!(old.status.code(), Some(0), "{}", stderr(&old));
    assert_eq!(stderr(&old).matches(NOTE).count(), 1, "{}", stderr(&old));
    assert!(!stderr(&new).contains("note:"), "{}", stderr(&new));
    let v: Value = serde_json::from_str(&stdout(&old)).unwrap();
    assert_eq!(v["preset"], "sector");
    assert_eq!(stdout(&old), stdout(&new));
}

#[test]
fn compare_with_the_old_name_writes_the_current_one() {
    let out = scratch("compare").join("report");
    let run = fairgrasp(&[
        "compare",
        "--preset",
        "seed",
        "--episodes",
        "2",
        "--replay-episodes",
        "0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    assert_eq!(stderr(&run).matches(NOTE).count(), 1, "{}", stderr(&run));
    let csv = std::fs::read_to_string(out.join("compare.csv")).unwrap();
    let presets: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|row| row.split(',').nth(1).unwrap())
        .collect();
    assert!(!presets.is_empty(), "{csv}");
    assert!(presets.iter().all(|p| *p == "sector"), "{csv}");
    let json = std::fs::read_to_string(out.join("compare.json")).unwrap();
    let v: Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["presets"], serde_json::json!(["sector"]));
    assert!(
        v["results"]
            .as_array()
            .unwrap()
            .iter()
            .all(|r| r["preset"] == "sector")
    );
    std::fs::remove_dir_all(out.parent().unwrap()).ok();
}

#[test]
fn the_preset_list_names_sector_and_the_old_name_once() {
    let help = stdout(&fairgrasp(&["baseline", "--help"]));
    assert!(
        help.contains("sector (the cube anywhere in a sector"),
        "{help}"
    );
    assert_eq!(
        help.matches("seed is the old name of sector").count(),
        1,
        "{help}"
    );
}

#[test]
fn a_recipe_with_the_old_name_trains_noting_it_and_saves_the_current_one() {
    let dir = scratch("train");
    let (config, run) = tiny_recipe(&dir, "seed", 32);
    let out = train(&config, &run);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let note = format!(
        "note: {}: preset \"seed\" is now called \"sector\"; the old name still works for now",
        config.display()
    );
    assert_eq!(stderr(&out).matches(&note).count(), 1, "{}", stderr(&out));
    assert!(
        stdout(&out).contains("on preset `sector`"),
        "{}",
        stdout(&out)
    );
    let saved = std::fs::read_to_string(run.join("config.toml")).unwrap();
    assert!(saved.contains("preset = \"sector\""), "{saved}");
    std::fs::remove_dir_all(&dir).ok();
}
