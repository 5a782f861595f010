//! Where each scenario family's settings are checked ([`EnvConfig::validate`] calls this): one
//! line per family, its rules in the family's own folder (`env/src/scenario/<family>/settings.rs`).

use crate::config::env_config::EnvConfig;
use crate::config::error::ConfigError;

impl EnvConfig {
    /// The scenario families' fields of `[randomization]`: the wrist camera, the camera offset,
    /// the push.
    pub(crate) fn validate_families(&self) -> Result<(), ConfigError> {
        let r = &self.randomization;
        if let Some(w) = &r.wrist_camera {
            w.check()?;
        }
        if let Some(c) = &r.camera_offset {
            c.check()?;
        }
        if let Some(n) = &r.nudge {
            n.check(self.task.max_steps, r.position)?;
        }
        Ok(())
    }
}
