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
    result = fairgrasp.evaluate(lambda obs: np.zeros(7), "sector", episodes=3, seed=0, name="still")
    assert result["episodes"] == 3 and result["successes"] == 0
    assert sum(result["outcomes"].values()) == 3

    def broken(obs):
        raise RuntimeError("out of cheese")

    for policy, words in [
        (broken, "raised RuntimeError: out of cheese"),
        (lambda obs: np.zeros(3), "shape (3,)"),
        (lambda obs: np.full(7, np.nan), "is not finite"),
    ]:
        with pytest.raises(fairgrasp.PolicyError, match="preset 'sector', episode 0") as e:
            fairgrasp.evaluate(policy, "sector", episodes=2, seed=0, name="bad")
        assert words in str(e.value) and "policy 'bad'" in str(e.value) and "step 0" in str(e.value)


class _FakeSb3:
    """An object with Stable-Baselines3's model API (``predict``, ``env``,
    ``get_vec_normalize_env``), recording the observations it is shown."""

    def __init__(self, env=None, normalizer=None):
        self.env = env
        self._normalizer = normalizer
        self.seen = []

    def get_vec_normalize_env(self):
        return self._normalizer

    def predict(self, obs, state=None, episode_start=None, deterministic=True):
        self.seen.append(np.array(obs))
        return np.zeros(7), None


class _Shift:
    """A VecNormalize stand-in: ``normalize_obs`` subtracts 1000 (a batch of one)."""

    def normalize_obs(self, batch):
        return batch - 1000.0


def test_an_sb3_model_sees_observations_through_its_vec_normalize_or_is_refused(tmp_path):
    first = fairgrasp._native.scenario_seeds("sector", 3, 1, "servo")[0]
    raw = fairgrasp.FairGraspEnv(preset="sector").reset(seed=first)[0]
    # The model's own statistics (trained behind VecNormalize, its env attached).
    own = _FakeSb3(env=object(), normalizer=_Shift())
    fairgrasp.evaluate(own, "sector", episodes=1, seed=3)
    np.testing.assert_allclose(own.seen[0], raw - 1000.0)
    # Statistics given for a model loaded without its env.
    given = _FakeSb3()
    fairgrasp.evaluate(given, "sector", episodes=1, seed=3, vec_normalize=_Shift())
    np.testing.assert_allclose(given.seen[0], raw - 1000.0)
    # A model loaded without its env: refused, unless told it had no VecNormalize.
    with pytest.raises(ValueError, match="VecNormalize"):
        fairgrasp.evaluate(_FakeSb3(), "sector", episodes=1, seed=3)
    plain = _FakeSb3()
    fairgrasp.evaluate(plain, "sector", episodes=1, seed=3, vec_normalize=None)
    np.testing.assert_array_equal(plain.seen[0], raw)
    # compare() takes the dict's vec_normalize; a misspelt key is named, and nothing is written.
    out = tmp_path / "report"
    with pytest.raises(ValueError, match="vec_normalize"):
        fairgrasp.compare(policies={"m": {"policy": plain, "vec_normalise": None}}, presets=["sector"],
                          episodes=1, out=out)
    assert not out.exists()
