//! What a comparison runs: the presets, the scenario count and seed, the recorded episodes, and
//! the presets `fairgrasp compare` uses by default.

use fairgrasp_env::EnvConfig;

use crate::compare::error::CompareError;

/// One preset of a comparison: its name (as given) and its environment config.
#[derive(Clone, Debug)]
pub struct ComparePreset {
    pub name: String,
    pub config: EnvConfig,
}

/// What to compare and how.
#[derive(Clone, Debug)]
pub struct CompareSpec {
    /// Presets in run order; the charts' recorded episode is taken on the last one.
    pub presets: Vec<ComparePreset>,
    /// Scenarios per preset; every method meets the same ones.
    pub episodes: usize,
    /// Seed of the scenario sets.
    pub seed: u64,
    /// Worker threads of each evaluation.
    pub threads: usize,
    /// Scenario index recorded on the last preset. `None`: the first where the first two methods
    /// end differently, else 0.
    pub episode: Option<usize>,
    /// Scenarios of every preset recorded for every method for the 3D replay (the first ones of
    /// each set, at most `episodes`, and the first where the baseline and the first learned
    /// method end differently; on the last preset the charts' `episode` is always among them).
    pub replay_episodes: usize,
    /// The command line kept in the result.
    pub command: String,
}

/// Scenarios per preset the 3D replay records by default (with 7 methods on 8 presets: about
/// 220 episodes, a replay.html of a few MB).
pub const DEFAULT_REPLAY_EPISODES: usize = 3;

/// The most worker threads a comparison takes.
pub const MAX_THREADS: usize = 256;

/// Worker threads when none are asked for: one per core.
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

impl CompareSpec {
    /// Refuses an empty or repeated preset list, zero episodes, an out-of-range episode and a
    /// thread count outside 1–[`MAX_THREADS`].
    pub fn check(&self) -> Result<(), CompareError> {
        let request = |m: String| Err(CompareError::Request(m));
        if self.presets.is_empty() {
            return request("no preset to compare on".into());
        }
        if let Some(dup) = self.presets.iter().enumerate().find_map(|(i, p)| {
            self.presets[..i]
                .iter()
                .any(|q| q.name == p.name)
                .then_some(p)
        }) {
            return request(format!("--preset {} is given twice", dup.name));
        }
        if let Some(p) = self
            .presets
            .iter()
            .find(|p| p.config.task.kind != self.presets[0].config.task.kind)
        {
            return request(format!(
                "--preset {} is a {} preset and {} a {} one: the two tasks have different \
                 scripts; compare each task's presets on their own",
                self.presets[0].name,
                self.presets[0].config.task.kind.name(),
                p.name,
                p.config.task.kind.name()
            ));
        }
        if self.episodes == 0 {
            return request("at least one episode per preset is needed".into());
        }
        if !(1..=MAX_THREADS).contains(&self.threads) {
            return request(format!("threads = {}: 1–{MAX_THREADS}", self.threads));
        }
        if let Some(k) = self.episode.filter(|&k| k >= self.episodes) {
            return request(format!(
                "--episode {k}: the scenario sets have {} episodes (0–{})",
                self.episodes,
                self.episodes - 1
            ));
        }
        Ok(())
    }
}

/// The presets `fairgrasp compare` compares on by default: the sector in front of the base
/// (`sector`), the full randomisation, the hard one, the four scenario families and the
/// contact family.
pub const DEFAULT_PRESETS: [&str; 8] = [
    "sector",
    "full",
    "hard",
    "miscalibrated",
    "miscalibrated_b",
    "nudged",
    "wrist_camera",
    "heavy_slippery",
];
