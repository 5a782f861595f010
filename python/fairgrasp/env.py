"""``FairGraspEnv``: one Rust grasping env behind gymnasium's ``Env`` interface — a preset's env,
or the env a training recipe trains on (``recipe=``)."""

import json

import gymnasium as gym
import numpy as np
from gymnasium.utils import EzPickle

from . import _native
from .presets import current_preset


def _box(space_json, dtype=np.float32):
    space = json.loads(space_json)
    low = np.asarray(space["low"], dtype=dtype)
    high = np.asarray(space["high"], dtype=dtype)
    return gym.spaces.Box(low=low, high=high, dtype=dtype), space["names"]


def native_args(preset, arm, config_toml, recipe, evaluation, overrides):
    """The native constructor's arguments: ``(preset, arm, config_toml, recipe, overrides_json)``.

    Without a recipe: ``preset`` (default ``"full"``) and ``arm`` (default ``"servo"``), and no
    other keyword. With one: ``preset`` and ``arm`` are overrides like the others (default: the
    recipe's), ``config_toml`` is refused, and ``evaluation=True`` drops the recipe's
    training-only ``[env]`` settings and its curriculum (the env its evaluations use). A renamed
    preset's old name gives its current one, with a ``DeprecationWarning``."""
    preset = current_preset(preset)
    if recipe is None:
        if overrides or evaluation:
            names = ", ".join(sorted(overrides)) or "evaluation"
            raise ValueError(
                f"unknown keyword(s) {names}: without a recipe the env takes preset, arm, "
                "config_toml, render_mode; with recipe=... it takes the overrides "
                + ", ".join(_native.recipe_keys())
            )
        return preset or "full", arm or "servo", config_toml, None, None
    if config_toml is not None:
        raise ValueError("config_toml and recipe exclude each other: override the recipe's env with env={...}")
    overrides = dict(overrides)
    if preset is not None:
        overrides["preset"] = preset
    if arm is not None:
        overrides["arm"] = arm
    if evaluation:
        for key in ("env", "curriculum"):
            if overrides.get(key) is not None:
                raise ValueError(f"evaluation=True drops the recipe's {key}: do not give {key}= as well")
            overrides[key] = None
    return "full", "servo", None, str(recipe), json.dumps(overrides)


class FairGraspEnv(gym.Env, EzPickle):
    """The FR3 grasping env (Rust, rapier3d).

    A preset's env: ``preset`` a shipped preset name (see ``fairgrasp.preset_names()``) or a
    .toml path, ``arm`` ``"servo"`` or ``"multibody"``, ``config_toml`` a whole env config as
    TOML text (instead of a preset). Observation: 23 float32 values with finite bounds (names in
    ``obs_names``); action: 7 values in [-1, 1] (joint velocities and gripper, or TCP velocity,
    yaw rate and gripper when the config's ``arm.action_space = "tcp"``).

    A recipe's env: ``recipe`` a shipped recipe name (``fairgrasp.recipe_names()``) or a
    training config's path; keyword overrides ``preset``, ``arm``, ``agent``, ``curriculum``,
    ``env`` are laid over the recipe (tables merge: ``env={"task": {"max_steps": 50}}``;
    ``curriculum=None`` drops one; a misspelt key is refused with the valid ones). The env is the
    one ``fairgrasp train`` steps for that recipe: the agent's action space and gripper mode,
    the recipe's ``[env]`` reward and episode length, and its curriculum (the Rust one, advancing
    on the episodes this env plays; stage in ``info["curriculum_stage"]``). For a residual recipe
    the observation is the residual policy's input (observation and the script's features) and
    the action is the correction, both computed by the Rust agent code.

    ``terminated`` and ``truncated`` are the Rust env's; ``info`` has ``success``, ``step``,
    ``scenario_seed``, and at an episode's end ``outcome``, ``collision_pair`` and the env's
    ``episode_record`` (``info["episode"]`` is left to gymnasium's and SB3's episode
    statistics). The physics runs with the GIL released. Pickles by its constructor arguments.
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 10}

    def __init__(self, preset=None, arm=None, config_toml=None, render_mode=None, recipe=None, evaluation=False, **overrides):
        preset = current_preset(preset)
        EzPickle.__init__(
            self, preset=preset, arm=arm, config_toml=config_toml, render_mode=render_mode,
            recipe=recipe, evaluation=evaluation, **overrides,
        )
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode = {render_mode!r}: choose None or 'rgb_array'")
        args = native_args(preset, arm, config_toml, recipe, evaluation, overrides)
        self.render_mode = render_mode
        self.recipe = recipe
        self.preset = args[0] if recipe is None else overrides.get("preset", preset)
        self._native = _native.Env(*args[:3], render_mode == "rgb_array", *args[3:])
        self.observation_space, self.obs_names = _box(self._native.observation_space_json())
        self.action_space, self.action_names = _box(self._native.action_space_json())
        self._episode_seed = None

    @property
    def max_steps(self):
        return self._native.max_steps

    @property
    def curriculum_stage(self):
        """``(index, name)`` of the curriculum's stage, or None without a curriculum."""
        return self._native.curriculum_stage()

    def set_curriculum_stage(self, stage):
        """Moves the curriculum to ``stage`` (clamped to the last) from the next reset on."""
        self._native.set_curriculum_stage(int(stage))

    def reset(self, *, seed=None, options=None):
        """Starts an episode. ``reset(seed=s)`` plays scenario ``s`` (the Rust
        ``TaskEnv::reset(s)``, bit for bit); later resets without a seed draw the next scenario
        seeds from a generator seeded with ``s``."""
        super().reset(seed=seed)
        if seed is not None:
            scenario_seed = int(seed)
        else:
            scenario_seed = int(self.np_random.integers(0, 2**62))
        if options and "scenario_seed" in options:
            scenario_seed = int(options["scenario_seed"])
        self._episode_seed = scenario_seed
        return self._native.reset(scenario_seed)

    def step(self, action):
        if type(action) is not np.ndarray or action.dtype != np.float64:
            action = np.asarray(action, dtype=np.float64)
        if action.shape != (7,):
            raise ValueError(f"action has shape {action.shape}, expected (7,)")
        return self._native.step(action)

    def render(self):
        if self.render_mode != "rgb_array":
            return None
        return self._native.render_rgb()

    def close(self):
        pass
