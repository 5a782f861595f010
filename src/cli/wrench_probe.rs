//! `fairgrasp wrench-probe`: what the six-axis wrist sensor tells at a place cycle's first touch,
//! checked against the truth on training scenarios before any control or learner uses it
//! ([`fairgrasp_evaluate::wrench_probe`]).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use fairgrasp_env::ArmSimulation;
use fairgrasp_evaluate::wrench_probe::{TouchRow, first_touches};
use fairgrasp_types::eval_report::wilson_interval;

use super::baseline::{preset_config, progress_bar};

#[derive(Args, Debug)]
pub struct WrenchProbeArgs {
    /// A place preset (a task with a fixture, so the cell has the wrist sensor).
    #[arg(long, default_value = "place_cell", value_parser = crate::cli::args::preset)]
    preset: String,
    /// First scenario seed, 0–9007199254740991 (2⁵³ − 1): training scenarios by default (11,
    /// the tunings'), never a reported set.
    #[arg(long, default_value_t = 11, value_parser = crate::cli::args::seed)]
    seed: u64,
    /// Scenarios, 1–1000000.
    #[arg(long, default_value_t = 300, value_parser = crate::cli::args::episode_count)]
    episodes: u32,
    /// Also write every scenario's first touch as CSV here (a new file; never replaced).
    #[arg(long)]
    csv: Option<PathBuf>,
}

pub fn run(a: &WrenchProbeArgs) -> anyhow::Result<ExitCode> {
    let config = preset_config(&a.preset, ArmSimulation::Servo)?;
    if config.wrench_sensor().is_none() {
        anyhow::bail!(
            "--preset {}: its {} task has no fixture, so its cell has no wrist sensor to probe; use a place preset (e.g. place_cell)",
            a.preset,
            config.task.kind.spec().name
        );
    }
    if let Some(csv) = &a.csv
        && csv.exists()
    {
        anyhow::bail!(
            "--csv {}: the file exists; the probe never replaces a file",
            csv.display()
        );
    }
    let bar = progress_bar(u64::from(a.episodes), false, "first touches");
    let rows = first_touches(&config, a.seed, a.episodes as usize, |k| {
        bar.set_position(k as u64)
    })?;
    bar.finish_and_clear();
    print_summary(a, &rows);
    if let Some(csv) = &a.csv {
        fairgrasp_types::write_atomic(csv, touches_csv(&rows).as_bytes())
            .with_context(|| format!("writing {}", csv.display()))?;
        println!("rows in {}", csv.display());
    }
    Ok(ExitCode::SUCCESS)
}

/// `k of n (p %, 95 % interval lo–hi %)`.
fn rate(k: usize, n: usize) -> String {
    if n == 0 {
        return "0 of 0".into();
    }
    let (lo, hi) = wilson_interval(k, n);
    format!(
        "{k} of {n} ({:.1} %, {:.1}–{:.1} %)",
        100.0 * k as f64 / n as f64,
        100.0 * lo,
        100.0 * hi
    )
}

fn print_summary(a: &WrenchProbeArgs, rows: &[TouchRow]) {
    println!(
        "The wrist sensor at the first touch: the force search on `{}`, {} scenarios from seed {}",
        a.preset, a.episodes, a.seed
    );
    let touched = rows.iter().filter(|r| r.step.is_some()).count();
    println!("  touched                 {}", rate(touched, rows.len()));
    let families: Vec<Option<String>> = {
        let mut f: Vec<_> = rows
            .iter()
            .map(|r| r.family.map(|f| format!("{f:?}")))
            .collect();
        f.sort();
        f.dedup();
        f
    };
    for family in std::iter::once(None).chain(families.iter().map(Some)) {
        let of: Vec<&TouchRow> = rows
            .iter()
            .filter(|r| family.is_none_or(|f| r.family.map(|x| format!("{x:?}")) == *f))
            .collect();
        let name = family.map_or("all".to_string(), |f| f.clone().unwrap_or("none".into()));
        let rim: Vec<_> = of.iter().filter(|r| r.on_rim()).collect();
        let walls = rim.iter().filter(|r| r.wall_read_right()).count();
        let any_wall = rim.iter().filter(|r| r.a_rim_wall_read()).count();
        let tilted: Vec<bool> = of.iter().filter_map(|r| r.tilt_sign_read_right()).collect();
        let signs = tilted.iter().filter(|&&ok| ok).count();
        println!(
            "  {name:<13} on the rim {}; named the wall its centre is off towards {}, a wall it rests on {}; tilt's sign right {}",
            rate(rim.len(), of.len()),
            rate(walls, rim.len()),
            rate(any_wall, rim.len()),
            rate(signs, tilted.len())
        );
    }
}

fn touches_csv(rows: &[TouchRow]) -> String {
    let mut out = String::from(
        "seed,family,step,true_wall,read_wall,grip_tilt_rad,cop_tcp_y_m,fx,fy,fz,mx,my,mz,cop_pocket_x_m,cop_pocket_y_m,cube_in_pocket_x_m,cube_in_pocket_y_m,cube_in_pocket_z_m,rim_walls\n",
    );
    let opt = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x}"));
    let name = |w: Option<fairgrasp_evaluate::wrench_probe::Wall>| {
        w.map_or(String::new(), |w| format!("{w:?}"))
    };
    for r in rows {
        let f = r.force.map_or([None; 3], |f| f.map(Some));
        let m = r.torque.map_or([None; 3], |m| m.map(Some));
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            r.seed,
            r.family.map_or(String::new(), |f| format!("{f:?}")),
            r.step.map_or(String::new(), |s| s.to_string()),
            name(r.true_wall),
            name(r.read_wall),
            r.grip_tilt,
            opt(r.cop_tcp_y),
            opt(f[0]),
            opt(f[1]),
            opt(f[2]),
            opt(m[0]),
            opt(m[1]),
            opt(m[2]),
            opt(r.cop_pocket.map(|c| c[0])),
            opt(r.cop_pocket.map(|c| c[1])),
            opt(r.cube_in_pocket.map(|c| c[0])),
            opt(r.cube_in_pocket.map(|c| c[1])),
            opt(r.cube_in_pocket.map(|c| c[2])),
            r.rim_walls
                .iter()
                .map(|w| format!("{w:?}"))
                .collect::<Vec<_>>()
                .join(" "),
        ));
    }
    out
}
