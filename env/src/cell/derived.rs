//! The cell a config describes, derived in one place: the arm's model, its mount and how it is
//! simulated. Everything that needs "which arm, mounted how, simulated how" asks [`Cell`].

use fairgrasp_kinematics::{ArmModel, Pose};
use fairgrasp_types::ArmSimulation;

use crate::cell::arm::arm_model;
use crate::cell::mount::Mount;
use crate::config::env_config::EnvConfig;

/// Which arm, mounted how, simulated how.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// The arm's kinematic model (limits, capsules, TCP).
    pub model: ArmModel,
    /// `base_link` and the table frame in `world` (`arm.base_xyz`, `arm.base_rpy`,
    /// `scene.table_height`).
    pub mount: Mount,
    /// Servo (kinematic links placed by FK) or multibody (`arm.model`).
    pub simulation: ArmSimulation,
}

impl Cell {
    /// The cell of `config`.
    pub fn from_config(config: &EnvConfig) -> Cell {
        Cell {
            model: arm_model(),
            mount: Mount::from_config(config),
            simulation: config.arm.model,
        }
    }
}

impl Mount {
    /// The mount a config describes (`arm.base_xyz`, `arm.base_rpy`, `scene.table_height`).
    pub fn from_config(config: &EnvConfig) -> Mount {
        Mount::new(
            Pose::from_xyz_rpy(config.arm.base_xyz, config.arm.base_rpy),
            config.scene.table_height,
        )
    }
}
