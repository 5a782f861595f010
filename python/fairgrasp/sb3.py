"""Stable-Baselines3's own ``VecEnv`` interface over the native vector env (SB3 does not take
gymnasium vector envs). Importing this module imports SB3 (and torch); nothing else in
fairgrasp does.

    from stable_baselines3 import PPO
    from fairgrasp.sb3 import FairGraspVecEnv
    env = FairGraspVecEnv(8, recipe="pure_full")   # the env the recipe trains on, its curriculum
    model = PPO("MlpPolicy", env, verbose=1).learn(200_000)

SB3's conventions: ``step_wait`` returns ``dones = terminated | truncated``; an ended env's last
observation is ``infos[i]["terminal_observation"]`` and ``infos[i]["TimeLimit.truncated"]`` says
whether it was cut rather than terminated (SB3 then bootstraps its value); at an episode's end
``infos[i]`` also has ``is_success`` (SB3 logs ``rollout/success_rate``), ``episode`` (``r``,
``l``, ``t``, as SB3's ``Monitor`` writes it: ``rollout/ep_rew_mean``), ``outcome``,
``episode_record`` and ``curriculum_stage``.
"""

import time

import numpy as np
from stable_baselines3.common.vec_env.base_vec_env import VecEnv

from . import _native
from .env import _box, native_args


class FairGraspVecEnv(VecEnv):
    """``n_envs`` FairGrasp envs on ``threads`` Rust threads, as an SB3 ``VecEnv``: a preset's
    envs, or a recipe's (``recipe=`` and keyword overrides, as ``fairgrasp.make``)."""

    def __init__(self, n_envs=8, preset=None, arm=None, threads=2, seed=0, config_toml=None, recipe=None,
                 evaluation=False, **overrides):
        self._native_args = native_args(preset, arm, config_toml, recipe, evaluation, overrides)
        self._threads = int(threads)
        self._n = int(n_envs)
        self._native = self._make(int(seed))
        obs_space, self.obs_names = _box(self._native.observation_space_json())
        act_space, self.action_names = _box(self._native.action_space_json())
        super().__init__(self._n, obs_space, act_space)
        self._actions = None
        self._start = time.time()

    def _make(self, seed):
        preset, arm, config_toml, recipe, overrides_json = self._native_args
        return _native.VecEnv(self._n, preset, arm, self._threads, seed, config_toml, recipe, overrides_json)

    @property
    def curriculum_stage(self):
        """``(index, name)`` of the shared curriculum's stage, or None without a curriculum."""
        return self._native.curriculum_stage()

    def reset(self):
        seeds = getattr(self, "_seeds", [])
        seed = next((s for s in seeds if s is not None), None)
        if seed is not None:
            self._native = self._make(int(seed))
            self._reset_seeds()
        obs, info = self._native.reset()
        self.reset_infos = [{"scenario_seed": int(s)} for s in info["scenario_seed"]]
        return obs

    def step_async(self, actions):
        self._actions = np.ascontiguousarray(actions, dtype=np.float64).reshape(self.num_envs, -1)

    def step_wait(self):
        obs, rewards, terminated, truncated, _, ended = self._native.step(self._actions)
        dones = terminated | truncated
        infos = [{} for _ in range(self.num_envs)]
        now = round(time.time() - self._start, 6)
        for i, last, info in ended:
            record = info["episode_record"]
            info["terminal_observation"] = last
            info["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
            info["is_success"] = record["outcome"] == "success"
            info["episode"] = {"r": record["episode_return"], "l": record["steps"], "t": now}
            infos[i] = info
        return obs, rewards.astype(np.float32), dones, infos

    def close(self):
        self._native = None

    def get_attr(self, attr_name, indices=None):
        return [getattr(self, attr_name, None) for _ in self._get_indices(indices)]

    def set_attr(self, attr_name, value, indices=None):
        setattr(self, attr_name, value)

    def env_method(self, method_name, *method_args, indices=None, **method_kwargs):
        raise AttributeError(f"FairGraspVecEnv sub-envs are Rust envs: no Python method {method_name!r}")

    def env_is_wrapped(self, wrapper_class, indices=None):
        return [False for _ in self._get_indices(indices)]
