//! Every chart is written at its size, is not blank, and carries rendered text.

mod common;

use common::{Image, temp_dir, trajectory_json, write_comparison, write_run};
use fairgrasp_report::charts::{curves, episode, replay, success, workspace};
use fairgrasp_report::trajectory;
use fairgrasp_report::{Comparison, Outcome, RunFolder};

/// The PNG has `size`, real contrast, and dark (text) pixels in its title band `0..title_rows`.
fn assert_chart(path: &std::path::Path, size: (u32, u32), title_rows: u32) {
    let img = Image::read_png(path);
    assert_eq!((img.width, img.height), size, "{}", path.display());
    let variance = img.variance();
    assert!(
        variance > 200.0,
        "{}: luminance variance {variance}",
        path.display()
    );
    let text = img.dark_pixels(0, title_rows);
    assert!(
        text > 300,
        "{}: {text} dark pixels in the title band",
        path.display()
    );
}

#[test]
fn success_and_workspace_charts() {
    let dir = temp_dir("charts-compare");
    let c = write_comparison(&dir, Vec::new());
    success::success_chart(&c, &dir.join("success.png")).unwrap();
    assert_chart(&dir.join("success.png"), success::SIZE, 40);
    workspace::workspace_map(&c, "hard", &dir.join("ws.png")).unwrap();
    assert_chart(
        &dir.join("ws.png"),
        (2 * workspace::PANEL_WIDTH, workspace::HEIGHT),
        36,
    );
}

#[test]
fn workspace_map_colours_failures_where_they_started() {
    let dir = temp_dir("charts-ws-colour");
    let mut c: Comparison = write_comparison(&dir, Vec::new());
    // One method, every episode a collision: the map must hold the collision red and no
    // success green.
    c.results
        .retain(|r| r.preset == "hard" && r.method == "scripted baseline");
    for e in &mut c.results[0].report.results {
        e.outcome = Outcome::Collision;
    }
    workspace::workspace_map(&c, "hard", &dir.join("ws.png")).unwrap();
    let img = Image::read_png(&dir.join("ws.png"));
    let count = |rgb: [u8; 3]| {
        img.pixels
            .chunks_exact(img.channels)
            .skip(img.width as usize * 80)
            .filter(|p| p[..3] == rgb)
            .count()
    };
    assert!(count([225, 87, 89]) > 100, "no collision-red dots");
    assert_eq!(count([89, 161, 79]), 0, "success green without any success");
}

#[test]
fn learning_curves_of_two_runs() {
    let dir = temp_dir("charts-curves");
    write_run(&dir.join("a"), 60, 1);
    write_run(&dir.join("b"), 40, 2);
    let runs: Vec<RunFolder> = ["a", "b"]
        .iter()
        .map(|r| RunFolder::load(&dir.join(r)).unwrap())
        .collect();
    assert_eq!(runs[0].metrics.stage_changes().len(), 1);
    curves::learning_curves(&runs, &dir.join("curves.png")).unwrap();
    assert_chart(&dir.join("curves.png"), curves::SIZE, 40);
}

#[test]
fn episode_chart_and_replay() {
    let dir = temp_dir("charts-episode");
    let path = dir.join("ep.json");
    std::fs::write(&path, serde_json::to_vec(&trajectory_json(150)).unwrap()).unwrap();
    let t = trajectory::load(&path).unwrap();
    episode::episode_chart(&t, "test episode", &dir.join("ep.png")).unwrap();
    assert_chart(&dir.join("ep.png"), episode::SIZE, 40);
    replay::replay_still(&t, "test episode", 100, &dir.join("still.png")).unwrap();
    assert_chart(&dir.join("still.png"), replay::SIZE, 36);

    replay::replay_gif(&t, "test episode", &dir.join("ep.gif")).unwrap();
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(dir.join("ep.gif")).unwrap())
        .unwrap();
    assert_eq!(
        (u32::from(decoder.width()), u32::from(decoder.height())),
        replay::SIZE
    );
    let mut frames = 0;
    let mut first_variance = 0.0;
    let mut changed_in_every_frame = true;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        let opaque: Vec<f64> = frame
            .buffer
            .chunks_exact(4)
            .filter(|p| p[3] == 255)
            .map(|p| f64::from(p[0]) + f64::from(p[1]) + f64::from(p[2]))
            .collect();
        if frames == 0 {
            assert_eq!(
                opaque.len(),
                frame.buffer.len() / 4,
                "first frame fully drawn"
            );
            let mean = opaque.iter().sum::<f64>() / opaque.len() as f64;
            first_variance =
                opaque.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / opaque.len() as f64;
        } else {
            // Later frames hold only what changed: at least the time in the title.
            changed_in_every_frame &= !opaque.is_empty();
        }
        frames += 1;
    }
    // 150 steps at most 40 frames → every 4th step (38 frames) plus the final state.
    assert_eq!(frames, 39);
    assert!(
        first_variance > 1000.0,
        "first frame variance {first_variance}"
    );
    assert!(changed_in_every_frame);
}

#[test]
fn a_broken_trajectory_is_refused_with_its_file_and_row() {
    let dir = temp_dir("charts-broken-trajectory");
    let mut json = trajectory_json(5);
    json["rows"][3]["capsules"].as_array_mut().unwrap().pop();
    let path = dir.join("bad.json");
    std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    let e = trajectory::load(&path).unwrap_err().to_string();
    assert!(e.contains("bad.json") && e.contains("row 3"), "{e}");
}

#[test]
fn a_place_episodes_replay_draws_the_fixture() {
    // The fixture's colour in the replay (charts/replay.rs).
    const FIXTURE: [u8; 3] = [120, 150, 110];
    let count = |t: &trajectory::Trajectory| {
        replay::replay_frame_rgb(t, "place", 0)
            .unwrap()
            .chunks_exact(3)
            .filter(|p| *p == FIXTURE)
            .count()
    };
    let mut lift = trajectory_json(20);
    let plain: trajectory::Trajectory = serde_json::from_value(lift.clone()).unwrap();
    // A pocket of four 1 cm walls around (0.25, −0.2) on the table.
    let wall = |name: &str, centre: [f64; 3], half: [f64; 3]| serde_json::json!({"name": name, "body": 0, "kind": "box", "centre": centre, "half_extents": half});
    lift["scene"]["bodies"] = serde_json::json!(["fixture"]);
    lift["scene"]["shapes"] = serde_json::json!([
        wall("fixture_wall_0", [0.032, 0.0, 0.005], [0.005, 0.037, 0.005]),
        wall(
            "fixture_wall_1",
            [-0.032, 0.0, 0.005],
            [0.005, 0.037, 0.005]
        ),
        wall("fixture_wall_2", [0.0, 0.032, 0.005], [0.027, 0.005, 0.005]),
        wall(
            "fixture_wall_3",
            [0.0, -0.032, 0.005],
            [0.027, 0.005, 0.005]
        ),
    ]);
    for row in lift["rows"].as_array_mut().unwrap() {
        row["bodies"] = serde_json::json!([[0.25, -0.2, 0.0, 0.0, 0.0, 0.0, 1.0]]);
    }
    let place: trajectory::Trajectory = serde_json::from_value(lift).unwrap();
    assert_eq!(count(&plain), 0);
    // Seen from above and from the side: hundreds of pixels.
    assert!(count(&place) > 300, "{} fixture pixels", count(&place));
}
