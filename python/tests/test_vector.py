"""The native vector env: equal to N single envs (same scenario seeds, same actions), same-step
autoreset with final observations, built by gym.make_vec, bad actions refused."""

import gymnasium as gym
import numpy as np
import pytest

import fairgrasp


def test_the_vector_env_equals_n_single_envs():
    n, steps = 3, 260
    vec = fairgrasp.VectorEnv(num_envs=n, preset="fixed", threads=2, seed=9)
    obs, info = vec.reset()
    rng = np.random.default_rng(0)
    actions = rng.uniform(-1, 1, size=(steps, n, 7))
    # Per env: the episodes' seeds and the observations each episode produced.
    episodes = [[[int(info["scenario_seed"][i]), [obs[i]], []]] for i in range(n)]
    ended_any = False
    for t in range(steps):
        obs, rewards, terminated, truncated, info = vec.step(actions[t])
        for i in range(n):
            episode = episodes[i][-1]
            seed, seen, acts = episode
            acts.append(actions[t, i])
            if terminated[i] or truncated[i]:
                ended_any = True
                assert info["_final_obs"][i]
                seen.append(info["final_obs"][i])
                reported = info["final_info"][i]["scenario"]["seed"]
                if seed is None:
                    episode[0] = reported
                else:
                    assert reported == seed
                episodes[i].append([None, [obs[i]], []])
            else:
                seen.append(obs[i])
    assert ended_any, "no episode ended: the autoreset path is untested"
    single = fairgrasp.FairGraspEnv(preset="fixed")
    for i in range(n):
        for k, (seed, seen, acts) in enumerate(episodes[i]):
            if seed is None:
                continue  # the next episode's seed is reported when it ends
            first, _ = single.reset(seed=seed)
            assert np.array_equal(first, seen[0]), f"env {i} episode {k}"
            for j, a in enumerate(acts):
                o, *_ = single.step(a)
                assert np.array_equal(o, seen[j + 1]), f"env {i} episode {k} step {j}"


def test_make_vec_uses_the_native_vector_env():
    envs = gym.make_vec("FairGrasp-Seed-v0", num_envs=4, vectorization_mode="vector_entry_point")
    assert isinstance(envs, fairgrasp.VectorEnv)
    obs, _ = envs.reset(seed=1)
    assert obs.shape == (4, fairgrasp.OBS_DIM)
    obs, r, te, tr, _ = envs.step(np.zeros((4, 7)))
    assert r.shape == (4,) and te.dtype == bool
    again = gym.make_vec("FairGrasp-Seed-v0", num_envs=4, vectorization_mode="vector_entry_point")
    obs2, _ = again.reset(seed=1)
    assert np.array_equal(obs2, envs.reset(seed=1)[0])


def test_bad_vector_actions_raise_value_error_naming_env_and_index():
    vec = fairgrasp.VectorEnv(num_envs=2, preset="seed")
    vec.reset(seed=0)
    bad = np.zeros((2, 7))
    bad[1, 4] = np.nan
    with pytest.raises(ValueError, match=r"actions\[1\]\[4\]"):
        vec.step(bad)
    with pytest.raises(ValueError, match="shape"):
        vec.step(np.zeros((3, 7)))
