//! Loading and checking an [`EnvConfig`]: TOML in and out, and refusals that name the field.

use std::path::Path;

use fairgrasp_kinematics::Pose;

use crate::config::check::{Lowest, check, check_range};
use crate::config::env_config::{EnvConfig, SIMULATED_ARM};
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
        Some((field, value, rule)) => Err(ConfigError::Invalid { field, value, rule }),
        None => Ok(()),
    }
}

/// The most physics substeps per env step the env accepts (each costs a full rigid-body step).
pub const MAX_SUBSTEPS: usize = 200;
/// The most solver iterations per substep the env accepts.
pub const MAX_SOLVER_ITERATIONS: usize = 100;
/// The longest episode the env accepts \[steps\].
pub const MAX_EPISODE_STEPS: usize = 100_000;

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

    /// Parses TOML text and validates it.
    pub fn from_toml_str(text: &str) -> Result<Self, ConfigError> {
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
        self.validate_families()
    }

    /// `[physics]`: the time step, substeps, solver iterations and contact stiffness.
    fn validate_physics(&self) -> Result<(), ConfigError> {
        let p = &self.physics;
        check(
            p.dt > 0.0 && p.dt <= 0.05,
            "physics.dt",
            p.dt,
            "must be in (0, 0.05] s",
        )?;
        check(
            (1..=MAX_SUBSTEPS).contains(&p.substeps),
            "physics.substeps",
            p.substeps,
            "must be in 1..=200",
        )?;
        check(
            (1..=MAX_SOLVER_ITERATIONS).contains(&p.solver_iterations),
            "physics.solver_iterations",
            p.solver_iterations,
            "must be in 1..=100",
        )?;
        check(
            p.contact_natural_frequency > 0.0 && p.contact_natural_frequency <= 10_000.0,
            "physics.contact_natural_frequency",
            p.contact_natural_frequency,
            "must be in (0, 10000] Hz (default 120)",
        )
    }

    /// `[arm]`: the action's scales, then where the arm stands ([`Self::validate_mount`]).
    fn validate_arm(&self) -> Result<(), ConfigError> {
        let a = &self.arm;
        check(
            a.action_scale > 0.0 && a.action_scale <= 3.15,
            "arm.action_scale",
            a.action_scale,
            "must be in (0, 3.15] rad/s (the FR3 velocity limit)",
        )?;
        check(
            a.max_acceleration > 0.0 && a.max_acceleration <= 1000.0,
            "arm.max_acceleration",
            a.max_acceleration,
            "must be in (0, 1000] rad/s² (default 10)",
        )?;
        check(
            a.tcp_speed > 0.0 && a.tcp_speed <= 1.0,
            "arm.tcp_speed",
            a.tcp_speed,
            "must be in (0, 1] m/s",
        )?;
        check(
            a.tcp_yaw_rate > 0.0 && a.tcp_yaw_rate <= 3.2,
            "arm.tcp_yaw_rate",
            a.tcp_yaw_rate,
            "must be in (0, 3.2] rad/s (the FR3's wrist velocity limit)",
        )?;
        self.validate_mount()
    }

    /// Where the arm stands and starts: a finite base pose tilted at most [`MAX_BASE_TILT`], and
    /// home joints within the [`SIMULATED_ARM`]'s limits.
    fn validate_mount(&self) -> Result<(), ConfigError> {
        let a = &self.arm;
        check(
            a.base_xyz.iter().chain(&a.base_rpy).all(|v| v.is_finite()),
            "arm.base_xyz/base_rpy",
            (a.base_xyz, a.base_rpy),
            "must be finite",
        )?;
        let tilt = base_tilt(&Pose::from_xyz_rpy(a.base_xyz, a.base_rpy));
        check(
            tilt <= MAX_BASE_TILT + 1e-9,
            "arm.base_rpy",
            format_args!("{:?} (tilt {:.1}°)", a.base_rpy, tilt.to_degrees()),
            "tilts the base more than 15° from upright: a wedge mount may tilt at most 15° \
             (roll and pitch together), with any yaw",
        )?;
        check(
            SIMULATED_ARM.model().in_limits(&a.home_joints, 0.0),
            "arm.home_joints",
            a.home_joints,
            "must be within the FR3 joint limits",
        )
    }

    /// `[gripper]` and the grip force of `[control]`.
    fn validate_gripper(&self) -> Result<(), ConfigError> {
        let g = &self.gripper;
        check(
            g.force > 0.0 && g.force <= 100.0,
            "gripper.force",
            g.force,
            "must be in (0, 100] N",
        )?;
        check(
            (0.0..=10.0).contains(&g.pad_friction),
            "gripper.pad_friction",
            g.pad_friction,
            "must be in [0, 10]",
        )?;
        if let Some(force) = self.control.grip_force {
            check(
                force > 0.0 && force <= 100.0,
                "control.grip_force",
                force,
                "must be in (0, 100] N (gripper.force's range)",
            )?;
        }
        Ok(())
    }

    /// `[scene]`: the table and the cube.
    fn validate_scene(&self) -> Result<(), ConfigError> {
        let s = &self.scene;
        check(
            (0.0..=2.0).contains(&s.table_height),
            "scene.table_height",
            s.table_height,
            "must be in [0, 2] m",
        )?;
        check(
            s.table_size.iter().all(|v| *v > 0.2 && *v <= 10.0),
            "scene.table_size",
            s.table_size,
            "each side must be in (0.2, 10] m",
        )?;
        check(
            (0.0..=10.0).contains(&s.table_friction),
            "scene.table_friction",
            s.table_friction,
            "must be in [0, 10]",
        )?;
        check(
            s.cube_size >= 0.01 && s.cube_size <= 0.08,
            "scene.cube_size",
            s.cube_size,
            "must be in [0.01, 0.08] m (the gripper opens 0.085 m)",
        )?;
        check(
            s.cube_mass > 0.0 && s.cube_mass <= 3.0,
            "scene.cube_mass",
            s.cube_mass,
            "must be in (0, 3] kg (the FR3's payload)",
        )?;
        check(
            (0.0..=10.0).contains(&s.cube_friction),
            "scene.cube_friction",
            s.cube_friction,
            "must be in [0, 10]",
        )
    }

    /// The randomisation's ranges and noise levels (`[randomization]`; the families' fields are
    /// `validate_families`').
    fn validate_randomization(&self) -> Result<(), ConfigError> {
        let r = &self.randomization;
        check_range(&r.radius, "randomization.radius", Lowest::Zero)?;
        check_range(&r.angle, "randomization.angle", Lowest::MinusPi)?;
        if let Some(f) = &r.friction {
            check_range(f, "randomization.friction", Lowest::Zero)?;
        }
        if let Some(m) = &r.mass_scale {
            check_range(m, "randomization.mass_scale", Lowest::Zero)?;
            check(
                m[0] > 0.0,
                "randomization.mass_scale",
                m,
                "must be positive",
            )?;
        }
        // Noise beyond this puts the start joints outside anything a scenario means.
        check(
            r.joint_noise.is_finite() && (0.0..=0.5).contains(&r.joint_noise),
            "randomization.joint_noise",
            r.joint_noise,
            "must be in [0, 0.5] rad (default 0.05 on the randomised presets)",
        )?;
        check_perception_noise(r.observed_position_noise, r.observed_yaw_noise)
    }

    /// The task's fields (`[task]`, the staged reward's weights, `[task.place]`).
    fn validate_task(&self) -> Result<(), ConfigError> {
        let t = &self.task;
        check(
            (1..=MAX_EPISODE_STEPS).contains(&t.max_steps),
            "task.max_steps",
            t.max_steps,
            "must be in 1..=100000",
        )?;
        check(
            t.lift_height > 0.0 && t.lift_height <= 2.0,
            "task.lift_height",
            t.lift_height,
            "must be in (0, 2] m (default 0.03; a height the arm cannot reach means no success)",
        )?;
        check(
            t.protective_stop_force.is_finite() && t.protective_stop_force > 0.0,
            "task.protective_stop_force",
            t.protective_stop_force,
            "must be a finite force in (0, inf) N (default 35 N)",
        )?;
        t.staged.check()?;
        check(
            (-10.0..=0.0).contains(&t.distance.time),
            "task.time_reward",
            t.distance.time,
            "must be in [-10, 0] per step (a cost; default 0)",
        )?;
        crate::task::place::settings::check_place(&t.place, self.scene.cube_size)?;
        if let Some(mix) = &t.place.mix {
            let (p, r) = (&t.place, &self.randomization);
            let drawn = [
                p.observed_position_noise > 0.0 || p.observed_yaw_noise > 0.0,
                r.observed_position_noise > 0.0 || r.observed_yaw_noise > 0.0,
                p.grip_tilt[1] > 0.0,
            ];
            crate::scenario::error_mix::settings::check_error_mix(mix, drawn)?;
        }
        check(
            !(t.kind == crate::config::TaskKind::Place
                && t.reward == crate::config::RewardKind::Staged),
            "task.reward",
            "staged",
            "the staged reward is the lift task's (reach, grasp, lift): with task.kind = \"place\" use \"distance\"",
        )?;
        Ok(())
    }
}
