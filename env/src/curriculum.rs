//! A curriculum over the randomisation: fixed → position → +yaw → +friction/mass, advancing when
//! the rolling success rate passes a threshold.

use std::collections::VecDeque;

use serde::{Deserialize, Serialize};

use crate::config::RandomizationConfig;

/// Curriculum settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CurriculumConfig {
    /// Advance when the success rate over the last `window` episodes reaches this (0–1).
    pub threshold: f64,
    /// Episodes in the rolling window.
    pub window: usize,
}

impl Default for CurriculumConfig {
    fn default() -> Self {
        Self {
            threshold: 0.6,
            window: 50,
        }
    }
}

/// The stages, in order.
pub const STAGES: [&str; 4] = [
    "fixed",
    "position",
    "position+yaw",
    "position+yaw+friction/mass",
];

/// Curriculum state: the stage and the recent outcomes.
#[derive(Clone, Debug, PartialEq)]
pub struct Curriculum {
    config: CurriculumConfig,
    target: RandomizationConfig,
    stage: usize,
    recent: VecDeque<bool>,
}

impl Curriculum {
    /// Starts at stage 0; `target` is the randomisation of the last stage.
    pub fn new(config: CurriculumConfig, target: RandomizationConfig) -> Self {
        Self {
            config,
            target,
            stage: 0,
            recent: VecDeque::new(),
        }
    }

    /// The current stage index (0 … 3).
    pub fn stage(&self) -> usize {
        self.stage
    }

    /// Success rate over the window so far (0 when empty).
    pub fn success_rate(&self) -> f64 {
        if self.recent.is_empty() {
            0.0
        } else {
            self.recent.iter().filter(|s| **s).count() as f64 / self.recent.len() as f64
        }
    }

    /// Records an episode outcome; returns true if this advanced the stage. A stage advances
    /// only with a full window, which then starts empty again.
    pub fn record(&mut self, success: bool) -> bool {
        self.recent.push_back(success);
        while self.recent.len() > self.config.window {
            self.recent.pop_front();
        }
        let full = self.recent.len() == self.config.window;
        if full && self.success_rate() >= self.config.threshold && self.stage + 1 < STAGES.len() {
            self.stage += 1;
            self.recent.clear();
            return true;
        }
        false
    }

    /// The randomisation in force at the current stage.
    pub fn randomization(&self) -> RandomizationConfig {
        let t = &self.target;
        let none = RandomizationConfig {
            radius: t.radius,
            angle: t.angle,
            ..RandomizationConfig::default()
        };
        match self.stage {
            0 => none,
            1 => RandomizationConfig {
                position: t.position,
                joint_noise: t.joint_noise,
                ..none
            },
            2 => RandomizationConfig {
                yaw: t.yaw,
                ..RandomizationConfig {
                    position: t.position,
                    joint_noise: t.joint_noise,
                    ..none
                }
            },
            _ => t.clone(),
        }
    }
}
