//! The tuning's trials: one row each in `trials.csv` (rewritten whole and atomically after each
//! trial, so an interrupt never leaves half a row), read back to resume.

use std::path::Path;

use fairgrasp_planner::controls::ParamValues;
use fairgrasp_types::fs::{MAX_DATA_BYTES, read_bounded, write_atomic};

use crate::tune::error::TuneError;

/// One evaluated setting of the control.
#[derive(Clone, Debug, PartialEq)]
pub struct Trial {
    /// 0, 1, … in the order the optimiser asked.
    pub index: usize,
    /// The optimiser's generation (its restarts continue the count).
    pub generation: usize,
    /// The parameters' values, by name.
    pub values: ParamValues,
    /// Episodes run, env steps they took, successes, successes within the takt.
    pub episodes: usize,
    pub env_steps: u64,
    pub successes: usize,
    pub within_takt: usize,
    /// What the optimiser maximises: the rate of `within_takt` (place) or `successes` (lift);
    /// −1 for a setting the preset refuses (then nothing ran).
    pub objective: f64,
    /// Mean cycle time of the successes \[s\] (`None` without any).
    pub mean_cycle_time_s: Option<f64>,
}

/// The CSV's header for parameters named `names`.
fn header(names: &[&str]) -> String {
    let mut cols = vec!["trial", "generation"];
    cols.extend(names);
    cols.extend([
        "episodes",
        "env_steps",
        "successes",
        "within_takt",
        "objective",
        "mean_cycle_time_s",
    ]);
    cols.join(",")
}

/// `trials` as CSV, parameters in the order of `names`.
pub fn to_csv(trials: &[Trial], names: &[&str]) -> String {
    let mut out = header(names);
    out.push('\n');
    for t in trials {
        let mut row = vec![t.index.to_string(), t.generation.to_string()];
        row.extend(
            names
                .iter()
                .map(|n| t.values.get(*n).map_or(String::new(), f64::to_string)),
        );
        row.extend([
            t.episodes.to_string(),
            t.env_steps.to_string(),
            t.successes.to_string(),
            t.within_takt.to_string(),
            t.objective.to_string(),
            t.mean_cycle_time_s.map_or(String::new(), |c| c.to_string()),
        ]);
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

/// Writes `trials` to `path` atomically.
pub fn save(path: &Path, trials: &[Trial], names: &[&str]) -> Result<(), TuneError> {
    write_atomic(path, to_csv(trials, names).as_bytes()).map_err(|e| TuneError::io(path, e))
}

/// Reads the trials of `path` (parameters `names`); every row must be whole (the file is
/// written whole, so a last line without its line end was cut), numbered in order, carry
/// finite numbers in their ranges and an objective that is its counts' rate; an error names
/// the file, the line, the column, the value and what it may be.
pub fn load(path: &Path, names: &[&str]) -> Result<Vec<Trial>, TuneError> {
    let bytes = read_bounded(path, MAX_DATA_BYTES).map_err(|e| TuneError::io(path, e))?;
    let text = String::from_utf8(bytes)
        .map_err(|_| TuneError::file(path, "not UTF-8 text".to_string()))?;
    if !text.is_empty() && !text.ends_with('\n') {
        let line = text.lines().count();
        return Err(TuneError::file(
            path,
            format!(
                "line {line}: cut short (no line end; the file is always written whole): restore it, or delete that line to run the trial again"
            ),
        ));
    }
    let mut lines = text.lines();
    let expected = header(names);
    match lines.next() {
        Some(h) if h == expected => {}
        Some(h) => {
            return Err(TuneError::file(
                path,
                format!(
                    "line 1: header `{h}` is not this tuning's `{expected}` (another control or parameter list)"
                ),
            ));
        }
        None => return Ok(Vec::new()),
    }
    lines
        .enumerate()
        .map(|(i, line)| {
            parse_row(line, names, i)
                .map_err(|m| TuneError::file(path, format!("line {}: {m}", i + 2)))
        })
        .collect()
}

/// One row, expected to be trial `index`.
fn parse_row(line: &str, names: &[&str], index: usize) -> Result<Trial, String> {
    let cells: Vec<&str> = line.split(',').collect();
    let want = names.len() + 8;
    if cells.len() != want {
        return Err(format!(
            "{} fields, expected {want} (the header's columns)",
            cells.len()
        ));
    }
    let num = |k: usize, what: &str| -> Result<f64, String> {
        let v: f64 = cells[k]
            .parse()
            .map_err(|_| format!("{what} `{}` is not a number", cells[k]))?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(format!("{what} `{}` is not a finite number", cells[k]))
        }
    };
    let count = |k: usize, what: &str| -> Result<u64, String> {
        cells[k]
            .parse()
            .map_err(|_| format!("{what} `{}` is not a whole number", cells[k]))
    };
    if count(0, "trial")? != index as u64 {
        return Err(format!(
            "trial `{}`, expected {index} (rows in order, none missing)",
            cells[0]
        ));
    }
    let mut values = ParamValues::new();
    for (j, name) in names.iter().enumerate() {
        values.insert(name.to_string(), num(2 + j, name)?);
    }
    let k = 2 + names.len();
    let episodes = count(k, "episodes")? as usize;
    let successes = count(k + 2, "successes")? as usize;
    let within_takt = count(k + 3, "within_takt")? as usize;
    if successes > episodes || within_takt > successes {
        return Err(format!(
            "successes {successes}, within_takt {within_takt} of {episodes} episodes: successes must be at most the episodes, and within_takt at most the successes"
        ));
    }
    let objective = num(k + 4, "objective")?;
    check_objective(objective, episodes, successes, within_takt)?;
    Ok(Trial {
        index,
        generation: count(1, "generation")? as usize,
        values,
        episodes,
        env_steps: count(k + 1, "env_steps")?,
        successes,
        within_takt,
        objective,
        mean_cycle_time_s: match cells[k + 5] {
            "" => None,
            _ => Some(num(k + 5, "mean_cycle_time_s")?),
        },
    })
}

/// A trial's objective is the rate of its successes or of its successes within the takt
/// (whichever the tuning maximises), or −1 for a setting the preset refused (no episodes).
fn check_objective(
    objective: f64,
    episodes: usize,
    successes: usize,
    within_takt: usize,
) -> Result<(), String> {
    if !(-1.0..=1.0).contains(&objective) {
        return Err(format!("objective {objective} is not in [-1, 1]"));
    }
    if episodes == 0 {
        return if objective == -1.0 {
            Ok(())
        } else {
            Err(format!(
                "objective {objective} with 0 episodes: a trial that ran nothing scores -1"
            ))
        };
    }
    let n = episodes as f64;
    let rates = [within_takt as f64 / n, successes as f64 / n];
    if rates.contains(&objective) {
        Ok(())
    } else {
        Err(format!(
            "objective {objective} is neither successes/episodes ({}) nor within_takt/episodes ({}) of its row",
            rates[1], rates[0]
        ))
    }
}
