//! A small continuous-control task of our own, to check that PPO learns: a point mass on a line
//! pushed toward a goal. Optimal behaviour is known, so a test can demand near-optimal return.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::ppo::vec_api::{EpisodeStats, StepBatch, VecEnvError, VecEnvironment, check_finite};

/// Time step \[s\].
const DT: f32 = 0.1;
/// Episode length \[steps\].
pub const HORIZON: usize = 30;

#[derive(Clone, Copy, Debug)]
struct Mass {
    position: f32,
    velocity: f32,
    goal: f32,
    t: usize,
    episode_return: f32,
}

/// `n` point masses: observation `[position − goal, velocity]`, action a force in [-1, 1]
/// (clipped), reward `−|position − goal|` per step. Starts uniform in ±1 from the goal.
pub struct PointMass {
    masses: Vec<Mass>,
    rng: ChaCha8Rng,
    batch: StepBatch,
}

impl PointMass {
    pub fn new(n: usize, seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let masses = (0..n).map(|_| Self::spawn(&mut rng)).collect();
        Self {
            masses,
            rng,
            batch: StepBatch::new(n, 2),
        }
    }

    fn spawn(rng: &mut ChaCha8Rng) -> Mass {
        Mass {
            position: rng.random_range(-1.0..1.0),
            velocity: 0.0,
            goal: 0.0,
            t: 0,
            episode_return: 0.0,
        }
    }

    fn observe(m: &Mass, out: &mut [f32]) {
        out.copy_from_slice(&[m.position - m.goal, m.velocity]);
    }

    /// The return of doing nothing, for scale: the mass stays where it started.
    pub fn idle_return(start: f32) -> f32 {
        -start.abs() * HORIZON as f32
    }
}

impl VecEnvironment for PointMass {
    fn n_envs(&self) -> usize {
        self.masses.len()
    }
    fn obs_dim(&self) -> usize {
        2
    }
    fn act_dim(&self) -> usize {
        1
    }
    fn reset(&mut self) -> Result<&[f32], VecEnvError> {
        for (m, o) in self.masses.iter_mut().zip(self.batch.obs.chunks_mut(2)) {
            *m = Self::spawn(&mut self.rng);
            Self::observe(m, o);
        }
        Ok(&self.batch.obs)
    }
    fn step(&mut self, actions: &[f32]) -> Result<&StepBatch, VecEnvError> {
        if actions.len() != self.masses.len() {
            return Err(VecEnvError::ActionShape {
                n_envs: self.masses.len(),
                act_dim: 1,
                got: actions.len(),
            });
        }
        check_finite(actions, 1, "action")?;
        let b = &mut self.batch;
        for (e, (m, a)) in self.masses.iter_mut().zip(actions).enumerate() {
            let force = a.clamp(-1.0, 1.0) * 2.0;
            m.velocity = (m.velocity + force * DT) * 0.95;
            m.position += m.velocity * DT;
            m.t += 1;
            let reward = -(m.position - m.goal).abs();
            m.episode_return += reward;
            let truncated = m.t >= HORIZON;
            b.rewards[e] = reward;
            b.terminated[e] = false;
            b.truncated[e] = truncated;
            b.finished[e] = None;
            if truncated {
                Self::observe(m, &mut b.final_obs[2 * e..2 * e + 2]);
                b.finished[e] = Some(EpisodeStats {
                    success: false,
                    outcome: None,
                    episode_return: m.episode_return,
                    length: m.t,
                    object_xy: None,
                });
                *m = Self::spawn(&mut self.rng);
            }
            Self::observe(m, &mut b.obs[2 * e..2 * e + 2]);
        }
        Ok(&self.batch)
    }
}
