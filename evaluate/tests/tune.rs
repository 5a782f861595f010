//! `fairgrasp tune` as a library: it improves a deliberately bad setting on a tiny budget,
//! resumes a folder to the very trials an uninterrupted tuning makes, writes a fragment that
//! reads back into the preset it was tuned on, and refuses bad requests by name, touching
//! nothing.

use std::path::{Path, PathBuf};

use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::presets;
use fairgrasp_evaluate::tune::{TuneError, TuneSpec, fragment, run_tune};

/// A fresh folder under the test's temporary root.
fn folder(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("tune")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// `place_fixture_error` with a deliberately bad spiral: coarse and fast (it outruns the press
/// and skips the opening).
fn bad_start() -> EnvConfig {
    let mut config = presets::load("place_fixture_error").unwrap();
    config.task.place.search.pitch = 0.006;
    config.task.place.search.speed = 0.05;
    config
}

/// The tuning of the spiral's pitch and speed from the bad start: 12 episodes a trial.
fn spiral_tuning(budget: u64) -> TuneSpec {
    let ranges = [("pitch".to_string(), None), ("speed".to_string(), None)];
    TuneSpec::new(
        "place_fixture_error",
        bad_start(),
        "force_search",
        &ranges,
        11,
        12,
        budget,
        0,
    )
    .unwrap()
}

fn tune(spec: &TuneSpec, dir: &Path) -> Result<fairgrasp_evaluate::tune::TuneOutcome, TuneError> {
    run_tune(spec, dir, 2, &|_| {})
}

fn csv(dir: &Path) -> String {
    std::fs::read_to_string(dir.join("trials.csv")).unwrap()
}

#[test]
fn tuning_improves_a_bad_start_and_resumes_to_the_same_trials() {
    let whole = folder("whole");
    let out = tune(&spiral_tuning(60_000), &whole).unwrap();
    let first = &out.trials[0];
    assert_eq!(
        first.values["pitch"], 0.006,
        "trial 0 is the preset's own setting"
    );
    assert_eq!(first.values["speed"], 0.05);
    let best = &out.trials[out.best];
    assert!(
        best.objective >= first.objective + 0.15,
        "the best trial {:.2} against the bad start's {:.2}",
        best.objective,
        first.objective
    );
    let spent: u64 = out.trials.iter().map(|t| t.env_steps).sum();
    assert!(spent >= 60_000 && out.note.env_steps == spent);
    // Interrupted after 4 trials (a kill leaves whole rows: the file is rewritten atomically),
    // then run again: the same trials, to the last digit.
    let resumed = folder("resumed");
    tune(&spiral_tuning(60_000), &resumed).unwrap();
    let all = csv(&whole);
    let rows: Vec<&str> = all.lines().take(5).collect();
    std::fs::write(resumed.join("trials.csv"), rows.join("\n") + "\n").unwrap();
    tune(&spiral_tuning(60_000), &resumed).unwrap();
    assert_eq!(csv(&resumed), csv(&whole));
    // A larger budget goes on from where the smaller one stopped.
    let more = tune(&spiral_tuning(90_000), &resumed).unwrap();
    assert!(more.trials.len() > out.trials.len());
    assert!(csv(&resumed).starts_with(&csv(&whole)));
    // The fragment reads back into the preset: the best trial's setting, and how it was found.
    let mut config = presets::load("place_fixture_error").unwrap();
    let control = fragment::apply(
        &mut config,
        "place_fixture_error",
        &whole.join("tuned.toml"),
    )
    .unwrap();
    assert_eq!(control.cli, "force_search");
    assert_eq!(config.task.place.search.pitch, best.values["pitch"]);
    assert_eq!(config.task.place.search.speed, best.values["speed"]);
    let note = &config.control.tuned["force_search"];
    assert_eq!((note.trials, note.scenario_seed), (out.trials.len(), 11));
}

/// Each bad request names what is wrong and what would be right.
#[test]
fn bad_requests_are_refused_by_name() {
    let config = presets::load("place_cell").unwrap();
    let spec = |control: &str, ranges: &[(String, Option<[f64; 2]>)], episodes, budget| {
        TuneSpec::new(
            "place_cell",
            config.clone(),
            control,
            ranges,
            11,
            episodes,
            budget,
            0,
        )
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default()
    };
    let p = |name: &str, r: Option<[f64; 2]>| vec![(name.to_string(), r)];
    for (message, wants) in [
        (
            spec("spiral", &[], 10, 1000),
            vec!["--control spiral", "force_search"],
        ),
        (
            spec("open_loop", &[], 10, 1000),
            vec!["no parameters", "force_search"],
        ),
        (
            spec("force_search", &p("wobble", None), 10, 1000),
            vec!["--param wobble", "contact_force"],
        ),
        (
            spec(
                "force_search",
                &p("contact_force", Some([0.05, 3.0])),
                10,
                1000,
            ),
            vec!["contact_force=0.05:3", "[0.1, 30] N"],
        ),
        (
            spec("force_search", &p("pitch", Some([0.004, 0.002])), 10, 1000),
            vec!["pitch=0.004:0.002", "low below high"],
        ),
        (
            spec("force_search", &[], 10, 0),
            vec!["--budget 0", "[1, 1000000000]"],
        ),
        (
            spec("force_search", &[], 10, 2_000_000_000),
            vec!["--budget 2000000000"],
        ),
        (spec("force_search", &[], 0, 1000), vec!["--episodes 0"]),
        (
            spec("tuned_grip", &[], 10, 1000),
            vec!["--control tuned_grip", "force_search"],
        ),
    ] {
        for w in wants {
            assert!(message.contains(w), "`{message}` should name `{w}`");
        }
    }
}

/// A folder of one tuning is not resumed as another's: another preset, another objective or
/// a preset edited since are refused naming what changed, and the folder's files stay as they
/// were; a folder that is no tuning's is refused too.
#[test]
fn a_resumed_tuning_must_be_the_same_tuning() {
    let dir = folder("changed");
    tune(&spiral_tuning(3_000), &dir).unwrap();
    let before = csv(&dir);
    let mut edited = bad_start();
    edited.task.place.wall_height = 0.012;
    let ranges = [("pitch".to_string(), None), ("speed".to_string(), None)];
    let other = TuneSpec::new(
        "place_fixture_error",
        edited,
        "force_search",
        &ranges,
        11,
        12,
        3_000,
        0,
    )
    .unwrap();
    let e = tune(&other, &dir).err().unwrap().to_string();
    // The refusal names the field that differs, with both values.
    assert!(
        e.contains("preset's config") && e.contains("task.place.wall_height = 0.012"),
        "{e}"
    );
    let record = std::fs::read_to_string(dir.join("tune.json")).unwrap();
    std::fs::write(
        dir.join("tune.json"),
        record.replace("success_within_takt", "success"),
    )
    .unwrap();
    let e = tune(&spiral_tuning(3_000), &dir).err().unwrap().to_string();
    assert!(e.contains("objective"), "{e}");
    assert_eq!(csv(&dir), before, "a refused resume writes nothing");
    let stranger = folder("stranger");
    std::fs::create_dir_all(&stranger).unwrap();
    std::fs::write(stranger.join("notes.txt"), "mine").unwrap();
    let e = tune(&spiral_tuning(3_000), &stranger)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("not a tuning folder"), "{e}");
    assert_eq!(
        std::fs::read_to_string(stranger.join("notes.txt")).unwrap(),
        "mine"
    );
}

/// A fragment is read only into the preset and control it was tuned for, and only with its
/// control's table.
#[test]
fn a_fragment_that_conflicts_with_the_preset_is_refused() {
    let dir = folder("fragment");
    tune(&spiral_tuning(3_000), &dir).unwrap();
    let path = dir.join("tuned.toml");
    let mut tilted = presets::load("place_tilted").unwrap();
    let e = fragment::apply(&mut tilted, "place_tilted", &path)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("conflicts with the preset") && e.contains("place_fixture_error"),
        "{e}"
    );
    assert_eq!(
        tilted,
        presets::load("place_tilted").unwrap(),
        "nothing applied"
    );
    let text = std::fs::read_to_string(&path).unwrap();
    let foreign = dir.join("foreign.toml");
    std::fs::write(&foreign, format!("{text}\n[task]\nmax_steps = 50\n")).unwrap();
    let mut config = presets::load("place_fixture_error").unwrap();
    let e = fragment::apply(&mut config, "place_fixture_error", &foreign)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("task.max_steps"), "{e}");
    let refused = dir.join("refused.toml");
    // A pitch the preset refuses (more than 2 cm a turn).
    let too_coarse: Vec<String> = text
        .lines()
        .map(|l| {
            if l.starts_with("pitch =") {
                "pitch = 0.5".to_string()
            } else {
                l.to_string()
            }
        })
        .collect();
    std::fs::write(&refused, too_coarse.join("\n")).unwrap();
    let e = fragment::apply(&mut config, "place_fixture_error", &refused)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("task.place.search.pitch") && e.contains("0.5"),
        "{e}"
    );
    let plain = dir.join("plain.toml");
    std::fs::write(&plain, "[task.place.search]\npitch = 0.002\n").unwrap();
    let e = fragment::apply(&mut config, "place_fixture_error", &plain)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("[control.tuned"), "{e}");
}

/// A `trials.csv` edited or cut by hand is refused on resume, naming the file, the line and
/// what is wrong with it, and the refusal writes nothing (the file and `tuned.toml` stay).
#[test]
fn a_trials_csv_edited_by_hand_is_refused_naming_the_line_and_the_field() {
    let dir = folder("edited");
    let spec = spiral_tuning(8_000);
    tune(&spec, &dir).unwrap();
    let good = csv(&dir);
    let lines: Vec<&str> = good.lines().collect();
    assert!(lines.len() >= 3, "two trials at least: {good}");
    let header: Vec<&str> = lines[0].split(',').collect();
    let column = |name: &str| header.iter().position(|c| *c == name).unwrap();
    // `good` with the cell `name` of line `line` (1 = the header) set to `value`.
    let with = |line: usize, name: &str, value: &str| {
        let mut rows: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        let mut cells: Vec<&str> = lines[line - 1].split(',').collect();
        cells[column(name)] = value;
        rows[line - 1] = cells.join(",");
        rows.join("\n") + "\n"
    };
    let pitch = lines[1]
        .split(',')
        .nth(column("pitch"))
        .unwrap()
        .to_string();
    let other_pitch = if pitch == "0.005" { "0.004" } else { "0.005" };
    let mut swapped: Vec<&str> = lines.clone();
    swapped.swap(1, 2);
    let cases: Vec<(&str, String, Vec<String>)> = vec![
        (
            "cut",
            good[..good.len() - 3].to_string(),
            vec![format!("line {}", lines.len()), "cut short".into()],
        ),
        (
            "NaN",
            with(2, "objective", "NaN"),
            vec![
                "line 2".into(),
                "objective `NaN` is not a finite number".into(),
            ],
        ),
        (
            "extra column",
            good.replacen(lines[1], &format!("{},7", lines[1]), 1),
            vec![
                "line 2".into(),
                format!("{} fields, expected {}", header.len() + 1, header.len()),
            ],
        ),
        (
            "out of order",
            swapped.join("\n") + "\n",
            vec!["line 2".into(), "trial `1`, expected 0".into()],
        ),
        (
            "objective",
            with(2, "objective", "0.99"),
            vec!["line 2".into(), "objective 0.99 is neither".into()],
        ),
        (
            "more successes than episodes",
            with(2, "successes", "99"),
            vec!["line 2".into(), "successes 99".into()],
        ),
        (
            "value",
            with(2, "pitch", other_pitch),
            vec![
                format!("trial 0: pitch = {other_pitch} in the file"),
                format!("asks for {pitch} again"),
            ],
        ),
    ];
    let fragment = std::fs::read(dir.join("tuned.toml")).unwrap();
    for (what, text, needles) in cases {
        std::fs::write(dir.join("trials.csv"), &text).unwrap();
        let e = tune(&spec, &dir)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(e.contains("trials.csv"), "{what}: {e}");
        for n in needles {
            assert!(e.contains(&n), "{what}: `{n}` not in `{e}`");
        }
        assert_eq!(csv(&dir), text, "{what}: the refused file was rewritten");
        assert_eq!(
            std::fs::read(dir.join("tuned.toml")).unwrap(),
            fragment,
            "{what}"
        );
    }
    // Put back as it was, it resumes.
    std::fs::write(dir.join("trials.csv"), &good).unwrap();
    tune(&spec, &dir).unwrap();
    assert_eq!(csv(&dir), good);
}

/// A tuning of a preset file goes on with the preset its folder recorded, whatever the file
/// of that name holds now, and says how that file differs.
#[test]
fn a_resumed_tuning_of_a_preset_file_runs_on_the_recorded_preset() {
    let dir = folder("file");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.with_extension("toml");
    std::fs::write(&file, bad_start().to_toml()).unwrap();
    let name = file.to_str().unwrap();
    assert!(
        fairgrasp_evaluate::tune::folder::recorded_preset_file(&dir, name)
            .unwrap()
            .is_none()
    );
    let ranges = [("pitch".to_string(), None)];
    let spec = |config: EnvConfig| {
        TuneSpec::new(name, config, "force_search", &ranges, 11, 12, 3_000, 0).unwrap()
    };
    tune(&spec(bad_start()), &dir).unwrap();
    let mut edited = bad_start();
    edited.task.place.search.speed = 0.02;
    std::fs::write(&file, edited.to_toml()).unwrap();
    let (recorded, note) = fairgrasp_evaluate::tune::folder::recorded_preset_file(&dir, name)
        .unwrap()
        .unwrap();
    assert_eq!(recorded, bad_start());
    let note = note.unwrap();
    assert!(
        note.contains("task.place.search.speed: 0.05 → 0.02"),
        "{note}"
    );
    // The edited file itself is another tuning: refused naming the field.
    let e = tune(&spec(edited), &dir).err().unwrap().to_string();
    assert!(
        e.contains("task.place.search.speed = 0.05 (tune.json)"),
        "{e}"
    );
    std::fs::remove_file(&file).unwrap();
    let (_, note) = fairgrasp_evaluate::tune::folder::recorded_preset_file(&dir, name)
        .unwrap()
        .unwrap();
    assert!(note.unwrap().contains("missing"));
}
