//! `Env` (one grasping env) and `Baseline` (the scripted grasp as a policy object).

use std::sync::Mutex;

use fairgrasp_env::env::obs::OBS_DIM;
use fairgrasp_env::episode::Policy;
use fairgrasp_env::episode::trajectory::{Recorder, Trajectory};
use fairgrasp_env::{GraspEnv, Observation};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};
use fairgrasp_report::charts::replay::{SIZE, replay_frame_rgb};
use numpy::{IntoPyArray, PyArray1, PyArray3, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::{checked_action, env_config, value_error};

/// The observation as f32, gymnasium's dtype for it.
pub(crate) fn obs_array(obs: &Observation) -> Vec<f32> {
    obs.to_array().to_vec()
}

/// One step's result: observation, reward, terminated, truncated, info as JSON.
type StepTuple<'py> = (Bound<'py, PyArray1<f32>>, f64, bool, bool, String);

/// One grasping env (the Rust `GraspEnv`): `reset(seed)`, `step(action)`; infos as JSON text.
#[pyclass(module = "fairgrasp._native")]
pub struct Env {
    env: Mutex<GraspEnv>,
    /// The episode so far, recorded only when rendering (`record = True`).
    trajectory: Mutex<Option<Trajectory>>,
}

#[pymethods]
impl Env {
    /// `preset`: a shipped preset name or a .toml path; `config_toml`: a whole env config as
    /// TOML text (overrides `preset`); `arm`: "servo" or "multibody".
    /// `record`: keep the episode's trajectory for `render_rgb`.
    #[new]
    #[pyo3(signature = (preset = "full", arm = "servo", config_toml = None, record = false))]
    fn new(preset: &str, arm: &str, config_toml: Option<&str>, record: bool) -> PyResult<Self> {
        let config = env_config(preset, arm, config_toml)?;
        let env = GraspEnv::new(config).map_err(value_error)?;
        Ok(Self {
            env: Mutex::new(env),
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

    /// Starts the episode of scenario `seed`: (observation, info JSON).
    fn reset<'py>(
        &self,
        py: Python<'py>,
        seed: u64,
    ) -> PyResult<(Bound<'py, PyArray1<f32>>, String)> {
        let mut guard = self.env.lock().map_err(value_error)?;
        let env: &mut GraspEnv = &mut guard;
        let (obs, info) = py.detach(|| env.reset(seed)).map_err(value_error)?;
        if let Some(t) = self.trajectory.lock().map_err(value_error)?.as_mut() {
            t.record_reset(env, obs.gripper_opening);
        }
        let info = serde_json::to_string(&info).map_err(value_error)?;
        Ok((obs_array(&obs).into_pyarray(py), info))
    }

    /// One control step (physics with the GIL released): (obs, reward, terminated, truncated,
    /// info JSON). A wrong length or a non-finite value raises `ValueError` naming the index.
    fn step<'py>(
        &self,
        py: Python<'py>,
        action: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<StepTuple<'py>> {
        let action = checked_action(action.as_slice()?, "action")?;
        let mut guard = self.env.lock().map_err(value_error)?;
        let env: &mut GraspEnv = &mut guard;
        let step = py.detach(|| env.step(&action)).map_err(value_error)?;
        if let Some(t) = self.trajectory.lock().map_err(value_error)?.as_mut() {
            t.record_step(env, &action, &step, None);
        }
        let info = serde_json::to_string(&step.info).map_err(value_error)?;
        Ok((
            obs_array(&step.obs).into_pyarray(py),
            step.reward,
            step.terminated,
            step.truncated,
            info,
        ))
    }

    /// The observation space as JSON: names, units, low and high per entry (all finite).
    fn observation_space_json(&self) -> PyResult<String> {
        let env = self.env.lock().map_err(value_error)?;
        let space = fairgrasp_env::env::spaces::observation_space(env.config(), env.model());
        serde_json::to_string(&space).map_err(value_error)
    }

    /// The action space as JSON (joint velocities and gripper, or TCP velocity, yaw rate and
    /// gripper, per the config's `arm.action_space`), each in [−1, 1].
    fn action_space_json(&self) -> PyResult<String> {
        let env = self.env.lock().map_err(value_error)?;
        let space = fairgrasp_env::env::spaces::action_space_of(env.config().arm.action_space);
        serde_json::to_string(&space).map_err(value_error)
    }

    /// The env config as TOML (what `config_toml` takes back).
    fn config_toml(&self) -> PyResult<String> {
        Ok(self.env.lock().map_err(value_error)?.config().to_toml())
    }

    /// Steps per episode before truncation.
    #[getter]
    fn max_steps(&self) -> PyResult<usize> {
        Ok(self
            .env
            .lock()
            .map_err(value_error)?
            .config()
            .task
            .max_steps)
    }

    /// Joint angles q1 … q6 now [rad].
    fn joints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        Ok(self
            .env
            .lock()
            .map_err(value_error)?
            .joints()
            .to_vec()
            .into_pyarray(py))
    }

    /// The cube's position in base_link [m] (the truth, not the observation).
    fn object_xyz<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let env = self.env.lock().map_err(value_error)?;
        Ok(env.object_in_base().xyz().to_vec().into_pyarray(py))
    }
}

/// The scripted grasp (`fairgrasp baseline`) as a policy: `reset(seed)` at every episode, then
/// `act(obs)` → the env action (7 values in [−1, 1]).
#[pyclass(module = "fairgrasp._native")]
pub struct Baseline {
    script: Mutex<ScriptedGrasp>,
}

#[pymethods]
impl Baseline {
    #[new]
    #[pyo3(signature = (preset = "full", arm = "servo", config_toml = None))]
    fn new(preset: &str, arm: &str, config_toml: Option<&str>) -> PyResult<Self> {
        let config = env_config(preset, arm, config_toml)?;
        Ok(Self {
            script: Mutex::new(ScriptedGrasp::new(&config, BaselineConfig::default())),
        })
    }

    /// Forgets the last episode's plan.
    fn reset(&self, seed: u64) -> PyResult<()> {
        self.script.lock().map_err(value_error)?.reset(seed);
        Ok(())
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
