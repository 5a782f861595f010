//! The vectorised env (auto-reset, thread-count independence) and trajectory export.

use fairgrasp_env::episode::trajectory::{Recorder, Trajectory};
use fairgrasp_env::vec::VecEnv;
use fairgrasp_env::{Action, EnvConfig, Observation, TaskEnv};
use fairgrasp_types::body::compose;

fn cfg() -> EnvConfig {
    let mut c = EnvConfig::default();
    c.task.max_steps = 5;
    c.randomization.position = true;
    c
}

fn run(threads: usize) -> Vec<Vec<Observation>> {
    let mut v = VecEnv::new(&cfg(), 4, threads, 100).unwrap();
    let mut trace = vec![v.reset().unwrap().to_vec()];
    let actions: Vec<Action> = (0..4)
        .map(|i| Action([0.3 * i as f64 - 0.5, 0.2, 0.0, 0.0, 0.0, 0.0, -1.0]))
        .collect();
    for _ in 0..12 {
        trace.push(v.step(&actions).unwrap().obs.clone());
    }
    trace
}

#[test]
fn results_do_not_depend_on_the_number_of_threads() {
    assert_eq!(run(1), run(2));
}

#[test]
fn ended_episodes_are_reset_and_their_final_observation_kept() {
    let mut v = VecEnv::new(&cfg(), 2, 2, 0).unwrap();
    let first = v.reset().unwrap().to_vec();
    let actions = vec![Action::hold_open(); 2];
    let mut ended = 0;
    for n in 1..=10 {
        let s = v.step(&actions).unwrap();
        for i in 0..2 {
            let done = s.terminated[i] || s.truncated[i];
            assert_eq!(done, n % 5 == 0, "env {i} step {n}");
            assert_eq!(s.final_obs[i].is_some(), done);
            if done {
                ended += 1;
                assert!(s.truncated[i]);
            }
        }
        if n == 5 {
            // Episode 2 starts from another seed: another cube position.
            assert_ne!(s.obs[0].object_rel_tcp, first[0].object_rel_tcp);
        }
    }
    assert_eq!(ended, 4);
    assert!(
        v.step(&[Action::hold_open()]).is_err(),
        "wrong action count"
    );
}

#[test]
fn the_batch_holds_each_envs_own_observation_and_episode_seed() {
    // Three envs on two threads against three envs stepped alone with the seeds the batch
    // reports: observations, rewards, flags and final observations are the same values (f64,
    // not a flattened copy), across an auto-reset.
    let config = cfg();
    let mut v = VecEnv::new(&config, 3, 2, 500).unwrap();
    let first = v.reset().unwrap().to_vec();
    let seeds = v.batch().seeds.clone();
    assert_eq!(seeds, vec![500, 1_000_500, 2_000_500]);
    let mut alone: Vec<TaskEnv> = (0..3)
        .map(|_| TaskEnv::new(config.clone()).unwrap())
        .collect();
    for (e, env) in alone.iter_mut().enumerate() {
        assert_eq!(env.reset(seeds[e]).unwrap().0, first[e]);
    }
    let actions: Vec<Action> = (0..3)
        .map(|i| Action([0.1 * i as f64, -0.3, 0.2, 0.0, 0.1, 0.0, -1.0]))
        .collect();
    let mut resets = 0;
    for _ in 0..7 {
        let s = v.step(&actions).unwrap();
        for (e, env) in alone.iter_mut().enumerate() {
            let step = env.step(&actions[e]).unwrap();
            assert_eq!(s.rewards[e], step.reward);
            assert_eq!(
                (s.terminated[e], s.truncated[e]),
                (step.terminated, step.truncated)
            );
            if step.terminated || step.truncated {
                resets += 1;
                assert_eq!(s.final_obs[e], Some(step.obs));
                assert_eq!(s.seeds[e], seeds[e] + 1, "the next episode's seed");
                assert_eq!(env.reset(s.seeds[e]).unwrap().0, s.obs[e]);
            } else {
                assert_eq!(s.final_obs[e], None);
                assert_eq!(s.obs[e], step.obs);
            }
        }
    }
    assert_eq!(resets, 3, "each env ended one episode (5 steps each)");
}

#[test]
fn an_episode_exports_to_csv_and_json_with_one_row_per_step() {
    let mut env = TaskEnv::new(EnvConfig::default()).unwrap();
    let (obs, _) = env.reset(0).unwrap();
    let mut t = Trajectory::default();
    t.record_reset(&env, obs.gripper_opening);
    let action = Action([0.5, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]);
    for _ in 0..10 {
        let step = env.step(&action).unwrap();
        t.record_step(&env, &action, &step, None);
    }
    assert_eq!(t.rows.len(), 11);
    assert!(t.rows[10].joints[0] > t.rows[0].joints[0]);
    let dir = std::env::temp_dir().join(format!("fairgrasp-traj-{}", std::process::id()));
    t.save(&dir, "episode_0").unwrap();
    let csv = std::fs::read_to_string(dir.join("episode_0.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 12);
    let columns = lines[0].split(',').count();
    assert!(lines.iter().all(|l| l.split(',').count() == columns));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("episode_0.json")).unwrap())
            .unwrap();
    assert_eq!(json["rows"].as_array().unwrap().len(), 11);
    assert_eq!(json["rows"][3]["action"][0], 0.5);
    // Replay geometry: one capsule per name; the finger capsules sit the opening plus one pad
    // apart, centred on the line through the TCP along tool0 z.
    let names = &t.scene.capsule_names;
    let row = &t.rows[10];
    assert_eq!(row.capsules.len(), names.len());
    let finger = |n: &str| row.capsules[names.iter().position(|x| x == n).unwrap()];
    let (l, r) = (finger("finger_left"), finger("finger_right"));
    let gap = ((l[3] - r[3]).powi(2) + (l[4] - r[4]).powi(2) + (l[5] - r[5]).powi(2)).sqrt();
    let pad = env.model().gripper.pad_size[0];
    assert!(
        (gap - row.gripper_opening_m - pad).abs() < 1e-9,
        "finger gap {gap}"
    );
    let mid = [
        0.5 * (l[3] + r[3]),
        0.5 * (l[4] + r[4]),
        0.5 * (l[5] + r[5]),
    ];
    let tcp = row.tcp_xyz;
    let off = [mid[0] - tcp[0], mid[1] - tcp[1], mid[2] - tcp[2]];
    let along = off.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!(along < 0.03, "finger tips {along} m from the TCP");
    let cfg = env.config();
    let table_z = cfg.scene.table_height - cfg.arm.base_xyz[2];
    assert!((t.scene.table_top_z - table_z).abs() < 1e-12);
    // Body poses for 3D replays: the palm's frame is tool0 and the TCP sits 0.14 m along its
    // z; the pads sit the opening apart (inner faces); every shape is on a listed body; the
    // base stands where the config puts it.
    let body = |n: &str| row.bodies[t.scene.bodies.iter().position(|b| b == n).unwrap()];
    let tcp_from_palm = compose(&body("palm"), &[0.0, 0.0, 0.14, 0.0, 0.0, 0.0, 1.0]);
    for k in 0..3 {
        assert!(
            (tcp_from_palm[k] - row.tcp_xyz[k]).abs() < 1e-9,
            "{tcp_from_palm:?}"
        );
    }
    let (fl, fr) = (body("finger_left"), body("finger_right"));
    let finger_gap =
        ((fl[0] - fr[0]).powi(2) + (fl[1] - fr[1]).powi(2) + (fl[2] - fr[2]).powi(2)).sqrt();
    assert!(
        (finger_gap - row.gripper_opening_m - pad).abs() < 1e-9,
        "{finger_gap}"
    );
    assert_eq!(t.scene.shapes.len(), 12);
    assert!(t.scene.shapes.iter().all(|s| s.body < t.scene.bodies.len()));
    assert_eq!(t.scene.base_in_world[..3], cfg.arm.base_xyz);
    let table = t.scene.table_in_world.unwrap();
    assert!((table.centre[2] + table.half_extents[2] - cfg.scene.table_height).abs() < 1e-12);
    let back = Trajectory::from_json(&std::fs::read_to_string(dir.join("episode_0.json")).unwrap())
        .unwrap();
    assert_eq!(back, t);
    assert!(
        !std::fs::read_dir(&dir).unwrap().any(|e| e
            .unwrap()
            .path()
            .to_string_lossy()
            .contains(".tmp"))
    );
    std::fs::remove_dir_all(&dir).ok();
}
