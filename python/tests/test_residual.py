"""The task-space residual env from Python: an all-zero correction is the open-loop script,
episode for episode and step for step (the Rust script playing the plain env of the same config
gives the same observations, rewards and episode records), in a single env and in the vector
env; the policy input's script features are the Rust agent's; the joint-space residual (the
documented negative result) is only reachable as a recipe override, and a zero correction there
is the baseline too."""

import numpy as np
import pytest

import fairgrasp


def script_episodes(config_toml, seeds):
    """The open-loop script (the Rust `ScriptedGrasp`) playing each seed on the plain env of
    `config_toml`, on the env's own observations (`Baseline.play`, as `fairgrasp baseline`):
    per episode, the observations, rewards and last info."""
    script = fairgrasp.Baseline(config_toml=config_toml)
    return [script.play(s) for s in seeds]


def zero_residual_episodes(env, seeds):
    out = []
    for s in seeds:
        obs, _ = env.reset(seed=s)
        seen, rewards = [obs], []
        while True:
            obs, r, te, tr, info = env.step(np.zeros(7))
            assert env.observation_space.contains(obs), f"seed {s}: observation outside its space"
            seen.append(obs)
            rewards.append(r)
            if te or tr:
                out.append((np.array(seen), rewards, info))
                break
    return out


@pytest.mark.parametrize("preset", ["nudged", "miscalibrated", "wrist_camera"])
def test_a_zero_correction_is_the_open_loop_script_episode_for_episode(preset):
    env = fairgrasp.make("residual_miscalibrated", preset=preset)
    seeds = [preset_seed * 1_000_003 + i for preset_seed in (7,) for i in range(12)]
    residual = zero_residual_episodes(env, seeds)
    script = script_episodes(env.unwrapped._native.config_toml(), seeds)
    outcomes = []
    for s, (obs_r, rew_r, info_r), (obs_s, rew_s, info_s) in zip(seeds, residual, script):
        assert obs_r.shape[0] == obs_s.shape[0], f"seed {s}: episode lengths differ"
        assert np.array_equal(obs_r[:, : fairgrasp.OBS_DIM], obs_s), f"seed {s}: observations differ"
        assert rew_r == rew_s, f"seed {s}: rewards differ"
        assert info_r["outcome"] == info_s["outcome"], f"seed {s}"
        assert info_r["episode_record"] == info_s["episode_record"], f"seed {s}"
        outcomes.append(info_r["outcome"])
    # Whole episodes, not a few steps: each ran to its end, and both kinds of ending occur.
    assert all(len(o) > 20 for o, _, _ in residual)
    assert "success" in outcomes, outcomes


def test_the_script_features_follow_the_script():
    env = fairgrasp.make("residual_miscalibrated", preset="nudged")
    obs, _ = env.reset(seed=3)
    features = dict(zip(env.unwrapped.obs_names[fairgrasp.OBS_DIM:], obs[fairgrasp.OBS_DIM:]))
    phases = ["phase_approach", "phase_descend", "phase_close", "phase_lift", "phase_hold"]
    # Before the first action the script has not planned yet (its `plan` phase has no flag),
    # exactly as the Rust trainer's policy sees the first observation.
    assert all(features[p] == 0.0 for p in phases), features
    seen = []
    moved = 0.0
    while True:
        obs, _, te, tr, _ = env.step(np.zeros(7))
        f = dict(zip(env.unwrapped.obs_names[fairgrasp.OBS_DIM:], obs[fairgrasp.OBS_DIM:]))
        on = [p for p in phases if f[p] == 1.0]
        assert len(on) <= 1
        if on and (not seen or seen[-1] != on[0]):
            seen.append(on[0])
        moved = max(moved, abs(f["cube_moved_x"]) + abs(f["cube_moved_y"]))
        # A zero command keeps the correction at zero.
        assert f["correction_x"] == f["correction_y"] == f["close_signal"] == 0.0
        if te or tr:
            break
    assert seen[:3] == phases[:3], seen
    # `nudged` pushes the cube during the approach: the features show it.
    assert moved > 0.05


def test_a_correction_changes_the_grasp():
    env = fairgrasp.make("residual_miscalibrated", preset="nudged")
    env.reset(seed=3)
    obs, *_ = env.step(np.array([1.0, 0, 0, 0, 0, 0, 0]))
    names = env.unwrapped.obs_names
    assert obs[names.index("correction_x")] > 0.0


def test_the_residual_vector_env_equals_single_envs():
    n, steps = 3, 150
    vec = fairgrasp.make_vec("residual_miscalibrated", num_envs=n, preset="nudged", seed=40)
    obs, info = vec.reset()
    rng = np.random.default_rng(1)
    actions = rng.normal(0, 0.5, size=(steps, n, 7))
    rows = [[(int(info["scenario_seed"][i]), [obs[i]], [], [])] for i in range(n)]
    for t in range(steps):
        obs, rewards, te, tr, info = vec.step(actions[t])
        for i in range(n):
            seed, seen, acts, rews = rows[i][-1]
            acts.append(actions[t, i])
            rews.append(rewards[i])
            if te[i] or tr[i]:
                seen.append(info["final_obs"][i])
                assert info["final_info"]["scenario_seed"][i] == seed
                rows[i].append((int(info["scenario_seed"][i]), [obs[i]], [], []))
            else:
                seen.append(obs[i])
    single = fairgrasp.make("residual_miscalibrated", preset="nudged")
    checked = 0
    for i in range(n):
        for seed, seen, acts, rews in rows[i]:
            first, _ = single.reset(seed=seed)
            assert np.array_equal(first, seen[0])
            for j, a in enumerate(acts):
                o, r, *_ = single.step(a)
                assert np.array_equal(o, seen[j + 1]), f"env {i} seed {seed} step {j}"
                assert r == rews[j]
                checked += 1
    assert checked == n * steps


def test_the_joint_residual_is_only_an_override_and_a_zero_policy_is_the_baseline():
    assert not hasattr(fairgrasp, "ResidualWrapper")
    env = fairgrasp.make("residual_miscalibrated", preset="sector", agent={"action_space": "joint"})
    assert env.observation_space.shape == (fairgrasp.OBS_DIM + 7,)
    assert env.unwrapped.obs_names[-1] == "baseline_action_6"
    seeds = list(range(100, 110))
    residual = zero_residual_episodes(env, seeds)
    script = script_episodes(env.unwrapped._native.config_toml(), seeds)
    for (obs_r, rew_r, info_r), (obs_s, rew_s, info_s) in zip(residual, script):
        assert np.array_equal(obs_r[:, : fairgrasp.OBS_DIM], obs_s)
        assert info_r["outcome"] == info_s["outcome"]
    assert sum(i["success"] for _, _, i in residual) >= 9
