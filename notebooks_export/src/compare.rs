//! The comparison of methods on presets: its data (what `compare.json` holds), `compare.csv`,
//! and the same table as text and as Markdown.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{ReportError, read_text};

/// Every episode outcome fairgrasp classifies, in table order (the env's `Outcome`, snake_case).
pub const OUTCOMES: [&str; 8] = [
    "success",
    "missed_grasp",
    "slip_or_drop",
    "collision",
    "ik_failure",
    "object_off_table",
    "timeout",
    "physics_fault",
];

/// One evaluated episode.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeRecord {
    /// Scenario seed.
    pub seed: u64,
    /// One of [`OUTCOMES`].
    pub outcome: String,
    pub steps: usize,
    pub episode_return: f64,
    /// Object start position in `base_link` [m].
    pub object_xy: [f64; 2],
}

/// One method on one preset's scenario set.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MethodResult {
    pub method: String,
    pub preset: String,
    /// Arm simulation (`servo` or `multibody`).
    pub arm: String,
    /// Seed of the scenario set (the same for every method).
    pub seed: u64,
    pub episodes: usize,
    pub successes: usize,
    pub success_rate: f64,
    /// 95 % Wilson interval of the success rate.
    pub ci_low: f64,
    pub ci_high: f64,
    pub collision_rate: f64,
    /// Mean steps of the successful episodes (`None` without any).
    pub mean_steps_to_success: Option<f64>,
    pub mean_return: f64,
    /// Episodes per outcome (outcomes with no episode may be absent).
    pub outcomes: BTreeMap<String, usize>,
    /// Checkpoint folder of a learned policy.
    #[serde(default)]
    pub policy: Option<String>,
    pub results: Vec<EpisodeRecord>,
}

/// A recorded episode kept with the comparison (for the episode charts and replays).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RecordedEpisode {
    pub method: String,
    pub preset: String,
    /// Index of the scenario in the preset's set.
    pub episode: usize,
    pub outcome: String,
    /// Trajectory JSON, relative to the comparison folder.
    pub trajectory: String,
}

/// Everything `fairgrasp compare` measured: `compare.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    /// The command line that produced it.
    pub command: String,
    /// Presets in run order.
    pub presets: Vec<String>,
    /// Methods in run order.
    pub methods: Vec<String>,
    /// Environment config (TOML) of each preset.
    pub preset_configs: BTreeMap<String, String>,
    /// Run folders of the learned policies (with metrics.csv), for learning curves.
    #[serde(default)]
    pub run_folders: Vec<String>,
    #[serde(default)]
    pub recorded: Vec<RecordedEpisode>,
    pub results: Vec<MethodResult>,
}

impl Comparison {
    /// Reads and checks `compare.json`.
    pub fn load(path: &Path) -> Result<Self, ReportError> {
        let text = read_text(path)?;
        let c: Self = serde_json::from_str(&text).map_err(|e| {
            ReportError::malformed(path, format!("not a fairgrasp compare.json: {e}"))
        })?;
        c.check()
            .map_err(|what| ReportError::malformed(path, what))?;
        Ok(c)
    }

    /// The comparison as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("plain data serialises")
    }

    /// Internal consistency: counts add up, rates match counts, outcomes are known.
    pub fn check(&self) -> Result<(), String> {
        for r in &self.results {
            let name = format!("result `{}` on `{}`", r.method, r.preset);
            if r.results.len() != r.episodes {
                return Err(format!(
                    "{name}: episodes = {} but {} episode records",
                    r.episodes,
                    r.results.len()
                ));
            }
            if let Some(o) = r.outcomes.keys().find(|o| !OUTCOMES.contains(&o.as_str())) {
                return Err(format!(
                    "{name}: unknown outcome `{o}` (known: {})",
                    OUTCOMES.join(", ")
                ));
            }
            if r.outcomes.values().sum::<usize>() != r.episodes {
                return Err(format!(
                    "{name}: outcome counts do not add up to {}",
                    r.episodes
                ));
            }
            if r.episodes > 0
                && (r.success_rate - r.successes as f64 / r.episodes as f64).abs() > 1e-9
            {
                return Err(format!(
                    "{name}: success_rate {} ≠ successes/episodes",
                    r.success_rate
                ));
            }
        }
        Ok(())
    }

    /// The result of `method` on `preset`.
    pub fn get(&self, method: &str, preset: &str) -> Option<&MethodResult> {
        self.results
            .iter()
            .find(|r| r.method == method && r.preset == preset)
    }
}

/// The header of `compare.csv`.
pub fn csv_header() -> String {
    let mut cols: Vec<&str> = vec![
        "method",
        "preset",
        "arm",
        "seed",
        "episodes",
        "successes",
        "success_rate",
        "ci_low",
        "ci_high",
        "collision_rate",
        "mean_steps_to_success",
        "mean_return",
    ];
    cols.extend(OUTCOMES);
    cols.join(",")
}

/// `compare.csv`: one row per method and preset, rates as fractions, an empty
/// `mean_steps_to_success` when nothing succeeded.
pub fn to_csv(c: &Comparison) -> String {
    let mut out = csv_header();
    out.push('\n');
    for r in &c.results {
        let mut fields = vec![
            csv_field(&r.method),
            csv_field(&r.preset),
            r.arm.clone(),
            r.seed.to_string(),
            r.episodes.to_string(),
            r.successes.to_string(),
            r.success_rate.to_string(),
            r.ci_low.to_string(),
            r.ci_high.to_string(),
            r.collision_rate.to_string(),
            r.mean_steps_to_success
                .map_or(String::new(), |s| s.to_string()),
            r.mean_return.to_string(),
        ];
        fields.extend(
            OUTCOMES
                .iter()
                .map(|o| r.outcomes.get(*o).copied().unwrap_or(0).to_string()),
        );
        out.push_str(&fields.join(","));
        out.push('\n');
    }
    out
}

/// Quotes a CSV field when it holds a comma or a quote.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Failures as `name count` pairs, most frequent first (no successes listed).
pub fn failure_breakdown(r: &MethodResult) -> String {
    let mut failures: Vec<(&String, &usize)> = r
        .outcomes
        .iter()
        .filter(|(o, n)| o.as_str() != "success" && **n > 0)
        .collect();
    failures.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
    if failures.is_empty() {
        return "none".into();
    }
    failures
        .iter()
        .map(|(o, n)| format!("{o} {n}"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn pct(x: f64) -> String {
    format!("{:.1}", 100.0 * x)
}

/// The table's cells, shared by the text and Markdown forms.
fn cells(r: &MethodResult) -> [String; 7] {
    [
        r.preset.clone(),
        r.method.clone(),
        r.episodes.to_string(),
        format!(
            "{} % ({}–{})",
            pct(r.success_rate),
            pct(r.ci_low),
            pct(r.ci_high)
        ),
        format!("{} %", pct(r.collision_rate)),
        r.mean_steps_to_success
            .map_or("n/a".into(), |s| format!("{s:.1}")),
        failure_breakdown(r),
    ]
}

const HEADER: [&str; 7] = [
    "preset",
    "method",
    "episodes",
    "success (95 % CI)",
    "collisions",
    "steps to success",
    "failures",
];

/// The table as aligned text, one line per method and preset.
pub fn text_table(c: &Comparison) -> String {
    let rows: Vec<[String; 7]> = c.results.iter().map(cells).collect();
    let mut widths = HEADER.map(|h| h.chars().count());
    for row in &rows {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |cells: &[String]| {
        let padded: Vec<String> = cells
            .iter()
            .zip(widths)
            .map(|(c, w)| format!("{c}{}", " ".repeat(w - c.chars().count())))
            .collect();
        padded.join("  ").trim_end().to_string() + "\n"
    };
    let mut out = line(&HEADER.map(String::from));
    out += &line(&widths.map(|w| "-".repeat(w)));
    for row in &rows {
        out += &line(row);
    }
    out
}

/// The table in Markdown.
pub fn markdown_table(c: &Comparison) -> String {
    let mut out = format!("| {} |\n", HEADER.join(" | "));
    out += &format!("|{}\n", "---|".repeat(HEADER.len()));
    for r in &c.results {
        out += &format!("| {} |\n", cells(r).join(" | "));
    }
    out
}
