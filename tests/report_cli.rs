//! `fairgrasp compare | plot | report` end to end: the printed table, compare.csv and
//! compare.json agree; the folder holds every chart; bad inputs are named.

use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

mod common;
use common::fairgrasp;

fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("cli-{name}"));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn ok(out: &Output) -> String {
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

#[test]
fn compare_writes_agreeing_table_csv_json_and_every_chart() {
    let dir = temp_dir("compare");
    let out_dir = dir.join("report");
    let stdout = ok(&fairgrasp(&[
        "compare",
        "--preset",
        "fixed",
        "--preset",
        "hard",
        "--episodes",
        "6",
        "--threads",
        "2",
        "--verbose",
        "--out",
        out_dir.to_str().unwrap(),
    ]));
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("compare.json")).unwrap())
            .unwrap();
    let results = json["results"].as_array().unwrap();
    let methods = assert_scripts_then_policies(&json, results);
    assert_paired_tests_count_discordant_pairs(&stdout, results, &methods);
    assert_csv_and_printed_table_agree_with_json(&out_dir, &stdout, results);
    assert_every_method_saw_the_same_scenarios(results);
    assert_recorded_episodes_replay_their_evaluation(&json, results);
    assert_folder_holds_every_chart(&out_dir, methods.len());
    assert_report_redraws_the_same_chart(&dir, &out_dir);
    assert_plot_draws_episodes_outside_report_folders(&dir, &out_dir);
}

/// compare.json's methods: the five scripts, then every shipped policy (two at least), each on
/// both presets. Returns the method names in order.
fn assert_scripts_then_policies<'a>(json: &'a Value, results: &[Value]) -> Vec<&'a str> {
    let methods: Vec<&str> = json["methods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap())
        .collect();
    assert_eq!(
        methods[..5],
        [
            "scripted baseline",
            "closed-loop script",
            "oracle script",
            "script + calibration",
            "script + tuned grip"
        ]
    );
    let learned = results.iter().filter(|r| !r["policy"].is_null()).count() / 2;
    assert!(learned >= 2, "{methods:?}");
    assert_eq!(methods.len(), 5 + learned);
    assert_eq!(results.len(), 2 * methods.len());
    methods
}

/// Whether each episode of `method` on `preset` succeeded, in episode order.
fn outcome_list(results: &[Value], method: &str, preset: &str) -> Vec<bool> {
    let r = results
        .iter()
        .find(|r| r["method"] == method && r["preset"] == preset)
        .unwrap();
    r["results"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["outcome"] == "success")
        .collect()
}

/// The printed paired tests: every learned method against every script on each preset, with
/// the discordant counts of the two result lists, and no other rows.
fn assert_paired_tests_count_discordant_pairs(stdout: &str, results: &[Value], methods: &[&str]) {
    let paired: Vec<&str> = stdout
        .lines()
        .skip_while(|l| !l.starts_with("Paired tests"))
        .take_while(|l| !l.is_empty())
        .collect();
    let mut pairs = 0;
    for preset in ["fixed", "hard"] {
        for l in &methods[5..] {
            for s in &methods[..5] {
                let (a, b) = (
                    outcome_list(results, l, preset),
                    outcome_list(results, s, preset),
                );
                let only_a = a.iter().zip(&b).filter(|(x, y)| **x && !**y).count();
                let only_b = a.iter().zip(&b).filter(|(x, y)| !**x && **y).count();
                let line = paired
                    .iter()
                    .find(|line| line.starts_with(preset) && line.contains(l) && line.contains(s))
                    .unwrap_or_else(|| panic!("no paired line {l} vs {s} on {preset}:\n{stdout}"));
                let cells: Vec<&str> = line
                    .split("  ")
                    .map(str::trim)
                    .filter(|c| !c.is_empty())
                    .collect();
                assert_eq!(cells[4], format!("{only_a} / {only_b}"), "{line}");
                pairs += 1;
            }
        }
    }
    assert_eq!(paired.len(), 3 + pairs, "{stdout}");
}

/// compare.csv has one row per result with compare.json's method, preset, rate and successes;
/// the printed table shows the same rate, interval and collision rate, rounded.
fn assert_csv_and_printed_table_agree_with_json(out_dir: &Path, stdout: &str, results: &[Value]) {
    let csv = std::fs::read_to_string(out_dir.join("compare.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), results.len());
    for (row, r) in rows.iter().zip(results) {
        let col = |name: &str| row[header.iter().position(|h| *h == name).unwrap()];
        let (method, preset) = (r["method"].as_str().unwrap(), r["preset"].as_str().unwrap());
        assert_eq!(col("method"), method);
        assert_eq!(col("preset"), preset);
        let rate = r["success_rate"].as_f64().unwrap();
        assert_eq!(col("success_rate").parse::<f64>().unwrap(), rate);
        assert_eq!(
            col("successes").parse::<u64>().unwrap(),
            r["successes"].as_u64().unwrap()
        );
        let line = stdout
            .lines()
            .find(|l| l.starts_with(preset) && l.contains(method))
            .unwrap_or_else(|| panic!("no printed line for {method} on {preset}:\n{stdout}"));
        let ci_low = r["ci_low"].as_f64().unwrap();
        let collisions = r["collision_rate"].as_f64().unwrap();
        assert!(
            line.contains(&format!("{:.1} % ({:.1}–", 100.0 * rate, 100.0 * ci_low)),
            "{line}"
        );
        assert!(
            line.contains(&format!("{:.1} %", 100.0 * collisions)),
            "{line}"
        );
    }
}

/// Every method saw the identical scenarios: same seeds and cube positions per preset.
fn assert_every_method_saw_the_same_scenarios(results: &[Value]) {
    for preset in ["fixed", "hard"] {
        let sets: Vec<Vec<(u64, String)>> = results
            .iter()
            .filter(|r| r["preset"] == preset)
            .map(|r| {
                r["results"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|e| (e["seed"].as_u64().unwrap(), e["object_xy"].to_string()))
                    .collect()
            })
            .collect();
        assert!(
            sets.windows(2).all(|w| w[0] == w[1]),
            "{preset}: scenarios differ"
        );
    }
}

/// The recorded episode replays its evaluation exactly: same outcome for every method.
fn assert_recorded_episodes_replay_their_evaluation(json: &Value, results: &[Value]) {
    for rec in json["recorded"].as_array().unwrap() {
        let k = rec["episode"].as_u64().unwrap() as usize;
        let r = results
            .iter()
            .find(|r| r["method"] == rec["method"] && r["preset"] == rec["preset"])
            .unwrap();
        assert_eq!(r["results"][k]["outcome"], rec["outcome"], "{rec}");
    }
}

/// The report folder holds the charts and documents, one recorded episode (chart and replay)
/// per method of the `method_count`, and no temporary file.
fn assert_folder_holds_every_chart(out_dir: &Path, method_count: usize) {
    let names: Vec<String> = std::fs::read_dir(out_dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    for expected in [
        "success_rate.png",
        "workspace_fixed.png",
        "workspace_hard.png",
        "learning_curves.png",
        "report.md",
        "report.ipynb",
    ] {
        assert!(
            names.iter().any(|n| n == expected),
            "{expected} missing: {names:?}"
        );
    }
    assert_eq!(
        names.iter().filter(|n| n.starts_with("episode_")).count(),
        method_count
    );
    assert_eq!(
        names.iter().filter(|n| n.ends_with(".gif")).count(),
        method_count
    );
    assert!(!names.iter().any(|n| n.contains(".tmp")), "{names:?}");
}

/// `report` redraws the same report from the folder alone.
fn assert_report_redraws_the_same_chart(dir: &Path, out_dir: &Path) {
    let again = dir.join("again");
    ok(&fairgrasp(&[
        "report",
        out_dir.to_str().unwrap(),
        "--out",
        again.to_str().unwrap(),
    ]));
    assert_eq!(
        std::fs::read(again.join("success_rate.png")).unwrap(),
        std::fs::read(out_dir.join("success_rate.png")).unwrap(),
        "the same data must give the same chart"
    );
}

/// `plot` draws a recorded episode next to its file, but never inside a report folder (whose
/// files only compare and report write); a compare episode (gzipped JSON) is drawn under its
/// name without `.json.gz`.
fn assert_plot_draws_episodes_outside_report_folders(dir: &Path, out_dir: &Path) {
    let recorded = std::fs::read_dir(out_dir.join("episodes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "gz"))
        .unwrap();
    let refused = fairgrasp(&["plot", recorded.to_str().unwrap()]);
    assert_eq!(refused.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("inside the report folder"));
    let episode = dir.join("episode_0005.json.gz");
    std::fs::copy(&recorded, &episode).unwrap();
    ok(&fairgrasp(&["plot", episode.to_str().unwrap()]));
    assert!(dir.join("episode_0005.png").is_file());
    assert!(dir.join("episode_0005.gif").is_file());
}

#[test]
fn plot_draws_the_shipped_learning_curves() {
    let dir = temp_dir("plot");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/policies");
    let png = dir.join("curves.png");
    let stdout = ok(&fairgrasp(&[
        "plot",
        root.join("residual_hard").to_str().unwrap(),
        root.join("pure_hard").to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
    ]));
    assert!(stdout.contains("2 run(s)"), "{stdout}");
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn missing_or_wrong_folders_are_named_and_nothing_is_written() {
    let dir = temp_dir("report-errors");
    let out = fairgrasp(&[
        "report",
        dir.join("no_such_run").to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("no_such_run: no such folder"), "{stderr}");
    assert!(!dir.join("out").exists());

    let out = fairgrasp(&["plot", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("not a run folder: no metrics.csv"),
        "{stderr}"
    );

    let out = fairgrasp(&[
        "compare",
        "--policy",
        dir.to_str().unwrap(),
        "--episodes",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--policy") && stderr.contains("meta.json"),
        "{stderr}"
    );
}
