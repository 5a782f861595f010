"""``FairGraspEnv``: one Rust grasping env behind gymnasium's ``Env`` interface."""

import json

import gymnasium as gym
import numpy as np
from gymnasium.utils import EzPickle

from . import _native


def _box(space_json, dtype=np.float32):
    space = json.loads(space_json)
    low = np.asarray(space["low"], dtype=dtype)
    high = np.asarray(space["high"], dtype=dtype)
    return gym.spaces.Box(low=low, high=high, dtype=dtype), space["names"]


def parse_info(info_json, terminated=False, truncated=False):
    """The Rust step's info as a dict, with ``outcome`` and ``collision_pair`` added from the
    episode record the Rust env computes at the terminal step (``info["episode"]``: outcome,
    success, steps, return, held, lifted, ...): the outcome is Rust's, never re-derived here.
    Both are ``None`` while the episode runs."""
    info = json.loads(info_json)
    record = info.get("episode")
    info["outcome"] = record["outcome"] if record else None
    pair = record.get("collision_pair") if record else None
    info["collision_pair"] = tuple(pair) if pair else None
    return info


class FairGraspEnv(gym.Env, EzPickle):
    """The FR3 grasping env (Rust, rapier3d). ``preset``: a shipped preset name (see
    ``fairgrasp.preset_names()``) or a .toml path; ``arm``: ``"servo"`` or ``"multibody"``;
    ``config_toml``: a whole env config as TOML text (instead of a preset).

    Observation: 23 float32 values with finite bounds (names in ``obs_names``); action: 7 values
    in [-1, 1] (joint velocities and gripper, or TCP velocity, yaw rate and gripper when the
    config's ``arm.action_space = "tcp"``). ``terminated`` and ``truncated`` are the Rust env's;
    ``info`` has ``success``, ``outcome``, ``collision_pair`` and the scenario. The physics runs
    with the GIL released. Pickles by its constructor arguments (subprocess vector envs, Ray).
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 10}

    def __init__(self, preset="full", arm="servo", config_toml=None, render_mode=None):
        EzPickle.__init__(self, preset=preset, arm=arm, config_toml=config_toml, render_mode=render_mode)
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode = {render_mode!r}: choose None or 'rgb_array'")
        self.render_mode = render_mode
        self.preset = preset
        self._native = _native.Env(preset, arm, config_toml, render_mode == "rgb_array")
        self.observation_space, self.obs_names = _box(self._native.observation_space_json())
        self.action_space, self.action_names = _box(self._native.action_space_json())
        self._episode_seed = None

    @property
    def max_steps(self):
        return self._native.max_steps

    def reset(self, *, seed=None, options=None):
        """Starts an episode. ``reset(seed=s)`` plays scenario ``s`` (the Rust
        ``GraspEnv::reset(s)``, bit for bit); later resets without a seed draw the next scenario
        seeds from a generator seeded with ``s``."""
        super().reset(seed=seed)
        if seed is not None:
            scenario_seed = int(seed)
        else:
            scenario_seed = int(self.np_random.integers(0, 2**62))
        if options and "scenario_seed" in options:
            scenario_seed = int(options["scenario_seed"])
        self._episode_seed = scenario_seed
        obs, info = self._native.reset(scenario_seed)
        return obs, parse_info(info)

    def step(self, action):
        action = np.asarray(action, dtype=np.float64)
        if action.shape != (self.action_space.shape[0],):
            raise ValueError(f"action has shape {action.shape}, expected ({self.action_space.shape[0]},)")
        obs, reward, terminated, truncated, info = self._native.step(np.ascontiguousarray(action))
        return obs, float(reward), bool(terminated), bool(truncated), parse_info(info, terminated, truncated)

    def render(self):
        if self.render_mode != "rgb_array":
            return None
        return self._native.render_rgb()

    def close(self):
        pass
