//! The tuning loop: CMA-ES (the `cmaes` crate) over the searched parameters mapped to the unit
//! cube, each trial the control's success on the same training scenarios, until the budget of
//! env steps is spent. The optimiser is seeded, so a resumed tuning asks for the same settings
//! in the same order: the trials already in `trials.csv` answer for themselves (checked to be
//! the same settings), and the tuning goes on where it stopped. Trial 0 is the preset's own
//! setting, the optimiser's start; the budget is checked before every trial, so a tuning stops
//! within one trial of it.

use std::cell::{Cell, RefCell};
use std::path::{Path, PathBuf};

use cmaes::{CMAESOptions, DVector, Mode};
use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::TuningNote;
use fairgrasp_env::episode::evaluate_seeded;
use fairgrasp_planner::CameraCalibration;
use fairgrasp_planner::controls::ParamValues;

use crate::tune::error::TuneError;
use crate::tune::spec::{Objective, TuneSpec};
use crate::tune::trials::{self, Trial};

/// The optimiser as a tuning note names it.
pub const OPTIMISER: &str = "CMA-ES (cmaes 0.2.2)";
/// The search distribution's first spread, in the unit cube (a quarter of each range).
const INITIAL_SIGMA: f64 = 0.25;
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
}

/// A finished tuning.
pub struct TuneOutcome {
    pub trials: Vec<Trial>,
    /// Index of the best trial (the highest objective; the earliest of equals).
    pub best: usize,
    /// The preset's config with the best trial's settings.
    pub tuned: EnvConfig,
    pub note: TuningNote,
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
        self.done.borrow().iter().map(|t| t.env_steps).sum()
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
        if index >= self.previous.len() && self.spent() >= self.spec.budget {
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
            .map(|s| {
                s.param
                    .to_unit(best.values[s.param.name], s.range)
                    .clamp(0.0, 1.0)
            })
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

/// Runs (or resumes) the tuning `spec` in the folder `dir` on `threads` threads.
pub fn run_tune(
    spec: &TuneSpec,
    dir: &Path,
    threads: usize,
    progress: &(dyn Fn(TuneEvent<'_>) + Sync),
) -> Result<TuneOutcome, TuneError> {
    let previous = crate::tune::folder::open(spec, dir)?;
    if !previous.is_empty() {
        progress(TuneEvent::Resumed {
            trials: previous.len(),
            env_steps: previous.iter().map(|t| t.env_steps).sum(),
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
    while session.spent() < spec.budget {
        let mut cma = CMAESOptions::new(start.clone(), INITIAL_SIGMA)
            .mode(Mode::Maximize)
            .seed(spec.optimiser_seed.wrapping_add(restart))
            .build(&objective)
            .map_err(|e| TuneError::Request(format!("the optimiser refused its options: {e:?}")))?;
        while session.spent() < spec.budget {
            let ended = cma.next();
            session.failed()?;
            if session.budget_spent.get() {
                break;
            }
            session.generation.set(session.generation.get() + 1);
            if ended.is_some() {
                break; // converged or stalled: restart from the best so far
            }
        }
        restart += 1;
        start = session.best_point();
    }
    finish(spec, dir, session.done.into_inner())
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
    let build = spec.control.build;
    let report = evaluate_seeded(
        &config,
        spec.scenario_seed,
        spec.episodes,
        threads,
        None,
        &|| build(&config, calibration),
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
        ..refused
    })
}

/// The tuned config and its note from the trials; writes the fragment.
fn finish(spec: &TuneSpec, dir: &Path, trials: Vec<Trial>) -> Result<TuneOutcome, TuneError> {
    let best = best_of(&trials);
    let note = TuningNote {
        preset: spec.preset.clone(),
        optimiser: OPTIMISER.to_string(),
        objective: spec.objective.describe().to_string(),
        env_steps: trials.iter().map(|t| t.env_steps).sum(),
        trials: trials.len(),
        episodes_per_trial: spec.episodes,
        scenario_seed: spec.scenario_seed,
        best: trials[best].objective,
    };
    let mut tuned = spec.config.clone();
    (spec.control.set)(&mut tuned, &trials[best].values);
    tuned
        .control
        .tuned
        .insert(spec.control.cli.to_string(), note.clone());
    crate::tune::fragment::write(&dir.join("tuned.toml"), &tuned, spec.control, &note)?;
    Ok(TuneOutcome {
        trials,
        best,
        tuned,
        note,
    })
}
