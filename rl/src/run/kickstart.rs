//! A run's teachers (`[kickstart]` in its config): one trained policy per preset it trains on,
//! whose mean actions the policy is pulled towards on its own rollouts
//! ([`crate::ppo::teacher`]). This is how one generalist learns what several specialists know:
//! each env's teacher is the specialist of that env's preset.
//!
//! A teacher is a shipped policy's name (`residual_nudged`), a checkpoint folder or a run folder
//! (its `checkpoints/best`). It must see the same policy input and command the same output as
//! the student (the same agent, but for the squeeze); it labels only the output entries both
//! use, so a teacher without the squeeze has no say in the student's squeeze.
//!
//! A teacher is named, not copied: a resumed run loads it again from the same name. The run
//! records the folder each name gave and its checksum when it started
//! ([`crate::run::inputs`]): a resume on which a name gives another folder (a relative path from
//! another working directory) or another checkpoint (a teacher run's `best` replaced since, a
//! shipped policy changed in another build) is refused naming the teacher, unless the change is
//! accepted (`--accept-config-changes`).

use fairgrasp_env::EnvConfig;
use fairgrasp_policy::actor::Actor;
use fairgrasp_policy::agent::env_agent::output_names;
use fairgrasp_policy::checkpoint::{load_actor, normalizer::RunningNorm};
use fairgrasp_policy::shipped::checkpoint_folder;

pub use fairgrasp_policy::recipe::kickstart::KickstartConfig;

use crate::agent::grasp_agent::AgentConfig;
use crate::ppo::teacher::{Kickstart, Teacher};
use crate::run::error::TrainError;

/// One preset's teacher, ready to label.
struct Specialist {
    actor: Actor,
    norm: RunningNorm,
    /// 1 for each output entry the teacher labels.
    mask: Vec<f32>,
}

/// The teachers of a mixed run: env `e` trains on preset `e % presets` and is labelled by that
/// preset's teacher.
struct Specialists(Vec<Specialist>);

impl Teacher for Specialists {
    fn label(&self, env: usize, input: &[f32], target: &mut [f32], mask: &mut [f32]) {
        let s = &self.0[fairgrasp_env::vec::preset_of_env(env, self.0.len())];
        let y = s.actor.mean(&s.norm.normalize(input));
        for (j, &m) in s.mask.iter().enumerate() {
            if m > 0.0 {
                target[j] = y[j];
                mask[j] = 1.0;
            }
        }
    }
}

/// Loads the teachers of `k` for a student `agent` trained on `envs` (the presets' evaluation
/// configurations, in the run's order); an error names the teacher and what does not fit.
pub fn load(
    k: &KickstartConfig,
    student: &AgentConfig,
    envs: &[EnvConfig],
) -> Result<Kickstart, TrainError> {
    k.check(envs.len()).map_err(TrainError::Config)?;
    let mut all = Vec::new();
    for (name, env) in k.teachers.iter().zip(envs) {
        let bad = |why: String| TrainError::Config(format!("kickstart.teachers: {name}: {why}"));
        let dir = checkpoint_folder(name).map_err(bad)?;
        let (meta, actor) = load_actor(&dir).map_err(|e| bad(e.to_string()))?;
        let same_but_squeeze = AgentConfig {
            squeeze: student.squeeze,
            ..meta.agent.clone()
        };
        if &same_but_squeeze != student || meta.input_dim != student.input_dim() {
            return Err(bad(format!(
                "its agent ({:?}) differs from the run's ({student:?}) in more than the squeeze",
                meta.agent
            )));
        }
        let used = |agent| {
            output_names(agent, env)
                .into_iter()
                .map(|n| !n.starts_with("unused"))
                .collect::<Vec<bool>>()
        };
        let mask = used(&meta.agent)
            .into_iter()
            .zip(used(student))
            .map(|(t, s)| f32::from(u8::from(t && s)))
            .collect();
        all.push(Specialist {
            actor,
            norm: meta.obs_norm,
            mask,
        });
    }
    Ok(Kickstart {
        teacher: Box::new(Specialists(all)),
        weight: k.weight as f32,
        anneal: k.anneal,
    })
}
