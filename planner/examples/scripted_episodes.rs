//! Steps the open-loop script through a preset's scenario set and prints env steps per
//! CPU-second — the env's contact-rich workload (approach, close, lift), for profiling
//! (`valgrind --tool=callgrind`) and for `scripts/env_ratio_scripted.sh`.
//!
//! Usage: `cargo run --release -p fairgrasp-planner --example scripted_episodes -- [PRESET]
//! [EPISODES]` (default `full`, 100).

use std::time::Instant;

use fairgrasp_env::TaskEnv;
use fairgrasp_env::config::presets;
use fairgrasp_env::episode::run_episode;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};

fn cpu_seconds() -> f64 {
    // Linux: the process's user + system time.
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (ticks(11) + ticks(12)) / 100.0
}

fn main() {
    let mut args = std::env::args().skip(1);
    let preset = args.next().unwrap_or_else(|| "full".into());
    let episodes: usize = args.next().and_then(|n| n.parse().ok()).unwrap_or(100);
    let config = presets::load(&preset).expect("a preset");
    let scenarios = scenario_set(&config, 0, episodes).expect("scenarios");
    let mut env = TaskEnv::new(config.clone()).expect("an env");
    let mut script = ScriptedGrasp::new(&config, BaselineConfig::default());
    let (wall, cpu) = (Instant::now(), cpu_seconds());
    let (mut steps, mut successes) = (0usize, 0usize);
    for s in &scenarios {
        let r = run_episode(&mut env, &mut script, s, None).expect("an episode");
        steps += r.steps;
        successes += usize::from(r.success());
    }
    let cpu = (cpu_seconds() - cpu).max(1e-9);
    println!(
        "preset {preset}: {episodes} episodes, {successes} successes, {steps} env steps, {:.0} env steps per CPU-s ({:.1} s wall)",
        steps as f64 / cpu,
        wall.elapsed().as_secs_f64()
    );
    println!("STEPS_PER_CPU_S={:.1}", steps as f64 / cpu);
}
