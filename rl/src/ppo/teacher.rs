//! Kickstarting (Schmitt et al. 2018, "Kickstarting Deep Reinforcement Learning"): PPO's loss
//! plus a term that pulls the policy's mean action towards a teacher's on the states the
//! policy itself visits, so a student can learn from several specialist teachers at once (each
//! env has the teacher of its task) and keep improving on the reward.
//!
//! The term, per minibatch of `B` samples: `w · Σ_i Σ_j m_ij (μ_ij − y_ij)² / B`, with `μ` the
//! student's mean action, `y` the teacher's mean action for the same raw input, `m_ij` 1 where the
//! teacher commands entry `j` and 0 where it has no opinion (an entry its agent does not use).
//! It is DAgger's imitation loss (Ross et al. 2011) on PPO's own rollouts: the student visits
//! the states, the teachers label them.
//!
//! Nothing here knows what a teacher is: the run supplies one through [`Teacher`].

/// Labels for kickstarting: what the teacher of env `env` would do for a raw policy input.
pub trait Teacher: Send {
    /// Writes the teacher's mean action for env `env`'s raw (unnormalised) policy input `input`
    /// into `target`, and 1 into `mask[j]` for every entry `j` it commands (0 elsewhere).
    fn label(&self, env: usize, input: &[f32], target: &mut [f32], mask: &mut [f32]);
}

/// The teacher and the weight of its term.
pub struct Kickstart {
    pub teacher: Box<dyn Teacher>,
    /// `w` at the start of training.
    pub weight: f32,
    /// Lower `w` linearly to 0 at the end of training (else it stays at `weight`).
    pub anneal: bool,
}

impl Kickstart {
    /// `w` when `progress` (in [0, 1]) of the training is done.
    pub fn weight_at(&self, progress: f64) -> f32 {
        if self.anneal {
            self.weight * (1.0 - progress.clamp(0.0, 1.0)) as f32
        } else {
            self.weight
        }
    }

    /// Labels the raw inputs of one step of every env (`[env][obs_dim]`) into `targets` and
    /// `mask` (`[env][act_dim]`).
    pub fn label_step(
        &self,
        raw: &[f32],
        obs_dim: usize,
        act_dim: usize,
        targets: &mut [f32],
        mask: &mut [f32],
    ) {
        let rows = raw.chunks(obs_dim.max(1));
        let outs = targets
            .chunks_mut(act_dim.max(1))
            .zip(mask.chunks_mut(act_dim.max(1)));
        for (env, (input, (target, m))) in rows.zip(outs).enumerate() {
            target.fill(0.0);
            m.fill(0.0);
            self.teacher.label(env, input, target, m);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Env `e` labels entry `e % 2` with the input's first value.
    struct Alternating;
    impl Teacher for Alternating {
        fn label(&self, env: usize, input: &[f32], target: &mut [f32], mask: &mut [f32]) {
            target[env % 2] = input[0];
            mask[env % 2] = 1.0;
        }
    }

    #[test]
    fn each_env_is_labelled_by_its_teacher_and_the_weight_anneals() {
        let k = Kickstart {
            teacher: Box::new(Alternating),
            weight: 2.0,
            anneal: true,
        };
        // Three envs, inputs of 2 values, actions of 2: stale values are cleared.
        let raw = [0.5, 9.0, -0.25, 9.0, 0.75, 9.0];
        let mut targets = [7.0; 6];
        let mut mask = [7.0; 6];
        k.label_step(&raw, 2, 2, &mut targets, &mut mask);
        assert_eq!(targets, [0.5, 0.0, 0.0, -0.25, 0.75, 0.0]);
        assert_eq!(mask, [1.0, 0.0, 0.0, 1.0, 1.0, 0.0]);
        assert_eq!(k.weight_at(0.0), 2.0);
        assert_eq!(k.weight_at(0.75), 0.5);
        assert_eq!(k.weight_at(1.5), 0.0);
        let flat = Kickstart { anneal: false, ..k };
        assert_eq!(flat.weight_at(0.75), 2.0);
    }
}
