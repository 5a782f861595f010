//! A comparison of methods on presets: what `compare.json` holds.

use std::collections::BTreeMap;
use std::fmt;

use serde::{Deserialize, Serialize};

use crate::eval_report::EvalReport;
use crate::names::{ArmSimulation, Outcome};

/// One method evaluated on one preset's scenario set.
///
/// In JSON the report's fields sit beside the method's (one flat object per result).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MethodResult {
    pub method: String,
    pub preset: String,
    /// Arm simulation.
    pub arm: ArmSimulation,
    /// Seed of the scenario set (the same for every method).
    pub seed: u64,
    /// Checkpoint folder of a learned policy (`None` for the scripted baseline).
    #[serde(default)]
    pub policy: Option<String>,
    /// Success rate, interval, outcomes and every episode.
    #[serde(flatten)]
    pub report: EvalReport,
}

/// A recorded episode kept with the comparison (for the episode charts and replays).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RecordedEpisode {
    pub method: String,
    pub preset: String,
    /// Index of the scenario in the preset's set.
    pub episode: usize,
    pub outcome: Outcome,
    /// Trajectory JSON, relative to the comparison folder.
    pub trajectory: String,
}

/// How a hand-written control with parameters was set for one preset of a comparison.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ControlTuning {
    pub preset: String,
    /// The control's name in the comparison.
    pub method: String,
    /// How its setting was found (`CMA-ES (cmaes 0.2.2), 80 trials × 150 episodes of seed 11,
    /// 3.01 M env steps; success within the takt`), or that the preset's own setting runs.
    pub how: String,
    /// The tuning's trials on its training scenarios, as (mean cycle time of the successes
    /// \[s\], objective as a fraction), where they are known.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub trials: Vec<[f64; 2]>,
}

/// Everything `fairgrasp compare` measured: `compare.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    /// The command line that produced it.
    pub command: String,
    /// Presets in run order.
    pub presets: Vec<String>,
    /// Methods in run order.
    pub methods: Vec<String>,
    /// Environment config (TOML) of each preset.
    pub preset_configs: BTreeMap<String, String>,
    /// Run folders of the learned policies (with metrics.csv), for learning curves.
    #[serde(default)]
    pub run_folders: Vec<String>,
    #[serde(default)]
    pub recorded: Vec<RecordedEpisode>,
    /// Episodes recorded for the 3D replay (`replay.html`): every method on the first
    /// scenarios of the last preset, and on the `recorded` one (empty in older files: the
    /// replay then shows the `recorded` episodes).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub replay: Vec<RecordedEpisode>,
    /// How each control with parameters was set, per preset (empty in older files).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tuning: Vec<ControlTuning>,
    pub results: Vec<MethodResult>,
}

/// A `compare.json` that does not parse or whose numbers disagree with each other.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SchemaError(pub String);

impl fmt::Display for SchemaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SchemaError {}

impl Comparison {
    /// Parses and checks the text of a `compare.json`.
    pub fn from_json(text: &str) -> Result<Self, SchemaError> {
        let mut c: Self = serde_json::from_str(text)
            .map_err(|e| SchemaError(format!("not a fairgrasp compare.json: {e}")))?;
        c.check()?;
        // The cycle-time summary follows from the records (files from before it have none).
        for r in &mut c.results {
            r.report = std::mem::replace(&mut r.report, EvalReport::from_results(Vec::new()))
                .with_takt_summary();
        }
        Ok(c)
    }

    /// The comparison as compact JSON (every episode's record: indentation would add 70 %).
    pub fn to_json(&self) -> String {
        // Plain data with string map keys: serialising cannot fail.
        serde_json::to_string(self).unwrap_or_default()
    }

    /// Internal consistency: counts add up, rates match counts, every method and preset of a
    /// result or a recorded episode is listed.
    pub fn check(&self) -> Result<(), SchemaError> {
        for r in &self.results {
            let name = format!("result `{}` on `{}`", r.method, r.preset);
            let e = &r.report;
            if e.results.len() != e.episodes {
                return Err(SchemaError(format!(
                    "{name}: episodes = {} but {} episode records",
                    e.episodes,
                    e.results.len()
                )));
            }
            if e.outcomes.values().sum::<usize>() != e.episodes {
                return Err(SchemaError(format!(
                    "{name}: outcome counts do not add up to {}",
                    e.episodes
                )));
            }
            if e.episodes > 0
                && (e.success_rate - e.successes as f64 / e.episodes as f64).abs() > 1e-9
            {
                return Err(SchemaError(format!(
                    "{name}: success_rate {} ≠ successes/episodes",
                    e.success_rate
                )));
            }
        }
        let listed = |method: &str, preset: &str| {
            self.methods.iter().any(|m| m == method) && self.presets.iter().any(|p| p == preset)
        };
        if let Some(r) = self.results.iter().find(|r| !listed(&r.method, &r.preset)) {
            return Err(SchemaError(format!(
                "result `{}` on `{}`: method or preset not listed in `methods`/`presets`",
                r.method, r.preset
            )));
        }
        if let Some(r) = self
            .recorded
            .iter()
            .chain(&self.replay)
            .find(|r| !listed(&r.method, &r.preset))
        {
            return Err(SchemaError(format!(
                "recorded episode of `{}` on `{}`: method or preset not listed",
                r.method, r.preset
            )));
        }
        // Paths are read relative to the comparison's folder: only plain names below it.
        let inside = |p: &str| {
            !p.is_empty()
                && std::path::Path::new(p)
                    .components()
                    .all(|c| matches!(c, std::path::Component::Normal(_)))
        };
        if let Some(r) = self
            .recorded
            .iter()
            .chain(&self.replay)
            .find(|r| !inside(&r.trajectory))
        {
            let shown: String = r.trajectory.chars().take(80).collect();
            return Err(SchemaError(format!(
                "recorded episode of `{}` on `{}`: trajectory `{shown}` is not a path inside the comparison folder (absolute paths and `..` are refused)",
                r.method, r.preset
            )));
        }
        Ok(())
    }

    /// Adds a method evaluated outside the comparison (a Python policy) on each preset's very
    /// scenario list: `results` holds one preset's episode records, whose seeds must be the
    /// scripts' there, in order (so the paired tests pair the same scenarios). `policy` says
    /// where the method came from (it marks the method as learned in the paired tests).
    pub fn add_method(
        &mut self,
        method: &str,
        policy: &str,
        results: Vec<(String, Vec<crate::EpisodeRecord>)>,
    ) -> Result<(), SchemaError> {
        if method.trim().is_empty() || self.methods.iter().any(|m| m == method) {
            return Err(SchemaError(format!(
                "method `{method}`: the name is empty or already taken (methods: {})",
                self.methods.join(", ")
            )));
        }
        let mut added = Vec::new();
        for (preset, records) in results {
            let Some(script) = self
                .results
                .iter()
                .find(|r| r.preset == preset && r.policy.is_none())
            else {
                return Err(SchemaError(format!(
                    "method `{method}`: preset `{preset}` is not in this comparison ({})",
                    self.presets.join(", ")
                )));
            };
            let expected: Vec<u64> = script.report.results.iter().map(|r| r.seed).collect();
            let found: Vec<u64> = records.iter().map(|r| r.seed).collect();
            if expected != found {
                return Err(SchemaError(format!(
                    "method `{method}` on `{preset}`: its {} episodes are not the comparison's {} scenarios (seeds differ)",
                    found.len(),
                    expected.len()
                )));
            }
            added.push(MethodResult {
                method: method.to_string(),
                preset,
                arm: script.arm,
                seed: script.seed,
                policy: Some(policy.to_string()),
                report: EvalReport::from_results(records),
            });
        }
        let mut covered: Vec<&str> = added.iter().map(|r| r.preset.as_str()).collect();
        covered.sort_unstable();
        covered.dedup();
        if covered.len() != added.len() || covered.len() != self.presets.len() {
            return Err(SchemaError(format!(
                "method `{method}`: needs one result per preset of the comparison ({}), got {}",
                self.presets.join(", "),
                added.len()
            )));
        }
        self.methods.push(method.to_string());
        self.results.extend(added);
        self.check()
    }

    /// The result of `method` on `preset`.
    pub fn get(&self, method: &str, preset: &str) -> Option<&MethodResult> {
        self.results
            .iter()
            .find(|r| r.method == method && r.preset == preset)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A compare.json as fairgrasp wrote it before this crate existed (flat results, string
    /// outcomes), cut to one result of two episodes.
    const FLAT: &str = r#"{
      "command": "fairgrasp compare --episodes 2", "presets": ["sector"],
      "methods": ["scripted baseline"], "preset_configs": {"sector": "[physics]\n"},
      "run_folders": [],
      "recorded": [{"method": "scripted baseline", "preset": "sector", "episode": 1,
                    "outcome": "collision", "trajectory": "episodes/x.json"}],
      "results": [{
        "method": "scripted baseline", "preset": "sector", "arm": "servo", "seed": 0,
        "episodes": 2, "successes": 1, "success_rate": 0.5, "ci_low": 0.09, "ci_high": 0.91,
        "collision_rate": 0.5, "mean_steps_to_success": 61.0, "mean_return": 4.5,
        "outcomes": {"success": 1, "collision": 1}, "policy": null,
        "results": [
          {"seed": 0, "outcome": "success", "steps": 61, "episode_return": 10.0, "object_xy": [0.3, 0.0]},
          {"seed": 1, "outcome": "collision", "steps": 9, "episode_return": -1.0, "object_xy": [0.25, 0.1]}
        ]
      }]
    }"#;

    #[test]
    fn a_flat_compare_json_parses_into_typed_results_and_writes_back_flat() {
        let c = Comparison::from_json(FLAT).unwrap();
        let r = &c.results[0];
        assert_eq!(r.arm, ArmSimulation::Servo);
        assert_eq!(r.report.count(Outcome::Collision), 1);
        assert_eq!(r.report.results[1].outcome, Outcome::Collision);
        assert_eq!(c.recorded[0].outcome, Outcome::Collision);
        let v: serde_json::Value = serde_json::from_str(&c.to_json()).unwrap();
        assert_eq!(
            v["results"][0]["success_rate"], 0.5,
            "report fields stay flat"
        );
        assert!(v["results"][0].get("report").is_none());
        assert_eq!(Comparison::from_json(&c.to_json()).unwrap(), c);
    }

    #[test]
    fn an_unknown_outcome_or_inconsistent_counts_are_refused() {
        let e = Comparison::from_json(
            &FLAT.replace("\"collision\", \"steps\"", "\"teleported\", \"steps\""),
        )
        .unwrap_err();
        assert!(e.0.contains("teleported"), "{e}");
        let e = Comparison::from_json(&FLAT.replace("\"successes\": 1", "\"successes\": 2"))
            .unwrap_err();
        assert!(e.0.contains("success_rate"), "{e}");
        let e = Comparison::from_json(&FLAT.replace("\"collision\": 1}", "\"collision\": 2}"))
            .unwrap_err();
        assert!(e.0.contains("do not add up"), "{e}");
        let e = Comparison::from_json(
            &FLAT.replace("\"methods\": [\"scripted baseline\"]", "\"methods\": []"),
        )
        .unwrap_err();
        assert!(e.0.contains("not listed"), "{e}");
    }

    #[test]
    fn recorded_paths_outside_the_comparison_folder_are_refused() {
        let base = FLAT;
        for bad in [
            "/etc/passwd",
            "../../secret.json",
            "episodes/../../x.json",
            "",
        ] {
            let text = base.replace("episodes/x.json", bad);
            let e = Comparison::from_json(&text).unwrap_err();
            assert!(
                e.0.contains("not a path inside the comparison folder"),
                "{bad}: {e:?}"
            );
        }
        assert!(Comparison::from_json(&base.replace("episodes/x.json", "a/b/c.json")).is_ok());
    }
}
