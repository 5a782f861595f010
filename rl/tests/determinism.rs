//! The seed decides a training, whatever else the process does: every random draw (weights,
//! sampled actions, minibatch shuffles, scenarios) comes from generators the run owns, so two
//! trainings in parallel threads of one process give each exactly what it gives alone.

use burn::tensor::Device;
use fairgrasp_rl::ppo::model::{ActorCritic, ModelConfig};
use fairgrasp_rl::ppo::normalizer::RunningNorm;
use fairgrasp_rl::ppo::point_mass::PointMass;
use fairgrasp_rl::ppo::{Ppo, PpoConfig, UpdateStats};
use fairgrasp_rl::run::checkpoint;
use fairgrasp_rl::run::train::{TrainConfig, train};

/// PPO on the point mass for `iterations` updates: every update's statistics and the final
/// parameters.
fn point_mass_run(seed: u64, iterations: usize) -> (Vec<UpdateStats>, Vec<f32>) {
    let device = Device::flex().autodiff();
    let mut env = PointMass::new(4, seed);
    let config = PpoConfig {
        n_steps: 32,
        batch_size: 32,
        n_epochs: 3,
        learning_rate: 3e-3,
        ..PpoConfig::default()
    };
    let model = ActorCritic::new(2, 1, &ModelConfig::default(), seed, &device);
    let mut ppo = Ppo::new(config, model, RunningNorm::new(2, true), device, seed);
    let stats = (0..iterations)
        .map(|_| ppo.iterate(&mut env, 0.0).unwrap())
        .collect();
    (stats, ppo.model.flat_parameters())
}

#[test]
fn two_ppo_runs_in_parallel_threads_each_equal_the_run_alone_bit_for_bit() {
    let alone: Vec<_> = [11, 12].map(|s| point_mass_run(s, 6)).into();
    let together: Vec<_> = std::thread::scope(|scope| {
        let handles = [11, 12].map(|s| scope.spawn(move || point_mass_run(s, 6)));
        handles.map(|h| h.join().unwrap()).into()
    });
    for (a, t) in alone.iter().zip(&together) {
        assert_eq!(a.0, t.0, "update statistics differ");
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a.1), bits(&t.1), "parameters differ");
    }
    assert_ne!(alone[0].1, alone[1].1, "two seeds gave the same network");
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "fairgrasp-determinism-{name}-{}",
        std::process::id()
    ));
    std::fs::remove_dir_all(&dir).ok();
    dir
}

fn tiny(seed: u64) -> TrainConfig {
    TrainConfig {
        preset: "fixed".into(),
        seed,
        total_timesteps: 96,
        n_envs: 2,
        threads: 2,
        eval_every: 0,
        eval_episodes: 2,
        ppo: PpoConfig {
            n_steps: 16,
            batch_size: 16,
            n_epochs: 2,
            ..PpoConfig::default()
        },
        ..TrainConfig::default()
    }
}

/// The final network's parameters (as bits) and `metrics.csv` without the clock's columns
/// (`wall_time_s`, `steps_per_second`).
fn outcome(dir: &std::path::Path) -> (Vec<u32>, Vec<String>) {
    let (_, model) =
        checkpoint::load_model(&dir.join("checkpoints/latest"), &Device::flex()).unwrap();
    let csv = std::fs::read_to_string(dir.join("metrics.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let clock = |name: &str| header.iter().position(|c| *c == name).unwrap();
    let (wall, speed) = (clock("wall_time_s"), clock("steps_per_second"));
    let rows = csv
        .lines()
        .map(|row| {
            let cells: Vec<&str> = row.split(',').collect();
            let kept: Vec<&str> = cells
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != wall && *i != speed)
                .map(|(_, c)| *c)
                .collect();
            kept.join(",")
        })
        .collect();
    let bits = model
        .flat_parameters()
        .iter()
        .map(|x| x.to_bits())
        .collect();
    (bits, rows)
}

#[test]
fn two_grasp_trainings_in_parallel_threads_each_equal_the_training_alone() {
    let seeds = [3u64, 4];
    let alone: Vec<_> = seeds
        .iter()
        .map(|&s| {
            let dir = scratch(&format!("alone-{s}"));
            train(&tiny(s), &dir, false, &mut |_| {}).unwrap();
            let o = outcome(&dir);
            std::fs::remove_dir_all(&dir).ok();
            o
        })
        .collect();
    let together: Vec<_> = std::thread::scope(|scope| {
        let handles: Vec<_> = seeds
            .iter()
            .map(|&s| {
                scope.spawn(move || {
                    let dir = scratch(&format!("together-{s}"));
                    train(&tiny(s), &dir, false, &mut |_| {}).unwrap();
                    let o = outcome(&dir);
                    std::fs::remove_dir_all(&dir).ok();
                    o
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for ((a, t), seed) in alone.iter().zip(&together).zip(seeds) {
        assert_eq!(a.1, t.1, "seed {seed}: metrics.csv differs");
        assert!(a.0 == t.0, "seed {seed}: the trained parameters differ");
        assert_eq!(a.1.len(), 1 + 3, "header + 3 updates");
    }
    assert_ne!(alone[0].0, alone[1].0, "two seeds trained the same network");
}
