//! A comparison's charts drawn at once: PNG and GIF encoding are most of a report's time, and
//! every chart is its own file, so they are jobs of a queue shared by the threads
//! ([`fairgrasp_types::work_queue`]). The files are the same as drawn one after another; a
//! failure returns the error of the first failing chart in the order listed here.

use std::path::Path;

use fairgrasp_types::fs::slug;
use fairgrasp_types::work_queue::run_in_order;

use crate::charts::{episode, heatmap, replay, takt, workspace};
use crate::comparison_table::Comparison;
use crate::error::ReportError;
use crate::trajectory::Trajectory;

/// The chart files of one comparison section, relative to the report folder.
pub(crate) struct ComparisonCharts {
    /// Success rate per method and preset (a heatmap).
    pub success: String,
    /// A workspace map per preset: (file, preset).
    pub workspaces: Vec<(String, String)>,
    /// Per recorded episode that has its trajectory: (episode chart PNG, replay GIF, title).
    pub episodes: Vec<(String, String, String)>,
    /// Per preset that runs on a takt: (file, preset, takt \[s\]), success within it against
    /// cycle time.
    pub takts: Vec<(String, String, f64)>,
}

/// Draws the success chart, a workspace map per preset and, per recorded episode (`trajectories`
/// in the order of `c.recorded`), its chart and GIF replay into `out`, file names starting with
/// `prefix`, on `threads` threads.
pub(crate) fn draw_comparison_charts(
    c: &Comparison,
    trajectories: &[Trajectory],
    out: &Path,
    prefix: &str,
    threads: usize,
) -> Result<ComparisonCharts, ReportError> {
    let charts = ComparisonCharts {
        success: format!("{prefix}success_rate.png"),
        workspaces: c
            .presets
            .iter()
            .map(|p| (format!("{prefix}workspace_{}.png", slug(p)), p.clone()))
            .collect(),
        episodes: c
            .recorded
            .iter()
            .zip(trajectories)
            .map(|(rec, _)| {
                let stem = format!(
                    "{prefix}{}_{}_ep{}",
                    slug(&rec.method),
                    slug(&rec.preset),
                    rec.episode
                );
                let title = format!(
                    "{} on `{}`, episode {} ({})",
                    rec.method, rec.preset, rec.episode, rec.outcome
                );
                (
                    format!("episode_{stem}.png"),
                    format!("replay_{stem}.gif"),
                    title,
                )
            })
            .collect(),
        takts: c
            .presets
            .iter()
            .filter_map(|p| {
                let takt = c.results.iter().find(|r| r.preset == *p)?.report.takt_s?;
                Some((format!("{prefix}takt_{}.png", slug(p)), p.clone(), takt))
            })
            .collect(),
    };
    // Job 0: the success chart; then one per workspace map, one per takt chart; then two per
    // recorded episode.
    let maps = charts.workspaces.len() + charts.takts.len();
    let episodes = charts.episodes.len();
    let draw = |_: &mut (), j: usize| -> Result<(), ReportError> {
        if j == 0 {
            return heatmap::success_heatmap(c, &out.join(&charts.success));
        }
        if let Some((file, preset)) = charts.workspaces.get(j - 1) {
            return workspace::workspace_map(c, preset, &out.join(file));
        }
        if let Some((file, preset, takt)) = charts.takts.get(j - 1 - charts.workspaces.len()) {
            return takt::takt_chart(c, preset, *takt, &out.join(file));
        }
        let k = j - 1 - maps;
        let ((png, gif, title), t) = (&charts.episodes[k / 2], &trajectories[k / 2]);
        if k.is_multiple_of(2) {
            episode::episode_chart(t, title, &out.join(png))
        } else {
            replay::replay_gif(t, title, &out.join(gif))
        }
    };
    run_in_order(1 + maps + 2 * episodes, threads, &|_| {}, &|| (), &draw)?;
    Ok(charts)
}
