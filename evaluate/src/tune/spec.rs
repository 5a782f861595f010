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
/// The seed results are reported on: never a tuning's scenarios, nor its validation's.
pub const REPORTED_SEED: u64 = 7;
/// The validation's scenarios by default: a training seed of their own (the tuning's is 11).
pub const DEFAULT_VALIDATION_SEED: u64 = 12;
/// Validation episodes per finalist by default (a standard error of about 2.5 points).
pub const DEFAULT_VALIDATION_EPISODES: usize = 300;
/// Finalists re-evaluated by default: the best few trials.
pub const DEFAULT_FINALISTS: usize = 5;
/// The most finalists one tuning may re-evaluate.
pub const MAX_FINALISTS: usize = 100;
/// Generations without a better trial after which the search restarts around the best
/// (by default).
pub const DEFAULT_STALL_GENERATIONS: usize = 6;

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

impl Searched {
    /// The one value of a switch whose range holds it there (`0:0` or `1:1`).
    pub fn held(&self) -> Option<f64> {
        (self.param.scale == Scale::Switch && self.range[0] == self.range[1])
            .then_some(self.range[0])
    }

    /// Where `value` lies in the unit cube, clamped into it (a held switch: the middle).
    pub fn unit(&self, value: f64) -> f64 {
        if self.held().is_some() {
            return 0.5;
        }
        self.param.to_unit(value, self.range).clamp(0.0, 1.0)
    }
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
    /// How the best trials are re-evaluated before one is chosen ([`TuneSpec::with_validation`]).
    pub validation: Validation,
    /// Generations without a better trial after which the search restarts around the best
    /// trial with half the spread ([`TuneSpec::with_stall_generations`]).
    pub stall_generations: usize,
}

/// The re-evaluation of a tuning's best trials on scenarios of their own: the `finalists`
/// best trials (by their objective, distinct settings) each run `episodes` scenarios of
/// `seed`, and the best there is the tuned setting. A trial's score is the best of many noisy
/// draws; the validation's is not.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Validation {
    pub seed: u64,
    pub episodes: usize,
    pub finalists: usize,
}

impl Validation {
    /// The default validation for a tuning on scenarios of `scenario_seed`: seed 12 (or the
    /// next seed that is neither the tuning's nor the reported one), 300 episodes, 5 finalists.
    pub fn default_for(scenario_seed: u64) -> Self {
        let seed = (DEFAULT_VALIDATION_SEED..)
            .find(|s| *s != scenario_seed && *s != REPORTED_SEED)
            .unwrap_or(DEFAULT_VALIDATION_SEED);
        Self {
            seed,
            episodes: DEFAULT_VALIDATION_EPISODES,
            finalists: DEFAULT_FINALISTS,
        }
    }
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
            let choose = if tunable.is_empty() {
                "this task has no control with parameters to tune".to_string()
            } else {
                format!(
                    "the tunable controls of this task are {}",
                    tunable.join(", ")
                )
            };
            return Err(TuneError::Request(format!(
                "--control {control_name}: has no parameters to tune; {choose}"
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
            validation: Validation::default_for(scenario_seed),
            stall_generations: DEFAULT_STALL_GENERATIONS,
        })
    }

    /// The validation `validation` instead of the default; refused naming the flag when its
    /// seed is the reported one (7) or the tuning's, or a count is out of bounds.
    pub fn with_validation(mut self, validation: Validation) -> Result<Self, TuneError> {
        let Validation {
            seed,
            episodes,
            finalists,
        } = validation;
        if seed == REPORTED_SEED {
            return Err(TuneError::Request(format!(
                "--validation-seed {seed}: the seed results are reported on is never used to choose; give another training seed (e.g. {DEFAULT_VALIDATION_SEED})"
            )));
        }
        if seed == self.scenario_seed {
            return Err(TuneError::Request(format!(
                "--validation-seed {seed}: the tuning's own scenarios (--seed {}); the validation needs scenarios of its own",
                self.scenario_seed
            )));
        }
        if episodes == 0 || episodes > MAX_EPISODES_PER_TRIAL {
            return Err(TuneError::Request(format!(
                "--validation-episodes {episodes}: must be in [1, {MAX_EPISODES_PER_TRIAL}]"
            )));
        }
        if finalists == 0 || finalists > MAX_FINALISTS {
            return Err(TuneError::Request(format!(
                "--finalists {finalists}: must be in [1, {MAX_FINALISTS}]"
            )));
        }
        self.validation = validation;
        Ok(self)
    }

    /// Restarts after `generations` generations without a better trial (0: never).
    pub fn with_stall_generations(mut self, generations: usize) -> Self {
        self.stall_generations = generations;
        self
    }

    /// The length of one of the preset's episodes \[s\]: its longest cycle.
    pub fn episode_seconds(&self) -> f64 {
        self.config.task.max_steps as f64
            * self.config.physics.dt
            * self.config.physics.substeps as f64
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
            let v = match s.held() {
                // A switch held at one position by its range (`check_floor=1:1`).
                Some(held) => held,
                None => exact.unwrap_or_else(|| s.param.from_unit(u, s.range)),
            };
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
                s.unit(v)
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
        if param.scale == Scale::Switch {
            // A switch is off (0) or on (1): searched over both, or held at one.
            if ![[0.0, 1.0], [0.0, 0.0], [1.0, 1.0]].contains(&range) {
                return Err(TuneError::Request(format!(
                    "--param {name}={lo}:{hi}: {name} is a switch, off (0) or on (1): its range is 0:1 (searched), 0:0 or 1:1 (held off or on)"
                )));
            }
            out.push(Searched { param, range });
            continue;
        }
        let ordered = lo < hi;
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
