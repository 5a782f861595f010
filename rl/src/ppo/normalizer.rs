//! Running mean and variance of observations, as SB3's `VecNormalize` keeps them: saved in
//! checkpoints and applied at inference, so they live with the checkpoint in `fairgrasp-policy`
//! and are re-exported here for the trainer.

pub use fairgrasp_policy::checkpoint::normalizer::RunningNorm;
