//! The tuning's trials: one row each in `trials.csv` (rewritten whole and atomically after each
//! trial, so an interrupt never leaves half a row), read back to resume.

use std::path::Path;

use fairgrasp_planner::controls::ParamValues;
use fairgrasp_types::fs::{MAX_DATA_BYTES, read_bounded, write_atomic};

use crate::tune::error::TuneError;
use crate::tune::spec::TuneSpec;

/// What every row of a tuning's `trials.csv` must agree with: the tuning it belongs to.
#[derive(Clone, Copy, Debug)]
pub struct RowRules {
    /// Episodes per trial (a refused setting ran none).
    pub episodes: usize,
    /// The most env steps one episode may take (the preset's `task.max_steps`).
    pub max_steps: u64,
    /// The longest cycle \[s\]: `max_steps` steps of the preset.
    pub episode_seconds: f64,
}

impl RowRules {
    /// The rules of `spec`'s trials.
    pub fn of(spec: &TuneSpec) -> Self {
        Self {
            episodes: spec.episodes,
            max_steps: spec.config.task.max_steps as u64,
            episode_seconds: spec.episode_seconds(),
        }
    }
}

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

/// A trial's first columns in a CSV: its index, generation and parameters in the order of
/// `names` (`trials.csv`'s and `finalists.csv`'s).
pub fn trial_columns(t: &Trial, names: &[&str]) -> Vec<String> {
    let mut row = vec![t.index.to_string(), t.generation.to_string()];
    row.extend(
        names
            .iter()
            .map(|n| t.values.get(*n).map_or(String::new(), f64::to_string)),
    );
    row
}

/// `trials` as CSV, parameters in the order of `names`.
pub fn to_csv(trials: &[Trial], names: &[&str]) -> String {
    let mut out = header(names);
    out.push('\n');
    for t in trials {
        let mut row = trial_columns(t, names);
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

/// Reads the trials of `path` (parameters `names`, of a tuning whose rows obey `rules`); every
/// row must be whole (the file is written whole, so a last line without its line end was cut),
/// numbered in order, carry finite numbers in their ranges, the tuning's episodes per trial, env
/// steps its episodes could take (summed without overflow), an objective that is its counts'
/// rate and a cycle time within an episode; an error names the file, the line, the column, the
/// value and what it may be.
pub fn load(path: &Path, names: &[&str], rules: &RowRules) -> Result<Vec<Trial>, TuneError> {
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
    let mut total: u64 = 0;
    lines
        .enumerate()
        .map(|(i, line)| {
            let at = |m: String| TuneError::file(path, format!("line {}: {m}", i + 2));
            let trial = parse_row(line, names, i).map_err(at)?;
            check_row(&trial, rules).map_err(at)?;
            check_objective(
                trial.objective,
                trial.episodes,
                trial.successes,
                trial.within_takt,
            )
            .map_err(at)?;
            total = total.checked_add(trial.env_steps).ok_or_else(|| {
                at(format!(
                    "env_steps {}: the sum of the rows so far passes {} (a wrapped count)",
                    trial.env_steps,
                    u64::MAX
                ))
            })?;
            Ok(trial)
        })
        .collect()
}

/// `v` as a message shows it: in scientific notation when plain digits would be many.
fn shown(v: f64) -> String {
    if v != 0.0 && !(1e-6..1e9).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}

/// A row against the tuning it belongs to: its episodes the tuning's (or none, for a setting
/// the preset refused), its env steps at least one and at most `max_steps` an episode, its
/// cycle time within an episode's length and given only with successes.
fn check_row(t: &Trial, rules: &RowRules) -> Result<(), String> {
    if t.episodes == 0 {
        if t.env_steps != 0 || t.mean_cycle_time_s.is_some() {
            return Err(format!(
                "env_steps {} or a cycle time with 0 episodes: a refused setting ran nothing",
                t.env_steps
            ));
        }
        return Ok(());
    }
    if t.episodes != rules.episodes {
        return Err(format!(
            "episodes {}: this tuning runs {} a trial (or 0 for a setting the preset refused)",
            t.episodes, rules.episodes
        ));
    }
    let most = (t.episodes as u64).saturating_mul(rules.max_steps);
    if t.env_steps < t.episodes as u64 || t.env_steps > most {
        return Err(format!(
            "env_steps {}: {} episodes of at most {} steps take between {} and {most}",
            t.env_steps, t.episodes, rules.max_steps, t.episodes
        ));
    }
    match t.mean_cycle_time_s {
        Some(c) if t.successes == 0 => Err(format!(
            "mean_cycle_time_s {} without a success: it is the successes' mean (empty without any)",
            shown(c)
        )),
        Some(c) if !(0.0..=rules.episode_seconds * (1.0 + 1e-9)).contains(&c) => Err(format!(
            "mean_cycle_time_s {}: a cycle lasts between 0 and the episode's {} s",
            shown(c),
            rules.episode_seconds
        )),
        None if t.successes > 0 => Err(format!(
            "mean_cycle_time_s empty with {} successes: the successes' mean cycle time is missing",
            t.successes
        )),
        _ => Ok(()),
    }
}

/// One row, expected to be trial `index` (its objective checked by [`check_objective`]).
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
