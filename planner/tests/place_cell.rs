//! The place cell's controls and its clock: the cycle time and success within the takt that an
//! episode's record carries, the squaring that turns a tilted cube flat in the grip, and the
//! switching search that reads a tilted cube from its first touch. Physical facts read from the
//! simulator.

use fairgrasp_env::TaskEnv;
use fairgrasp_env::config::presets;
use fairgrasp_env::episode::{Policy, run_episode};
use fairgrasp_env::scenario::Scenario;
use fairgrasp_planner::ScriptedPlace;

/// The cube's tilt from standing on a face \[rad\].
fn tilt(env: &TaskEnv) -> f64 {
    let r = env.object_in_base().iso.rotation.to_rotation_matrix();
    let upright = (0..3).map(|i| r[(2, i)].abs()).fold(0.0, f64::max);
    upright.clamp(-1.0, 1.0).acos()
}

/// A successful episode's cycle time is its steps times the env step's duration, and it is
/// within the takt exactly when that time is at most the takt: the same episode judged against
/// a takt just above and just below its cycle.
#[test]
fn the_cycle_time_is_the_episodes_simulated_time_and_the_takt_judges_it() {
    let mut config = presets::load("place").unwrap();
    let step = config.physics.dt * config.physics.substeps as f64;
    let scenario = Scenario::sample(&config, 7).unwrap();
    let run = |config: &fairgrasp_env::EnvConfig| {
        let mut env = TaskEnv::new(config.clone()).unwrap();
        let mut script = ScriptedPlace::new(config);
        run_episode(&mut env, &mut script, &scenario, None).unwrap()
    };
    let record = run(&config);
    assert!(
        record.success(),
        "the noise-free place succeeds: {:?}",
        record.outcome
    );
    let cycle = record.cycle_time_s.expect("a success has a cycle time");
    assert!(
        (cycle - record.steps as f64 * step).abs() < 1e-12,
        "{cycle}"
    );
    assert!(
        cycle > 5.0 && cycle < 30.0,
        "a place takes seconds: {cycle}"
    );
    assert_eq!(record.takt_s, Some(20.0));
    for (takt, within) in [(cycle + step, true), (cycle - step, false)] {
        config.task.place.takt = takt;
        let r = run(&config);
        assert_eq!(r.steps, record.steps, "the takt changes nothing physical");
        assert_eq!(
            r.success_within_takt(),
            within,
            "takt {takt} s, cycle {cycle} s"
        );
    }
    // The lift task runs on no takt: every success counts.
    let lift = presets::load("sector").unwrap();
    let mut env = TaskEnv::new(lift.clone()).unwrap();
    let mut grasp = fairgrasp_planner::ScriptedGrasp::new(&lift, Default::default());
    let s = Scenario::sample(&lift, 0).unwrap();
    let r = run_episode(&mut env, &mut grasp, &s, None).unwrap();
    assert!(r.success() && r.takt_s.is_none() && r.success_within_takt());
}

/// The squaring presses a cube that hangs 4–10° tilted flat against the table: after it, the
/// cube's tilt is under 2° (the seated criterion) in every scenario where it ran to its end
/// (at least 4 of 6; the carry to its spot can end an episode in a collision), where before
/// it the cube hung at the drawn angle.
#[test]
fn the_squaring_turns_a_tilted_cube_back_within_two_degrees() {
    let mut config = presets::load("place_tilted").unwrap();
    let q = &mut config.task.place.square;
    q.press = 0.004;
    q.force = 20.0;
    q.squeeze = 0.5;
    q.hold = 0.5;
    let mut squared = 0;
    for seed in 0..6 {
        let mut env = TaskEnv::new(config.clone()).unwrap();
        let mut script = ScriptedPlace::with_squaring(&config, config.task.place.square);
        let (mut obs, _) = env.reset(seed).unwrap();
        script.reset(seed);
        let drawn = env.scenario().and_then(|s| s.fixture).unwrap().grip_tilt;
        let mut before = None;
        for step in 0.. {
            assert!(step < 360, "seed {seed}: the squaring never ended");
            let action = script.act(&obs);
            // The squeeze the script asks for, as `run_episode` applies it.
            if let Some(force) = script.grip_force() {
                env.set_grip_force(force).unwrap();
            }
            let step = env.step(&action).unwrap();
            obs = step.obs;
            if step.info.episode.is_some() {
                break; // ended before the squaring did (a collision on the way to its spot)
            }
            match script.phase() {
                Some("square_press") if before.is_none() => before = Some(tilt(&env)),
                Some("square_done") | Some("carry") => {
                    squared += 1;
                    break;
                }
                _ => {}
            }
        }
        if !matches!(script.phase(), Some("square_done") | Some("carry")) {
            continue;
        }
        let before = before.expect("the squaring pressed");
        assert!(
            (before - drawn.abs()).abs() < 1.5f64.to_radians(),
            "seed {seed}: hung {:.1}° before, drawn {:.1}°",
            before.to_degrees(),
            drawn.to_degrees()
        );
        let after = tilt(&env);
        assert!(
            after < 2f64.to_radians(),
            "seed {seed}: {:.1}° after the squaring (drawn {:.1}°)",
            after.to_degrees(),
            drawn.to_degrees()
        );
    }
    assert!(
        squared >= 4,
        "the squaring ran to its end in {squared} of 6"
    );
}

/// The switching search reads a cycle from its first touch: on `place_tilted` (every cube
/// tilted) it reads tilted, on `place_fixture_error` and `place_grasp_error` (square cubes, an
/// error of pose) it reads square, in at least 9 of 10 of the cycles that touched.
#[test]
fn the_switch_reads_the_family_from_the_first_touch() {
    let place_cell = presets::load("place_cell").unwrap();
    let switch = place_cell.task.place.switch;
    for (preset, tilted) in [
        ("place_tilted", true),
        ("place_fixture_error", false),
        ("place_grasp_error", false),
    ] {
        let config = presets::load(preset).unwrap();
        let mut env = TaskEnv::new(config.clone()).unwrap();
        let mut script = ScriptedPlace::with_switch(&config, switch);
        let (mut touched, mut right) = (0, 0);
        for seed in 0..16 {
            let scenario = Scenario::sample(&config, seed).unwrap();
            run_episode(&mut env, &mut script, &scenario, None).unwrap();
            // A cube that went straight in never touched: nothing to read, nothing to switch.
            let Some(read) = script.search().and_then(|s| s.read_tilted()) else {
                continue;
            };
            touched += 1;
            right += usize::from(read == tilted);
        }
        assert!(touched >= 6, "{preset}: only {touched} of 16 touched");
        assert!(
            right * 10 >= touched * 9,
            "{preset}: read right in {right} of {touched} touches"
        );
    }
}
