//! `fairgrasp plot` (learning curves, episode charts and replays) and `fairgrasp report`
//! (charts, report.md and report.ipynb from comparison and run folders).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::bail;
use clap::Args;
use fairgrasp_report::charts::{curves, episode, replay};
use fairgrasp_report::trajectory::{self, Trajectory};
use fairgrasp_report::{Existing, RunFolder, build_report};

#[derive(Args, Debug)]
pub struct PlotArgs {
    /// Training run folders (from `fairgrasp train`: metrics.csv, config.toml), drawn together
    /// as learning curves; or recorded episodes (episode_NNNN.json from `--record`), each drawn
    /// as an episode chart (.png) and a replay (.gif) next to the file.
    #[arg(required = true, value_name = "RUN_OR_EPISODE")]
    inputs: Vec<PathBuf>,
    /// Learning-curve PNG. Default: <first run>/plots/learning_curves.png.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Also write one replay frame at this step as <episode>_step<N>.png (for documents that
    /// cannot show GIFs). Steps are numbered from 0; a step past an episode's last one is
    /// refused (the error gives the range) before anything is drawn.
    #[arg(long, value_name = "STEP")]
    still: Option<usize>,
}

pub fn run_plot(a: &PlotArgs) -> anyhow::Result<ExitCode> {
    let (episodes, run_paths): (Vec<&PathBuf>, Vec<&PathBuf>) = a
        .inputs
        .iter()
        .partition(|p| p.extension().is_some_and(|e| e == "json"));
    // Load everything first: a bad input stops the command before any file is written.
    let runs: Vec<RunFolder> = run_paths
        .iter()
        .map(|p| RunFolder::load(p))
        .collect::<Result<_, _>>()?;
    let trajectories: Vec<Trajectory> = episodes
        .iter()
        .map(|p| trajectory::load(p))
        .collect::<Result<_, _>>()?;
    if a.out.is_some() && runs.is_empty() {
        bail!("--out names the learning-curve file, but no run folder was given");
    }
    if let Some(step) = a.still {
        for (path, t) in episodes.iter().zip(&trajectories) {
            let n = t.rows.len();
            if step >= n {
                bail!(
                    "--still {step}: {} has {n} recorded steps, numbered 0–{}; choose a step in \
                     that range",
                    path.display(),
                    n.saturating_sub(1)
                );
            }
        }
    }
    if let Some(first) = runs.first() {
        let out = a
            .out
            .clone()
            .unwrap_or_else(|| first.path.join("plots/learning_curves.png"));
        curves::learning_curves(&runs, &out)?;
        println!(
            "learning curves of {} run(s): {}",
            runs.len(),
            out.display()
        );
    }
    for (path, t) in episodes.iter().zip(&trajectories) {
        let title = format!(
            "{} ({} steps, {:.1} s)",
            path.file_stem().unwrap_or_default().to_string_lossy(),
            t.rows.len(),
            t.rows.last().map_or(0.0, |r| r.time_s)
        );
        let (png, gif) = (path.with_extension("png"), path.with_extension("gif"));
        episode::episode_chart(t, &title, &png)?;
        replay::replay_gif(t, &title, &gif)?;
        println!(
            "episode chart: {}\nreplay:        {}",
            png.display(),
            gif.display()
        );
        if let Some(step) = a.still {
            let stem = path.file_stem().unwrap_or_default().to_string_lossy();
            let still = path.with_file_name(format!("{stem}_step{step}.png"));
            replay::replay_still(t, &title, step, &still)?;
            println!("still:         {}", still.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

#[derive(Args, Debug)]
pub struct ReportArgs {
    /// Comparison folders (from `fairgrasp compare`) and training run folders (from
    /// `fairgrasp train`).
    #[arg(required = true, value_name = "RUN_OR_COMPARE_DIR")]
    inputs: Vec<PathBuf>,
    /// Output folder for report.md, report.ipynb and the charts they show. It must be new or
    /// empty, or (with --force) one an earlier `fairgrasp compare` or `report` wrote; it may not
    /// be one of the input folders. The report is built next to it in DIR.partial-<pid> and
    /// moved into place only when complete: an error leaves DIR as it was.
    #[arg(long, value_name = "DIR", default_value = "report")]
    out: PathBuf,
    /// Replace --out if an earlier `fairgrasp compare` or `fairgrasp report` wrote it (it holds
    /// a .fairgrasp-report file) and no file in it was edited or added since; otherwise the
    /// files in the way are named and nothing is replaced. A folder fairgrasp did not write is
    /// never replaced, --force or not.
    #[arg(long)]
    force: bool,
}

/// `--force` as the report crate's rule for an existing output folder.
pub fn existing_rule(force: bool) -> Existing {
    if force {
        Existing::Replace
    } else {
        Existing::Refuse
    }
}

pub fn run_report(a: &ReportArgs) -> anyhow::Result<ExitCode> {
    let written = build_report(&a.inputs, &a.out, existing_rule(a.force))?;
    println!("Written to {}:", a.out.display());
    for p in &written {
        println!("  {}", p.strip_prefix(&a.out).unwrap_or(p).display());
    }
    println!("Open report.ipynb in Jupyter (nothing to run) or report.md in any Markdown viewer.");
    Ok(ExitCode::SUCCESS)
}
