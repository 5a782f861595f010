"""The scripted grasp baseline as a policy object."""

import numpy as np

from . import _native


class Baseline:
    """``fairgrasp baseline``'s scripted grasp: call ``reset(seed)`` at each episode's start,
    then ``act(obs)`` for the env action (7 values in [-1, 1])."""

    def __init__(self, preset="full", arm="servo", config_toml=None):
        self._native = _native.Baseline(preset, arm, config_toml)

    def reset(self, seed=0):
        self._native.reset(int(seed))

    def act(self, obs):
        return self._native.act(np.ascontiguousarray(obs, dtype=np.float32))
