"""The native vector env: equal to N single envs (same scenario seeds, same actions), same-step
autoreset with final observations, built by gym.make_vec, bad actions refused."""

import gymnasium as gym
import numpy as np
import pytest

import fairgrasp


def test_the_vector_env_equals_n_single_envs():
    """Every array the vector env returns (observations, rewards, flags, the info arrays, the
    final observations and infos) equals what N single envs return for the same seeds and
    actions, across autoresets."""
    n, steps = 3, 260
    vec = fairgrasp.VectorEnv(num_envs=n, preset="fixed", threads=2, seed=9)
    obs, info = vec.reset()
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(steps, n, 7))
    singles = [fairgrasp.FairGraspEnv(preset="fixed") for _ in range(n)]
    for i, env in enumerate(singles):
        first, first_info = env.reset(seed=int(info["scenario_seed"][i]))
        assert np.array_equal(first, obs[i])
        assert first_info["scenario_seed"] == info["scenario_seed"][i]
    ended = 0
    for t in range(steps):
        obs, rewards, terminated, truncated, info = vec.step(actions[t])
        assert obs.dtype == np.float32 and rewards.dtype == np.float64
        for i, env in enumerate(singles):
            o, r, te, tr, single = env.step(actions[t, i])
            assert (r, te, tr) == (rewards[i], terminated[i], truncated[i]), f"env {i} step {t}"
            if te or tr:
                ended += 1
                assert info["_final_obs"][i] and info["_final_info"][i]
                assert np.array_equal(info["final_obs"][i], o), f"env {i} step {t}"
                final = info["final_info"]
                for key in ("success", "step", "scenario_seed", "outcome"):
                    assert final[key][i] == single[key], key
                assert final["scenario"]["seed"][i] == single["scenario"]["seed"]
                assert final["episode_record"]["outcome"][i] == single["episode_record"]["outcome"]
                assert final["episode_record"]["steps"][i] == single["episode_record"]["steps"]
                # The env has moved on: its new episode's first observation and seed.
                o, _ = env.reset(seed=int(info["scenario_seed"][i]))
                assert info["step"][i] == 0 and not info["success"][i]
            else:
                for key in ("success", "step", "simulated", "scenario_seed"):
                    assert info[key][i] == single[key], f"{key} env {i} step {t}"
                assert "_final_obs" not in info or not info["_final_obs"][i]
            assert np.array_equal(obs[i], o), f"env {i} step {t}"
    assert ended >= 3, "too few episodes ended: the autoreset path is barely tested"


def test_make_vec_uses_the_native_vector_env():
    envs = gym.make_vec("FairGrasp-Sector-v0", num_envs=4, vectorization_mode="vector_entry_point")
    assert isinstance(envs, fairgrasp.VectorEnv)
    obs, _ = envs.reset(seed=1)
    assert obs.shape == (4, fairgrasp.OBS_DIM)
    obs, r, te, tr, _ = envs.step(np.zeros((4, 7)))
    assert r.shape == (4,) and te.dtype == bool
    again = gym.make_vec("FairGrasp-Sector-v0", num_envs=4, vectorization_mode="vector_entry_point")
    obs2, _ = again.reset(seed=1)
    assert np.array_equal(obs2, envs.reset(seed=1)[0])


def test_bad_vector_actions_raise_value_error_naming_env_and_index():
    vec = fairgrasp.VectorEnv(num_envs=2, preset="sector")
    vec.reset(seed=0)
    bad = np.zeros((2, 7))
    bad[1, 4] = np.nan
    with pytest.raises(ValueError, match=r"actions\[1\]\[4\]"):
        vec.step(bad)
    with pytest.raises(ValueError, match="shape"):
        vec.step(np.zeros((3, 7)))


def test_episodes_ending_in_one_step_with_and_without_a_failure_batch_their_infos():
    # Env 0's episode ended without a failure (its info says failure None), env 2's with one:
    # batched, env 2's failure is there and masked in, env 0's masked out; env 1 did not end.
    vec = fairgrasp.VectorEnv(num_envs=3, preset="fixed", threads=1, seed=1)
    no_failure = {"step": 40, "success": True, "failure": None}
    failure = {"step": 12, "success": False, "failure": {"kind": "collision", "bodies": "link3"}}
    for order in ([(0, None, no_failure), (2, None, failure)], [(2, None, failure), (0, None, no_failure)]):
        info = vec._final_infos(order)
        assert list(info["_failure"]) == [False, False, True]
        assert info["failure"]["kind"][2] == "collision"
        assert list(info["success"][[0, 2]]) == [True, False]
        assert list(info["_step"]) == [True, False, True]
