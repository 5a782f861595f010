//! Paired comparisons of two methods on the same scenarios: McNemar's exact test.
//!
//! Two methods run on one scenario list succeed or fail on each scenario. Only the discordant
//! scenarios carry information about which is better: `only_a` (A succeeded, B failed) and
//! `only_b`. Under "equally good" each discordant scenario is a fair coin, so the two-sided
//! p-value is `min(1, 2·P[Bin(n, ½) ≤ min(only_a, only_b)])`, `n = only_a + only_b` (exact; no
//! χ² approximation, which is poor for the handful of discordant pairs two good methods leave).

use serde::{Deserialize, Serialize};

use crate::comparison::{Comparison, MethodResult};

/// McNemar's exact two-sided p-value for `only_a` and `only_b` discordant pairs (1 without any).
pub fn mcnemar_exact(only_a: usize, only_b: usize) -> f64 {
    let n = only_a + only_b;
    let k = only_a.min(only_b);
    // Σ_{i ≤ k} C(n, i) / 2ⁿ, summed in log space so that n in the thousands cannot underflow.
    let mut log_pmf = -(n as f64) * std::f64::consts::LN_2;
    let mut tail = 0.0;
    for i in 0..=k {
        tail += log_pmf.exp();
        log_pmf += ((n - i) as f64).ln() - ((i + 1) as f64).ln();
    }
    (2.0 * tail).min(1.0)
}

/// Method A against method B on one preset's scenario list.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PairedTest {
    pub preset: String,
    pub a: String,
    pub b: String,
    /// Scenarios in the pair.
    pub episodes: usize,
    /// Successes of A and of B.
    pub successes_a: usize,
    pub successes_b: usize,
    /// Scenarios only A succeeded on, and only B.
    pub only_a: usize,
    pub only_b: usize,
    /// McNemar's exact two-sided p-value.
    pub p_value: f64,
}

/// Why two results cannot be paired.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PairingError {
    pub preset: String,
    pub a: String,
    pub b: String,
    pub why: String,
}

impl std::fmt::Display for PairingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} and {} on {}: {}",
            self.a, self.b, self.preset, self.why
        )
    }
}

impl std::error::Error for PairingError {}

/// Pairs two results scenario by scenario (same preset, same seeds in the same order), on
/// success within the task's takt (on a task without one, every success counts).
pub fn paired_test(a: &MethodResult, b: &MethodResult) -> Result<PairedTest, PairingError> {
    let error = |why: String| PairingError {
        preset: a.preset.clone(),
        a: a.method.clone(),
        b: b.method.clone(),
        why,
    };
    if a.preset != b.preset {
        return Err(error(format!(
            "different presets ({} vs {})",
            a.preset, b.preset
        )));
    }
    let (ra, rb) = (&a.report.results, &b.report.results);
    if ra.len() != rb.len() {
        return Err(error(format!("{} vs {} episodes", ra.len(), rb.len())));
    }
    let (mut only_a, mut only_b) = (0, 0);
    for (k, (x, y)) in ra.iter().zip(rb).enumerate() {
        if x.seed != y.seed {
            return Err(error(format!(
                "episode {k} has scenario seed {} vs {}",
                x.seed, y.seed
            )));
        }
        match (x.success_within_takt(), y.success_within_takt()) {
            (true, false) => only_a += 1,
            (false, true) => only_b += 1,
            _ => {}
        }
    }
    let successes = |r: &MethodResult| {
        r.report
            .results
            .iter()
            .filter(|e| e.success_within_takt())
            .count()
    };
    Ok(PairedTest {
        preset: a.preset.clone(),
        a: a.method.clone(),
        b: b.method.clone(),
        episodes: ra.len(),
        successes_a: successes(a),
        successes_b: successes(b),
        only_a,
        only_b,
        p_value: mcnemar_exact(only_a, only_b),
    })
}

/// Every learned method (a result with a policy folder) against every script (a result
/// without one), preset by preset, in the comparison's order.
pub fn learned_vs_scripts(c: &Comparison) -> Result<Vec<PairedTest>, PairingError> {
    let mut out = Vec::new();
    for preset in &c.presets {
        let here: Vec<&MethodResult> = c.results.iter().filter(|r| &r.preset == preset).collect();
        for learned in here.iter().filter(|r| r.policy.is_some()) {
            for script in here.iter().filter(|r| r.policy.is_none()) {
                out.push(paired_test(learned, script)?);
            }
        }
    }
    Ok(out)
}

/// Does `method` see the truth (the oracle script: the cube's true pose; the oracle switch: each
/// cycle's family)? Such a method is a ceiling, never the control a learned method is measured
/// against: that control uses the same information as the learned method.
pub fn sees_the_truth(method: &str) -> bool {
    method.contains("oracle")
}

/// The script a learned method must beat on one preset's results `here`: the one with the most
/// successes (within the takt, on a task with one) among those that do not see the truth
/// ([`sees_the_truth`]); on a tie the first in the comparison's order (the simplest, as the
/// scripts are listed from the open loop up).
pub fn best_script<'a>(here: &[&'a MethodResult]) -> Option<&'a MethodResult> {
    let mut best: Option<&MethodResult> = None;
    for r in here
        .iter()
        .filter(|r| r.policy.is_none() && !sees_the_truth(&r.method))
    {
        let within = |m: &MethodResult| m.report.successes_within_takt;
        if best.is_none_or(|b| within(r) > within(b)) {
            best = Some(r);
        }
    }
    best
}

/// The paired tests a report leads with: every learned method against the open-loop baseline
/// (the first script) and against the preset's best script ([`best_script`]; once when they
/// are the same), preset by preset, in the comparison's order.
pub fn learned_vs_key_scripts(c: &Comparison) -> Result<Vec<PairedTest>, PairingError> {
    let mut out = Vec::new();
    for preset in &c.presets {
        let here: Vec<&MethodResult> = c.results.iter().filter(|r| &r.preset == preset).collect();
        let baseline = here.iter().find(|r| r.policy.is_none());
        let best = best_script(&here);
        for learned in here.iter().filter(|r| r.policy.is_some()) {
            if let Some(b) = baseline {
                out.push(paired_test(learned, b)?);
            }
            if let Some(best) = best.filter(|s| baseline.is_none_or(|b| b.method != s.method)) {
                out.push(paired_test(learned, best)?);
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_p_values_match_the_binomial_tail() {
        // No discordant pair: no evidence.
        assert_eq!(mcnemar_exact(0, 0), 1.0);
        // 5 vs 0: 2 · (1/2)^5 = 0.0625.
        assert!((mcnemar_exact(5, 0) - 0.0625).abs() < 1e-12);
        assert_eq!(mcnemar_exact(5, 0), mcnemar_exact(0, 5));
        // 10 vs 2: 2 · (1 + 12 + 66) / 4096.
        assert!((mcnemar_exact(10, 2) - 2.0 * 79.0 / 4096.0).abs() < 1e-12);
        // Balanced: p = 1.
        assert_eq!(mcnemar_exact(7, 7), 1.0);
        // Large n stays finite and tiny: 100 vs 0.
        let p = mcnemar_exact(100, 0);
        assert!(p > 0.0 && (p - 2.0 * 0.5f64.powi(100)).abs() < 1e-40, "{p}");
        let big = mcnemar_exact(2000, 1900);
        assert!(big.is_finite() && big > 0.0 && big < 0.2, "{big}");
    }
}
