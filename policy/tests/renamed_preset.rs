//! A recipe naming a renamed preset by its old name (`preset = "seed"`, now `sector`) still
//! loads, as the current name, wherever a recipe is read (a file, a run's saved config, Python's
//! keyword overrides), and the reader can tell which old names the file gave.

use fairgrasp_policy::recipe::read::old_preset_names_in;
use fairgrasp_policy::recipe::{EnvFor, Recipe};

#[test]
fn a_recipe_with_the_old_preset_name_loads_as_the_current_one_and_says_so() {
    let dir = std::env::temp_dir().join(format!("fairgrasp_renamed_preset_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let old = dir.join("old.toml");
    let new = dir.join("new.toml");
    std::fs::write(
        &old,
        "preset = \"seed\"\nmix = [\"full\", \"seed\"]\nn_envs = 4\n",
    )
    .unwrap();
    std::fs::write(
        &new,
        "preset = \"sector\"\nmix = [\"full\", \"sector\"]\nn_envs = 4\n",
    )
    .unwrap();
    let from_old = Recipe::from_toml_file(&old).unwrap();
    assert_eq!(from_old.preset, "sector");
    assert_eq!(from_old.mix, ["full", "sector"]);
    assert_eq!(from_old, Recipe::from_toml_file(&new).unwrap());
    assert_eq!(
        from_old.env_configs(EnvFor::Evaluation).unwrap(),
        Recipe::from_toml_file(&new)
            .unwrap()
            .env_configs(EnvFor::Evaluation)
            .unwrap()
    );
    // Written back (a run's config.toml) with the current name only.
    let written = toml::to_string(&from_old).unwrap();
    assert!(written.contains("preset = \"sector\""), "{written}");
    assert!(!written.contains("\"seed\""), "{written}");
    assert_eq!(old_preset_names_in(&old), ["seed", "seed"]);
    assert!(old_preset_names_in(&new).is_empty());
    assert!(old_preset_names_in(&dir.join("missing.toml")).is_empty());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_keyword_override_with_the_old_preset_name_gives_the_current_one() {
    let overrides: toml::Table = toml::from_str("preset = \"seed\"").unwrap();
    let r = Recipe::with_overrides("", "r.toml", &overrides, &[]).unwrap();
    assert_eq!(r.preset, "sector");
}
