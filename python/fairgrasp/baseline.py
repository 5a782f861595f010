"""The scripted grasp baseline as a policy object."""

import numpy as np

from . import _native
from .presets import current_preset


class Baseline:
    """``fairgrasp baseline``'s scripted grasp: call ``reset(seed)`` at each episode's start,
    then ``act(obs)`` for the env action (7 values in [-1, 1]); ``act`` sees the float32
    observation, so its episodes can part from the script's own (``play``) by rounding."""

    def __init__(self, preset="full", arm="servo", config_toml=None):
        self._native = _native.Baseline(current_preset(preset), arm, config_toml)

    def reset(self, seed=0):
        self._native.reset(int(seed))

    def play(self, seed):
        """Scenario ``seed`` played to its end by the script on its own env, acting on the env's
        own (f64) observations as ``fairgrasp baseline`` does: ``(observations [steps + 1, 23],
        rewards, last info)``."""
        return self._native.play(int(seed))

    def act(self, obs):
        return self._native.act(np.ascontiguousarray(obs, dtype=np.float32))
