"""The gymnasium env: every registered id passes check_env; bit-identical to the Rust TaskEnv;
bad actions raise ValueError naming the index; pickling round-trips; infos carry the outcome."""

import pickle

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import fairgrasp
from fairgrasp.registration import env_id


def ids():
    return ["FairGrasp-v0"] + [env_id(p) for p in fairgrasp.preset_names()]


@pytest.mark.parametrize("name", ids())
def test_every_registered_id_passes_check_env(name):
    env = gym.make(name)
    check_env(env.unwrapped, skip_render_check=True)
    assert np.isfinite(env.observation_space.low).all() and np.isfinite(env.observation_space.high).all()
    env.close()


def test_observations_are_bit_identical_to_the_rust_env(rust_reference):
    ref = rust_reference
    env = fairgrasp.FairGraspEnv(preset=ref["preset"])
    obs, _ = env.reset(seed=ref["seed"])
    assert obs.dtype == np.float32
    assert obs.tolist() == ref["observations"][0]
    for t, action in enumerate(ref["actions"]):
        obs, reward, terminated, truncated, _ = env.step(np.array(action))
        assert obs.tolist() == ref["observations"][t + 1], f"step {t}"
        assert reward == ref["rewards"][t]
        if terminated or truncated:
            break


def test_the_same_seed_and_actions_give_the_same_episode():
    rng = np.random.default_rng(3)
    actions = rng.uniform(-1, 1, size=(60, 7))
    runs = []
    for _ in range(2):
        env = gym.make("FairGrasp-Full-v0")
        obs, _ = env.reset(seed=21)
        seq = [obs]
        for a in actions:
            obs, *_ = env.step(a)
            seq.append(obs)
        runs.append(np.array(seq))
    assert np.array_equal(runs[0], runs[1])


@pytest.mark.parametrize(
    "action, message",
    [
        (np.array([0, 0, np.nan, 0, 0, 0, 0.0]), r"action\[2\]"),
        (np.array([0, 0, 0, 0, 0, np.inf, 0.0]), r"action\[5\]"),
        (np.zeros(6), r"shape"),
        (np.zeros((2, 7)), r"shape"),
    ],
)
def test_a_bad_action_raises_value_error_naming_it(action, message):
    env = fairgrasp.FairGraspEnv(preset="sector")
    env.reset(seed=0)
    with pytest.raises(ValueError, match=message):
        env.step(action)


def test_pickling_round_trips_to_an_env_that_plays_the_same_episode():
    env = fairgrasp.FairGraspEnv(preset="hard", arm="servo")
    clone = pickle.loads(pickle.dumps(env))
    assert clone.preset == "hard"
    a, _ = env.reset(seed=5)
    b, _ = clone.reset(seed=5)
    assert np.array_equal(a, b)
    step = np.full(7, 0.2)
    assert np.array_equal(env.step(step)[0], clone.step(step)[0])


def test_an_episode_ends_with_an_outcome_in_its_info():
    env = fairgrasp.FairGraspEnv(preset="fixed")
    env.reset(seed=1)
    for _ in range(env.max_steps + 1):
        _, _, terminated, truncated, info = env.step(np.zeros(7))
        if terminated or truncated:
            break
    assert truncated and not terminated
    # The outcome is the Rust env's episode record, not re-derived here: a gripper command of 0
    # closes the fingers halfway, past the cube's width, without both pads on it.
    assert info["outcome"] == info["episode_record"]["outcome"] == "missed_grasp"
    assert info["success"] is False and info["episode_record"]["success"] is False
    assert info["episode_record"]["steps"] == env.max_steps and not info["episode_record"]["held"]
    assert info["scenario"]["seed"] == info["scenario_seed"] == 1
    # gymnasium's episode statistics own info["episode"]: they wrap the env without complaint.
    stats = gym.wrappers.RecordEpisodeStatistics(fairgrasp.FairGraspEnv(preset="fixed"))
    stats.reset(seed=1)
    for _ in range(env.max_steps):
        *_, terminated, truncated, info = stats.step(np.zeros(7))
        if terminated or truncated:
            break
    assert info["episode"]["l"] == env.max_steps and info["outcome"] == "missed_grasp"


def test_render_returns_the_replay_view_as_rgb():
    env = fairgrasp.FairGraspEnv(preset="sector", render_mode="rgb_array")
    env.reset(seed=2)
    env.step(np.full(7, 0.3))
    frame = env.render()
    assert frame.shape == (500, 960, 3) and frame.dtype == np.uint8
    assert (frame < 200).any(), "nothing drawn"
    assert fairgrasp.FairGraspEnv(preset="sector").render() is None


def test_each_preset_has_a_task_space_residual_id_named_for_what_it_corrects():
    from fairgrasp.registration import residual_id

    lift = gym.make(residual_id("nudged")).unwrapped
    assert lift.preset == "nudged"
    assert "cube_moved_x" in lift.obs_names and lift.action_names[0] == "offset_x"
    place = gym.make("FairGrasp-Residual-PlaceGraspError-v0").unwrapped
    assert place.preset == "place_grasp_error"
    assert "wrist_force_z" in place.obs_names and place.action_names[0] == "search_offset_x"
    check_env(place, skip_render_check=True)


def test_the_stack_task_has_its_id_and_a_second_cube_to_set_the_cube_on():
    env = gym.make("FairGrasp-Stack-v0")
    config = env.unwrapped._native.config_toml()
    assert 'kind = "stack"' in config
    obs, info = env.reset(seed=4)
    assert env.observation_space.contains(obs)
    # Nothing stacked at the start: the cube rests on the table, not on the second cube.
    _, reward, terminated, truncated, info = env.step(np.zeros(env.action_space.shape, dtype=np.float32))
    assert not info.get("success", False) and not terminated
    assert np.isfinite(reward)
    env.close()
