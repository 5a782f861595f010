"""A renamed preset's old name (``"seed"``, now ``"sector"``) still works from Python with a
``DeprecationWarning`` naming the current one, and what Python reports carries the current name."""

import warnings

import gymnasium as gym
import numpy as np
import pytest

import fairgrasp

NOTE = r'preset "seed" is now called "sector"; the old name still works for now'


def test_the_old_name_warns_and_gives_the_current_preset():
    with pytest.warns(DeprecationWarning, match=NOTE) as caught:
        env = fairgrasp.FairGraspEnv(preset="seed")
    assert len(caught) == 1
    # The warning points at this file (the caller), not at fairgrasp's own code.
    assert caught[0].filename == __file__
    assert env.preset == "sector"
    new = fairgrasp.FairGraspEnv(preset="sector")
    assert env._native.config_toml() == new._native.config_toml()
    assert np.array_equal(env.reset(seed=3)[0], new.reset(seed=3)[0])


def test_the_current_name_gives_no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fairgrasp.FairGraspEnv(preset="sector")
        fairgrasp.evaluate(lambda obs: np.zeros(7), "sector", episodes=1, seed=0)
    assert "sector" in fairgrasp.preset_names() and "seed" not in fairgrasp.preset_names()


def test_evaluate_compare_make_and_baseline_accept_the_old_name(tmp_path):
    still = lambda obs: np.zeros(7)  # noqa: E731
    with pytest.warns(DeprecationWarning, match=NOTE):
        result = fairgrasp.evaluate(still, "seed", episodes=2, seed=0, name="still")
    assert result["preset"] == "sector"
    assert result["records"] == fairgrasp.evaluate(still, "sector", episodes=2, seed=0)["records"]
    with pytest.warns(DeprecationWarning, match=NOTE):
        fairgrasp.compare(policies={"still": still}, presets=["seed"], episodes=1, out=tmp_path / "r",
                          shipped=False)
    csv = (tmp_path / "r" / "compare.csv").read_text().splitlines()
    assert [row.split(",")[1] for row in csv[1:]] == ["sector"] * (len(csv) - 1)
    with pytest.warns(DeprecationWarning, match=NOTE):
        env = fairgrasp.make("residual_miscalibrated", preset="seed", evaluation=True)
    assert env.preset == "sector"
    with pytest.warns(DeprecationWarning, match=NOTE):
        fairgrasp.Baseline(preset="seed")


def test_the_old_registered_id_still_makes_the_current_preset():
    with pytest.warns(DeprecationWarning, match=NOTE):
        env = gym.make("FairGrasp-Seed-v0")
    assert env.unwrapped.preset == "sector"
