//! A training run folder as `fairgrasp train` writes it: `config.toml`, `metrics.csv` (one row
//! per PPO update) and, when training finished, `eval.json`.

use std::path::{Path, PathBuf};

use crate::error::{ReportError, read_text};

/// Columns a learning-curve chart needs from `metrics.csv`.
pub const REQUIRED_COLUMNS: [&str; 7] = [
    "timesteps",
    "episode_return",
    "success_rate",
    "policy_loss",
    "value_loss",
    "entropy",
    "stage",
];

/// `metrics.csv` as numbers by column; an empty cell (no evaluation at that update) is NaN.
#[derive(Clone, Debug, PartialEq)]
pub struct Metrics {
    pub columns: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl Metrics {
    /// Parses `metrics.csv` text; `path` names the file in errors.
    pub fn parse(text: &str, path: &Path) -> Result<Self, ReportError> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let Some((_, header)) = lines.next() else {
            return Err(ReportError::malformed(
                path,
                "empty file (expected a header line)",
            ));
        };
        let columns: Vec<String> = header.split(',').map(|c| c.trim().to_string()).collect();
        if let Some(missing) = REQUIRED_COLUMNS
            .iter()
            .find(|c| !columns.iter().any(|h| h == *c))
        {
            return Err(ReportError::malformed(
                path,
                format!(
                    "header has no `{missing}` column (needs {}; found {})",
                    REQUIRED_COLUMNS.join(", "),
                    columns.join(", ")
                ),
            ));
        }
        let mut rows = Vec::new();
        for (i, line) in lines {
            let fields: Vec<&str> = line.split(',').collect();
            if fields.len() != columns.len() {
                return Err(ReportError::malformed(
                    path,
                    format!(
                        "line {}: {} fields, the header has {}",
                        i + 1,
                        fields.len(),
                        columns.len()
                    ),
                ));
            }
            let mut row = Vec::with_capacity(fields.len());
            for (field, column) in fields.iter().zip(&columns) {
                let field = field.trim();
                row.push(if field.is_empty() {
                    f64::NAN
                } else {
                    field.parse().map_err(|_| {
                        ReportError::malformed(
                            path,
                            format!(
                                "line {}, column `{column}`: `{field}` is not a number",
                                i + 1
                            ),
                        )
                    })?
                });
            }
            rows.push(row);
        }
        if rows.is_empty() {
            return Err(ReportError::malformed(
                path,
                "no rows after the header (no update finished)",
            ));
        }
        Ok(Self { columns, rows })
    }

    /// One column's values, if the column exists.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let i = self.columns.iter().position(|c| c == name)?;
        Some(self.rows.iter().map(|r| r[i]).collect())
    }

    /// `(timesteps, value)` pairs of a column, skipping NaN cells.
    pub fn series(&self, name: &str) -> Vec<(f64, f64)> {
        let (Some(x), Some(y)) = (self.column("timesteps"), self.column(name)) else {
            return Vec::new();
        };
        x.into_iter()
            .zip(y)
            .filter(|(_, y)| y.is_finite())
            .collect()
    }

    /// Timesteps at which the curriculum stage changed (the first row of each new stage).
    pub fn stage_changes(&self) -> Vec<(f64, f64)> {
        let stages = self.series("stage");
        stages
            .windows(2)
            .filter(|w| w[1].1 != w[0].1)
            .map(|w| w[1])
            .collect()
    }
}

/// A loaded run folder.
#[derive(Clone, Debug)]
pub struct RunFolder {
    pub path: PathBuf,
    /// The folder's name, used as the run's label.
    pub name: String,
    /// `config.toml` text (the complete training config).
    pub config_toml: String,
    pub metrics: Metrics,
    /// `eval.json` when training finished.
    pub eval: Option<serde_json::Value>,
}

impl RunFolder {
    /// Loads a run folder, naming what is missing or malformed.
    pub fn load(path: &Path) -> Result<Self, ReportError> {
        if !path.is_dir() {
            return Err(ReportError::NotAReportInput {
                path: path.to_path_buf(),
                what: "no such folder".into(),
            });
        }
        let metrics_path = path.join("metrics.csv");
        if !metrics_path.is_file() {
            return Err(ReportError::NotAReportInput {
                path: path.to_path_buf(),
                what:
                    "not a run folder: no metrics.csv (a run folder from `fairgrasp train` holds \
                       config.toml, metrics.csv and checkpoints/)"
                        .into(),
            });
        }
        let metrics = Metrics::parse(&read_text(&metrics_path)?, &metrics_path)?;
        let config_path = path.join("config.toml");
        let config_toml = if config_path.is_file() {
            read_text(&config_path)?
        } else {
            return Err(ReportError::NotAReportInput {
                path: path.to_path_buf(),
                what: "run folder without config.toml (the config that produced the run)".into(),
            });
        };
        let eval_path = path.join("eval.json");
        let eval = if eval_path.is_file() {
            Some(
                serde_json::from_str(&read_text(&eval_path)?)
                    .map_err(|e| ReportError::malformed(&eval_path, format!("not JSON: {e}")))?,
            )
        } else {
            None
        };
        let name = path
            .canonicalize()
            .ok()
            .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| path.display().to_string());
        Ok(Self {
            path: path.to_path_buf(),
            name,
            config_toml,
            metrics,
            eval,
        })
    }
}
