//! `fairgrasp bench env`: environment throughput and reset times.

use std::process::ExitCode;
use std::time::Instant;

use clap::{Args, Subcommand, ValueEnum};
use fairgrasp_env::vec_env::VecEnv;
use fairgrasp_env::{Action, ArmModelKind, EnvConfig, GraspEnv};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::json;

#[derive(Args, Debug)]
pub struct BenchArgs {
    #[command(subcommand)]
    what: BenchWhat,
}

#[derive(Subcommand, Debug)]
enum BenchWhat {
    /// Env steps per second (wall and CPU), soft and hard reset times, random actions.
    Env(EnvBenchArgs),
    /// PPO update throughput (samples/s, 64×64 network) and training throughput with the env.
    Ppo(PpoBenchArgs),
}

#[derive(Args, Debug)]
pub struct PpoBenchArgs {
    /// PPO iterations to time (each: 512 steps × 4 envs, 10 epochs of minibatches of 64).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..))]
    iterations: u32,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ArmArg {
    /// Kinematic links placed by FK (the default).
    Servo,
    /// rapier multibody with joint motors.
    Multibody,
}

#[derive(Args, Debug)]
pub struct EnvBenchArgs {
    /// Arm simulation.
    #[arg(long, value_enum, default_value = "servo")]
    arm: ArmArg,
    /// Threads stepping environments in parallel.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..=64))]
    threads: u16,
    /// Environments per thread (a PPO rollout steps several; 1 measures the sync overhead).
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u16).range(1..=64))]
    envs_per_thread: u16,
    /// Steps of each environment (each 20 physics steps of 1/240 s by default).
    #[arg(long, default_value_t = 5000, value_parser = clap::value_parser!(u32).range(1..))]
    steps: u32,
    /// Preset or env config (.toml) to bench. Default: the default scene with the cube's
    /// position and yaw randomised.
    #[arg(long)]
    preset: Option<String>,
    /// Resets timed for each of soft and hard reset.
    #[arg(long, default_value_t = 50, value_parser = clap::value_parser!(u32).range(1..))]
    resets: u32,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// CPU time used by this process so far [s] (user + system, all threads).
fn cpu_seconds() -> f64 {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
    // SAFETY: getrusage writes a complete rusage into the pointer it is given.
    let usage = unsafe {
        libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr());
        usage.assume_init()
    };
    let tv = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    tv(usage.ru_utime) + tv(usage.ru_stime)
}

pub fn run(a: &BenchArgs) -> anyhow::Result<ExitCode> {
    match &a.what {
        BenchWhat::Env(a) => run_env(a),
        BenchWhat::Ppo(a) => super::bench_ppo::run(a.iterations, a.json),
    }
}

fn run_env(a: &EnvBenchArgs) -> anyhow::Result<ExitCode> {
    let mut config = match &a.preset {
        Some(p) => fairgrasp_env::presets::load(p)?,
        None => {
            let mut c = EnvConfig::default();
            c.randomization.position = true;
            c.randomization.yaw = true;
            c
        }
    };
    config.arm.model = match a.arm {
        ArmArg::Servo => ArmModelKind::Servo,
        ArmArg::Multibody => ArmModelKind::Multibody,
    };

    // Resets, on one env.
    let mut env = GraspEnv::new(config.clone())?;
    let t = Instant::now();
    for seed in 0..a.resets as u64 {
        env.reset(seed)?;
    }
    let soft_reset_ms = t.elapsed().as_secs_f64() * 1e3 / a.resets as f64;
    let t = Instant::now();
    for seed in 0..a.resets as u64 {
        env.hard_reset(seed)?;
    }
    let hard_reset_ms = t.elapsed().as_secs_f64() * 1e3 / a.resets as f64;

    // Throughput: random actions, auto-reset, one env per thread.
    let n = a.threads as usize;
    let per = a.envs_per_thread as usize;
    let mut vec_env = VecEnv::new(&config, n * per, n, 0)?;
    vec_env.reset()?;
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    let actions: Vec<Vec<Action>> = (0..256)
        .map(|_| {
            (0..n * per)
                .map(|_| Action(std::array::from_fn(|_| rng.random_range(-1.0..1.0))))
                .collect()
        })
        .collect();
    if !a.json {
        eprintln!(
            "stepping {} env(s) on {n} thread(s), {} steps each ({:?} arm) …",
            n * per,
            a.steps,
            a.arm
        );
    }
    let (cpu0, t) = (cpu_seconds(), Instant::now());
    for k in 0..a.steps as usize {
        vec_env.step(&actions[k % actions.len()])?;
    }
    let wall = t.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - cpu0;
    let total = a.steps as f64 * (n * per) as f64;
    let physics_per_step = config.physics.substeps as f64;
    let out = json!({
        "arm": format!("{:?}", a.arm).to_lowercase(),
        "threads": n,
        "envs": n * per,
        "env_steps": total,
        "env_steps_per_s": total / wall,
        "env_steps_per_cpu_s": total / cpu.max(1e-9),
        "physics_steps_per_s": total * physics_per_step / wall,
        "soft_reset_ms": soft_reset_ms,
        "hard_reset_ms": hard_reset_ms,
    });
    if a.json {
        println!("{out}");
    } else {
        println!(
            "arm {:?}, {n} thread(s) × {per} env(s), {total} env steps of {} × {:.5} s",
            a.arm, physics_per_step, config.physics.dt
        );
        println!("  env steps per second     {:>10.0}", total / wall);
        println!("  env steps per CPU-second {:>10.0}", total / cpu.max(1e-9));
        println!(
            "  physics steps per second {:>10.0}",
            total * physics_per_step / wall
        );
        println!("  soft reset               {soft_reset_ms:>10.3} ms");
        println!("  hard reset               {hard_reset_ms:>10.3} ms");
    }
    Ok(ExitCode::SUCCESS)
}
