"""The recipes from Python: every recipe id builds the env its assets/experiments file trains on
(spaces, reward, episode length, curriculum stage in the info); the curriculum advances on the
env's own episodes and changes what it samples (one shared state in a vector env); overrides
merge, drop, and are refused with the valid keys when misspelt."""

import os
import tomllib

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import fairgrasp
from fairgrasp.registration import recipe_id

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FEATURES = [
    "phase_approach", "phase_descend", "phase_close", "phase_lift", "phase_hold",
    "cube_moved_x", "cube_moved_y", "cube_moved_z", "cube_turned",
    "correction_x", "correction_y", "correction_z", "correction_yaw", "close_signal",
    "wrist_valid", "wrist_offset_x", "wrist_offset_y", "wrist_offset_z", "wrist_turn",
]
# The place task's residual corrects the force-guided search (planner/src/place/residual.rs).
PLACE_FEATURES = [
    "place_phase_grasp", "place_phase_carry", "place_phase_search_descend",
    "place_phase_search_spiral", "place_phase_search_insert", "place_phase_release",
    "wrist_force_x", "wrist_force_y", "wrist_force_z", "search_x", "search_y", "search_depth",
    "correction_x", "correction_y", "correction_z", "correction_yaw",
    "first_touch_below_rim", "peak_force", "cycle_time",
]


def recipe_file(name):
    with open(os.path.join(ROOT, "assets", "experiments", name + ".toml"), "rb") as f:
        return tomllib.load(f)


def preset_file(name):
    with open(os.path.join(ROOT, "assets", "configs", name + ".toml"), "rb") as f:
        return tomllib.load(f)


def test_every_shipped_recipe_has_an_id():
    on_disk = sorted(f[:-5] for f in os.listdir(os.path.join(ROOT, "assets", "experiments")) if f.endswith(".toml"))
    assert fairgrasp.recipe_names() == on_disk
    for name in on_disk:
        assert recipe_id(name) in gym.envs.registry


@pytest.mark.parametrize("name", sorted(f[:-5] for f in os.listdir(os.path.join(ROOT, "assets", "experiments"))))
def test_a_recipe_id_builds_the_env_the_recipe_trains_on(name):
    recipe = recipe_file(name)
    env = gym.make(recipe_id(name))
    check_env(env.unwrapped, skip_render_check=True)
    config = tomllib.loads(env.unwrapped._native.config_toml())
    agent = recipe["agent"]
    task = recipe.get("env", {}).get("task", {})
    preset_task = preset_file(recipe["preset"]).get("task", {})
    # Reward and episode length: the recipe's [env.task], else the preset's (else the default).
    for key in ("reward", "max_steps", "terminate_on_collision"):
        if key in task:
            assert config["task"][key] == task[key], key
        elif key in preset_task:
            assert config["task"][key] == preset_task[key], key
    assert env.unwrapped.max_steps == config["task"]["max_steps"]
    names = env.unwrapped.obs_names
    if agent["mode"] == "pure":
        assert env.observation_space.shape == (fairgrasp.OBS_DIM,)
        if agent["action_space"] == "tcp":
            # The agent's task-space action, saturated at action_scale, with a binary gripper.
            assert config["arm"]["action_space"] == "tcp"
            assert config["arm"]["gripper_command"] == "binary"
            assert config["arm"]["tcp_saturation"] == "action_scale"
            assert env.unwrapped.action_names[:4] == ["tcp_vx", "tcp_vy", "tcp_vz", "tcp_yaw_rate"]
        else:
            assert config["arm"]["action_space"] == "joint"
            assert env.unwrapped.action_names[0] == "j1_velocity"
    elif agent["action_space"] == "joint":
        # The seed's residual: observation ⊕ the baseline's 7 action values in, a correction of
        # each out.
        assert env.observation_space.shape == (fairgrasp.OBS_DIM + 7,)
        assert names[fairgrasp.OBS_DIM:] == [f"baseline_action_{i}" for i in range(7)]
        assert config["arm"]["action_space"] == "joint"
        assert env.unwrapped.action_names[0] == "j1_velocity_correction"
    else:
        # The task-space residual: observation ⊕ the script's 19 features in, the correction
        # out; with the squeeze, entry 4 commands the grip force.
        assert env.observation_space.shape == (fairgrasp.OBS_DIM + 19,)
        # The place and stack tasks' residuals correct a force-guided lower (the stack's is the
        # search's descent, planner/src/stack/script.rs): the same interface, the same names.
        place = config["task"].get("kind") in ("place", "stack")
        assert names[fairgrasp.OBS_DIM:] == (PLACE_FEATURES if place else FEATURES)
        assert config["arm"]["action_space"] == "joint"
        entry_4 = "squeeze" if agent.get("squeeze", False) else "unused_4"
        lift_actions = ["offset_x", "offset_y", "offset_z", "offset_yaw", entry_4, "unused_5", "close_timing"]
        # Entries 4-6 of a place residual scale the search (its floor band, spiral pace, touch force).
        place_actions = [f"search_offset_{a}" for a in ("x", "y", "z", "yaw")] + [
            "search_floor_band",
            "search_spiral_pace",
            "search_touch_force",
        ]
        assert env.unwrapped.action_names == (place_actions if place else lift_actions)
    _, info = env.reset(seed=3)
    if "curriculum" in recipe:
        assert info["curriculum_stage"] == 0 and info["curriculum_stage_name"] == "fixed"
        stages = 1 + len(recipe["curriculum"].get("position_steps", [])) + 3
        assert env.unwrapped._native.curriculum_stage_count() == stages
    else:
        assert "curriculum_stage" not in info
    env.close()


def test_pure_full_plays_100_step_episodes_with_the_staged_reward():
    env = fairgrasp.make("pure_full")
    plain = fairgrasp.make("pure_full", env=None)
    assert plain.max_steps == fairgrasp.FairGraspEnv(preset="full").max_steps != 100
    env.reset(seed=5)
    plain.reset(seed=5)
    hold = np.array([0, 0, 0, 0, 0, 0, -1.0])
    rewards, plain_rewards = [], []
    for t in range(200):
        _, r, te, tr, info = env.step(hold)
        rewards.append(r)
        if te or tr:
            break
    for _ in range(len(rewards)):
        plain_rewards.append(plain.step(hold)[1])
    assert tr and not te and info["episode_record"]["steps"] == 100 == len(rewards)
    # The staged reward pays for approaching; the distance reward (the preset's) is −0.005/m.
    assert rewards != plain_rewards
    assert info["curriculum_stage"] == 0


def scenario_xy(env, seed):
    _, info = env.reset(seed=seed)
    return tuple(info["scenario"]["object_xy"])


def play_script(env, seed):
    """Zero correction (the open-loop script) until the episode ends; its outcome."""
    env.reset(seed=seed)
    while True:
        _, _, te, tr, info = env.step(np.zeros(7))
        if te or tr:
            return info


def test_the_curriculum_advances_on_the_envs_episodes_and_widens_the_sampling():
    env = fairgrasp.make("residual_miscalibrated", preset="sector", curriculum={"window": 2, "threshold": 0.5})
    assert env.curriculum_stage == (0, "fixed")
    # Stage 0 (fixed): every seed puts the cube in the same place.
    assert len({scenario_xy(env, s) for s in range(4)}) == 1
    outcomes = [play_script(env, s) for s in (10, 11)]
    assert any(i["success"] for i in outcomes), "the script should grasp the fixed cube"
    assert outcomes[-1]["curriculum_stage"] == 1 and env.curriculum_stage == (1, "position")
    assert len({scenario_xy(env, s) for s in range(4)}) == 4
    env.set_curriculum_stage(0)
    assert env.curriculum_stage[0] == 0 and len({scenario_xy(env, s) for s in range(3)}) == 1


def test_a_vector_env_shares_one_curriculum():
    vec = fairgrasp.make_vec("residual_miscalibrated", num_envs=2, preset="sector", seed=4,
                             curriculum={"window": 2, "threshold": 0.5})
    obs, info = vec.reset()
    assert obs.shape == (2, fairgrasp.OBS_DIM + 19)
    assert list(info["curriculum_stage"]) == [0, 0]
    ended = 0
    for _ in range(400):
        obs, _, te, tr, info = vec.step(np.zeros((2, 7)))
        ended += int((te | tr).sum())
        if ended >= 2:
            break
    # Two episodes (one per env, or two of one) fill the shared window of 2; the script grasps
    # the fixed cube, so both envs are now at stage 1.
    assert ended >= 2 and vec.curriculum_stage == (1, "position")
    assert list(info["curriculum_stage"]) == [1, 1]


def test_misspelt_overrides_are_refused_with_the_valid_keys():
    with pytest.raises(ValueError, match="unknown override `presett`.*preset, arm, agent, curriculum, env"):
        fairgrasp.make("pure_full", presett="sector")
    with pytest.raises(ValueError, match="pure_full.*residual_miscalibrated"):
        fairgrasp.make("pure_fll")
    with pytest.raises(ValueError, match="threshold"):
        fairgrasp.make("pure_full", curriculum={"threshhold": 0.5})
    with pytest.raises(ValueError, match="unknown keyword"):
        fairgrasp.FairGraspEnv(preset="sector", curriculum=None)
    with pytest.raises(ValueError, match="action_space must stay"):
        fairgrasp.make("pure_full", env={"arm": {"action_space": "tcp"}})


def test_overrides_merge_and_drop():
    env = fairgrasp.make("pure_full", preset="sector", env={"task": {"max_steps": 40}}, curriculum=None)
    config = tomllib.loads(env.unwrapped._native.config_toml())
    assert env.max_steps == 40 and config["task"]["reward"] == "staged"
    assert env.curriculum_stage is None
    _, info = env.reset(seed=1)
    assert "curriculum_stage" not in info
    evaluation = fairgrasp.make("pure_full", preset="sector", evaluation=True)
    config = tomllib.loads(evaluation._native.config_toml())
    assert config["task"]["reward"] == preset_file("sector").get("task", {}).get("reward", "distance")
    assert config["arm"]["action_space"] == "tcp" and evaluation.curriculum_stage is None


def test_the_squeeze_reaches_the_env_from_python():
    """`residual_heavy_slippery`'s entry 4 commands the grip force in Python's env as in
    training: a full squeeze lifts the heavy, slippery cubes the script's 5 N grip leaves on the
    table."""
    env = fairgrasp.make("residual_heavy_slippery")
    squeeze = np.array([0, 0, 0, 0, 1.0, 0, 0])

    def outcome(seed, action):
        env.reset(seed=seed)
        while True:
            _, _, te, tr, info = env.step(action)
            if te or tr:
                return info["episode_record"]["outcome"]

    seeds = range(100, 108)
    held = [outcome(s, squeeze) for s in seeds]
    plain = [outcome(s, np.zeros(7)) for s in seeds]
    assert held.count("success") >= 7, held
    assert plain.count("success") <= 5, plain
