//! Loading and checking an [`EnvConfig`]: TOML in and out, and refusals that name the field.

use std::f64::consts::TAU;
use std::path::Path;

use fairgrasp_kinematics::Pose;

use crate::config::check::{
    Bounds, RangeBounds, SECTOR_ANGLE, SECTOR_RADIUS, check, check_in, check_range,
};
use crate::config::env_config::{EnvConfig, SIMULATED_ARM, WrenchSensorConfig};
pub use crate::config::error::ConfigError;
pub use crate::config::numbers::{first_bad_number, first_non_finite, toml_error_message};
use crate::scenario::perception_noise::check_perception_noise;

/// The largest tilt of the base from upright that the env accepts \[rad\] (15°).
pub const MAX_BASE_TILT: f64 = 15.0 * std::f64::consts::PI / 180.0;

/// The angle between the z axis of `base_in_world` and the world's z axis \[rad\]: 0 for a
/// level base (what [`MAX_BASE_TILT`] bounds; `Mount::tilt` asks this too).
pub fn base_tilt(base_in_world: &Pose) -> f64 {
    let z = base_in_world.transform_vector([0.0, 0.0, 1.0]);
    z[2].clamp(-1.0, 1.0).acos()
}

/// Refuses any non-finite number or out-of-range integer in a configuration, naming the field.
pub fn check_all_finite(config: &impl serde::Serialize) -> Result<(), ConfigError> {
    match first_bad_number(config) {
        Some((field, value, rule)) => Err(ConfigError::Invalid {
            field,
            value,
            rule: rule.into(),
        }),
        None => Ok(()),
    }
}

/// The most physics substeps per env step the env accepts (each costs a full rigid-body step).
pub const MAX_SUBSTEPS: usize = 200;
/// The most solver iterations per substep the env accepts.
pub const MAX_SOLVER_ITERATIONS: usize = 100;
/// The longest episode the env accepts \[steps\].
pub const MAX_EPISODE_STEPS: usize = 100_000;
/// Where a body may stand on a coordinate, world frame \[m\]: within the largest table's side.
const ON_THE_TABLE: Bounds = Bounds::closed(-10.0, 10.0).unit("m");
/// The FR3's payload \[kg\]: the heaviest cube a scene may hold.
const PAYLOAD: f64 = 3.0;
/// A friction coefficient: the table's, the cube's, the pads', a drawn one.
const FRICTION: Bounds = Bounds::closed(0.0, 10.0);
/// A grip force \[N\]: the gripper's own and the control's.
const GRIP_FORCE: Bounds = Bounds::above_to(0.0, 100.0).unit("N");

impl EnvConfig {
    /// Reads a TOML file; missing fields take their defaults, unknown fields are refused.
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<Self, ConfigError> {
        let path_str = path.as_ref().display().to_string();
        let text = fairgrasp_types::fs::read_text_bounded(
            path.as_ref(),
            fairgrasp_types::fs::MAX_CONFIG_BYTES,
        )
        .map_err(|e| ConfigError::File {
            path: path_str.clone(),
            message: e.to_string(),
        })?;
        Self::from_toml_str(&text).map_err(|e| match e {
            ConfigError::File { message, .. } => ConfigError::File {
                path: path_str,
                message,
            },
            ConfigError::Invalid { field, value, rule } => ConfigError::File {
                path: path_str,
                message: format!("{field} = {value}: {rule}"),
            },
        })
    }

    /// Parses TOML text and validates it: every list read whole first
    /// ([`crate::config::lists`]: a list of another length than its field's is refused naming
    /// the field), then the typed reading, whose errors cite the line, then [`Self::validate`].
    pub fn from_toml_str(text: &str) -> Result<Self, ConfigError> {
        // A text that does not parse (or holds an integer beyond ±9.2·10¹⁸, which only the
        // typed reader takes) is the typed reader's to refuse.
        if let Ok(doc) = toml::from_str::<toml::Table>(text) {
            crate::config::lists::check_lists::<EnvConfig>(&doc)?;
        }
        let config: EnvConfig = toml::from_str(text).map_err(|e| ConfigError::File {
            path: "<string>".into(),
            message: toml_error_message(text, &e),
        })?;
        config.validate()?;
        Ok(config)
    }

    /// The exact TOML of this configuration (for run folders).
    pub fn to_toml(&self) -> String {
        toml::to_string_pretty(self).expect("EnvConfig always serialises")
    }

    /// Refuses values outside their allowed ranges, naming the field: every number finite, then
    /// each table's rules in the order of the file.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_all_finite(self)?;
        self.validate_physics()?;
        self.validate_arm()?;
        self.validate_gripper()?;
        self.validate_scene()?;
        self.validate_task()?;
        self.validate_randomization()?;
        self.validate_sensor()?;
        self.validate_families()
    }

    /// `[sensor.wrench]`: its numbers, and only on a task with a fixture (the wrist sensor reads
    /// the fixture's and the table's push; the lift task's observation has no place for it).
    fn validate_sensor(&self) -> Result<(), ConfigError> {
        let Some(wrench) = &self.sensor.wrench else {
            return Ok(());
        };
        let spec = self.task.kind.spec();
        if (spec.site)(&self.task, self.scene.cube_size).is_none() {
            return Err(ConfigError::Invalid {
                field: "sensor.wrench".into(),
                value: "(set)".into(),
                rule: format!(
                    "the {} task has no fixture: the six-axis wrist sensor is read only on a task with one (place, stack); remove [sensor.wrench]",
                    spec.name
                )
                .into(),
            });
        }
        wrench.check()
    }

    /// The six-axis wrist sensor this config's cell has: `[sensor.wrench]`, or its defaults,
    /// on a task with a fixture; `None` on a task without one.
    pub fn wrench_sensor(&self) -> Option<WrenchSensorConfig> {
        let spec = self.task.kind.spec();
        (spec.site)(&self.task, self.scene.cube_size)?;
        Some(self.sensor.wrench.clone().unwrap_or_default())
    }

    /// `[physics]`: the time step, substeps, solver iterations and contact stiffness.
    fn validate_physics(&self) -> Result<(), ConfigError> {
        let p = &self.physics;
        check_in(
            p.dt,
            "physics.dt",
            Bounds::above_to(0.0, 0.05).unit("s"),
            "",
        )?;
        check_in(
            p.substeps,
            "physics.substeps",
            Bounds::closed(1.0, MAX_SUBSTEPS as f64),
            "",
        )?;
        check_in(
            p.solver_iterations,
            "physics.solver_iterations",
            Bounds::closed(1.0, MAX_SOLVER_ITERATIONS as f64),
            "",
        )?;
        check_in(
            p.contact_natural_frequency,
            "physics.contact_natural_frequency",
            Bounds::above_to(0.0, 10_000.0).unit("Hz"),
            "(default 120)",
        )
    }

    /// `[arm]`: the action's scales, then where the arm stands ([`Self::validate_mount`]).
    fn validate_arm(&self) -> Result<(), ConfigError> {
        let a = &self.arm;
        check_in(
            a.action_scale,
            "arm.action_scale",
            Bounds::above_to(0.0, 3.15).unit("rad/s"),
            "(the FR3 velocity limit)",
        )?;
        check_in(
            a.max_acceleration,
            "arm.max_acceleration",
            Bounds::above_to(0.0, 1000.0).unit("rad/s²"),
            "(default 10)",
        )?;
        check_in(
            a.tcp_speed,
            "arm.tcp_speed",
            Bounds::above_to(0.0, 1.0).unit("m/s"),
            "",
        )?;
        check_in(
            a.tcp_yaw_rate,
            "arm.tcp_yaw_rate",
            Bounds::above_to(0.0, 3.2).unit("rad/s"),
            "(the FR3's wrist velocity limit)",
        )?;
        self.validate_mount()
    }

    /// Where the arm stands and starts: a base within ±10 m and ±2π on each axis, tilted at most
    /// [`MAX_BASE_TILT`], and home joints within the [`SIMULATED_ARM`]'s limits.
    fn validate_mount(&self) -> Result<(), ConfigError> {
        let a = &self.arm;
        for (v, field) in
            a.base_xyz
                .iter()
                .zip(["arm.base_xyz[0]", "arm.base_xyz[1]", "arm.base_xyz[2]"])
        {
            check_in(*v, field, ON_THE_TABLE, "(the largest table's side)")?;
        }
        for (v, field) in
            a.base_rpy
                .iter()
                .zip(["arm.base_rpy[0]", "arm.base_rpy[1]", "arm.base_rpy[2]"])
        {
            check_in(
                *v,
                field,
                Bounds::closed(-TAU, TAU).unit("rad"),
                "(one turn either way)",
            )?;
        }
        let tilt = base_tilt(&Pose::from_xyz_rpy(a.base_xyz, a.base_rpy));
        check(
            tilt <= MAX_BASE_TILT + 1e-9,
            "arm.base_rpy",
            format_args!("{:?} (tilt {:.1}°)", a.base_rpy, tilt.to_degrees()),
            "tilts the base more than 15° from upright: a wedge mount may tilt at most 15° \
             (roll and pitch together), with any yaw",
        )?;
        let fields = [
            "arm.home_joints[0]",
            "arm.home_joints[1]",
            "arm.home_joints[2]",
            "arm.home_joints[3]",
            "arm.home_joints[4]",
            "arm.home_joints[5]",
        ];
        for ((q, joint), field) in a
            .home_joints
            .iter()
            .zip(&SIMULATED_ARM.model().joints)
            .zip(fields)
        {
            let limits = Bounds::closed(joint.lower, joint.upper).unit("rad");
            check_in(*q, field, limits, "(the FR3's joint limits)")?;
        }
        Ok(())
    }

    /// `[gripper]` and the grip force of `[control]`.
    fn validate_gripper(&self) -> Result<(), ConfigError> {
        let g = &self.gripper;
        check_in(g.force, "gripper.force", GRIP_FORCE, "")?;
        check_in(g.pad_friction, "gripper.pad_friction", FRICTION, "")?;
        if let Some(force) = self.control.grip_force {
            check_in(
                force,
                "control.grip_force",
                GRIP_FORCE,
                "(gripper.force's range)",
            )?;
        }
        Ok(())
    }

    /// `[scene]`: the table and the cube.
    fn validate_scene(&self) -> Result<(), ConfigError> {
        let s = &self.scene;
        check_in(
            s.table_height,
            "scene.table_height",
            Bounds::closed(0.0, 2.0).unit("m"),
            "",
        )?;
        for (side, field) in s
            .table_size
            .iter()
            .zip(["scene.table_size[0]", "scene.table_size[1]"])
        {
            check_in(*side, field, Bounds::above_to(0.2, 10.0).unit("m"), "")?;
        }
        check_in(s.table_friction, "scene.table_friction", FRICTION, "")?;
        check_in(
            s.cube_size,
            "scene.cube_size",
            Bounds::closed(0.01, 0.08).unit("m"),
            "(the gripper opens 0.085 m)",
        )?;
        check_in(
            s.cube_mass,
            "scene.cube_mass",
            Bounds::above_to(0.0, PAYLOAD).unit("kg"),
            "(the FR3's payload)",
        )?;
        check_in(s.cube_friction, "scene.cube_friction", FRICTION, "")?;
        for (v, field) in s
            .cube_xy
            .iter()
            .zip(["scene.cube_xy[0]", "scene.cube_xy[1]"])
        {
            check_in(*v, field, ON_THE_TABLE, "(the largest table's side)")?;
        }
        Ok(())
    }

    /// A task's table is its own: a config whose task is `stack` may not set a field of
    /// `[task.place]` (its mix, its grip tilt: the fixture's draw would apply them to the second
    /// cube), nor one of `place` `[task.stack]`, nor a `lift` one either; refused naming the
    /// field, its table and the config's task.
    fn validate_own_tables(&self) -> Result<(), ConfigError> {
        let t = &self.task;
        for other in crate::config::TaskKind::ALL {
            if other == t.kind {
                continue;
            }
            if let Some((field, value)) = (other.spec().settings_set)(t) {
                let (table, task) = (other.name(), t.kind.name());
                return Err(ConfigError::Invalid {
                    field,
                    value,
                    rule: format!(
                        "[task.{table}] is the {table} task's table, and this config's task is \
                         {task} (task.kind = \"{task}\"): a config carries only its own task's \
                         table; remove [task.{table}], or set task.kind = \"{table}\""
                    )
                    .into(),
                });
            }
        }
        Ok(())
    }

    /// The randomisation's ranges and noise levels (`[randomization]`; the families' fields are
    /// `validate_families`').
    fn validate_randomization(&self) -> Result<(), ConfigError> {
        let r = &self.randomization;
        check_range(&r.radius, "randomization.radius", SECTOR_RADIUS)?;
        check_range(&r.angle, "randomization.angle", SECTOR_ANGLE)?;
        if let Some(f) = &r.friction {
            let bounds = RangeBounds::new(FRICTION, "(scene.cube_friction's range)");
            check_range(f, "randomization.friction", bounds)?;
        }
        if let Some(m) = &r.mass_scale {
            // A factor on scene.cube_mass, which has a range of its own (checked before); at
            // most 10⁶ (a cube of 5e-324 kg would make the payload's bound infinite).
            let most = (PAYLOAD / self.scene.cube_mass).min(1e6);
            let bounds = RangeBounds::new(
                Bounds::above_to(0.0, most),
                "(the drawn mass, scene.cube_mass times the factor, within the FR3's 3 kg payload)",
            );
            check_range(m, "randomization.mass_scale", bounds)?;
        }
        // Noise beyond this puts the start joints outside anything a scenario means.
        check_in(
            r.joint_noise,
            "randomization.joint_noise",
            Bounds::closed(0.0, 0.5).unit("rad"),
            "(default 0.05 on the randomised presets)",
        )?;
        check_perception_noise(r.observed_position_noise, r.observed_yaw_noise)
    }

    /// The task's fields (`[task]`, the staged reward's weights, `[task.place]`), after
    /// [`Self::validate_own_tables`].
    fn validate_task(&self) -> Result<(), ConfigError> {
        self.validate_own_tables()?;
        let t = &self.task;
        check_in(
            t.max_steps,
            "task.max_steps",
            Bounds::closed(1.0, MAX_EPISODE_STEPS as f64),
            "",
        )?;
        check_in(
            t.lift_height,
            "task.lift_height",
            Bounds::above_to(0.0, 2.0).unit("m"),
            "(default 0.03; a height the arm cannot reach means no success)",
        )?;
        check_in(
            t.protective_stop_force,
            "task.protective_stop_force",
            Bounds::above(0.0).unit("N"),
            "(default 35 N)",
        )?;
        t.staged.check()?;
        let reward = Bounds::closed(-1e4, 1e4);
        check_in(t.distance.success, "task.success_reward", reward, "")?;
        check_in(t.distance.collision, "task.collision_reward", reward, "")?;
        check_in(
            t.distance.distance,
            "task.distance_reward",
            reward.unit("1/m"),
            "",
        )?;
        check_in(
            t.distance.time,
            "task.time_reward",
            Bounds::closed(-10.0, 0.0).unit("per step"),
            "(a cost; default 0)",
        )?;
        for task in crate::config::TaskKind::ALL {
            (task.spec().check)(t, self.scene.cube_size)?;
        }
        if let Some(mix) = &t.place.mix {
            let (p, r) = (&t.place, &self.randomization);
            let drawn = [
                p.observed_position_noise > 0.0 || p.observed_yaw_noise > 0.0,
                r.observed_position_noise > 0.0 || r.observed_yaw_noise > 0.0,
                p.grip_tilt[1] > 0.0,
            ];
            crate::scenario::error_mix::settings::check_error_mix(mix, drawn)?;
        }
        if let Some(rule) = t.kind.spec().refuses_staged_reward {
            check(
                t.reward != crate::config::RewardKind::Staged,
                "task.reward",
                "staged",
                rule,
            )?;
        }
        Ok(())
    }
}
