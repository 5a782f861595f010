//! The training recipes shipped in `assets/experiments/`, built into every binary that links
//! this crate (Python's `fairgrasp.make(recipe=...)` and `fairgrasp.train` find them after a
//! `pip install`, with no path from the build machine).

use std::path::Path;

use fairgrasp_env::{ConfigError, TaskKind};

/// Name (the file's stem) and text of every shipped recipe, in name order.
pub const SHIPPED: [(&str, &str); 15] = [
    (
        "joint_residual_nudged",
        include_str!("../../assets/experiments/joint_residual_nudged.toml"),
    ),
    (
        "joint_residual_wrist_camera",
        include_str!("../../assets/experiments/joint_residual_wrist_camera.toml"),
    ),
    (
        "pure_full",
        include_str!("../../assets/experiments/pure_full.toml"),
    ),
    (
        "pure_full_10min",
        include_str!("../../assets/experiments/pure_full_10min.toml"),
    ),
    (
        "pure_joint_full",
        include_str!("../../assets/experiments/pure_joint_full.toml"),
    ),
    (
        "pure_tcp_distancereward_full",
        include_str!("../../assets/experiments/pure_tcp_distancereward_full.toml"),
    ),
    (
        "residual_generalist",
        include_str!("../../assets/experiments/residual_generalist.toml"),
    ),
    (
        "residual_generalist_ppo_only",
        include_str!("../../assets/experiments/residual_generalist_ppo_only.toml"),
    ),
    (
        "residual_heavy_slippery",
        include_str!("../../assets/experiments/residual_heavy_slippery.toml"),
    ),
    (
        "residual_miscalibrated",
        include_str!("../../assets/experiments/residual_miscalibrated.toml"),
    ),
    (
        "residual_place_cell",
        include_str!("../../assets/experiments/residual_place_cell.toml"),
    ),
    (
        "residual_place_grasp_error",
        include_str!("../../assets/experiments/residual_place_grasp_error.toml"),
    ),
    (
        "residual_place_tilted",
        include_str!("../../assets/experiments/residual_place_tilted.toml"),
    ),
    (
        "residual_stack",
        include_str!("../../assets/experiments/residual_stack.toml"),
    ),
    (
        "residual_wrist_camera",
        include_str!("../../assets/experiments/residual_wrist_camera.toml"),
    ),
];

/// The names of the shipped recipes.
pub fn names() -> Vec<&'static str> {
    SHIPPED.iter().map(|(name, _)| *name).collect()
}

/// The shipped recipe of the task-space residual for the preset `preset` (what Python's
/// `FairGrasp-Residual-<Preset>-v0` trains with, `preset` laid over it): the squeeze's on
/// `heavy_slippery`, the wrist-view family's on `wrist_camera`, `place_tilted`'s and
/// `place_cell`'s own, and elsewhere the residual recipe of the preset's task (`task`, its
/// [`TaskSpec::residual_recipe`](fairgrasp_env::config::task::TaskSpec::residual_recipe)).
pub fn task_residual_recipe(preset: &str, task: TaskKind) -> &'static str {
    match preset {
        "place_tilted" => "residual_place_tilted",
        "place_cell" => "residual_place_cell",
        "heavy_slippery" => "residual_heavy_slippery",
        "wrist_camera" => "residual_wrist_camera",
        _ => task.spec().residual_recipe,
    }
}

/// The text of a recipe given by a shipped name or a path to a training config (.toml), and
/// how to name it in messages; an unknown name lists the shipped ones.
pub fn text(name_or_path: &str) -> Result<(String, String), ConfigError> {
    if let Some((name, text)) = SHIPPED.iter().find(|(n, _)| *n == name_or_path) {
        return Ok((text.to_string(), format!("recipe {name}")));
    }
    let path = Path::new(name_or_path);
    if path.extension().is_some_and(|e| e == "toml") || path.exists() {
        let text =
            fairgrasp_types::fs::read_text_bounded(path, fairgrasp_types::fs::MAX_CONFIG_BYTES)
                .map_err(|e| ConfigError::File {
                    path: name_or_path.to_string(),
                    message: e.to_string(),
                })?;
        return Ok((text, name_or_path.to_string()));
    }
    Err(ConfigError::File {
        path: name_or_path.to_string(),
        message: format!(
            "no such recipe: give one of {} or a training config's .toml path",
            names().join(", ")
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recipe::{EnvFor, Recipe};

    #[test]
    fn every_shipped_recipe_is_a_file_of_assets_experiments_and_parses() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/experiments");
        let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
            .collect();
        on_disk.sort();
        assert_eq!(
            on_disk,
            names(),
            "SHIPPED must list assets/experiments/*.toml"
        );
        for (name, text) in SHIPPED {
            let r = Recipe::with_overrides(text, name, &toml::Table::new(), &[]).unwrap();
            r.env_configs(EnvFor::Training).unwrap();
        }
    }

    #[test]
    fn overrides_merge_remove_and_refuse_misspelt_keys() {
        let (body, what) = text("pure_full").unwrap();
        let overrides: toml::Table =
            toml::from_str("preset = \"sector\"\nenv = { task = { max_steps = 50 } }").unwrap();
        let r = Recipe::with_overrides(&body, &what, &overrides, &[]).unwrap();
        assert_eq!(r.preset, "sector");
        let env = r.env_configs(EnvFor::Training).unwrap().remove(0);
        assert_eq!(env.task.max_steps, 50);
        // The recipe's other [env.task] settings stay.
        assert!(!env.task.terminate_on_collision);
        let plain =
            Recipe::with_overrides(&body, &what, &toml::Table::new(), &["env".into()]).unwrap();
        assert_eq!(plain.env, None);
        assert!(plain.curriculum.is_some());
        let bad: toml::Table = toml::from_str("preet = \"sector\"").unwrap();
        let e = Recipe::with_overrides(&body, &what, &bad, &[])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("preet") && e.contains("preset, arm, agent, curriculum, env"),
            "{e}"
        );
        let e = text_err("no_such_recipe");
        assert!(
            e.contains("pure_full") && e.contains("residual_miscalibrated"),
            "{e}"
        );
    }

    fn text_err(name: &str) -> String {
        text(name).unwrap_err().to_string()
    }
}
