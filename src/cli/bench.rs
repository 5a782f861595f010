//! `fairgrasp bench env` (the measurement is `fairgrasp_bench::env`) and `fairgrasp bench ppo`.

use std::process::ExitCode;

use clap::{Args, Subcommand};
use fairgrasp_bench::env::{EnvBenchSpec, bench_env};
use fairgrasp_env::EnvConfig;
use fairgrasp_types::ArmSimulation;

use super::args::whole_number_in;

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
    /// IK for any serial arm (the chain IK of 3 built-in URDFs, or --urdf) on random reachable
    /// poses, beside the FR3's closed form on the same FR3 poses: success, median and p90 time.
    Ik(IkBenchArgs),
    /// Soak every preset's env (default 1 M steps each) driven by the scripted grasp with noise
    /// (or random actions): counts non-finite observations and rewards, physics faults, env
    /// errors, and shows resident memory. Exits 1 if any of them was seen.
    Soak(super::soak::SoakArgs),
}

#[derive(Args, Debug)]
pub struct PpoBenchArgs {
    /// PPO iterations to time, 1–1000 (each: 512 steps × 4 envs, 10 epochs of minibatches of
    /// 64).
    #[arg(long, default_value_t = 3, value_parser = |t: &str| whole_number_in(t, 1..=1000).map(|n| n as u32))]
    iterations: u32,
    /// Preset or env config (.toml) of the training phase (e.g. one with `[physics]
    /// free_space = false` to time always-simulated training).
    #[arg(long, default_value = "hard", value_parser = super::args::preset)]
    preset: String,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Args, Debug)]
pub struct EnvBenchArgs {
    /// Arm simulation.
    #[arg(long, value_enum, default_value = "servo")]
    arm: ArmSimulation,
    /// Threads stepping environments in parallel, 1–64.
    #[arg(long, default_value_t = 1, value_parser = |t: &str| whole_number_in(t, 1..=64).map(|n| n as u16))]
    threads: u16,
    /// Environments per thread, 1–64 (a PPO rollout steps several; 1 measures the sync overhead).
    #[arg(long, default_value_t = 4, value_parser = |t: &str| whole_number_in(t, 1..=64).map(|n| n as u16))]
    envs_per_thread: u16,
    /// Steps of each environment, 1–1000000 (each 20 physics steps of 1/240 s by default).
    #[arg(long, default_value_t = 5000, value_parser = |t: &str| whole_number_in(t, 1..=1_000_000).map(|n| n as u32))]
    steps: u32,
    /// Preset or env config (.toml) to bench. Default: the default scene with the cube's
    /// position and yaw randomised.
    #[arg(long, value_parser = super::args::preset)]
    preset: Option<String>,
    /// Resets timed for each of soft and hard reset, 1–100000.
    #[arg(long, default_value_t = 50, value_parser = |t: &str| whole_number_in(t, 1..=100_000).map(|n| n as u32))]
    resets: u32,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Args, Debug)]
pub struct IkBenchArgs {
    /// Random reachable poses per arm, 1–1000000.
    #[arg(long, default_value_t = 10_000, value_parser = |t: &str| whole_number_in(t, 1..=1_000_000).map(|n| n as u32))]
    poses: u32,
    /// Seed of the poses and starts, 0–9007199254740991 (2⁵³ − 1).
    #[arg(long, default_value_t = 0, value_parser = super::args::seed)]
    seed: u64,
    /// Bench this URDF's chain instead of the built-in FR3, FR5 and 7-joint arm.
    #[arg(long, value_name = "FILE")]
    urdf: Option<std::path::PathBuf>,
    /// The chain's tip link (default: the URDF's only leaf).
    #[arg(long, value_name = "LINK", requires = "urdf")]
    tip: Option<String>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

fn run_ik(a: &IkBenchArgs) -> anyhow::Result<ExitCode> {
    use fairgrasp_bench::ik::{bench_chain, bench_fr3_closed_form};
    use fairgrasp_kinematics::chain_ik::ChainIk;
    use fairgrasp_kinematics::{FR3_URDF, FR5_URDF, SEVEN_JOINT_URDF, UrdfRobot};
    let built_in = |text: &str, file: &str, tip: Option<&str>| -> anyhow::Result<ChainIk> {
        Ok(ChainIk::new(&UrdfRobot::from_str_named(text, file)?, tip)?)
    };
    let fr3 = built_in(FR3_URDF, "fr3.urdf", Some("tool0"))?;
    let poses = a.poses as usize;
    let mut rows = vec![bench_fr3_closed_form(&fr3, poses, a.seed)];
    match &a.urdf {
        Some(path) => {
            let ik = ChainIk::new(&UrdfRobot::from_file(path)?, a.tip.as_deref())?;
            rows.push(bench_chain(&path.display().to_string(), &ik, poses, a.seed));
        }
        None => {
            rows.push(bench_chain("FR3 (tool0)", &fr3, poses, a.seed));
            let fr5 = built_in(FR5_URDF, "fr5.urdf", None)?;
            rows.push(bench_chain("FR5", &fr5, poses, a.seed));
            let seven = built_in(SEVEN_JOINT_URDF, "seven_joint_arm.urdf", None)?;
            rows.push(bench_chain("7-joint arm", &seven, poses, a.seed));
        }
    }
    if a.json {
        println!(
            "{}",
            serde_json::json!({ "poses": poses, "seed": a.seed, "rows": rows })
        );
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "{poses} random reachable poses per arm (seed {}), one thread:",
        a.seed
    );
    println!(
        "  {:<28} {:>4} {:>9} {:>11} {:>11} {:>9}",
        "solver", "dof", "solved", "median µs", "p90 µs", "attempts"
    );
    for r in &rows {
        println!(
            "  {:<28} {:>4} {:>8.2}% {:>11.1} {:>11.1} {:>9.2}",
            r.solver,
            r.dof,
            100.0 * r.solved as f64 / r.poses as f64,
            r.median_us,
            r.p90_us,
            r.mean_attempts
        );
    }
    Ok(ExitCode::SUCCESS)
}

pub fn run(a: &BenchArgs) -> anyhow::Result<ExitCode> {
    match &a.what {
        BenchWhat::Env(a) => run_env(a),
        #[cfg(feature = "train")]
        BenchWhat::Ppo(a) => super::bench_ppo::run(a.iterations, &a.preset, a.json),
        #[cfg(not(feature = "train"))]
        BenchWhat::Ppo(_) => anyhow::bail!(
            "bench ppo measures PPO in burn, which this fairgrasp was built without: \
             cargo run --release --features train -- bench ppo …"
        ),
        BenchWhat::Soak(a) => super::soak::run(a),
        BenchWhat::Ik(a) => run_ik(a),
    }
}

fn run_env(a: &EnvBenchArgs) -> anyhow::Result<ExitCode> {
    let mut config = match &a.preset {
        Some(p) => fairgrasp_env::config::presets::load(p)?,
        None => {
            let mut c = EnvConfig::default();
            c.randomization.position = true;
            c.randomization.yaw = true;
            c
        }
    };
    config.arm.model = a.arm;
    let spec = EnvBenchSpec {
        config,
        threads: usize::from(a.threads),
        envs_per_thread: usize::from(a.envs_per_thread),
        steps: a.steps as usize,
        resets: a.resets as usize,
    };
    let arm = a.arm;
    let announce = || {
        if !a.json {
            eprintln!(
                "stepping {} env(s) on {} thread(s), {} steps each ({arm} arm) …",
                spec.threads * spec.envs_per_thread,
                spec.threads,
                spec.steps
            );
        }
    };
    let r = bench_env(&spec, &announce)?;
    if a.json {
        println!("{}", serde_json::to_value(&r)?);
    } else {
        println!(
            "arm {}, {} thread(s) × {} env(s), {} env steps of {} × {:.5} s",
            r.arm, r.threads, spec.envs_per_thread, r.env_steps, r.substeps, r.dt
        );
        println!("  env steps per second     {:>10.0}", r.env_steps_per_s);
        println!("  env steps per CPU-second {:>10.0}", r.env_steps_per_cpu_s);
        println!("  physics steps per second {:>10.0}", r.physics_steps_per_s);
        println!(
            "  steps with full physics  {:>10.1} % (the rest free-space)",
            100.0 * r.simulated_share
        );
        println!(
            "  soft reset               {:>10.3} ms (fastest {:.3} ms)",
            r.soft_reset_ms, r.soft_reset_min_ms
        );
        println!(
            "  hard reset               {:>10.3} ms (fastest {:.3} ms)",
            r.hard_reset_ms, r.hard_reset_min_ms
        );
    }
    Ok(ExitCode::SUCCESS)
}
