//! `fairgrasp eval --squeeze-chart FILE.png`: what a squeezing residual learned, drawn. Each
//! episode's grip force as the lift began against the squeeze its cube needed
//! ([`fairgrasp_evaluate::squeeze_probe`]), as a PNG and the same rows as `FILE.csv`.

use std::path::{Path, PathBuf};

use anyhow::Context;
use fairgrasp_env::EnvConfig;
use fairgrasp_env::episode::Policy;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_evaluate::squeeze_probe::{correlation, probe_squeeze, squeeze_csv};
use fairgrasp_report::charts::squeeze::squeeze_chart;
use fairgrasp_types::output::{check_replaceable, png_is_ours};

use super::baseline::{ScenarioArgs, preset_config};

/// The CSV written beside the chart `png`.
fn csv_beside(png: &Path) -> PathBuf {
    png.with_extension("csv")
}

/// Checks, before any episode runs, that the chart and its CSV may be written: a `.png` name,
/// a chart fairgrasp drew or a new file, and a CSV that does not exist yet.
pub fn check_paths(png: &Path) -> anyhow::Result<()> {
    if png.extension().and_then(|e| e.to_str()) != Some("png") {
        anyhow::bail!(
            "--squeeze-chart {}: the chart is a PNG; give a name ending in .png",
            png.display()
        );
    }
    check_replaceable(png, "chart", png_is_ours).map_err(anyhow::Error::msg)?;
    let csv = csv_beside(png);
    if csv.exists() {
        anyhow::bail!(
            "{} exists: the squeeze chart writes its rows there and never replaces a file; move it away or choose another chart name",
            csv.display()
        );
    }
    Ok(())
}

/// Runs the policy on the scenario set of `a` again, noting its grip force at each lift, and
/// writes the chart and the CSV; prints where they went and what they show.
pub fn write<P: Policy>(
    a: &ScenarioArgs,
    method: &str,
    png: &Path,
    make: &(dyn Fn(&EnvConfig) -> P + Sync),
) -> anyhow::Result<()> {
    let config = preset_config(&a.preset, a.arm)?;
    let threads = a
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let scenarios = scenario_set(&config, a.seed, a.episodes as usize)?;
    let rows = probe_squeeze(&config, &scenarios, threads, &|| make(&config))?;
    let points: Vec<_> = rows
        .iter()
        .filter_map(|r| r.at_lift_n.map(|f| (r.needed_n, f, r.outcome)))
        .collect();
    let title = format!(
        "{method} on `{}`, {} episodes of set {}",
        a.preset, a.episodes, a.seed
    );
    squeeze_chart(&points, &title, png)?;
    let csv = csv_beside(png);
    fairgrasp_types::write_atomic(&csv, squeeze_csv(&rows).as_bytes())
        .with_context(|| format!("writing {}", csv.display()))?;
    if !a.json {
        let r = correlation(&rows).map_or("n/a (fewer than 3 lifts, or no spread)".into(), |r| {
            format!("{r:.2}")
        });
        println!(
            "  squeeze chart         {} ({} of {} episodes lifted; correlation of grip and need {r}), rows in {}",
            png.display(),
            points.len(),
            rows.len(),
            csv.display()
        );
    }
    Ok(())
}
