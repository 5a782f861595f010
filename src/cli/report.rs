//! `fairgrasp plot` (learning curves, episode charts and replays) and `fairgrasp report`
//! (charts, report.md and report.ipynb from comparison and run folders).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::bail;
use clap::Args;
use fairgrasp_report::charts::{curves, episode, replay};
use fairgrasp_report::trajectory::{self, Trajectory};
use fairgrasp_report::{Existing, RunFolder, build_report};

/// Parses `--still`: a step of an episode, 0–[`MAX_EPISODE_STEPS`] − 1 (clap value parser).
///
/// [`MAX_EPISODE_STEPS`]: fairgrasp_env::config::validate::MAX_EPISODE_STEPS
fn still_step(text: &str) -> Result<usize, String> {
    let last = fairgrasp_env::config::validate::MAX_EPISODE_STEPS as u64 - 1;
    super::args::whole_number_in(text, 0..=last).map(|n| n as usize)
}

#[derive(Args, Debug)]
pub struct PlotArgs {
    /// Training run folders (from `fairgrasp train`: metrics.csv, config.toml), drawn together
    /// as learning curves; or recorded episodes (episode_NNNN.json from `--record`, or
    /// `compare`'s episodes/*.json.gz), each drawn as an episode chart (.png) and a replay
    /// (.gif) next to the file.
    #[arg(required = true, value_name = "RUN_OR_EPISODE")]
    inputs: Vec<PathBuf>,
    /// Learning-curve PNG. Default: <first run>/plots/learning_curves.png. An existing file is
    /// replaced only if it is a chart fairgrasp wrote (never an input, a run's metrics.csv or
    /// model, a folder or a device, nor a file inside a report folder).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Also write one replay frame at this step as <episode>_step<N>.png (for documents that
    /// cannot show GIFs). Steps are numbered from 0; a step past an episode's last one is
    /// refused (the error gives the range) before anything is drawn; 0–99999 (an episode's
    /// longest, `task.max_steps`, is 100000 steps).
    #[arg(long, value_name = "STEP", value_parser = still_step)]
    still: Option<usize>,
    /// Write the episode charts, replays and stills into this folder (created if missing)
    /// instead of beside each episode file; needed for an episode inside a report folder,
    /// whose files only `compare` and `report` write.
    #[arg(long, value_name = "DIR")]
    out_dir: Option<PathBuf>,
}

/// Is `path` a recorded episode (`.json`, or a comparison's compact `.json.gz`)?
fn is_episode_file(path: &Path) -> bool {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    name.ends_with(".json") || name.ends_with(".json.gz")
}

/// An episode file's name without `.json` or `.json.gz`.
fn episode_stem(episode: &Path) -> String {
    let name = episode.file_name().unwrap_or_default().to_string_lossy();
    let name = name.strip_suffix(".gz").unwrap_or(&name);
    name.strip_suffix(".json").unwrap_or(name).to_string()
}

/// Where `plot` draws an episode's chart (`.png`), replay (`.gif`) and, with `--still N`, the
/// still (`_stepN.png`): beside the episode file, or in `out_dir`.
fn episode_outputs(
    episode: &Path,
    out_dir: Option<&Path>,
    still: Option<usize>,
) -> (PathBuf, PathBuf, Option<PathBuf>) {
    let stem = episode_stem(episode);
    let dir = out_dir.map_or_else(
        || episode.parent().unwrap_or(Path::new("")).to_path_buf(),
        Path::to_path_buf,
    );
    (
        dir.join(format!("{stem}.png")),
        dir.join(format!("{stem}.gif")),
        still.map(|step| dir.join(format!("{stem}_step{step}.png"))),
    )
}

pub fn run_plot(a: &PlotArgs) -> anyhow::Result<ExitCode> {
    let (episodes, run_paths): (Vec<&PathBuf>, Vec<&PathBuf>) =
        a.inputs.iter().partition(|p| is_episode_file(p));
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
    let curves_out = runs.first().map(|first| {
        a.out
            .clone()
            .unwrap_or_else(|| first.path.join("plots/learning_curves.png"))
    });
    check_plot_outputs(
        curves_out.as_deref(),
        &episodes,
        a.still,
        a.out_dir.as_deref(),
        &a.inputs,
    )?;
    if let Some(out) = curves_out {
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
            episode_stem(path),
            t.rows.len(),
            t.rows.last().map_or(0.0, |r| r.time_s)
        );
        let (png, gif, still) = episode_outputs(path, a.out_dir.as_deref(), a.still);
        episode::episode_chart(t, &title, &png)?;
        replay::replay_gif(t, &title, &gif)?;
        println!(
            "episode chart: {}\nreplay:        {}",
            png.display(),
            gif.display()
        );
        if let (Some(step), Some(still)) = (a.still, still) {
            replay::replay_still(t, &title, step, &still)?;
            println!("still:         {}", still.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// The files `plot` writes: the learning curves, then per episode its chart, replay and still.
/// Checked before anything is drawn: each must be new or a chart fairgrasp wrote
/// ([`fairgrasp_types::output`]), none may be an input or written twice, and `--out` is a PNG.
fn check_plot_outputs(
    curves: Option<&Path>,
    episodes: &[&PathBuf],
    still: Option<usize>,
    out_dir: Option<&Path>,
    inputs: &[PathBuf],
) -> anyhow::Result<()> {
    use fairgrasp_types::output::{check_replaceable, gif_is_ours, png_is_ours};
    let mut outputs: Vec<(PathBuf, bool)> = curves
        .map(|c| (c.to_path_buf(), true))
        .into_iter()
        .collect();
    for path in episodes {
        let (png, gif, still) = episode_outputs(path, out_dir, still);
        outputs.push((png, true));
        outputs.push((gif, false));
        outputs.extend(still.map(|p| (p, true)));
    }
    let same =
        |a: &Path, b: &Path| a == b || std::path::absolute(a).ok() == std::path::absolute(b).ok();
    for (i, (path, png)) in outputs.iter().enumerate() {
        if let Some(input) = inputs.iter().find(|input| same(input, path)) {
            bail!(
                "{} is an input of this command: it is never written over",
                input.display()
            );
        }
        if outputs[..i].iter().any(|(earlier, _)| same(earlier, path)) {
            bail!(
                "{} would be written twice by this command (--out names another chart's file): choose another --out",
                path.display()
            );
        }
        let checked = if *png {
            check_replaceable(path, "chart", png_is_ours)
        } else {
            check_replaceable(path, "replay", gif_is_ours)
        };
        checked.map_err(|e| match out_dir {
            None if !episodes.is_empty() && e.contains("inside the report folder") => {
                anyhow::anyhow!("{e} (for an episode of a report: plot … --out-dir DIR)")
            }
            _ => anyhow::Error::msg(e),
        })?;
    }
    if let Some(out) = curves
        && !out
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("png"))
    {
        bail!(
            "--out {}: the learning curves are a PNG; give a file name ending in .png",
            out.display()
        );
    }
    Ok(())
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
pub fn run_report(a: &ReportArgs) -> anyhow::Result<ExitCode> {
    let written = build_report(&a.inputs, &a.out, Existing::from_force(a.force))?;
    println!("Written to {}:", a.out.display());
    for p in &written {
        println!("  {}", p.strip_prefix(&a.out).unwrap_or(p).display());
    }
    println!("Open report.ipynb in Jupyter (nothing to run) or report.md in any Markdown viewer.");
    Ok(ExitCode::SUCCESS)
}
