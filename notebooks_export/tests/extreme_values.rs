//! Every chart finishes on any numbers a hand-edited or corrupted folder may hold: huge, tiny,
//! mixed, equal, a single point, none at all, NaN and infinities. Finite values are drawn
//! (pinned to the axis where they cannot fit); non-finite ones are skipped. A request past the
//! data (a replay still after the last step) is refused with the allowed range.
//!
//! Before the axes were bounded, 1.7e308 sent the tick computation into an endless loop: these
//! tests then never finished.

mod common;

use std::path::Path;

use common::{Image, temp_dir, trajectory_json, write_comparison};
use fairgrasp_report::RunFolder;
use fairgrasp_report::charts::{curves, episode, replay, success, workspace};
use fairgrasp_report::trajectory::{self, Trajectory};

/// Values a chart must survive: alone, mixed with ordinary numbers, and non-finite.
const EXTREMES: [f64; 5] = [1.7e308, -1e308, 1e-308, f64::MAX, -f64::MIN_POSITIVE];

/// Asserts `path` is a PNG of `size`.
fn assert_png(path: &Path, size: (u32, u32)) {
    let img = Image::read_png(path);
    assert_eq!((img.width, img.height), size, "{}", path.display());
}

/// A run folder whose metrics columns take `values` in turn (one row per value); timesteps are
/// `steps` per row.
fn write_run_with(dir: &Path, values: &[f64], steps: impl Fn(usize) -> f64) {
    std::fs::create_dir_all(dir).unwrap();
    let mut csv = String::from(
        "timesteps,episode_return,success_rate,policy_loss,value_loss,entropy,\
         explained_variance,stage,eval_success_rate\n",
    );
    for (i, v) in values.iter().enumerate() {
        // Rust prints NaN as `NaN` and infinity as `inf`: both parse back as f64.
        csv += &format!("{},{v},{v},{v},{v},{v},{v},{i},{v}\n", steps(i));
    }
    std::fs::write(dir.join("metrics.csv"), csv).unwrap();
    std::fs::write(dir.join("config.toml"), "seed = 0\n").unwrap();
}

#[test]
fn learning_curves_survive_extreme_equal_single_and_non_finite_metrics() {
    let dir = temp_dir("extreme-curves");
    let mut cases: Vec<(String, Vec<f64>)> = EXTREMES
        .iter()
        .map(|v| (format!("alone {v:e}"), vec![*v, *v, *v]))
        .collect();
    cases.extend([
        (
            "mixed".to_string(),
            vec![0.1, 1.7e308, 0.3, -1e308, 1e-308, 0.5],
        ),
        ("all equal".into(), vec![3.25; 8]),
        ("single point".into(), vec![0.7]),
        (
            "non-finite".into(),
            vec![f64::NAN, 0.2, f64::INFINITY, 0.4, f64::NEG_INFINITY],
        ),
        ("only NaN".into(), vec![f64::NAN, f64::NAN]),
    ]);
    for (k, (name, values)) in cases.iter().enumerate() {
        let run = dir.join(format!("run{k}"));
        write_run_with(&run, values, |i| 2048.0 * (i + 1) as f64);
        let runs = [RunFolder::load(&run).unwrap()];
        let png = dir.join(format!("curves{k}.png"));
        curves::learning_curves(&runs, &png).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_png(&png, curves::SIZE);
    }
    // Extreme steps on the x axis, and no run at all.
    for (k, step) in [1.7e308, -1e308, 1e-308, f64::NAN].into_iter().enumerate() {
        let run = dir.join(format!("steps{k}"));
        write_run_with(&run, &[0.1, 0.2, 0.3], |i| step * i as f64);
        let runs = [RunFolder::load(&run).unwrap()];
        let png = dir.join(format!("steps{k}.png"));
        curves::learning_curves(&runs, &png).unwrap_or_else(|e| panic!("steps {step}: {e}"));
        assert_png(&png, curves::SIZE);
    }
    curves::learning_curves(&[], &dir.join("none.png")).unwrap();
    assert_png(&dir.join("none.png"), curves::SIZE);
}

/// Sets `field[index]` (or `field` when `index` is None) of row `row` to `v`.
fn set(json: &mut serde_json::Value, row: usize, field: &str, index: Option<usize>, v: f64) {
    let cell = &mut json["rows"][row][field];
    match index {
        Some(i) => cell[i] = serde_json::json!(v),
        None => *cell = serde_json::json!(v),
    }
}

#[test]
fn episode_chart_replay_and_still_survive_extreme_positions() {
    let dir = temp_dir("extreme-episode");
    let edits: [(&str, Option<usize>); 7] = [
        ("tcp_xyz", Some(0)),
        ("object_xyz", Some(2)),
        ("joints", Some(1)),
        ("gripper_opening_m", None),
        ("time_s", None),
        ("object_quat_xyzw", Some(3)),
        ("capsules", None),
    ];
    for (k, (field, index)) in edits.iter().enumerate() {
        for (j, v) in EXTREMES.iter().enumerate() {
            let mut json = trajectory_json(12);
            for row in [4, 5] {
                if *field == "capsules" {
                    // Both ends of a capsule far away, and a huge radius.
                    json["rows"][row]["capsules"][1][3] = serde_json::json!(v);
                    json["rows"][row]["capsules"][2][6] = serde_json::json!(v.abs());
                } else {
                    set(&mut json, row, field, *index, *v);
                }
            }
            let path = dir.join(format!("ep{k}_{j}.json"));
            std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
            let t = trajectory::load(&path).unwrap();
            let what = format!("{field} = {v:e}");
            let png = dir.join(format!("ep{k}_{j}.png"));
            episode::episode_chart(&t, &what, &png).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert_png(&png, episode::SIZE);
            let still = dir.join(format!("still{k}_{j}.png"));
            replay::replay_still(&t, &what, 5, &still).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert_png(&still, replay::SIZE);
            let gif = dir.join(format!("ep{k}_{j}.gif"));
            replay::replay_gif(&t, &what, &gif).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!(std::fs::metadata(&gif).unwrap().len() > 0);
        }
    }
    // Every row at the same place: a single point on every axis.
    let mut json = trajectory_json(3);
    for row in 0..3 {
        json["rows"][row] = json["rows"][0].clone();
    }
    let path = dir.join("still.json");
    std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    let t = trajectory::load(&path).unwrap();
    episode::episode_chart(&t, "motionless", &dir.join("still.png")).unwrap();
    replay::replay_gif(&t, "motionless", &dir.join("still.gif")).unwrap();
}

#[test]
fn success_and_workspace_charts_survive_extreme_and_non_finite_results() {
    let dir = temp_dir("extreme-compare");
    for (k, v) in EXTREMES
        .iter()
        .chain(&[f64::NAN, f64::INFINITY])
        .enumerate()
    {
        let mut c = write_comparison(&dir.join(format!("c{k}")), Vec::new());
        let r = &mut c.results[0].report;
        r.success_rate = *v;
        r.ci_low = -v;
        r.ci_high = *v;
        r.results[0].object_xy = [*v, -v];
        r.results[1].object_xy = [0.3, *v];
        let png = dir.join(format!("success{k}.png"));
        success::success_chart(&c, &png).unwrap_or_else(|e| panic!("{v}: {e}"));
        assert_png(&png, success::SIZE);
        let preset = c.results[0].preset.clone();
        let png = dir.join(format!("ws{k}.png"));
        workspace::workspace_map(&c, &preset, &png).unwrap_or_else(|e| panic!("{v}: {e}"));
        assert_png(&png, (2 * workspace::PANEL_WIDTH, workspace::HEIGHT));
    }
}

#[test]
fn a_still_past_the_last_step_is_refused_with_the_allowed_range() {
    let dir = temp_dir("extreme-still");
    let path = dir.join("ep.json");
    std::fs::write(&path, serde_json::to_vec(&trajectory_json(30)).unwrap()).unwrap();
    let t = trajectory::load(&path).unwrap();
    let still = dir.join("still.png");
    let e = replay::replay_still(&t, "ep", 100_000, &still)
        .unwrap_err()
        .to_string();
    assert!(e.contains("100000") && e.contains("0–29"), "{e}");
    assert!(
        !still.exists(),
        "a still was written for a step past the end"
    );
    replay::replay_still(&t, "ep", 29, &still).unwrap();
    assert_png(&still, replay::SIZE);
}

#[test]
fn an_episode_without_steps_is_refused_instead_of_panicking() {
    let dir = temp_dir("extreme-empty");
    let t = Trajectory::default();
    for (name, result) in [
        (
            "chart",
            episode::episode_chart(&t, "empty", &dir.join("e.png")),
        ),
        ("gif", replay::replay_gif(&t, "empty", &dir.join("e.gif"))),
        (
            "still",
            replay::replay_still(&t, "empty", 0, &dir.join("s.png")),
        ),
    ] {
        let e = result.unwrap_err().to_string();
        assert!(e.contains("no recorded steps"), "{name}: {e}");
    }
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
}
