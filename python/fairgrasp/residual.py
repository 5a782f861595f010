"""``ResidualWrapper``: the Rust residual mode for any gymnasium learner. The policy sees the
observation with the scripted baseline's action appended, and its action is added to the
baseline's, scaled: ``env action = clip(a_baseline + scale · a_policy, -1, 1)``. A zero policy is
the baseline exactly."""

import gymnasium as gym
import numpy as np

from .baseline import Baseline


class ResidualWrapper(gym.Wrapper):
    """Wraps a ``FairGraspEnv`` (directly or under other wrappers). ``scale`` is the residual's
    authority in action units per policy unit (0.3, as ``[agent] residual_scale``)."""

    def __init__(self, env, scale=0.3):
        super().__init__(env)
        if not (np.isfinite(scale) and 0 < scale <= 10):
            raise ValueError(f"scale = {scale}: must be in (0, 10]")
        base = env.unwrapped
        self.scale = float(scale)
        self.baseline = Baseline(config_toml=base._native.config_toml())
        obs_space = env.observation_space
        act = env.action_space
        self.observation_space = gym.spaces.Box(
            low=np.concatenate([obs_space.low, act.low]).astype(np.float32),
            high=np.concatenate([obs_space.high, act.high]).astype(np.float32),
            dtype=np.float32,
        )
        self._base_action = np.zeros(act.shape, dtype=np.float64)

    def _augment(self, obs):
        self._base_action = self.baseline.act(obs)
        return np.concatenate([obs, self._base_action.astype(np.float32)])

    def reset(self, *, seed=None, options=None):
        obs, info = self.env.reset(seed=seed, options=options)
        self.baseline.reset(self.env.unwrapped._episode_seed)
        return self._augment(obs), info

    def step(self, action):
        action = np.asarray(action, dtype=np.float64)
        if action.shape != self._base_action.shape:
            raise ValueError(f"action has shape {action.shape}, expected {self._base_action.shape}")
        bad = np.flatnonzero(~np.isfinite(action))
        if bad.size:
            raise ValueError(f"action[{bad[0]}] = {action[bad[0]]} is not finite")
        combined = np.clip(self._base_action + self.scale * action, -1.0, 1.0)
        obs, reward, terminated, truncated, info = self.env.step(combined)
        info["baseline_action"] = self._base_action
        return self._augment(obs), reward, terminated, truncated, info
