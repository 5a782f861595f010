//! Which arm the env simulates: the FR3 (the only arm with the mass properties and collision
//! capsules a simulation needs; see `docs/FR3.md`).

use fairgrasp_kinematics::{ArmKind, ArmModel};

/// The simulated arm's model.
pub fn arm_model() -> ArmModel {
    ArmKind::Fr3.model()
}
