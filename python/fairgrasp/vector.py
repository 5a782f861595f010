"""``VectorEnv``: N FairGrasp envs stepped on Rust threads in one call (gymnasium ≥ 1.1 vector
API, registered as every FairGrasp id's ``vector_entry_point``).

Autoreset: **same step** (``gymnasium.vector.AutoresetMode.SAME_STEP``): when a sub-env's episode
ends, the observation returned for it is already the next episode's first one, and the ended
episode's last observation and info are in ``info["final_obs"]`` and ``info["final_info"]``
(masked by ``info["_final_obs"]``), as gymnasium documents that mode and as its wrappers
(``RecordEpisodeStatistics``) read it. Episode k of sub-env i plays the scenario seed derived
from (``seed``, i, k), reported in ``info["scenario_seed"]``.
"""

import json

import gymnasium as gym
import numpy as np

from . import _native
from .env import FairGraspEnv, parse_info


def _autoreset_metadata():
    mode = getattr(gym.vector, "AutoresetMode", None)
    if mode is None:
        return {}
    return {"autoreset_mode": mode.SAME_STEP}


class VectorEnv(gym.vector.VectorEnv):
    """``num_envs`` envs of ``preset`` on ``threads`` Rust threads (the physics runs with the
    GIL released). ``gym.make_vec("FairGrasp-Full-v0", num_envs=8,
    vectorization_mode="vector_entry_point")`` builds one."""

    metadata = {"render_modes": [], **_autoreset_metadata()}

    def __init__(self, num_envs=8, preset="full", arm="servo", threads=2, seed=0, config_toml=None, render_mode=None):
        if not hasattr(gym.vector, "AutoresetMode"):
            raise RuntimeError(
                f"fairgrasp.VectorEnv needs gymnasium >= 1.1 (found {gym.__version__}); with older "
                "versions use gymnasium.vector.SyncVectorEnv over FairGraspEnv"
            )
        if render_mode is not None:
            raise ValueError("the vector env does not render: use FairGraspEnv(render_mode='rgb_array')")
        self._args = dict(preset=preset, arm=arm, threads=threads, config_toml=config_toml)
        self.num_envs = int(num_envs)
        self._native = _native.VecEnv(self.num_envs, preset, arm, threads, seed, config_toml)
        single = FairGraspEnv(preset=preset, arm=arm, config_toml=config_toml)
        self.single_observation_space = single.observation_space
        self.single_action_space = single.action_space
        self.observation_space = gym.vector.utils.batch_space(single.observation_space, self.num_envs)
        self.action_space = gym.vector.utils.batch_space(single.action_space, self.num_envs)
        self.render_mode = None
        self.spec = None

    def __getstate__(self):
        return {"num_envs": self.num_envs, **self._args}

    def __setstate__(self, state):
        self.__init__(**state)

    def reset(self, *, seed=None, options=None):
        """Starts every sub-env's next episode; with ``seed``, rebuilds the envs so that the
        episode seeds derive from it (the same seed gives the same episodes)."""
        if seed is not None:
            base = int(seed[0] if isinstance(seed, (list, tuple)) else seed)
            a = self._args
            self._native = _native.VecEnv(self.num_envs, a["preset"], a["arm"], a["threads"], base, a["config_toml"])
        obs, infos = self._native.reset()
        parsed = [parse_info(i) for i in infos]
        return obs, self._batch_infos(parsed)

    def step(self, actions):
        actions = np.ascontiguousarray(actions, dtype=np.float64)
        if actions.shape != (self.num_envs, self.single_action_space.shape[0]):
            raise ValueError(f"actions have shape {actions.shape}, expected ({self.num_envs}, {self.single_action_space.shape[0]})")
        obs, rewards, terminated, truncated, final_obs, infos = self._native.step(actions)
        parsed = [parse_info(i, te, tr) for i, te, tr in zip(infos, terminated, truncated)]
        info = self._batch_infos(parsed)
        ended = terminated | truncated
        if ended.any():
            info["final_obs"] = np.array([final_obs[i] if e else None for i, e in enumerate(ended)], dtype=object)
            info["_final_obs"] = ended.copy()
            info["final_info"] = np.array([parsed[i] if e else None for i, e in enumerate(ended)], dtype=object)
            info["_final_info"] = ended.copy()
        return obs, rewards, terminated, truncated, info

    def _batch_infos(self, parsed):
        n = len(parsed)
        seeds = [p.get("scenario", {}) or {} for p in parsed]
        return {
            "success": np.array([bool(p.get("success")) for p in parsed]),
            "_success": np.ones(n, dtype=bool),
            "scenario_seed": np.array([s.get("seed", 0) for s in seeds], dtype=np.uint64),
            "_scenario_seed": np.ones(n, dtype=bool),
            "outcome": np.array([p.get("outcome") for p in parsed], dtype=object),
            "_outcome": np.array([p.get("outcome") is not None for p in parsed]),
        }

    def close_extras(self, **kwargs):
        self._native = None
