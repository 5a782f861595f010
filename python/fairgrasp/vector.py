"""``VectorEnv``: N FairGrasp envs stepped on Rust threads in one call (gymnasium ≥ 1.1 vector
API, registered as every FairGrasp id's ``vector_entry_point``) — a preset's envs, or the envs a
training recipe trains on with one curriculum shared by all (``recipe=``, as ``FairGraspEnv``).

Autoreset: **same step** (``gymnasium.vector.AutoresetMode.SAME_STEP``): when a sub-env's episode
ends, the observation returned for it is already the next episode's first one, and the ended
episode's last observation and info are in ``info["final_obs"]`` and ``info["final_info"]``
(masked by ``info["_final_obs"]``; ``final_info`` batched as gymnasium batches infos), as
gymnasium documents that mode. Episode k of sub-env i plays the scenario seed
``seed + i · 1 000 000 + k``, reported in ``info["scenario_seed"]``.

The per-env infos are arrays built in Rust (``success``, ``step``, ``simulated``,
``scenario_seed``, ``curriculum_stage``); nothing is parsed per step.
"""

import gymnasium as gym
import numpy as np

from . import _native
from .env import _box, native_args
from .presets import current_preset


def _autoreset_metadata():
    mode = getattr(gym.vector, "AutoresetMode", None)
    if mode is None:
        return {}
    return {"autoreset_mode": mode.SAME_STEP}


class VectorEnv(gym.vector.VectorEnv):
    """``num_envs`` envs of ``preset`` (or of ``recipe`` with keyword overrides, as
    ``FairGraspEnv``) on ``threads`` Rust threads (the physics and the agents' scripts run with
    the GIL released). ``gym.make_vec("FairGrasp-Recipe-PureFull-v0", num_envs=8,
    vectorization_mode="vector_entry_point")`` builds one."""

    metadata = {"render_modes": [], **_autoreset_metadata()}

    def __init__(self, num_envs=8, preset=None, arm=None, threads=2, seed=0, config_toml=None, render_mode=None,
                 recipe=None, evaluation=False, **overrides):
        if not hasattr(gym.vector, "AutoresetMode"):
            raise RuntimeError(
                f"fairgrasp.VectorEnv needs gymnasium >= 1.1 (found {gym.__version__}); with older "
                "versions use gymnasium.vector.SyncVectorEnv over FairGraspEnv"
            )
        if render_mode is not None:
            raise ValueError("the vector env does not render: use FairGraspEnv(render_mode='rgb_array')")
        preset = current_preset(preset)
        self._args = dict(preset=preset, arm=arm, threads=threads, config_toml=config_toml, recipe=recipe,
                          evaluation=evaluation, **overrides)
        self._native_args = native_args(preset, arm, config_toml, recipe, evaluation, overrides)
        self._threads = int(threads)
        self.num_envs = int(num_envs)
        self._native = self._make(int(seed))
        single_obs, self.obs_names = _box(self._native.observation_space_json())
        single_act, self.action_names = _box(self._native.action_space_json())
        self.single_observation_space = single_obs
        self.single_action_space = single_act
        self.observation_space = gym.vector.utils.batch_space(single_obs, self.num_envs)
        self.action_space = gym.vector.utils.batch_space(single_act, self.num_envs)
        self.render_mode = None
        self.spec = None
        self._all = np.ones(self.num_envs, dtype=bool)
        self._all.flags.writeable = False

    def _make(self, seed):
        preset, arm, config_toml, recipe, overrides_json = self._native_args
        return _native.VecEnv(self.num_envs, preset, arm, self._threads, seed, config_toml, recipe, overrides_json)

    def __getstate__(self):
        return {"num_envs": self.num_envs, **self._args}

    def __setstate__(self, state):
        self.__init__(**state)

    @property
    def curriculum_stage(self):
        """``(index, name)`` of the shared curriculum's stage, or None without a curriculum."""
        return self._native.curriculum_stage()

    def set_curriculum_stage(self, stage):
        """Moves the shared curriculum to ``stage`` (clamped to the last) from each env's next reset."""
        self._native.set_curriculum_stage(int(stage))

    def reset(self, *, seed=None, options=None):
        """Starts every sub-env's next episode; with ``seed``, rebuilds the envs (and the
        curriculum) so that the episode seeds derive from it (the same seed gives the same
        episodes)."""
        if seed is not None:
            self._native = self._make(int(seed[0] if isinstance(seed, (list, tuple)) else seed))
        obs, info = self._native.reset()
        return obs, self._masked(info)

    def step(self, actions):
        if type(actions) is not np.ndarray or actions.dtype != np.float64 or not actions.flags.c_contiguous:
            actions = np.ascontiguousarray(actions, dtype=np.float64)
        if actions.shape != (self.num_envs, 7):
            raise ValueError(f"actions have shape {actions.shape}, expected ({self.num_envs}, 7)")
        obs, rewards, terminated, truncated, info, ended = self._native.step(actions)
        info = self._masked(info)
        if ended:
            final_obs = np.full(self.num_envs, None, dtype=object)
            for i, last, _ in ended:
                final_obs[i] = last
            final_info = self._final_infos(ended)
            mask = terminated | truncated
            info["final_obs"], info["_final_obs"] = final_obs, mask
            info["final_info"], info["_final_info"] = final_info, mask.copy()
        return obs, rewards, terminated, truncated, info

    def _final_infos(self, ended):
        """The ended episodes' infos batched as gymnasium batches infos. A key whose value is
        ``None`` (``failure`` of an episode that did not fail) is left out of that env's info, so
        it is masked out (``_failure`` false) rather than stored: gymnasium's batching keeps the
        first value's kind, and a ``None`` batched before another env's ``failure`` dict made it
        an array that the dict could not be merged into (``AttributeError: 'numpy.ndarray' object
        has no attribute 'get'`` when two episodes ended in one step)."""
        final_info = {}
        for i, _, last_info in ended:
            present = {key: value for key, value in last_info.items() if value is not None}
            final_info = self._add_info(final_info, present, i)
        return final_info

    def _masked(self, info):
        for key in list(info):
            info["_" + key] = self._all
        return info

    def close_extras(self, **kwargs):
        self._native = None
