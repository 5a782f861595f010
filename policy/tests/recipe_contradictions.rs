//! A recipe whose settings contradict each other is refused at load naming both keys
//! (issue 50 item 6); the shipped recipes and the shipped policies' saved configs, which write
//! every key at its default, still load.

use std::path::Path;

use fairgrasp_policy::recipe::Recipe;

/// The message `Recipe::validate` gives for `text` (a recipe file's content).
fn refusal(text: &str) -> String {
    let recipe: Recipe = toml::from_str(text).unwrap_or_else(|e| panic!("{text}: {e}"));
    match recipe.validate() {
        Ok(()) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

fn names_both(text: &str, first: &str, second: &str) {
    let message = refusal(text);
    assert!(
        message.contains(first) && message.contains(second),
        "{message}"
    );
    assert!(message.contains("contradicts"), "{message}");
    assert!(
        message.len() < 400,
        "{} characters: {message}",
        message.len()
    );
}

#[test]
fn a_residual_scale_on_a_pure_policy_is_refused() {
    names_both(
        "[agent]\nmode = \"pure\"\nresidual_scale = 0.5\n",
        "agent.residual_scale = 0.5",
        "agent.mode = \"pure\"",
    );
}

#[test]
fn a_learned_gripper_on_a_pure_policy_is_refused() {
    names_both(
        "[agent]\nmode = \"pure\"\naction_space = \"tcp\"\ngripper = \"learned\"\n",
        "agent.gripper = \"learned\"",
        "agent.mode = \"pure\"",
    );
}

#[test]
fn a_residual_scale_on_a_task_space_residual_is_refused() {
    names_both(
        "[agent]\naction_space = \"tcp\"\nresidual_scale = 1.0\n",
        "agent.residual_scale = 1",
        "agent.action_space = \"tcp\"",
    );
}

#[test]
fn a_learned_gripper_on_a_task_space_residual_is_refused() {
    names_both(
        "[agent]\naction_space = \"tcp\"\ngripper = \"learned\"\n",
        "agent.gripper = \"learned\"",
        "agent.action_space = \"tcp\"",
    );
}

#[test]
fn an_env_arm_model_other_than_the_recipes_arm_is_refused() {
    names_both(
        "arm = \"servo\"\n[env.arm]\nmodel = \"multibody\"\n",
        "env.arm.model = \"multibody\"",
        "arm = \"servo\"",
    );
}

#[test]
fn task_space_arm_settings_are_refused_for_an_agent_that_does_not_use_them() {
    for key in [
        "tcp_speed = 0.3",
        "tcp_yaw_rate = 2.0",
        "tcp_saturation = \"action_scale\"",
        "gripper_command = \"binary\"",
    ] {
        for agent in ["", "mode = \"pure\"\n", "action_space = \"tcp\"\n"] {
            let name = key.split(' ').next().unwrap();
            names_both(
                &format!("[agent]\n{agent}[env.arm]\n{key}\n"),
                &format!("env.arm.{name}"),
                "agent.mode",
            );
        }
    }
}

#[test]
fn arm_settings_a_pure_tcp_agent_overrides_are_refused() {
    let pure_tcp = "[agent]\nmode = \"pure\"\naction_space = \"tcp\"\n";
    names_both(
        &format!("{pure_tcp}[env.arm]\ngripper_command = \"continuous\"\n"),
        "env.arm.gripper_command = \"continuous\"",
        "agent.action_space = \"tcp\"",
    );
    names_both(
        &format!("{pure_tcp}[env.arm]\ntcp_saturation = \"joint_limits\"\n"),
        "env.arm.tcp_saturation = \"joint_limits\"",
        "agent.action_space = \"tcp\"",
    );
    // What the agent drives anyway, and the speeds it reads, are no contradiction.
    for same in [
        "gripper_command = \"binary\"",
        "tcp_saturation = \"action_scale\"",
        "tcp_speed = 0.3",
    ] {
        let text = format!("{pure_tcp}[env.arm]\n{same}\n");
        let recipe: Recipe = toml::from_str(&text).unwrap();
        assert_eq!(recipe.validate(), Ok(()), "{text}");
    }
}

#[test]
fn a_warm_up_as_long_as_a_shortened_run_is_no_contradiction() {
    // `train --timesteps 2048` shortens a recipe for a smoke run (the guides, the Python tests):
    // its critic-only updates may then cover the run; that is asked for, not contradictory.
    let text =
        "total_timesteps = 2048\ncritic_warmup_updates = 5\nn_envs = 4\n[ppo]\nn_steps = 512\n";
    let recipe: Recipe = toml::from_str(text).unwrap();
    assert_eq!(recipe.validate(), Ok(()));
}

#[test]
fn the_shipped_recipes_and_saved_configs_load() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for entry in std::fs::read_dir(root.join("assets/experiments")).unwrap() {
        files.push(entry.unwrap().path());
    }
    for entry in std::fs::read_dir(root.join("assets/policies")).unwrap() {
        files.push(entry.unwrap().path().join("config.toml"));
    }
    files.retain(|f| f.extension().is_some_and(|e| e == "toml") && f.is_file());
    assert!(files.len() >= 20, "{files:?}");
    for f in files {
        if let Err(e) = Recipe::from_toml_file(&f) {
            panic!("{}: {e}", f.display());
        }
    }
}

#[test]
fn keyword_overrides_that_contradict_the_recipe_are_refused_too() {
    // Python's envs lay keyword overrides over a recipe: the same rule applies.
    let overrides: toml::Table = toml::from_str("agent = {mode = \"pure\"}").unwrap();
    let e = Recipe::with_overrides("[agent]\nresidual_scale = 0.5\n", "r.toml", &overrides, &[])
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("r.toml: ")
            && e.contains("agent.residual_scale = 0.5 contradicts agent.mode = \"pure\""),
        "{e}"
    );
    let fine: toml::Table = toml::from_str("agent = {residual_scale = 0.5}").unwrap();
    assert!(Recipe::with_overrides("", "r.toml", &fine, &[]).is_ok());
}
