//! The task's settings (`[task]`): which task, its time limit and success height, how a
//! collision ends an episode, the protective stop, and which reward it pays with that reward's
//! weights (one table each, [`DistanceReward`] and [`StagedReward`]).
//!
//! The TOML keeps the distance reward's weights as `[task]`'s own keys (`success_reward`,
//! `collision_reward`, `distance_reward`), as every shipped file writes them; [`TaskToml`] is
//! that shape, and [`TaskConfig`] is read and written through it.

use serde::{Deserialize, Serialize};

use crate::config::error::ConfigError;
use crate::config::reward::{DistanceReward, StagedReward};
use crate::scenario::fixture::settings::{FixtureBox, FixtureSite, SiteKeys};
use crate::task::place::settings::{PLACE_SITE_KEYS, PlaceConfig, check_place};
use crate::task::stack::settings::{STACK_SITE_KEYS, StackConfig, check_stack};

/// Which task an env runs (`[task] kind`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum TaskKind {
    /// Grasp the cube and lift it (the seed's task).
    #[default]
    Lift,
    /// Grasp the cube, carry it and seat it in the fixture's pocket, release it, move clear.
    Place,
    /// Grasp the cube, carry it and set it down squarely on a second cube, release it, move
    /// clear.
    Stack,
}

impl TaskKind {
    /// Every task, in the order the docs and `--help` list them.
    pub const ALL: [TaskKind; 3] = [TaskKind::Lift, TaskKind::Place, TaskKind::Stack];

    /// What the env's shared code reads of the task (its [`TaskSpec`], registered here).
    pub fn spec(self) -> &'static TaskSpec {
        match self {
            TaskKind::Lift => &LIFT,
            TaskKind::Place => &PLACE,
            TaskKind::Stack => &STACK,
        }
    }

    /// Its name in a preset's `[task] kind` and in messages (`lift`, `place`, `stack`).
    pub fn name(self) -> &'static str {
        self.spec().name
    }
}

/// What the code shared by every task (the scene, the scenario's draw, the config's checks, the
/// takt, the default residual recipe) reads of a task, so that it never asks which task it is.
/// One per task, below; the task's rules (success, distance to go) are registered in
/// `env/src/task/tasks.rs`, its settings and rules are in its folder (`env/src/task/<name>/`).
#[derive(Debug)]
pub struct TaskSpec {
    /// Its name in a preset's `[task] kind` and in messages.
    pub name: &'static str,
    /// Where the task's fixture stands and how it is seen, from the task's settings, for a
    /// cube of edge `cube_size` \[m\] (`None`: the scene has no fixture). The fixture is a
    /// fixed body the cube goes onto or into, drawn per scenario (`env/src/scenario/fixture/`).
    pub site: fn(&TaskConfig, f64) -> Option<FixtureSite>,
    /// The names of the site's settings in the task's table (`None`: no fixture), for a draw
    /// that finds no place for the fixture and names the numbers that make it impossible.
    pub site_keys: Option<&'static SiteKeys>,
    /// The fixture's boxes in its frame, for a cube of edge `cube_size` \[m\] (empty without
    /// a fixture).
    pub fixture_boxes: fn(&TaskConfig, f64) -> Vec<FixtureBox>,
    /// The fixture's name in a recorded trajectory's shapes (`<name>_<k>` for box `k`).
    pub fixture_part: &'static str,
    /// `None` if the task can pay the staged reward (reach, grasp, lift); else why not (the
    /// refusal's rule for `task.reward = "staged"`).
    pub refuses_staged_reward: Option<&'static str>,
    /// The takt the task runs on \[s\], from its settings (`None`: no takt).
    pub takt: fn(&TaskConfig) -> Option<f64>,
    /// Refuses the task's own settings (`[task.<name>]`) where one cannot mean what it says,
    /// for a cube of edge `cube_size` \[m\], naming the field. Every task's settings are checked,
    /// whichever task a preset runs (a file is valid or not as a whole).
    pub check: fn(&TaskConfig, f64) -> Result<(), ConfigError>,
    /// The shipped recipe (`assets/experiments/<name>.toml`) a task-space residual trains with
    /// on the task's presets that have no recipe of their own.
    pub residual_recipe: &'static str,
    /// The first field of the task's own table (`[task.<name>]`) that a config sets away from
    /// its default, as its dotted name and its value (`None`: the task has no table, or the
    /// config leaves it at its defaults). A config of another task may not set any
    /// (`EnvConfig::validate` refuses it naming the table and the config's task): the table
    /// is this task's, and another task's draw would read some of it.
    pub settings_set: fn(&TaskConfig) -> Option<(String, String)>,
}

/// The first field of `settings` (the table `table`) whose value differs from `default`'s, as
/// its dotted name and its value (`unset` for one the settings leave out).
fn first_set_field<T: Serialize>(
    table: &str,
    settings: &T,
    default: &T,
) -> Option<(String, String)> {
    fn differs(path: String, a: &toml::Value, b: Option<&toml::Value>) -> Option<(String, String)> {
        match (a, b) {
            (toml::Value::Table(a), Some(toml::Value::Table(b))) => a
                .iter()
                .find_map(|(k, v)| differs(format!("{path}.{k}"), v, b.get(k)))
                .or_else(|| {
                    b.keys()
                        .find(|k| !a.contains_key(*k))
                        .map(|k| (format!("{path}.{k}"), "unset".to_string()))
                }),
            (a, Some(b)) if a == b => None,
            (a, _) => Some((
                path,
                fairgrasp_types::text::excerpt(
                    &a.to_string(),
                    fairgrasp_types::text::MAX_QUOTED_CHARS,
                ),
            )),
        }
    }
    let settings = toml::Value::try_from(settings).ok()?;
    let default = toml::Value::try_from(default).ok()?;
    differs(table.to_string(), &settings, Some(&default))
}

/// The lift task to the shared code: no fixture, the staged reward (written for it), no takt.
const LIFT: TaskSpec = TaskSpec {
    name: "lift",
    site: |_, _| None,
    site_keys: None,
    fixture_boxes: |_, _| Vec::new(),
    fixture_part: "",
    check: |_, _| Ok(()),
    refuses_staged_reward: None,
    takt: |_| None,
    residual_recipe: "residual_miscalibrated",
    settings_set: |_| None,
};

/// The place task to the shared code: the fixture in the scene, drawn per scenario; the distance
/// reward only; its takt `[task.place] takt`.
const PLACE: TaskSpec = TaskSpec {
    name: "place",
    site: |task, _| Some(task.place.site()),
    site_keys: Some(&PLACE_SITE_KEYS),
    fixture_boxes: |task, cube_size| task.place.wall_boxes(cube_size),
    fixture_part: "fixture_wall",
    check: |task, cube_size| check_place(&task.place, cube_size),
    refuses_staged_reward: Some(
        "the staged reward is the lift task's (reach, grasp, lift): with task.kind = \"place\" use \"distance\"",
    ),
    takt: |task| Some(task.place.takt),
    residual_recipe: "residual_place_grasp_error",
    settings_set: |task| first_set_field("task.place", &task.place, &PlaceConfig::default()),
};

/// The stack task to the shared code: the second cube as the fixture, drawn per scenario; the
/// distance reward only; its takt `[task.stack] takt`.
const STACK: TaskSpec = TaskSpec {
    name: "stack",
    site: |task, cube_size| Some(task.stack.site(cube_size)),
    site_keys: Some(&STACK_SITE_KEYS),
    fixture_boxes: |_, cube_size| StackConfig::base_boxes(cube_size),
    fixture_part: "fixture_cube",
    check: |task, cube_size| check_stack(&task.stack, cube_size),
    refuses_staged_reward: Some(
        "the staged reward is the lift task's (reach, grasp, lift): with task.kind = \"stack\" use \"distance\"",
    ),
    takt: |task| Some(task.stack.takt),
    residual_recipe: "residual_stack",
    settings_set: |task| first_set_field("task.stack", &task.stack, &StackConfig::default()),
};

/// The task, its success, reward and time limit.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(from = "TaskToml", into = "TaskToml")]
pub struct TaskConfig {
    /// `lift` (the default), `place` (seat the cube in the fixture, `[task.place]`) or `stack`
    /// (set it down on a second cube, `[task.stack]`).
    pub kind: TaskKind,
    /// The place task's fixture and seated criterion (used when `kind = "place"`).
    pub place: PlaceConfig,
    /// The stack task's second cube and stacked criterion (used when `kind = "stack"`).
    pub stack: StackConfig,
    /// Steps before the episode is truncated (the seed's 200).
    pub max_steps: usize,
    /// Lift above the resting height that counts as success \[m\].
    pub lift_height: f64,
    /// Does a collision end the episode?
    pub terminate_on_collision: bool,
    /// With `terminate_on_collision = false` (training), is a success after a collision earlier
    /// in the episode void? Then that step ends the episode as the collision's failure, paid
    /// the collision's reward: what an evaluation, which ends the episode at the collision,
    /// would have judged. Default false (the success counts).
    pub collision_voids_success: bool,
    /// With `terminate_on_collision = false` (training), does a self-collision (two robot parts:
    /// the arm or the gripper against itself) still end the episode? A touch of the table then
    /// goes on as before. Default false (no collision ends a training episode).
    pub terminate_on_self_collision: bool,
    /// Which reward the task pays (the evaluation's success criterion is the same for all).
    pub reward: RewardKind,
    /// Protective stop threshold \[N\]: a contact between the robot (links, palm, finger struts,
    /// pads) and the cube or the table pushing harder than this ends the episode with
    /// `protective_stop`, as a real cobot's collision detection stops the arm. Checked after
    /// every physics substep; the force is the contact pair's solver impulse over `physics.dt`.
    ///
    /// Default 35 N, from measurement, well under the published limits (ISO/TS 15066 Annex A:
    /// 140 N quasi-static for hands and fingers, 65 N for the face, the lowest region; UR's
    /// default power-and-force limit 150 N; FAIRINO states its collision levels per joint, not
    /// as a TCP force). The simulated contacts are soft: a pad pressing the cube sinks it 2 mm
    /// into the table at 46–95 N (baseline on `hard`), so 140 N would stop nothing in time.
    /// Normal baseline grasps peak at 26 N (`full`) and 27 N (`hard`): the fingers' closing
    /// impact on the cube. See README, "Protective stop".
    pub protective_stop_force: f64,
    /// Weights of the distance reward (used when `reward = "distance"`; in the TOML `[task]`'s
    /// `success_reward`, `collision_reward` and `distance_reward`).
    pub distance: DistanceReward,
    /// Weights of the staged reward (used when `reward = "staged"`; `[task.staged]`).
    pub staged: StagedReward,
}

/// The task's reward function; each is a pure function in [`mod@crate::task::reward`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum RewardKind {
    /// `"distance"` (the seed recipe's reward): `success_reward` on success, `collision_reward`
    /// on a collision, else `distance_reward ·` the distance still to go
    /// ([`mod@crate::task::reward::distance`], weights [`DistanceReward`]). Files written with
    /// its old name `"seed"` still load as it.
    #[default]
    #[serde(alias = "seed")]
    Distance,
    /// Reach, grasp, lift shaping gated on the grasp, success; bounded per step
    /// ([`mod@crate::task::reward::staged`], weights in `[task.staged]`).
    Staged,
}

impl TaskConfig {
    /// The takt the task runs on \[s\]: a cell's time for one cycle, from the reset (the place
    /// task's `[task.place] takt`; the lift task has none).
    pub fn takt(&self) -> Option<f64> {
        (self.kind.spec().takt)(self)
    }
}

/// Default protective stop threshold \[N\] (see [`TaskConfig::protective_stop_force`]).
pub const DEFAULT_PROTECTIVE_STOP_FORCE: f64 = 35.0;

impl Default for TaskConfig {
    fn default() -> Self {
        Self {
            kind: TaskKind::Lift,
            place: PlaceConfig::default(),
            stack: StackConfig::default(),
            max_steps: 200,
            lift_height: 0.03,
            terminate_on_collision: true,
            collision_voids_success: false,
            terminate_on_self_collision: false,
            reward: RewardKind::Distance,
            protective_stop_force: DEFAULT_PROTECTIVE_STOP_FORCE,
            distance: DistanceReward::default(),
            staged: StagedReward::default(),
        }
    }
}

/// `[task]` as the TOML writes it: [`TaskConfig`] with the distance reward's weights as keys of
/// their own, in the order every shipped file and run folder has them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TaskToml {
    #[serde(skip_serializing_if = "is_lift")]
    pub kind: TaskKind,
    #[serde(skip_serializing_if = "is_default_place")]
    pub place: PlaceConfig,
    #[serde(skip_serializing_if = "is_default_stack")]
    pub stack: StackConfig,
    pub max_steps: usize,
    pub lift_height: f64,
    /// [`DistanceReward::success`].
    pub success_reward: f64,
    /// [`DistanceReward::collision`].
    pub collision_reward: f64,
    /// [`DistanceReward::distance`].
    pub distance_reward: f64,
    /// [`DistanceReward::time`] (left out of a written file at 0).
    #[serde(skip_serializing_if = "is_zero")]
    pub time_reward: f64,
    pub terminate_on_collision: bool,
    pub collision_voids_success: bool,
    pub terminate_on_self_collision: bool,
    pub reward: RewardKind,
    pub protective_stop_force: f64,
    pub staged: StagedReward,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

fn is_lift(kind: &TaskKind) -> bool {
    *kind == TaskKind::Lift
}

fn is_default_place(place: &PlaceConfig) -> bool {
    *place == PlaceConfig::default()
}

fn is_default_stack(stack: &StackConfig) -> bool {
    *stack == StackConfig::default()
}

impl Default for TaskToml {
    fn default() -> Self {
        TaskConfig::default().into()
    }
}

impl From<TaskToml> for TaskConfig {
    fn from(t: TaskToml) -> Self {
        TaskConfig {
            kind: t.kind,
            place: t.place,
            stack: t.stack,
            max_steps: t.max_steps,
            lift_height: t.lift_height,
            terminate_on_collision: t.terminate_on_collision,
            collision_voids_success: t.collision_voids_success,
            terminate_on_self_collision: t.terminate_on_self_collision,
            reward: t.reward,
            protective_stop_force: t.protective_stop_force,
            distance: DistanceReward {
                success: t.success_reward,
                collision: t.collision_reward,
                distance: t.distance_reward,
                time: t.time_reward,
            },
            staged: t.staged,
        }
    }
}

impl From<TaskConfig> for TaskToml {
    fn from(t: TaskConfig) -> Self {
        TaskToml {
            kind: t.kind,
            place: t.place,
            stack: t.stack,
            max_steps: t.max_steps,
            lift_height: t.lift_height,
            success_reward: t.distance.success,
            collision_reward: t.distance.collision,
            distance_reward: t.distance.distance,
            time_reward: t.distance.time,
            terminate_on_collision: t.terminate_on_collision,
            collision_voids_success: t.collision_voids_success,
            terminate_on_self_collision: t.terminate_on_self_collision,
            reward: t.reward,
            protective_stop_force: t.protective_stop_force,
            staged: t.staged,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_task_is_listed_once_under_the_name_its_presets_write() {
        for kind in TaskKind::ALL {
            let written = toml::Value::try_from(kind).unwrap();
            assert_eq!(written.as_str(), Some(kind.name()), "{kind:?}");
            assert_eq!(TaskKind::ALL.iter().filter(|k| **k == kind).count(), 1);
        }
    }
}
