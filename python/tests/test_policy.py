"""Rust policies in Python: ``load_policy`` plays ``fairgrasp eval``'s episodes with the same
outcomes, episode by episode; ``evaluate`` takes a callable and a ``predict`` object, and refuses
a policy that raises or returns a bad action, naming the policy, the preset and the step."""

from pathlib import Path

import numpy as np
import pytest

import fairgrasp

POLICIES = Path(__file__).resolve().parents[2] / "assets" / "policies"


@pytest.mark.parametrize("name, preset", [("residual_nudged", "nudged"), ("pure_full", "full")])
def test_a_loaded_policy_gives_the_outcomes_of_fairgrasp_eval_episode_by_episode(cli, name, preset):
    ours = fairgrasp.evaluate(fairgrasp.load_policy(name), preset, episodes=50, seed=3)
    rust = cli("eval", "--policy", str(POLICIES / name / "checkpoint"), "--preset", preset,
               "--episodes", "50", "--seed", "3", "--json")
    for key in ["seed", "outcome", "steps"]:
        assert [r[key] for r in ours["records"]] == [r[key] for r in rust["results"]], key
    assert ours["successes"] == rust["successes"]
    assert (ours["ci_low"], ours["ci_high"]) == pytest.approx((rust["ci_low"], rust["ci_high"]))
    assert ours["outcomes"] == rust["outcomes"]


def test_a_policy_loads_from_a_checkpoint_or_run_folder_and_predicts_like_sb3():
    by_name = fairgrasp.load_policy("residual_nudged")
    by_folder = fairgrasp.load_policy(POLICIES / "residual_nudged" / "checkpoint")
    env = by_name.make_env("nudged")
    obs, _ = env.reset(seed=11)
    assert obs.shape == (by_name._native.input_dim,)
    action, state = by_name.predict(obs, deterministic=True)
    assert action.shape == env.action_space.shape and state is None
    np.testing.assert_array_equal(action, by_folder.predict(obs)[0])
    batch, _ = by_name.predict(np.stack([obs, obs]))
    np.testing.assert_array_equal(batch[1], action)
    with pytest.raises(ValueError, match="neither a shipped policy"):
        fairgrasp.load_policy("no_such_policy")
    with pytest.raises(ValueError, match="this policy takes"):
        by_name.predict(np.zeros(5, dtype=np.float32))


def test_evaluate_takes_a_callable_and_names_a_bad_policy():
    result = fairgrasp.evaluate(lambda obs: np.zeros(7), "seed", episodes=3, seed=0, name="still")
    assert result["episodes"] == 3 and result["successes"] == 0
    assert sum(result["outcomes"].values()) == 3

    def broken(obs):
        raise RuntimeError("out of cheese")

    for policy, words in [
        (broken, "raised RuntimeError: out of cheese"),
        (lambda obs: np.zeros(3), "shape (3,)"),
        (lambda obs: np.full(7, np.nan), "is not finite"),
    ]:
        with pytest.raises(fairgrasp.PolicyError, match="preset 'seed', episode 0") as e:
            fairgrasp.evaluate(policy, "seed", episodes=2, seed=0, name="bad")
        assert words in str(e.value) and "policy 'bad'" in str(e.value) and "step 0" in str(e.value)
