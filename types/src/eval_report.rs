//! One evaluated episode, and the summary of a policy's episodes on a scenario set.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::episode::EpisodeRecord;
use crate::names::Outcome;

/// A 95 % Wilson score interval for `successes` out of `n` (`(0, 1)` when `n` is 0).
pub fn wilson_interval(successes: usize, n: usize) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let (n, p, z) = (n as f64, successes as f64 / n as f64, 1.959_963_984_540_054);
    let denominator = 1.0 + z * z / n;
    let centre = (p + z * z / (2.0 * n)) / denominator;
    let half = z * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt() / denominator;
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

/// Success rate, its interval, the failure breakdown and step counts over a scenario set.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EvalReport {
    pub episodes: usize,
    pub successes: usize,
    /// `successes / episodes` (0 without episodes).
    pub success_rate: f64,
    /// 95 % Wilson interval of the success rate.
    pub ci_low: f64,
    pub ci_high: f64,
    /// Fraction of episodes that ended in a collision.
    pub collision_rate: f64,
    /// Mean steps of the successful episodes (`None` without any).
    pub mean_steps_to_success: Option<f64>,
    pub mean_return: f64,
    /// Mean cycle time of the successful episodes, reset to success \[s\] (`None` without any).
    #[serde(default)]
    pub mean_cycle_time_s: Option<f64>,
    /// The takt the episodes ran on \[s\] (`None`: a task without one).
    #[serde(default)]
    pub takt_s: Option<f64>,
    /// Successes within the takt (every success without a takt), their fraction and its 95 %
    /// Wilson interval.
    #[serde(default)]
    pub successes_within_takt: usize,
    #[serde(default)]
    pub within_takt_rate: f64,
    #[serde(default)]
    pub within_takt_ci_low: f64,
    #[serde(default)]
    pub within_takt_ci_high: f64,
    /// Episodes per outcome (outcomes with no episode may be absent).
    pub outcomes: BTreeMap<Outcome, usize>,
    pub results: Vec<EpisodeRecord>,
}

impl EvalReport {
    /// Summarises episode results.
    pub fn from_results(results: Vec<EpisodeRecord>) -> Self {
        let n = results.len();
        let mut outcomes = BTreeMap::new();
        for r in &results {
            *outcomes.entry(r.outcome).or_insert(0) += 1;
        }
        let count = |o: Outcome| outcomes.get(&o).copied().unwrap_or(0);
        let successes = count(Outcome::Success);
        let (ci_low, ci_high) = wilson_interval(successes, n);
        let success_steps: Vec<f64> = results
            .iter()
            .filter(|r| r.outcome == Outcome::Success)
            .map(|r| r.steps as f64)
            .collect();
        let rate = |k: usize| if n == 0 { 0.0 } else { k as f64 / n as f64 };
        let cycle_times: Vec<f64> = results.iter().filter_map(|r| r.cycle_time_s).collect();
        let within = results.iter().filter(|r| r.success_within_takt()).count();
        let (within_takt_ci_low, within_takt_ci_high) = wilson_interval(within, n);
        Self {
            episodes: n,
            successes,
            success_rate: rate(successes),
            ci_low,
            ci_high,
            collision_rate: rate(count(Outcome::Collision)),
            mean_steps_to_success: (!success_steps.is_empty())
                .then(|| success_steps.iter().sum::<f64>() / success_steps.len() as f64),
            mean_return: if n == 0 {
                0.0
            } else {
                results.iter().map(|r| r.episode_return).sum::<f64>() / n as f64
            },
            mean_cycle_time_s: (!cycle_times.is_empty())
                .then(|| cycle_times.iter().sum::<f64>() / cycle_times.len() as f64),
            takt_s: results.iter().find_map(|r| r.takt_s),
            successes_within_takt: within,
            within_takt_rate: rate(within),
            within_takt_ci_low,
            within_takt_ci_high,
            outcomes,
            results,
        }
    }

    /// The report with its cycle-time and takt summary taken from its episode records: what
    /// a file written before those fields existed is read as (its records carry no takt, so
    /// every success counts as within it). The other fields stay as read.
    pub fn with_takt_summary(self) -> Self {
        let summary = Self::from_results(self.results);
        Self {
            mean_cycle_time_s: summary.mean_cycle_time_s,
            takt_s: summary.takt_s,
            successes_within_takt: summary.successes_within_takt,
            within_takt_rate: summary.within_takt_rate,
            within_takt_ci_low: summary.within_takt_ci_low,
            within_takt_ci_high: summary.within_takt_ci_high,
            results: summary.results,
            ..self
        }
    }

    /// Episodes that ended with `outcome`.
    pub fn count(&self, outcome: Outcome) -> usize {
        self.outcomes.get(&outcome).copied().unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn episode(seed: u64, outcome: Outcome, steps: usize) -> EpisodeRecord {
        EpisodeRecord {
            seed,
            outcome,
            steps,
            episode_return: seed as f64,
            object_xy: [0.3, 0.0],
            collision_pair: None,
            cycle_time_s: (outcome == Outcome::Success).then_some(steps as f64 / 12.0),
            takt_s: Some(5.0),
            facts: crate::EpisodeFacts::default(),
        }
        .normalized()
    }

    #[test]
    fn wilson_interval_matches_a_hand_computation_and_stays_in_0_1() {
        // 8 of 10 (z = 1.95996): centre (0.8 + 0.19207)/1.38415 = 0.71674, half 0.31362/1.38415 = 0.22658.
        let (lo, hi) = wilson_interval(8, 10);
        assert!(
            (lo - 0.4902).abs() < 1e-3 && (hi - 0.9433).abs() < 1e-3,
            "{lo} {hi}"
        );
        let (lo, hi) = wilson_interval(0, 5);
        assert_eq!(lo, 0.0);
        assert!(hi > 0.4 && hi < 0.5, "{hi}");
        assert_eq!(wilson_interval(0, 0), (0.0, 1.0));
    }

    #[test]
    fn a_report_counts_outcomes_and_averages_steps_of_successes_only() {
        let r = EvalReport::from_results(vec![
            episode(0, Outcome::Success, 60),
            episode(1, Outcome::Collision, 10),
            episode(2, Outcome::Success, 80),
            episode(3, Outcome::Timeout, 200),
        ]);
        assert_eq!((r.episodes, r.successes), (4, 2));
        assert_eq!(r.success_rate, 0.5);
        assert_eq!(r.collision_rate, 0.25);
        assert_eq!(r.mean_steps_to_success, Some(70.0));
        assert_eq!(r.mean_return, 1.5);
        assert_eq!(r.count(Outcome::Timeout), 1);
        assert_eq!(r.count(Outcome::IkFailure), 0);
        // Cycle times 5 s and 6.67 s: the second is past the 5 s takt.
        let cycle = r.mean_cycle_time_s.unwrap();
        assert!((cycle - 70.0 / 12.0).abs() < 1e-12, "{cycle}");
        assert_eq!((r.takt_s, r.successes_within_takt), (Some(5.0), 1));
        assert_eq!(r.within_takt_rate, 0.25);
        assert_eq!(
            (r.within_takt_ci_low, r.within_takt_ci_high),
            wilson_interval(1, 4)
        );
        let empty = EvalReport::from_results(Vec::new());
        assert_eq!(
            (empty.success_rate, empty.mean_steps_to_success),
            (0.0, None)
        );
    }

    #[test]
    fn a_report_survives_a_json_round_trip() {
        let r = EvalReport::from_results(vec![
            episode(7, Outcome::SlipOrDrop, 90),
            episode(8, Outcome::Success, 61),
        ]);
        let text = serde_json::to_string(&r).unwrap();
        assert!(text.contains("\"slip_or_drop\":1"), "{text}");
        assert_eq!(serde_json::from_str::<EvalReport>(&text).unwrap(), r);
    }
}
