"""Stable-Baselines3's own ``VecEnv`` interface over the native vector env (SB3 does not take
gymnasium vector envs). Importing this module imports SB3 (and torch); nothing else in
fairgrasp does.

    from stable_baselines3 import PPO
    from fairgrasp.sb3 import FairGraspVecEnv
    model = PPO("MlpPolicy", FairGraspVecEnv(8, preset="seed"), verbose=1).learn(200_000)

SB3's conventions: ``step_wait`` returns ``dones = terminated | truncated``; an ended env's last
observation is ``infos[i]["terminal_observation"]`` and ``infos[i]["TimeLimit.truncated"]`` says
whether it was cut rather than terminated (SB3 then bootstraps its value).
"""

import numpy as np
from stable_baselines3.common.vec_env.base_vec_env import VecEnv

from . import _native
from .env import FairGraspEnv, parse_info


class FairGraspVecEnv(VecEnv):
    """``n_envs`` FairGrasp envs on ``threads`` Rust threads, as an SB3 ``VecEnv``."""

    def __init__(self, n_envs=8, preset="full", arm="servo", threads=2, seed=0, config_toml=None):
        single = FairGraspEnv(preset=preset, arm=arm, config_toml=config_toml)
        super().__init__(n_envs, single.observation_space, single.action_space)
        self._args = (preset, arm, threads, config_toml)
        self._native = _native.VecEnv(n_envs, preset, arm, threads, seed, config_toml)
        self._actions = None

    def reset(self):
        seed = self._seeds[0] if any(s is not None for s in getattr(self, "_seeds", [])) else None
        if seed is not None:
            preset, arm, threads, config_toml = self._args
            self._native = _native.VecEnv(self.num_envs, preset, arm, threads, int(seed), config_toml)
            self._reset_seeds()
        obs, infos = self._native.reset()
        self.reset_infos = [parse_info(i) for i in infos]
        return obs

    def step_async(self, actions):
        self._actions = np.ascontiguousarray(actions, dtype=np.float64).reshape(self.num_envs, -1)

    def step_wait(self):
        obs, rewards, terminated, truncated, final_obs, infos = self._native.step(self._actions)
        dones = terminated | truncated
        out = []
        for i, text in enumerate(infos):
            info = parse_info(text, terminated[i], truncated[i])
            if dones[i]:
                info["terminal_observation"] = final_obs[i]
                info["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
            out.append(info)
        return obs, rewards.astype(np.float32), dones, out

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
