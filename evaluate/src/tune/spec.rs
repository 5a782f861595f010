//! What a tuning is: the control, the parameters and their ranges, the preset it runs on, the
//! objective, the training scenarios and the budget; checked before anything runs, and saved
//! (`tune.json`) so that a resumed tuning is refused if any of it changed.

use std::path::Path;

use fairgrasp_env::EnvConfig;
use fairgrasp_planner::controls::{Control, Param, ParamValues, Scale, control, control_names};
use fairgrasp_types::fs::{MAX_CONFIG_BYTES, read_text_bounded, write_atomic};
use serde::{Deserialize, Serialize};

use fairgrasp_policy::recipe::read::leaf_differences;

use crate::tune::error::TuneError;

/// The most env steps one tuning may spend (a billion: days on 2 cores).
pub const MAX_BUDGET: u64 = 1_000_000_000;
/// The most episodes one trial may run.
pub const MAX_EPISODES_PER_TRIAL: usize = 100_000;

/// What a trial's score is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Objective {
    /// Successes within the task's takt, as a fraction of the episodes (a task with a takt).
    SuccessWithinTakt,
    /// Successes, as a fraction (a task without a takt: lift).
    Success,
}

impl Objective {
    /// The objective of a task: within its takt if it runs on one.
    pub fn of(config: &EnvConfig) -> Self {
        if config.task.takt().is_some() {
            Self::SuccessWithinTakt
        } else {
            Self::Success
        }
    }

    /// As a note states it.
    pub fn describe(self) -> &'static str {
        match self {
            Self::SuccessWithinTakt => "success within the takt",
            Self::Success => "success",
        }
    }
}

/// One parameter searched, within `range` (inside what the control accepts).
#[derive(Clone, Copy, Debug)]
pub struct Searched {
    pub param: &'static Param,
    pub range: [f64; 2],
}

/// A tuning, checked.
pub struct TuneSpec {
    /// The preset's name (or file) and its config.
    pub preset: String,
    pub config: EnvConfig,
    pub control: &'static Control,
    /// The parameters searched, in the control's order.
    pub searched: Vec<Searched>,
    pub objective: Objective,
    /// The training scenarios: seed and episodes per trial (the same list for every trial).
    pub scenario_seed: u64,
    pub episodes: usize,
    /// Env steps to spend at least (the last generation may go past it).
    pub budget: u64,
    /// The optimiser's own seed.
    pub optimiser_seed: u64,
}

impl TuneSpec {
    /// Checks a request: the control is one of the preset's task, every named parameter is
    /// one of its parameters, every range within what it accepts, the budget and episodes in
    /// bounds. `ranges`: the parameters to search and their ranges (`None`: the default
    /// range); empty: every parameter with its default range.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        preset: &str,
        config: EnvConfig,
        control_name: &str,
        ranges: &[(String, Option<[f64; 2]>)],
        scenario_seed: u64,
        episodes: usize,
        budget: u64,
        optimiser_seed: u64,
    ) -> Result<Self, TuneError> {
        let task = config.task.kind;
        let c = control(task, control_name).ok_or_else(|| {
            TuneError::Request(format!(
                "--control {control_name}: not a control of preset `{preset}`'s task; choose one of {}",
                control_names(task).join(", ")
            ))
        })?;
        if c.params.is_empty() {
            let tunable: Vec<&str> = fairgrasp_planner::controls::controls_of(task)
                .filter(|c| !c.params.is_empty())
                .map(|c| c.cli)
                .collect();
            return Err(TuneError::Request(format!(
                "--control {control_name}: has no parameters to tune; the tunable controls of this task are {}",
                tunable.join(", ")
            )));
        }
        let searched = searched_params(c, ranges)?;
        if budget == 0 || budget > MAX_BUDGET {
            return Err(TuneError::Request(format!(
                "--budget {budget}: must be in [1, {MAX_BUDGET}] env steps"
            )));
        }
        if episodes == 0 || episodes > MAX_EPISODES_PER_TRIAL {
            return Err(TuneError::Request(format!(
                "--episodes {episodes}: must be in [1, {MAX_EPISODES_PER_TRIAL}] per trial"
            )));
        }
        Ok(Self {
            preset: preset.to_string(),
            objective: Objective::of(&config),
            config,
            control: c,
            searched,
            scenario_seed,
            episodes,
            budget,
            optimiser_seed,
        })
    }

    /// The names of the searched parameters, in order.
    pub fn names(&self) -> Vec<&'static str> {
        self.searched.iter().map(|s| s.param.name).collect()
    }

    /// The values of the searched parameters at `unit` (one coordinate in [0, 1] each, clamped),
    /// with the control's other parameters as the preset has them. A coordinate exactly at the
    /// start ([`TuneSpec::start`]) is the preset's own value, not its round trip through the
    /// unit cube: the search's outcome can turn on the last bit of a speed (docs/place.md).
    pub fn values_at(&self, unit: &[f64]) -> ParamValues {
        let now = (self.control.values)(&self.config);
        let start = self.start();
        let mut values = ParamValues::new();
        for ((s, &u), &u0) in self.searched.iter().zip(unit).zip(&start) {
            let exact = now.get(s.param.name).copied().filter(|_| u == u0);
            let v = exact.unwrap_or_else(|| s.param.from_unit(u, s.range));
            values.insert(s.param.name.to_string(), v);
        }
        values
    }

    /// Where the preset's own settings lie in the unit cube (the optimiser's start).
    pub fn start(&self) -> Vec<f64> {
        let now = (self.control.values)(&self.config);
        self.searched
            .iter()
            .map(|s| {
                let v = now.get(s.param.name).copied().unwrap_or(s.range[0]);
                s.param.to_unit(v, s.range).clamp(0.0, 1.0)
            })
            .collect()
    }

    /// What identifies the tuning in its folder.
    pub fn record(&self) -> SpecRecord {
        SpecRecord {
            preset: self.preset.clone(),
            preset_config: self.config.to_toml(),
            control: self.control.cli.to_string(),
            objective: self.objective,
            params: self
                .searched
                .iter()
                .map(|s| (s.param.name.to_string(), s.range))
                .collect(),
            scenario_seed: self.scenario_seed,
            episodes: self.episodes,
            optimiser_seed: self.optimiser_seed,
        }
    }
}

/// The parameters `ranges` names (all of the control's without any), each range checked.
fn searched_params(
    c: &'static Control,
    ranges: &[(String, Option<[f64; 2]>)],
) -> Result<Vec<Searched>, TuneError> {
    if ranges.is_empty() {
        return Ok(c
            .params
            .iter()
            .map(|param| Searched {
                param,
                range: param.range,
            })
            .collect());
    }
    let mut out: Vec<Searched> = Vec::new();
    for (name, range) in ranges {
        let param = c.param(name).ok_or_else(|| {
            TuneError::Request(format!(
                "--param {name}: not a parameter of {}; its parameters are {}",
                c.cli,
                c.params
                    .iter()
                    .map(|p| p.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
        })?;
        if out.iter().any(|s| s.param.name == param.name) {
            return Err(TuneError::Request(format!("--param {name}: named twice")));
        }
        let range = range.unwrap_or(param.range);
        let [lo, hi] = range;
        let [alo, ahi] = param.accepts;
        let ordered = lo < hi || param.scale == Scale::Switch;
        if !(param.accepts(lo) && param.accepts(hi) && ordered)
            || (param.scale == Scale::Log && lo <= 0.0)
        {
            return Err(TuneError::Request(format!(
                "--param {name}={lo}:{hi}: the range must lie in what {} accepts, [{alo}, {ahi}] {}, low below high",
                c.cli, param.unit
            )));
        }
        out.push(Searched { param, range });
    }
    // The control's order, whatever the command line's.
    out.sort_by_key(|s| c.params.iter().position(|p| p.name == s.param.name));
    Ok(out)
}

/// A tuning's identity as `tune.json` holds it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpecRecord {
    pub preset: String,
    /// The preset's whole config as TOML: a preset file edited since is another tuning.
    pub preset_config: String,
    pub control: String,
    pub objective: Objective,
    pub params: Vec<(String, [f64; 2])>,
    pub scenario_seed: u64,
    pub episodes: usize,
    pub optimiser_seed: u64,
}

impl SpecRecord {
    /// Writes it atomically.
    pub fn save(&self, path: &Path) -> Result<(), TuneError> {
        let text = serde_json::to_string_pretty(self).unwrap_or_default();
        write_atomic(path, text.as_bytes()).map_err(|e| TuneError::io(path, e))
    }

    /// Reads the record at `path`.
    pub fn load(path: &Path) -> Result<Self, TuneError> {
        let text = read_text_bounded(path, MAX_CONFIG_BYTES).map_err(|e| TuneError::io(path, e))?;
        serde_json::from_str(&text)
            .map_err(|e| TuneError::file(path, format!("not a tuning record: {e}")))
    }

    /// The first thing in which `saved` (a folder's) differs from `self` (the request), as
    /// (what, before, now); for the preset's config, the first field that differs.
    pub fn first_difference(&self, saved: &SpecRecord) -> Option<(&'static str, String, String)> {
        let pairs: [(&'static str, String, String); 7] = [
            ("preset", saved.preset.clone(), self.preset.clone()),
            ("control", saved.control.clone(), self.control.clone()),
            (
                "objective",
                saved.objective.describe().to_string(),
                self.objective.describe().to_string(),
            ),
            (
                "parameter list",
                params_text(&saved.params),
                params_text(&self.params),
            ),
            (
                "scenario seed",
                saved.scenario_seed.to_string(),
                self.scenario_seed.to_string(),
            ),
            (
                "episodes per trial",
                saved.episodes.to_string(),
                self.episodes.to_string(),
            ),
            (
                "optimiser seed",
                saved.optimiser_seed.to_string(),
                self.optimiser_seed.to_string(),
            ),
        ];
        if let Some(d) = pairs.into_iter().find(|(_, a, b)| a != b) {
            return Some(d);
        }
        (saved.preset_config != self.preset_config).then(|| {
            let parse = |t: &str| toml::from_str::<toml::Value>(t).ok();
            let field = match (parse(&saved.preset_config), parse(&self.preset_config)) {
                (Some(old), Some(new)) => leaf_differences(&old, &new).into_iter().next(),
                _ => None,
            };
            match field {
                Some(c) => (
                    "preset's config",
                    format!("{} = {} (tune.json)", c.path, c.before),
                    format!(
                        "{} = {} (the preset as it reads now: edited since, or another file of that name)",
                        c.path, c.now
                    ),
                ),
                None => (
                    "preset's config",
                    "the config saved in tune.json".to_string(),
                    "the preset as it reads now (edited since?)".to_string(),
                ),
            }
        })
    }

    /// The preset config the tuning was started on, as recorded.
    pub fn preset_env(&self, path: &Path) -> Result<EnvConfig, TuneError> {
        EnvConfig::from_toml_str(&self.preset_config)
            .map_err(|e| TuneError::file(path, format!("preset_config: not a valid preset: {e}")))
    }
}

/// A parameter list as `name [lo, hi], …`.
fn params_text(params: &[(String, [f64; 2])]) -> String {
    let list: Vec<String> = params
        .iter()
        .map(|(n, [lo, hi])| format!("{n} [{lo}, {hi}]"))
        .collect();
    format!("({})", list.join(", "))
}
