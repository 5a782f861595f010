//! Which arm the env simulates: the config's [`SIMULATED_ARM`], the FR3 (see `docs/FR3.md`).

use fairgrasp_kinematics::ArmModel;

use crate::config::env_config::SIMULATED_ARM;

/// The simulated arm's model.
pub fn arm_model() -> ArmModel {
    SIMULATED_ARM.model()
}
