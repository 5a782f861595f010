//! `fairgrasp tune` as a library: it improves a deliberately bad setting on a tiny budget,
//! resumes a folder to the very trials (and finalists, and fragment) an uninterrupted tuning
//! makes, chooses among its best trials on validation scenarios, restarts a stalled search,
//! writes a fragment that reads back into the preset it was tuned on (by content), and refuses
//! bad requests and files by name, touching nothing.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::presets;
use fairgrasp_evaluate::tune::{
    TuneError, TuneEvent, TuneSpec, Validation, best_of, chosen_of, finalists_of, fragment,
    run_tune,
};

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

/// A small validation: the 3 best trials on 12 scenarios of seed 12.
const SMALL_VALIDATION: Validation = Validation {
    seed: 12,
    episodes: 12,
    finalists: 3,
};

/// The tuning of the spiral's pitch and speed from the bad start: 12 episodes a trial, its 3
/// best trials validated on 12 episodes.
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
    .with_validation(SMALL_VALIDATION)
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
    // The budget holds the trials and the validation of the finalists.
    let spent: u64 = out.trials.iter().map(|t| t.env_steps).sum();
    let validated: u64 = out.finalists.iter().map(|f| f.validation.env_steps).sum();
    assert_eq!(out.finalists.len(), 3);
    assert!(validated > 0 && out.validation_env_steps == validated);
    // The search stops when its steps and the validation's, estimated from the trials' mean
    // steps an episode, reach the budget: the total lands near it (finalists, the better
    // settings, seat sooner than the mean trial), not exactly on it.
    assert_eq!(out.note.env_steps, spent + validated);
    assert!(
        spent + validated >= 48_000,
        "{spent} + {validated} env steps of a 60 000 budget"
    );
    assert!(
        spent < 60_000,
        "the search left the validation its part of the budget"
    );
    // Interrupted after 4 trials (a kill leaves whole rows: the file is rewritten atomically),
    // then run again: the same trials, finalists and fragment, to the last digit.
    let resumed = folder("resumed");
    tune(&spiral_tuning(60_000), &resumed).unwrap();
    let all = csv(&whole);
    let rows: Vec<&str> = all.lines().take(5).collect();
    std::fs::write(resumed.join("trials.csv"), rows.join("\n") + "\n").unwrap();
    std::fs::remove_file(resumed.join("finalists.csv")).unwrap();
    std::fs::remove_file(resumed.join("tuned.toml")).unwrap();
    tune(&spiral_tuning(60_000), &resumed).unwrap();
    for file in ["trials.csv", "finalists.csv", "tuned.toml"] {
        assert_eq!(
            std::fs::read_to_string(resumed.join(file)).unwrap(),
            std::fs::read_to_string(whole.join(file)).unwrap(),
            "{file}"
        );
    }
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
            "episodes of another tuning",
            with(2, "episodes", "1000"),
            vec![
                "line 2".into(),
                "episodes 1000".into(),
                "runs 12 a trial".into(),
            ],
        ),
        (
            "env steps that wrap",
            with(3, "env_steps", "18446744073709551615"),
            vec!["line 3".into(), "env_steps 18446744073709551615".into()],
        ),
        (
            "a negative cycle time",
            with(2, "mean_cycle_time_s", "-1e308"),
            vec!["line 2".into(), "mean_cycle_time_s -1e308".into()],
        ),
        (
            "a cycle longer than an episode",
            with(2, "mean_cycle_time_s", "1000000"),
            vec!["line 2".into(), "mean_cycle_time_s 1000000".into()],
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
        TuneSpec::new(name, config, "force_search", &ranges, 11, 12, 3_000, 0)
            .unwrap()
            .with_validation(SMALL_VALIDATION)
            .unwrap()
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

/// The finalists are the best trials (distinct settings, by their score), each run again on
/// the validation's scenarios; the tuned setting is the best there, not the best trial. With 2
/// episodes a trial the scores are noise (a trial is 0, 50 or 100 %): here the best trial loses
/// on validation to another finalist, and that other finalist is the one chosen — a tuning that
/// chose by the trials would write the best trial's setting.
#[test]
fn the_setting_chosen_is_the_best_finalist_on_validation_not_the_best_trial() {
    let dir = folder("finalists");
    let ranges = [("pitch".to_string(), None), ("speed".to_string(), None)];
    let validation = Validation {
        seed: 12,
        episodes: 24,
        finalists: 5,
    };
    let spec = TuneSpec::new(
        "place_fixture_error",
        bad_start(),
        "force_search",
        &ranges,
        11,
        NOISY_EPISODES,
        NOISY_BUDGET,
        NOISY_OPTIMISER_SEED,
    )
    .unwrap()
    .with_validation(validation)
    .unwrap();
    let out = tune(&spec, &dir).unwrap();
    let expected: Vec<usize> = finalists_of(&out.trials, 5)
        .iter()
        .map(|t| t.index)
        .collect();
    let got: Vec<usize> = out.finalists.iter().map(|f| f.trial.index).collect();
    assert_eq!(got, expected, "the 5 best trials, best first");
    assert_eq!(got.len(), 5);
    for f in &out.finalists {
        assert_eq!(f.validation.episodes, 24);
        assert_eq!(f.validation.values, f.trial.values);
        assert_eq!(f.trial, out.trials[f.trial.index]);
    }
    // The best trial is the first finalist; it loses on validation.
    let top = best_of(&out.trials);
    assert_eq!(got[0], top);
    let chosen = chosen_of(&out.finalists).unwrap();
    assert_eq!(out.best, chosen.trial.index);
    assert!(
        out.finalists
            .iter()
            .all(|f| f.validation.objective <= chosen.validation.objective)
    );
    assert_ne!(
        out.best,
        top,
        "the construction: the best trial must lose on validation ({:?})",
        out.finalists
            .iter()
            .map(|f| (f.trial.index, f.trial.objective, f.validation.objective))
            .collect::<Vec<_>>()
    );
    assert!(out.finalists[0].validation.objective < chosen.validation.objective);
    assert!(out.trials[top].objective >= out.trials[out.best].objective);
    // The fragment holds the chosen setting and both figures; finalists.csv every finalist's.
    let text = std::fs::read_to_string(dir.join("tuned.toml")).unwrap();
    // The preset as shipped differs from the bad start only in the table the fragment sets.
    let mut config = presets::load("place_fixture_error").unwrap();
    fragment::apply(&mut config, "place_fixture_error", &dir.join("tuned.toml")).unwrap();
    assert_eq!(
        config.task.place.search.pitch,
        out.trials[out.best].values["pitch"]
    );
    for needle in [
        format!("best = {}", out.trials[out.best].objective),
        format!("best_trial = {}", out.best),
        format!("validation_best = {}", chosen.validation.objective),
        "validation_seed = 12".to_string(),
        "validation_episodes = 24".to_string(),
        "finalists = 5".to_string(),
        format!("validation_env_steps = {}", out.validation_env_steps),
        "preset_checksum = \"fnv1a64:".to_string(),
    ] {
        assert!(text.contains(&needle), "`{needle}` not in {text}");
    }
    let finalists = std::fs::read_to_string(dir.join("finalists.csv")).unwrap();
    let lines: Vec<&str> = finalists.lines().collect();
    assert_eq!(lines.len(), 6, "{finalists}");
    let header: Vec<&str> = lines[0].split(',').collect();
    let col = |name: &str| header.iter().position(|c| *c == name).unwrap();
    for (line, f) in lines[1..].iter().zip(&out.finalists) {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells[col("trial")], f.trial.index.to_string());
        assert_eq!(cells[col("trial_objective")], f.trial.objective.to_string());
        assert_eq!(
            cells[col("validation_objective")],
            f.validation.objective.to_string()
        );
        assert_eq!(cells[col("validation_seed")], "12");
        assert_eq!(
            cells[col("chosen")],
            (f.trial.index == out.best).to_string()
        );
    }
}

/// The noisy tuning of the test above: 2 episodes a trial.
const NOISY_EPISODES: usize = 2;
const NOISY_BUDGET: u64 = 40_000;
const NOISY_OPTIMISER_SEED: u64 = 0;

/// The validation's seed is neither the reported seed (7) nor the tuning's; counts bounded.
#[test]
fn a_validation_on_the_reported_or_the_tuning_seed_is_refused() {
    let ranges = [("pitch".to_string(), None)];
    let spec = || {
        TuneSpec::new(
            "place_fixture_error",
            bad_start(),
            "force_search",
            &ranges,
            11,
            4,
            1000,
            0,
        )
        .unwrap()
    };
    assert_eq!(spec().validation.seed, 12, "the default");
    assert_eq!(spec().validation.episodes, 300);
    assert_eq!(spec().validation.finalists, 5);
    let with = |seed, episodes, finalists| {
        spec()
            .with_validation(Validation {
                seed,
                episodes,
                finalists,
            })
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    for (message, needle) in [
        (with(7, 10, 2), "--validation-seed 7"),
        (with(11, 10, 2), "--validation-seed 11"),
        (with(12, 0, 2), "--validation-episodes 0"),
        (with(12, 10, 0), "--finalists 0"),
    ] {
        assert!(
            message.contains(needle),
            "`{message}` should name `{needle}`"
        );
    }
    assert!(with(13, 10, 2).is_empty());
    let on_12 = TuneSpec::new(
        "place_fixture_error",
        bad_start(),
        "force_search",
        &ranges,
        12,
        4,
        1000,
        0,
    )
    .unwrap();
    assert_eq!(on_12.validation.seed, 13, "never the tuning's own seed");
}

/// A search that finds nothing better for `stall_generations` generations restarts around the
/// best trial with half the spread: a search whose every trial is one setting (its only
/// parameter a switch held on) never finds better, and restarts every 2 generations.
#[test]
fn a_stalled_search_restarts_around_the_best_with_half_the_spread() {
    let dir = folder("stall");
    let ranges = [("check_floor".to_string(), Some([1.0, 1.0]))];
    let spec = TuneSpec::new(
        "place_fixture_error",
        presets::load("place_fixture_error").unwrap(),
        "force_search",
        &ranges,
        11,
        STALL_EPISODES,
        8_000,
        0,
    )
    .unwrap()
    .with_validation(Validation {
        seed: 12,
        episodes: 1,
        finalists: 1,
    })
    .unwrap()
    .with_stall_generations(2);
    let restarts = Mutex::new(Vec::new());
    let out = run_tune(&spec, &dir, 2, &|e| {
        if let TuneEvent::Restart {
            generation,
            sigma,
            stalled,
        } = e
        {
            restarts.lock().unwrap().push((generation, sigma, stalled));
        }
    })
    .unwrap();
    assert!(
        out.trials
            .iter()
            .all(|t| t.objective == out.trials[0].objective)
    );
    let generations = out.trials.last().unwrap().generation;
    assert!(generations >= 4, "{generations} generations");
    let restarts = restarts.into_inner().unwrap();
    assert!(restarts.len() >= 2, "{restarts:?}");
    assert_eq!(restarts[0], (2, 0.125, Some(2)));
    assert_eq!(restarts[1], (4, 0.0625, Some(2)));
    assert_eq!(out.restarts, restarts.len());
    assert!(
        std::fs::read_to_string(dir.join("tuned.toml"))
            .unwrap()
            .contains(&format!("restarts = {}", restarts.len()))
    );
    // Without the stall rule, the same search never restarts for a stall.
    let plain = folder("stall-off");
    run_tune(&spec.with_stall_generations(0), &plain, 2, &|e| {
        assert!(!matches!(
            e,
            TuneEvent::Restart {
                stalled: Some(_),
                ..
            }
        ));
    })
    .unwrap();
}

/// Episodes a trial of the stall test.
const STALL_EPISODES: usize = 1;

/// A switch's range is honoured (`1:1` holds it on in every trial) or refused (`0.3:0.7`).
#[test]
fn a_switch_range_is_honoured_or_refused() {
    let config = presets::load("place_fixture_error").unwrap();
    assert!(!config.task.place.search.check_floor, "off in the preset");
    let ranges = [
        ("check_floor".to_string(), Some([1.0, 1.0])),
        ("pitch".to_string(), None),
    ];
    let spec = TuneSpec::new(
        "place_fixture_error",
        config.clone(),
        "force_search",
        &ranges,
        11,
        2,
        3_000,
        0,
    )
    .unwrap()
    .with_validation(Validation {
        seed: 12,
        episodes: 2,
        finalists: 2,
    })
    .unwrap();
    let dir = folder("switch");
    let out = tune(&spec, &dir).unwrap();
    assert!(out.trials.len() >= 2);
    for t in &out.trials {
        assert_eq!(t.values["check_floor"], 1.0, "trial {}", t.index);
    }
    assert!(out.tuned.task.place.search.check_floor);
    for range in [[0.3, 0.7], [1.0, 0.0], [0.0, 2.0]] {
        let e = TuneSpec::new(
            "place_fixture_error",
            config.clone(),
            "force_search",
            &[("check_floor".to_string(), Some(range))],
            11,
            2,
            3_000,
            0,
        )
        .err()
        .unwrap()
        .to_string();
        assert!(
            e.contains("check_floor") && e.contains("switch") && e.contains("1:1"),
            "{e}"
        );
    }
}

/// A folder another process tunes in is refused naming it, its files untouched.
#[test]
fn a_folder_locked_by_another_tuning_is_refused() {
    let dir = folder("locked");
    tune(&spiral_tuning(3_000), &dir).unwrap();
    let before = csv(&dir);
    let lock = fairgrasp_types::fs::FolderLock::acquire(&dir, ".lock", "tuning", "--out").unwrap();
    let e = tune(&spiral_tuning(12_000), &dir)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("is in use") && e.contains("--out"), "{e}");
    assert_eq!(csv(&dir), before);
    drop(lock);
    tune(&spiral_tuning(12_000), &dir).unwrap();
    assert!(csv(&dir).len() > before.len());
}

/// A finished tuning's `tuned.toml` that the user edited is kept; the new one goes beside it.
/// One `tune` wrote and nobody touched is rewritten.
#[test]
fn an_edited_fragment_is_kept_and_the_new_one_written_beside_it() {
    let dir = folder("edited-fragment");
    let out = tune(&spiral_tuning(3_000), &dir).unwrap();
    assert_eq!(out.fragment.path, dir.join("tuned.toml"));
    assert_eq!(out.fragment.kept_edited, None);
    let path = dir.join("tuned.toml");
    let first = std::fs::read_to_string(&path).unwrap();
    // Unedited: a larger budget rewrites it in place.
    let out = tune(&spiral_tuning(12_000), &dir).unwrap();
    assert_eq!(out.fragment.kept_edited, None);
    let text = std::fs::read_to_string(&path).unwrap();
    assert_ne!(text, first, "more trials, another note");
    assert!(!dir.join("tuned.new.toml").exists());
    let edited = text.replace("\n[task.place.search]", "\n# mine\n[task.place.search]");
    assert_ne!(edited, text);
    std::fs::write(&path, &edited).unwrap();
    let out = tune(&spiral_tuning(20_000), &dir).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), edited, "kept");
    assert_eq!(out.fragment.kept_edited, Some(path.clone()));
    assert_eq!(out.fragment.path, dir.join("tuned.new.toml"));
    let new = std::fs::read_to_string(dir.join("tuned.new.toml")).unwrap();
    assert!(
        new.contains(&format!("trials = {}", out.trials.len())),
        "{new}"
    );
}

/// Env steps read in the unit that fits: a small tuning's fragment says `N env steps`, never
/// `0.00 M`; a large one says millions.
#[test]
fn env_steps_are_written_in_the_unit_that_fits() {
    let dir = folder("units");
    let out = tune(&spiral_tuning(600), &dir).unwrap();
    let text = std::fs::read_to_string(dir.join("tuned.toml")).unwrap();
    let header = text.lines().take(3).collect::<Vec<_>>().join("\n");
    assert!(
        header.contains(&format!("{} env steps", out.note.env_steps)),
        "{header}"
    );
    assert!(!header.contains("0.00 M"), "{header}");
    assert_eq!(fragment::env_steps_text(624), "624 env steps");
    assert_eq!(fragment::env_steps_text(3_007_466), "3.01 M env steps");
    assert!(fragment::summary(&out.note).ends_with(&format!("{} env steps", out.note.env_steps)));
}

/// A fragment is checked against the preset by content (a file of the same name with other
/// walls is refused; the same content under another name is not), its rates bounded, and a
/// control without parameters refused.
#[test]
fn a_fragment_is_checked_by_the_content_of_its_preset_and_its_figures() {
    let dir = folder("content");
    std::fs::create_dir_all(&dir).unwrap();
    let ranges = [("pitch".to_string(), None)];
    let spec = TuneSpec::new(
        "cell.toml",
        bad_start(),
        "force_search",
        &ranges,
        11,
        4,
        2_000,
        0,
    )
    .unwrap()
    .with_validation(Validation {
        seed: 12,
        episodes: 2,
        finalists: 1,
    })
    .unwrap();
    tune(&spec, &dir.join("t")).unwrap();
    let path = dir.join("t").join("tuned.toml");
    // Another cell.toml: its fixture known less well.
    let mut other = bad_start();
    other.task.place.observed_position_noise = 0.004;
    let e = fragment::apply(&mut other, "cell.toml", &path)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("conflicts with the preset") && e.contains("content differs"),
        "{e}"
    );
    // The same content, called otherwise.
    let mut same = bad_start();
    fragment::apply(&mut same, "b/cell.toml", &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let line = |key: &str| {
        text.lines()
            .find(|l| l.starts_with(&format!("{key} =")))
            .unwrap()
            .to_string()
    };
    for (what, edited, needles) in [
        (
            "best 1e308",
            text.replace(&line("best"), "best = 1e308"),
            vec!["best = 1e308", "[0, 1]"],
        ),
        (
            "validation best -0.5",
            text.replace(&line("validation_best"), "validation_best = -0.5"),
            vec!["validation_best = -0.5"],
        ),
        (
            "no parameters",
            text.replace("[control.tuned.force_search]", "[control.tuned.open_loop]"),
            vec!["open_loop", "no parameters"],
        ),
        (
            "validated on 7",
            text.replace(&line("validation_seed"), "validation_seed = 7"),
            vec!["seed 7"],
        ),
    ] {
        let file = dir.join("edited.toml");
        std::fs::write(&file, &edited).unwrap();
        let mut config = bad_start();
        let e = fragment::apply(&mut config, "cell.toml", &file)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        for n in needles {
            assert!(e.contains(n), "{what}: `{n}` not in `{e}`");
        }
        assert_eq!(config, bad_start(), "{what}: nothing applied");
    }
    // A fragment without the checksum (written before it) is checked by the preset's name.
    let old: String = text
        .lines()
        .filter(|l| !l.starts_with("preset_checksum"))
        .collect::<Vec<_>>()
        .join("\n");
    let file = dir.join("old.toml");
    std::fs::write(&file, old).unwrap();
    let mut config = bad_start();
    fragment::apply(&mut config, "cell.toml", &file).unwrap();
    let e = fragment::apply(&mut bad_start(), "other.toml", &file)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("conflicts with the preset"), "{e}");
}

/// The shipped tunings' trials (`assets/tuned/place_cell/`) read as trials of their tuning: the
/// rules every row is checked by hold for what `tune` wrote.
#[test]
fn the_shipped_trials_pass_the_row_checks() {
    let config = presets::load("place_cell").unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/tuned/place_cell");
    for control in ["force_search", "square_search", "switch_search"] {
        let path = root.join(format!("{control}_trials.csv"));
        let text = std::fs::read_to_string(&path).unwrap();
        let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
        let names: Vec<&str> = header[2..header.len() - 6].to_vec();
        let spec = TuneSpec::new(
            "place_cell",
            config.clone(),
            control,
            &names
                .iter()
                .map(|n| (n.to_string(), None))
                .collect::<Vec<_>>(),
            11,
            150,
            3_000_000,
            0,
        )
        .unwrap();
        let rules = fairgrasp_evaluate::tune::trials::RowRules::of(&spec);
        let trials =
            fairgrasp_evaluate::tune::trials::load(&path, &names, &rules).unwrap_or_else(|e| {
                panic!("{control}: {e}");
            });
        assert!(trials.len() >= 70, "{control}: {}", trials.len());
    }
}
