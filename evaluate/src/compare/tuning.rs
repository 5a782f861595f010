//! How each control with parameters was set for each preset of a comparison
//! ([`ControlTuning`]): the `fairgrasp tune` record a preset carries (`[control.tuned.<control>]`),
//! with the tuning's trials where the repository ships them (`assets/tuned/`), or that the
//! preset's own setting runs.

use fairgrasp_planner::controls::Control;
use fairgrasp_types::ControlTuning;

use crate::compare::spec::CompareSpec;

/// The trials of the shipped tunings, as `fairgrasp tune` wrote them: (preset, control, CSV).
const SHIPPED_TRIALS: [(&str, &str, &str); 3] = [
    (
        "place_cell",
        "force_search",
        include_str!("../../../assets/tuned/place_cell/force_search_trials.csv"),
    ),
    (
        "place_cell",
        "square_search",
        include_str!("../../../assets/tuned/place_cell/square_search_trials.csv"),
    ),
    (
        "place_cell",
        "switch_search",
        include_str!("../../../assets/tuned/place_cell/switch_search_trials.csv"),
    ),
];

/// The tuning of every control with parameters on every preset of `spec`.
pub(crate) fn of_controls(spec: &CompareSpec, scripts: &[&'static Control]) -> Vec<ControlTuning> {
    let mut out = Vec::new();
    for preset in &spec.presets {
        for control in scripts.iter().filter(|c| !c.params.is_empty()) {
            let note = preset.config.control.tuned.get(control.cli);
            let how = match note {
                Some(n) => format!("{}; {}", crate::tune::fragment::summary(n), n.objective),
                None => "the preset's own setting (no `fairgrasp tune` record)".to_string(),
            };
            let trials = note
                .and_then(|n| {
                    SHIPPED_TRIALS
                        .iter()
                        .find(|(p, c, _)| *p == n.preset && *c == control.cli)
                })
                .map_or_else(Vec::new, |(_, _, csv)| trial_points(csv));
            out.push(ControlTuning {
                preset: preset.name.clone(),
                method: control.report.to_string(),
                how,
                trials,
            });
        }
    }
    out
}

/// (mean cycle time \[s\], objective) of every trial of a `trials.csv` that has both.
pub fn trial_points(csv: &str) -> Vec<[f64; 2]> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name);
    let (Some(objective), Some(cycle)) = (column("objective"), column("mean_cycle_time_s")) else {
        return Vec::new();
    };
    lines
        .filter_map(|line| {
            let cells: Vec<&str> = line.split(',').collect();
            let value = |k: usize| cells.get(k).and_then(|c| c.parse::<f64>().ok());
            Some([value(cycle)?, value(objective)?])
        })
        .collect()
}
