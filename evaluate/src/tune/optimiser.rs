//! The tuning loop: CMA-ES (the `cmaes` crate) over the searched parameters mapped to the unit
//! cube, each trial the control's success on the same training scenarios, until the budget of
//! env steps is spent. The optimiser is seeded, so a resumed tuning asks for the same settings
//! in the same order: the trials already in `trials.csv` answer for themselves (checked to be
//! the same settings), and the tuning goes on where it stopped. Trial 0 is the preset's own
//! setting, the optimiser's start; the budget is checked before every trial, so a tuning stops
//! within one trial of it.
//!
//! The budget holds the validation too: the search stops when what it spent and what the
//! validation will take (its finalists × episodes × the trials' mean steps an episode) reach
//! the budget. Then the best few trials ([`Validation::finalists`], distinct settings, by
//! their objective) run the validation's own scenarios, and the best there is the tuned
//! setting (`finalists.csv` holds both figures): the best of many noisy trials is expected
//! above its truth, a fresh measurement is not. A search that finds nothing better for
//! [`TuneSpec::stall_generations`] generations restarts around the best trial with half the
//! spread. Both depend on the trials only, so a resumed tuning still asks the same questions.

use std::cell::{Cell, RefCell};
use std::path::{Path, PathBuf};

use cmaes::{CMAESOptions, DVector, Mode};
use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::TuningNote;
use fairgrasp_env::episode::evaluate_seeded;
use fairgrasp_planner::CameraCalibration;
use fairgrasp_planner::controls::ParamValues;

use crate::tune::error::TuneError;
use crate::tune::fragment::{self, TuneRecord, Written};
use crate::tune::spec::{Objective, TuneSpec, Validation};
use crate::tune::trials::{self, Trial};

/// The optimiser as a tuning note names it.
pub const OPTIMISER: &str = "CMA-ES (cmaes 0.2.2)";
/// The search distribution's first spread, in the unit cube (a quarter of each range).
pub const INITIAL_SIGMA: f64 = 0.25;
/// The smallest spread a restart after a stall narrows to (1/64 of each range).
pub const MIN_SIGMA: f64 = INITIAL_SIGMA / 16.0;
/// The objective's cost per squared unit a sample lies outside the cube (its values are
/// clamped; the cost keeps the mean inside).
const OUTSIDE_PENALTY: f64 = 1.0;

/// What a tuning reports as it goes.
pub enum TuneEvent<'a> {
    /// `trials` were read back from the folder and answer for themselves.
    Resumed { trials: usize, env_steps: u64 },
    /// A trial starts (`index`), `spent` of `budget` env steps spent before it.
    TrialStart {
        index: usize,
        spent: u64,
        budget: u64,
    },
    /// One episode of the running trial ended.
    Episode,
    /// A trial ended; `best` is the best so far.
    TrialDone {
        trial: &'a Trial,
        best: &'a Trial,
        spent: u64,
        budget: u64,
    },
    /// The optimiser starts again around the best trial, from generation `generation`, with
    /// spread `sigma`: the search found nothing better for `stalled` generations (`None`: the
    /// optimiser itself ended, converged).
    Restart {
        generation: usize,
        sigma: f64,
        stalled: Option<usize>,
    },
    /// The validation of finalist `rank` (0: the best trial), trial `trial`, starts.
    FinalistStart {
        rank: usize,
        of: usize,
        trial: usize,
    },
    /// A finalist's validation ended.
    FinalistDone { finalist: &'a Finalist },
}

/// A finalist: a trial and its re-evaluation on the validation's scenarios.
#[derive(Clone, Debug, PartialEq)]
pub struct Finalist {
    /// The trial (its objective there is the trial's score).
    pub trial: Trial,
    /// The same setting on the validation's scenarios (`index`: the trial's).
    pub validation: Trial,
}

/// A finished tuning.
pub struct TuneOutcome {
    pub trials: Vec<Trial>,
    /// Index of the chosen trial: the finalist best on validation (the higher trial score, then
    /// the earlier trial, of equals).
    pub best: usize,
    /// The finalists, best trial first, with their validation.
    pub finalists: Vec<Finalist>,
    /// Env steps of the search's trials and of the validation.
    pub search_env_steps: u64,
    pub validation_env_steps: u64,
    /// Restarts of the optimiser.
    pub restarts: usize,
    /// The preset's config with the chosen trial's settings.
    pub tuned: EnvConfig,
    pub note: TuningNote,
    pub record: TuneRecord,
    /// Where the fragment went (beside an edited `tuned.toml`, which is kept).
    pub fragment: Written,
}

/// A running tuning: the trials so far, those read back from its folder, and what stopped it.
struct Session<'a> {
    spec: &'a TuneSpec,
    /// The trials of an earlier run in the folder, which answer for themselves in order.
    previous: Vec<Trial>,
    done: RefCell<Vec<Trial>>,
    failure: RefCell<Option<TuneError>>,
    generation: Cell<usize>,
    /// Set when a trial was asked for with the budget spent (the generation ends there).
    budget_spent: Cell<bool>,
    csv: PathBuf,
    threads: usize,
    calibration: CameraCalibration,
    progress: &'a (dyn Fn(TuneEvent<'_>) + Sync),
}

impl Session<'_> {
    /// Env steps spent so far.
    fn spent(&self) -> u64 {
        total_steps(&self.done.borrow())
    }

    /// Env steps the validation will take, estimated from the trials so far (their mean steps
    /// an episode): what the search leaves of the budget.
    fn reserve(&self) -> u64 {
        let done = self.done.borrow();
        let episodes: u64 = done.iter().map(|t| t.episodes as u64).sum();
        if episodes == 0 {
            return 0;
        }
        let v = &self.spec.validation;
        let finalists = v.finalists.min(done.len()) as u64;
        let per_episode = self.spent().div_ceil(episodes);
        finalists
            .saturating_mul(v.episodes as u64)
            .saturating_mul(per_episode)
    }

    /// Whether the search has spent its part of the budget.
    fn search_spent(&self) -> bool {
        self.spent().saturating_add(self.reserve()) >= self.spec.budget
    }

    /// The optimiser's objective at `point` (the unit cube's coordinates): the next trial's
    /// objective, less the cost of lying outside the cube; NaN (which ends the generation)
    /// once the budget is spent or something failed.
    fn score(&self, point: &DVector<f64>) -> f64 {
        if self.failure.borrow().is_some() {
            return f64::NAN;
        }
        let raw: Vec<f64> = point.iter().copied().collect();
        let unit: Vec<f64> = raw.iter().map(|u| u.clamp(0.0, 1.0)).collect();
        let outside: f64 = raw.iter().zip(&unit).map(|(r, u)| (r - u).powi(2)).sum();
        let index = self.done.borrow().len();
        if index >= self.previous.len() && self.search_spent() {
            self.budget_spent.set(true);
            return f64::NAN;
        }
        match self.trial(index, self.spec.values_at(&unit)) {
            Ok(objective) => objective - OUTSIDE_PENALTY * outside,
            Err(e) => {
                *self.failure.borrow_mut() = Some(e);
                f64::NAN
            }
        }
    }

    /// Trial `index` at `values`: read back from the folder, or run and saved; its objective.
    fn trial(&self, index: usize, values: ParamValues) -> Result<f64, TuneError> {
        if let Some(old) = self.previous.get(index) {
            if let Some(why) = replay_mismatch(old, &values, self.generation.get()) {
                return Err(TuneError::file(
                    &self.csv,
                    format!(
                        "trial {index}: {why}: the folder's trials are not this tuning's (edited by hand?); restore trials.csv, or delete the rows from this one on to run them again"
                    ),
                ));
            }
            self.done.borrow_mut().push(old.clone());
            return Ok(old.objective);
        }
        let spec = self.spec;
        (self.progress)(TuneEvent::TrialStart {
            index,
            spent: self.spent(),
            budget: spec.budget,
        });
        let trial = run_trial(
            spec,
            index,
            self.generation.get(),
            values,
            self.threads,
            &self.calibration,
            self.progress,
        )?;
        let objective = trial.objective;
        self.done.borrow_mut().push(trial);
        let all = self.done.borrow();
        trials::save(&self.csv, &all, &spec.names())?;
        (self.progress)(TuneEvent::TrialDone {
            trial: &all[index],
            best: &all[best_of(&all)],
            spent: self.spent(),
            budget: spec.budget,
        });
        Ok(objective)
    }

    /// Where the best trial so far lies in the unit cube.
    fn best_point(&self) -> Vec<f64> {
        let all = self.done.borrow();
        let best = &all[best_of(&all)];
        self.spec
            .searched
            .iter()
            .map(|s| s.unit(best.values[s.param.name]))
            .collect()
    }

    /// The failure a trial left, if any.
    fn failed(&self) -> Result<(), TuneError> {
        match self.failure.borrow_mut().take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

/// How a trial read back from the folder differs from the one the optimiser asks for again
/// (`values` in generation `generation`), naming the first parameter that differs; `None` if
/// it is the same trial.
fn replay_mismatch(old: &Trial, values: &ParamValues, generation: usize) -> Option<String> {
    if old.generation != generation {
        return Some(format!(
            "generation {} in the file, the optimiser is at {generation}",
            old.generation
        ));
    }
    values.iter().find_map(|(name, v)| {
        let saved = old.values.get(name);
        (saved != Some(v)).then(|| {
            format!(
                "{name} = {} in the file, the optimiser asks for {v} again",
                saved.map_or("(missing)".to_string(), f64::to_string)
            )
        })
    })
}

/// Env steps of `trials`, summed (saturating: a loaded file's sum is checked when read).
fn total_steps(trials: &[Trial]) -> u64 {
    trials
        .iter()
        .fold(0u64, |sum, t| sum.saturating_add(t.env_steps))
}

/// Runs (or resumes) the tuning `spec` in the folder `dir` on `threads` threads.
pub fn run_tune(
    spec: &TuneSpec,
    dir: &Path,
    threads: usize,
    progress: &(dyn Fn(TuneEvent<'_>) + Sync),
) -> Result<TuneOutcome, TuneError> {
    let (previous, _lock) = crate::tune::folder::open(spec, dir)?;
    if !previous.is_empty() {
        progress(TuneEvent::Resumed {
            trials: previous.len(),
            env_steps: total_steps(&previous),
        });
    }
    let session = Session {
        spec,
        previous,
        done: RefCell::new(Vec::new()),
        failure: RefCell::new(None),
        generation: Cell::new(0),
        budget_spent: Cell::new(false),
        csv: dir.join("trials.csv"),
        threads,
        calibration: CameraCalibration::of(&spec.config).map_err(TuneError::Request)?,
        progress,
    };
    // Trial 0 is the preset's own setting: the tuning's starting point, measured.
    let mut start = spec.start();
    session.score(&DVector::from_vec(start.clone()));
    session.failed()?;
    let objective = |point: &DVector<f64>| session.score(point);
    let mut restart = 0u64;
    let mut sigma = INITIAL_SIGMA;
    let best_objective = || {
        let done = session.done.borrow();
        done[best_of(&done)].objective
    };
    while !session.search_spent() {
        let mut cma = CMAESOptions::new(start.clone(), sigma)
            .mode(Mode::Maximize)
            .seed(spec.optimiser_seed.wrapping_add(restart))
            .build(&objective)
            .map_err(|e| TuneError::Request(format!("the optimiser refused its options: {e:?}")))?;
        let mut best = best_objective();
        let mut stalled = 0;
        let mut why = None;
        while !session.search_spent() {
            let ended = cma.next();
            session.failed()?;
            if session.budget_spent.get() {
                break;
            }
            session.generation.set(session.generation.get() + 1);
            if ended.is_some() {
                break; // converged: restart from the best so far
            }
            let now = best_objective();
            if now > best {
                (best, stalled) = (now, 0);
            } else {
                stalled += 1;
            }
            if spec.stall_generations > 0 && stalled >= spec.stall_generations {
                why = Some(stalled);
                break;
            }
        }
        if session.search_spent() {
            break;
        }
        restart += 1;
        start = session.best_point();
        // A stalled search narrows around the best; a converged one starts wide again.
        sigma = match why {
            Some(_) => (sigma / 2.0).max(MIN_SIGMA),
            None => INITIAL_SIGMA,
        };
        progress(TuneEvent::Restart {
            generation: session.generation.get(),
            sigma,
            stalled: why,
        });
    }
    let trials = session.done.into_inner();
    let finalists = validate_finalists(spec, &trials, threads, progress)?;
    finish(spec, dir, trials, finalists, restart as usize)
}

/// The finalists of `trials`: the `finalists` best by objective (distinct settings, none the
/// preset refused; the earlier of equals), best first.
pub fn finalists_of(trials: &[Trial], finalists: usize) -> Vec<&Trial> {
    let mut order: Vec<&Trial> = trials.iter().filter(|t| t.episodes > 0).collect();
    order.sort_by(|a, b| {
        b.objective
            .total_cmp(&a.objective)
            .then(a.index.cmp(&b.index))
    });
    let mut out: Vec<&Trial> = Vec::new();
    for t in order {
        if out.len() == finalists {
            break;
        }
        if !out.iter().any(|f| f.values == t.values) {
            out.push(t);
        }
    }
    out
}

/// Each finalist of `trials` run again on the validation's scenarios.
fn validate_finalists(
    spec: &TuneSpec,
    trials: &[Trial],
    threads: usize,
    progress: &(dyn Fn(TuneEvent<'_>) + Sync),
) -> Result<Vec<Finalist>, TuneError> {
    let Validation { seed, episodes, .. } = spec.validation;
    let chosen = finalists_of(trials, spec.validation.finalists);
    let calibration = CameraCalibration::of(&spec.config).map_err(TuneError::Request)?;
    let mut out = Vec::new();
    for (rank, t) in chosen.iter().enumerate() {
        progress(TuneEvent::FinalistStart {
            rank,
            of: chosen.len(),
            trial: t.index,
        });
        let validation = run_episodes(spec, t, seed, episodes, threads, &calibration, progress)?;
        out.push(Finalist {
            trial: (*t).clone(),
            validation,
        });
        progress(TuneEvent::FinalistDone {
            finalist: out.last().expect("just pushed"),
        });
    }
    Ok(out)
}

/// The finalist chosen: the best on validation, then the better trial, then the earlier.
pub fn chosen_of(finalists: &[Finalist]) -> Option<&Finalist> {
    finalists.iter().reduce(|best, f| {
        let better = f
            .validation
            .objective
            .total_cmp(&best.validation.objective)
            .then(f.trial.objective.total_cmp(&best.trial.objective))
            .then(best.trial.index.cmp(&f.trial.index));
        if better.is_gt() { f } else { best }
    })
}

/// The best trial's index: the highest objective, the earliest of equals.
pub fn best_of(trials: &[Trial]) -> usize {
    let mut best = 0;
    for (i, t) in trials.iter().enumerate() {
        if t.objective > trials[best].objective {
            best = i;
        }
    }
    best
}

/// One trial: the control with `values` on the spec's training scenarios.
fn run_trial(
    spec: &TuneSpec,
    index: usize,
    generation: usize,
    values: ParamValues,
    threads: usize,
    calibration: &CameraCalibration,
    progress: &(dyn Fn(TuneEvent<'_>) + Sync),
) -> Result<Trial, TuneError> {
    let mut config = spec.config.clone();
    (spec.control.set)(&mut config, &values);
    let refused = Trial {
        index,
        generation,
        values: values.clone(),
        episodes: 0,
        env_steps: 0,
        successes: 0,
        within_takt: 0,
        objective: -1.0,
        mean_cycle_time_s: None,
    };
    if config.validate().is_err() {
        return Ok(refused);
    }
    measure(
        spec,
        &config,
        (spec.scenario_seed, spec.episodes),
        threads,
        calibration,
        progress,
        refused,
    )
}

/// The setting of `trial` on `episodes` scenarios of `seed` (the validation's): a trial of
/// the same index and values, its counts from there.
fn run_episodes(
    spec: &TuneSpec,
    trial: &Trial,
    seed: u64,
    episodes: usize,
    threads: usize,
    calibration: &CameraCalibration,
    progress: &(dyn Fn(TuneEvent<'_>) + Sync),
) -> Result<Trial, TuneError> {
    let mut config = spec.config.clone();
    (spec.control.set)(&mut config, &trial.values);
    measure(
        spec,
        &config,
        (seed, episodes),
        threads,
        calibration,
        progress,
        trial.clone(),
    )
}

/// `config` with the spec's control on `episodes` scenarios of `seed`, as `base`'s counts.
fn measure(
    spec: &TuneSpec,
    config: &EnvConfig,
    (seed, episodes): (u64, usize),
    threads: usize,
    calibration: &CameraCalibration,
    progress: &(dyn Fn(TuneEvent<'_>) + Sync),
    base: Trial,
) -> Result<Trial, TuneError> {
    let build = spec.control.build;
    let report = evaluate_seeded(
        config,
        seed,
        episodes,
        threads,
        None,
        &|| build(config, calibration),
        &|| progress(TuneEvent::Episode),
    )?;
    let n = report.episodes.max(1) as f64;
    let objective = match spec.objective {
        Objective::SuccessWithinTakt => report.successes_within_takt as f64 / n,
        Objective::Success => report.successes as f64 / n,
    };
    Ok(Trial {
        episodes: report.episodes,
        env_steps: report.results.iter().map(|r| r.steps as u64).sum(),
        successes: report.successes,
        within_takt: report.successes_within_takt,
        objective,
        mean_cycle_time_s: report.mean_cycle_time_s,
        ..base
    })
}

/// The tuned config and its note from the trials and the finalists; writes `finalists.csv`
/// and the fragment.
fn finish(
    spec: &TuneSpec,
    dir: &Path,
    trials: Vec<Trial>,
    finalists: Vec<Finalist>,
    restarts: usize,
) -> Result<TuneOutcome, TuneError> {
    let best = chosen_of(&finalists).map_or_else(|| best_of(&trials), |f| f.trial.index);
    let search_env_steps = total_steps(&trials);
    let validation_env_steps = finalists
        .iter()
        .fold(0u64, |s, f| s.saturating_add(f.validation.env_steps));
    let chosen = finalists.iter().find(|f| f.trial.index == best);
    let note = TuningNote {
        preset: spec.preset.clone(),
        optimiser: OPTIMISER.to_string(),
        objective: spec.objective.describe().to_string(),
        env_steps: search_env_steps.saturating_add(validation_env_steps),
        trials: trials.len(),
        episodes_per_trial: spec.episodes,
        scenario_seed: spec.scenario_seed,
        best: trials[best].objective,
    };
    let record = TuneRecord {
        best_trial: Some(best),
        validation_best: chosen.map(|f| f.validation.objective),
        validation_seed: Some(spec.validation.seed),
        validation_episodes: Some(spec.validation.episodes),
        finalists: Some(finalists.len()),
        validation_env_steps: Some(validation_env_steps),
        restarts: Some(restarts),
        preset_checksum: Some(fragment::preset_checksum(&spec.config, spec.control)),
    };
    write_finalists(&dir.join("finalists.csv"), spec, &finalists, best)?;
    let mut tuned = spec.config.clone();
    (spec.control.set)(&mut tuned, &trials[best].values);
    tuned
        .control
        .tuned
        .insert(spec.control.cli.to_string(), note.clone());
    let written = fragment::write(
        &dir.join("tuned.toml"),
        &tuned,
        spec.control,
        &note,
        &record,
    )?;
    Ok(TuneOutcome {
        trials,
        best,
        finalists,
        search_env_steps,
        validation_env_steps,
        restarts,
        tuned,
        note,
        record,
        fragment: written,
    })
}

/// `finalists.csv`: a row a finalist, best trial first: the trial, its setting, its score on
/// the tuning's scenarios, then its validation (seed, episodes, env steps, counts, objective,
/// mean cycle time) and whether it was chosen.
fn write_finalists(
    path: &Path,
    spec: &TuneSpec,
    finalists: &[Finalist],
    chosen: usize,
) -> Result<(), TuneError> {
    let names = spec.names();
    let mut cols = vec!["trial", "generation"];
    cols.extend(&names);
    cols.extend([
        "trial_episodes",
        "trial_objective",
        "validation_seed",
        "validation_episodes",
        "validation_env_steps",
        "validation_successes",
        "validation_within_takt",
        "validation_objective",
        "validation_mean_cycle_time_s",
        "chosen",
    ]);
    let mut out = cols.join(",") + "\n";
    for f in finalists {
        let (t, v) = (&f.trial, &f.validation);
        let mut row = crate::tune::trials::trial_columns(t, &names);
        row.extend([
            t.episodes.to_string(),
            t.objective.to_string(),
            spec.validation.seed.to_string(),
            v.episodes.to_string(),
            v.env_steps.to_string(),
            v.successes.to_string(),
            v.within_takt.to_string(),
            v.objective.to_string(),
            v.mean_cycle_time_s.map_or(String::new(), |c| c.to_string()),
            (t.index == chosen).to_string(),
        ]);
        out.push_str(&row.join(","));
        out.push('\n');
    }
    fairgrasp_types::fs::write_atomic(path, out.as_bytes()).map_err(|e| TuneError::io(path, e))
}
