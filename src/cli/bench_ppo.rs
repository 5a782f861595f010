//! `fairgrasp bench ppo`: runs `fairgrasp_bench::ppo::bench_ppo` and prints its figures.

use std::process::ExitCode;

use fairgrasp_bench::ppo::bench_ppo;

/// Peak resident set size of this process \[MB\] (getrusage `ru_maxrss`, kB on Linux).
pub fn peak_rss_mb() -> f64 {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
    // SAFETY: getrusage writes a complete rusage into the pointer it is given.
    let usage = unsafe {
        libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr());
        usage.assume_init()
    };
    usage.ru_maxrss as f64 / 1024.0
}

pub fn run(iterations: u32, preset: &str, as_json: bool) -> anyhow::Result<ExitCode> {
    let b = bench_ppo(iterations, preset)?;
    let peak = peak_rss_mb();
    if as_json {
        let mut out = serde_json::to_value(&b)?;
        out["peak_rss_mb"] = serde_json::json!(peak);
        println!("{out}");
    } else {
        println!(
            "PPO, {}, input {}, {} samples × {} epochs, minibatch {}",
            b.network, b.input_dim, b.samples_per_iteration, b.epochs, b.minibatch
        );
        println!(
            "  update throughput        {:>10.0} samples/s (gradient steps over samples)",
            b.update_samples_per_s
        );
        println!(
            "  iteration without env    {:>10.3} s",
            b.ppo_iteration_s_without_env
        );
        println!(
            "  training with the env    {:>10.0} env steps/s (residual agent, preset {}, {} envs, 2 threads)",
            b.train_env_steps_per_s, b.preset, b.n_envs
        );
        println!("  peak resident memory     {peak:>10.1} MB");
    }
    Ok(ExitCode::SUCCESS)
}
