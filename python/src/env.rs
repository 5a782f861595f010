//! `Env` (one grasping env, or the env a training recipe trains on) and `Baseline` (the
//! scripted grasp as a policy object).

use std::sync::Mutex;

use fairgrasp_env::env::obs::OBS_DIM;
use fairgrasp_env::episode::Policy;
use fairgrasp_env::episode::trajectory::{Recorder, Trajectory};
use fairgrasp_env::{Observation, TaskEnv};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};
use fairgrasp_report::charts::replay::{SIZE, replay_frame_rgb};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::agent_env::AgentEnv;
use crate::args::{checked_action, env_config, value_error};
use crate::info::info_dict;
use crate::setup::Setup;

/// One step's result: observation, reward, terminated, truncated, info.
type StepTuple<'py> = (
    Bound<'py, PyArray1<f32>>,
    f64,
    bool,
    bool,
    Bound<'py, PyDict>,
);

/// A played episode: the flat observations [steps + 1, obs], the rewards, the last info.
type PlayedEpisode<'py> = (Bound<'py, PyArray2<f32>>, Vec<f64>, Bound<'py, PyDict>);

/// One grasping env (the Rust `TaskEnv`), or with a recipe the env that recipe trains on (its
/// agent's input and output, its curriculum): `reset(seed)`, `step(action)`; infos as dicts
/// (see `info.rs`).
#[pyclass(module = "fairgrasp._native")]
pub struct Env {
    env: Mutex<AgentEnv>,
    setup: Setup,
    /// The episode so far, recorded only when rendering (`record = True`).
    trajectory: Mutex<Option<Trajectory>>,
}

/// Seven finite action values from an array of any length, or a `ValueError` naming the
/// problem.
pub(crate) fn action7(values: &[f64], what: &str) -> PyResult<[f64; 7]> {
    Ok(checked_action(values, what)?.0)
}

#[pymethods]
impl Env {
    /// `preset`: a shipped preset name or a .toml path; `config_toml`: a whole env config as
    /// TOML text (overrides `preset`); `arm`: "servo" or "multibody". `recipe`: a shipped
    /// training recipe's name or a training config's path, with `overrides_json` (keyword
    /// overrides as JSON) laid over it: the env that recipe trains on.
    /// `record`: keep the episode's trajectory for `render_rgb`.
    #[new]
    #[pyo3(signature = (preset = "full", arm = "servo", config_toml = None, record = false, recipe = None, overrides_json = None))]
    fn new(
        preset: &str,
        arm: &str,
        config_toml: Option<&str>,
        record: bool,
        recipe: Option<&str>,
        overrides_json: Option<&str>,
    ) -> PyResult<Self> {
        let setup = Setup::new(preset, arm, config_toml, recipe, overrides_json)?;
        let env = AgentEnv::new(&setup).map_err(value_error)?;
        Ok(Self {
            env: Mutex::new(env),
            setup,
            trajectory: Mutex::new(record.then(Trajectory::default)),
        })
    }

    /// The replay view of the report (top and side views of base_link) at the current step, as
    /// an RGB array [500, 960, 3] of uint8; needs `record = True`.
    fn render_rgb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<u8>>> {
        let trajectory = self.trajectory.lock().map_err(value_error)?;
        let Some(t) = trajectory.as_ref().filter(|t| !t.rows.is_empty()) else {
            return Err(value_error(
                "nothing to render: create the env with record = True (render_mode = \"rgb_array\") and reset it",
            ));
        };
        let last = t.rows.len() - 1;
        let rgb = replay_frame_rgb(t, "fairgrasp", last).map_err(value_error)?;
        let (w, h) = SIZE;
        rgb.into_pyarray(py).reshape([h as usize, w as usize, 3])
    }

    /// Starts the episode of scenario `seed`: (observation, info).
    fn reset<'py>(
        &self,
        py: Python<'py>,
        seed: u64,
    ) -> PyResult<(Bound<'py, PyArray1<f32>>, Bound<'py, PyDict>)> {
        let mut guard = self.env.lock().map_err(value_error)?;
        let env: &mut AgentEnv = &mut guard;
        let info = py.detach(|| env.reset(seed)).map_err(value_error)?;
        if let Some(t) = self.trajectory.lock().map_err(value_error)?.as_mut() {
            let opening = env.last().map_or(0.0, |o| o.gripper_opening);
            t.record_reset(env.env(), opening);
        }
        let info = info_dict(py, &info, env.stage().as_ref(), true)?;
        Ok((PyArray1::from_slice(py, env.input()), info))
    }

    /// One control step (physics with the GIL released): (obs, reward, terminated, truncated,
    /// info). `action`: 7 values (the policy's output for a recipe's env); a wrong length or a
    /// non-finite value raises `ValueError` naming the index.
    fn step<'py>(
        &self,
        py: Python<'py>,
        action: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<StepTuple<'py>> {
        let values: Vec<f64> = action.as_array().iter().copied().collect();
        let action = action7(&values, "action")?;
        let mut guard = self.env.lock().map_err(value_error)?;
        let env: &mut AgentEnv = &mut guard;
        let (env_action, step) = py.detach(|| env.step(&action)).map_err(value_error)?;
        if let Some(t) = self.trajectory.lock().map_err(value_error)?.as_mut() {
            t.record_step(env.env(), &env_action, &step, None);
        }
        let ended = step.terminated || step.truncated;
        let info = info_dict(py, &step.info, env.stage().as_ref(), ended)?;
        Ok((
            PyArray1::from_slice(py, env.input()),
            step.reward,
            step.terminated,
            step.truncated,
            info,
        ))
    }

    /// The observation space as JSON: names, low and high per entry (all finite); for a
    /// recipe's env, the agent's policy input.
    fn observation_space_json(&self) -> PyResult<String> {
        self.setup.space_json(self.setup.observation_space())
    }

    /// The action space as JSON (joint velocities and gripper, TCP velocity, yaw rate and
    /// gripper, or a residual's correction), each in [−1, 1].
    fn action_space_json(&self) -> PyResult<String> {
        self.setup.space_json(self.setup.action_space())
    }

    /// The env config as TOML (what `config_toml` takes back): for a recipe, the env it trains
    /// on.
    fn config_toml(&self) -> String {
        self.setup.config.to_toml()
    }

    /// The recipe's agent config as TOML (None without a recipe).
    fn agent_toml(&self) -> PyResult<Option<String>> {
        self.setup
            .agent
            .as_ref()
            .map(|a| toml::to_string(a).map_err(value_error))
            .transpose()
    }

    /// Steps per episode before truncation.
    #[getter]
    fn max_steps(&self) -> usize {
        self.setup.config.task.max_steps
    }

    /// The curriculum's stage (index, name); None without a curriculum.
    fn curriculum_stage(&self) -> PyResult<Option<(usize, String)>> {
        Ok(self.env.lock().map_err(value_error)?.stage())
    }

    /// The number of curriculum stages (0 without a curriculum).
    fn curriculum_stage_count(&self) -> usize {
        self.setup.curriculum().map_or(0, |c| c.stage_count())
    }

    /// Moves the curriculum to `stage` (clamped to the last), from the next reset on.
    fn set_curriculum_stage(&self, stage: usize) -> PyResult<()> {
        let mut env = self.env.lock().map_err(value_error)?;
        env.set_stage(stage).map_err(value_error)
    }

    /// Joint angles q1 … q6 now [rad].
    fn joints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        Ok(self
            .env
            .lock()
            .map_err(value_error)?
            .env()
            .joints()
            .to_vec()
            .into_pyarray(py))
    }

    /// The cube's position in base_link [m] (the truth, not the observation).
    fn object_xyz<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let env = self.env.lock().map_err(value_error)?;
        Ok(env.env().object_in_base().xyz().to_vec().into_pyarray(py))
    }
}

/// The scripted grasp (`fairgrasp baseline`) as a policy: `reset(seed)` at every episode, then
/// `act(obs)` → the env action (7 values in [−1, 1]).
#[pyclass(module = "fairgrasp._native")]
pub struct Baseline {
    script: Mutex<ScriptedGrasp>,
    config: fairgrasp_env::EnvConfig,
}

#[pymethods]
impl Baseline {
    #[new]
    #[pyo3(signature = (preset = "full", arm = "servo", config_toml = None))]
    fn new(preset: &str, arm: &str, config_toml: Option<&str>) -> PyResult<Self> {
        let config = env_config(preset, arm, config_toml)?;
        Ok(Self {
            script: Mutex::new(ScriptedGrasp::new(&config, BaselineConfig::default())),
            config,
        })
    }

    /// Forgets the last episode's plan.
    fn reset(&self, seed: u64) -> PyResult<()> {
        self.script.lock().map_err(value_error)?.reset(seed);
        Ok(())
    }

    /// Plays scenario `seed` to its end with the script on an env of its own config, acting on
    /// the env's own observations (f64, with the wrist view), as `fairgrasp baseline` does
    /// (GIL released): (the flat observations [steps + 1, 23], the rewards, the last info with
    /// the script's verdict in its record). The reference a zero residual must reproduce.
    fn play<'py>(&self, py: Python<'py>, seed: u64) -> PyResult<PlayedEpisode<'py>> {
        let mut guard = self.script.lock().map_err(value_error)?;
        let script: &mut ScriptedGrasp = &mut guard;
        let config = self.config.clone();
        let (flat, rewards, info) = py
            .detach(|| -> Result<_, fairgrasp_env::EnvError> {
                let mut env = TaskEnv::new(config)?;
                let (mut obs, _) = env.reset(seed)?;
                script.reset(seed);
                let (mut flat, mut rewards) = (obs.to_array().to_vec(), Vec::new());
                loop {
                    let mut step = env.step(&script.act(&obs))?;
                    flat.extend(step.obs.to_array());
                    rewards.push(step.reward);
                    obs = step.obs;
                    if step.terminated || step.truncated {
                        step.info.episode = step
                            .info
                            .episode
                            .map(|r| r.with_policy_verdict(script.gave_up()));
                        return Ok((flat, rewards, step.info));
                    }
                }
            })
            .map_err(value_error)?;
        let rows = flat.len() / OBS_DIM;
        let obs = PyArray1::from_vec(py, flat).reshape([rows, OBS_DIM])?;
        Ok((obs, rewards, info_dict(py, &info, None, true)?))
    }

    /// The script's action for a (flat, float32) observation.
    fn act<'py>(
        &self,
        py: Python<'py>,
        obs: PyReadonlyArray1<'py, f32>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let values = obs.as_slice()?;
        let array: &[f32; OBS_DIM] = values.try_into().map_err(|_| {
            value_error(format!(
                "observation has {} values, expected {OBS_DIM}",
                values.len()
            ))
        })?;
        if let Some(i) = array.iter().position(|v| !v.is_finite()) {
            return Err(value_error(format!(
                "observation[{i}] = {} is not finite",
                array[i]
            )));
        }
        let obs = Observation::from_array(array);
        let mut script = self.script.lock().map_err(value_error)?;
        Ok(script.act(&obs).0.to_vec().into_pyarray(py))
    }
}
