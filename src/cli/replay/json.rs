//! `fairgrasp replay --json FILE`: the recorded episodes as one JSON file, the input of
//! `python -m fairgrasp.rerun` (which writes a Rerun `.rrd`; the Rust build stays free of the
//! Rerun SDK). Each method's entry holds its trajectory (the env's recording: joints, body
//! poses, TCP and cube poses, phase, reward, pad contacts, in `base_link` \[m\]) and the contact
//! forces of every step, measured by playing the recorded actions again in a fresh env; the file
//! carries the FR3's URDF (`assets/fr3.urdf`, the model the env simulates), so it stands alone.
//!
//! Why play again: the trajectory does not record forces, and the policies are built inside
//! `fairgrasp-evaluate`. The env is deterministic, so the same scenario and actions give the same
//! episode; every step's joints and cube pose are compared with the recording, and a method whose
//! replay departs from it (a policy that changed the grip force, which actions do not carry)
//! gets no forces rather than wrong ones.

use std::path::Path;

use anyhow::{Context, bail};
use fairgrasp_env::episode::trajectory::Trajectory;
use fairgrasp_env::scenario::Scenario;
use fairgrasp_env::sim::part::Part;
use fairgrasp_env::{Action, EnvConfig, TaskEnv};
use fairgrasp_types::fs::write_atomic;
use serde_json::{Value, json};

/// The key that marks a fairgrasp replay JSON (and its format version).
const FORMAT_KEY: &str = "fairgrasp_replay_json";
const FORMAT_VERSION: u32 = 1;

/// The contact forces after one step \[N\], over the step's last physics substep (each pair's
/// net contact impulse over the substep's `dt`, as the protective stop and the wrist sensor
/// measure them). Zero on a step that ran no physics (a free-space step: nothing touches).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepForces {
    /// Left and right pad on the cube \[N\].
    pub pad_cube_n: [f64; 2],
    /// The strongest robot–cube or robot–table contact \[N\] (what a protective stop watches).
    pub robot_strongest_n: f64,
    /// The six-axis wrist sensor's force in `base_link` \[N\] (a task with a fixture only, else
    /// zeros).
    pub wrist_n: [f64; 3],
    /// Its torque about the flange in `base_link` \[N·m\] (likewise).
    pub wrist_nm: [f64; 3],
}

impl StepForces {
    fn to_json(self) -> Value {
        json!({"pad_cube_n": self.pad_cube_n, "robot_strongest_n": self.robot_strongest_n,
               "wrist_n": self.wrist_n, "wrist_nm": self.wrist_nm})
    }
}

/// One method's episode for the JSON file.
pub struct MethodEpisode<'a> {
    pub method: &'a str,
    pub trajectory: &'a Trajectory,
}

/// True if `path` holds a fairgrasp replay JSON (so `--json` may replace it).
pub fn is_replay_json(path: &Path) -> bool {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|text| serde_json::from_str::<Value>(&text).ok())
        .is_some_and(|v| v.get(FORMAT_KEY).is_some())
}

/// Writes `episodes` (every method on the one `scenario`, index `episode` of `preset`'s set of
/// seed `seed`) to `path` atomically.
pub fn write_replay_json(
    path: &Path,
    config: &EnvConfig,
    scenario: &Scenario,
    (preset, episode, seed): (&str, usize, u64),
    episodes: &[MethodEpisode<'_>],
) -> anyhow::Result<()> {
    let mut methods = Vec::new();
    for e in episodes {
        let forces = measure_forces(config, scenario, e.trajectory)
            .with_context(|| format!("{}: measuring the contact forces", e.method))?;
        if forces.is_none() {
            eprintln!(
                "{}: playing the recorded actions again departs from the recording (the policy \
                 set its own grip force?): the JSON holds no contact forces for it",
                e.method
            );
        }
        methods.push(json!({
            "method": e.method,
            "outcome": e.trajectory.outcome,
            "trajectory": e.trajectory,
            "contact_forces": forces.map(|f| f.into_iter().map(StepForces::to_json).collect::<Vec<_>>()),
        }));
    }
    let physics = &config.physics;
    let doc = json!({
        FORMAT_KEY: FORMAT_VERSION,
        "preset": preset,
        "episode": episode,
        "seed": seed,
        "arm_model": "fr3",
        "urdf": fairgrasp_kinematics::FR3_URDF,
        "step_s": physics.dt * physics.substeps as f64,
        "frames": "poses in base_link [m], quaternions [x, y, z, w]; base_in_world places base_link",
        "methods": methods,
    });
    let text = serde_json::to_string(&doc).context("encoding the replay JSON")?;
    write_atomic(path, text.as_bytes()).with_context(|| format!("writing {}", path.display()))
}

/// Plays `trajectory`'s actions again from `scenario` in a fresh env and returns the contact
/// forces after every step (the first entry, for the reset, is zeros), or `None` if the replay
/// departs from the recording (joints or cube position off by more than 1 µm at some step).
fn measure_forces(
    config: &EnvConfig,
    scenario: &Scenario,
    trajectory: &Trajectory,
) -> anyhow::Result<Option<Vec<StepForces>>> {
    let mut env = TaskEnv::new(config.clone())?;
    env.reset_to(scenario);
    let mut forces = vec![StepForces::default()];
    for row in trajectory.rows.iter().skip(1) {
        let step = env.step(&Action(row.action))?;
        if !same_state(&env, row) {
            return Ok(None);
        }
        let mut f = if step.info.simulated {
            contact_forces(&mut env)
        } else {
            StepForces::default()
        };
        f.wrist_n = step.obs.wrist_force.unwrap_or_default();
        f.wrist_nm = step.obs.wrist_torque.unwrap_or_default();
        forces.push(f);
        if step.terminated || step.truncated {
            break;
        }
    }
    if forces.len() != trajectory.rows.len() {
        bail!(
            "the replay ended after {} steps, the recording after {}",
            forces.len() - 1,
            trajectory.rows.len() - 1
        );
    }
    Ok(Some(forces))
}

/// The env's joints and cube position equal `row`'s within 1 µm (rad, m).
fn same_state(env: &TaskEnv, row: &fairgrasp_env::episode::trajectory::TrajectoryRow) -> bool {
    let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-6);
    close(&env.joints(), &row.joints) && close(&env.object_in_base().xyz(), &row.object_xyz)
}

/// The pad–cube forces and the strongest robot contact of the env's last physics substep.
fn contact_forces(env: &mut TaskEnv) -> StepForces {
    let (world, handles) = env.world_mut();
    let dt = f64::from(world.integration_parameters.dt);
    let mut out = StepForces::default();
    for pair in world.narrow_phase.contact_pairs_with(handles.cube_collider) {
        let parts = (
            handles.parts.get(&pair.collider1),
            handles.parts.get(&pair.collider2),
        );
        let pad = match parts {
            (Some(Part::Pad(f)), _) | (_, Some(Part::Pad(f))) => f,
            _ => continue,
        };
        out.pad_cube_n[pad] += f64::from(pair.total_impulse().length()) / dt;
    }
    out.robot_strongest_n = fairgrasp_env::sim::contacts::strongest_robot_contact(
        world,
        &handles.parts,
        handles.cube_collider,
        handles.table_collider,
        dt,
    )
    .map_or(0.0, |c| c.force);
    out
}
