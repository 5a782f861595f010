//! Recipes that contradict themselves: two settings of which one makes the other mean nothing
//! (a residual scale on a pure policy, an `[env.arm]` setting the agent does not drive the arm
//! through). Each is refused at load naming both keys; a key left at its default, as a run's
//! saved `config.toml` writes every key, is not a contradiction.
//!
//! [`check`] is the one rule; [`crate::recipe::Recipe::validate`] calls it.

use fairgrasp_env::config::{ActionSpace, ArmConfig};

use crate::agent::{AgentConfig, GripperMode, Mode};
use crate::recipe::settings::Recipe;

/// The first contradiction of `recipe`, naming both keys and how to resolve it.
pub fn check(recipe: &Recipe) -> Result<(), String> {
    agent_keys(&recipe.agent)?;
    arm_keys(recipe)
}

/// Keys of `[agent]` that its `mode` or `action_space` leaves unused.
fn agent_keys(agent: &AgentConfig) -> Result<(), String> {
    let default = AgentConfig::default();
    let scaled = agent.residual_scale != default.residual_scale;
    let learned = agent.gripper == GripperMode::Learned;
    let (owner, why) = match (agent.mode, agent.action_space) {
        (Mode::Pure, _) => (
            "agent.mode = \"pure\"",
            "a pure policy's output is the action itself, with no script to correct",
        ),
        (Mode::Residual, ActionSpace::Tcp) => (
            "agent.action_space = \"tcp\"",
            "a task-space residual corrects the script's grasp within its own limits and times \
             the close itself",
        ),
        (Mode::Residual, ActionSpace::Joint) => return Ok(()),
    };
    if scaled {
        return Err(format!(
            "agent.residual_scale = {} contradicts {owner}: {why}, so nothing is scaled (remove \
             residual_scale, or use a joint residual: mode = \"residual\", action_space = \"joint\")",
            agent.residual_scale
        ));
    }
    if learned {
        return Err(format!(
            "agent.gripper = \"learned\" contradicts {owner}: {why}, so no gripper correction is \
             replaced (remove gripper, or use a joint residual: mode = \"residual\", \
             action_space = \"joint\")"
        ));
    }
    Ok(())
}

/// `[env.arm]` keys that contradict the recipe's `arm` or that its agent does not drive the arm
/// through: the env's task-space action alone reads `tcp_speed`, `tcp_yaw_rate`,
/// `tcp_saturation` and `gripper_command`, and only a pure `tcp` agent acts through it, with
/// its own saturation and gripper ([`AgentConfig::env_for`]).
fn arm_keys(recipe: &Recipe) -> Result<(), String> {
    let Some(arm) = recipe
        .env
        .as_ref()
        .and_then(|env| env.get("arm"))
        .and_then(|arm| arm.as_table())
    else {
        return Ok(());
    };
    if let Some(model) = arm.get("model").and_then(|m| m.as_str())
        && model != recipe.arm.to_string()
    {
        return Err(format!(
            "env.arm.model = \"{model}\" contradicts arm = \"{}\": training would step one arm \
             and its evaluations the other (choose the arm with `arm` alone)",
            recipe.arm
        ));
    }
    let agent = &recipe.agent;
    let pure_tcp = agent.mode == Mode::Pure && agent.action_space == ActionSpace::Tcp;
    let driven = driven_arm(agent);
    for key in [
        "tcp_speed",
        "tcp_yaw_rate",
        "tcp_saturation",
        "gripper_command",
    ] {
        let Some(value) = arm.get(key) else { continue };
        if !pure_tcp {
            return Err(format!(
                "env.arm.{key} = {value} contradicts agent.mode = \"{}\" with agent.action_space \
                 = \"{}\": only the env's task-space action reads it, and only a pure tcp agent \
                 acts through it (remove env.arm.{key})",
                agent.mode,
                action_space_name(agent.action_space)
            ));
        }
        let forced = match key {
            "tcp_saturation" => Some(toml::Value::try_from(driven.tcp_saturation)),
            "gripper_command" => Some(toml::Value::try_from(driven.gripper_command)),
            _ => None,
        };
        if let Some(Ok(forced)) = forced
            && &forced != value
        {
            return Err(format!(
                "env.arm.{key} = {value} contradicts agent.mode = \"pure\" with \
                 agent.action_space = \"tcp\": that agent drives the arm with {key} = {forced} \
                 (remove env.arm.{key})"
            ));
        }
    }
    Ok(())
}

/// The arm settings a pure `tcp` agent imposes on its env.
fn driven_arm(agent: &AgentConfig) -> ArmConfig {
    agent.env_for(&fairgrasp_env::EnvConfig::default()).arm
}

/// The config's name of an action space.
fn action_space_name(space: ActionSpace) -> &'static str {
    match space {
        ActionSpace::Joint => "joint",
        ActionSpace::Tcp => "tcp",
    }
}
